// shadelab shader exporter: a lexer for the shading dialect (src/shadelab/kernels/sl.h) and for the C-like
// shading languages it is translated to. It splits text into tokens that, concatenated, give the text back
// exactly (whitespace and comments are tokens too), so a translation that maps identifiers leaves comments,
// layout and line numbers intact.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace shadelab::shaders {

enum class TokenKind {
  whitespace,    // spaces, tabs, newlines
  comment,       // // to the end of the line (newline excluded), or /* ... */
  preprocessor,  // a # line, to its end (newline excluded; backslash continuations included)
  identifier,    // [A-Za-z_][A-Za-z0-9_]*
  number,        // a numeric literal, suffixes included
  punctuation,   // an operator or separator, longest match ("<=", "++", "+=", ...)
};

struct Token {
  TokenKind kind;
  std::string text;
  int line;  // 1-based line of the token's first character
};

// Tokenizes text; never fails (an unknown character becomes a one-character punctuation token).
std::vector<Token> lex(std::string_view text);

// The text of tokens [begin, end) concatenated.
std::string join(const std::vector<Token>& tokens, std::size_t begin = 0, std::size_t end = std::string::npos);

// True for tokens that carry no code (whitespace and comments).
inline bool is_trivia(const Token& t) { return t.kind == TokenKind::whitespace || t.kind == TokenKind::comment; }

}  // namespace shadelab::shaders
