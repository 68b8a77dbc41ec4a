#include "sl_lexer.h"

#include <array>
#include <cctype>

namespace shadelab::shaders {

namespace {

bool is_ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_'; }
bool is_ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// Two- and three-character operators of C, GLSL and HLSL, longest first.
constexpr std::array<std::string_view, 21> kOperators = {"<<=", ">>=", "::", "<=", ">=", "==", "!=", "&&", "||", "++", "--",
                                                         "+=",  "-=",  "*=", "/=", "%=", "&=", "|=", "^=", "<<", ">>"};

}  // namespace

std::vector<Token> lex(std::string_view s) {
  std::vector<Token> out;
  std::size_t i = 0;
  int line = 1;
  bool line_start = true;  // only whitespace since the last newline: a '#' starts a directive
  auto push = [&](TokenKind kind, std::size_t begin, std::size_t end) {
    Token t{kind, std::string(s.substr(begin, end - begin)), line};
    for (std::size_t k = begin; k < end; ++k) {
      if (s[k] == '\n') ++line;
    }
    out.push_back(std::move(t));
  };
  while (i < s.size()) {
    const char c = s[i];
    const std::size_t begin = i;
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
      while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r' || s[i] == '\f' || s[i] == '\v')) {
        if (s[i] == '\n') line_start = true;
        ++i;
      }
      push(TokenKind::whitespace, begin, i);
      continue;
    }
    if (c == '/' && i + 1 < s.size() && s[i + 1] == '/') {
      while (i < s.size() && s[i] != '\n') ++i;
      push(TokenKind::comment, begin, i);
      continue;
    }
    if (c == '/' && i + 1 < s.size() && s[i + 1] == '*') {
      const std::size_t close = s.find("*/", i + 2);
      i = close == std::string_view::npos ? s.size() : close + 2;
      push(TokenKind::comment, begin, i);
      continue;
    }
    if (c == '#' && line_start) {
      while (i < s.size() && s[i] != '\n') {
        if (s[i] == '\\' && i + 1 < s.size() && s[i + 1] == '\n') ++i;  // continuation
        ++i;
      }
      push(TokenKind::preprocessor, begin, i);
      continue;
    }
    line_start = false;
    if (is_ident_start(c)) {
      while (i < s.size() && is_ident_char(s[i])) ++i;
      push(TokenKind::identifier, begin, i);
      continue;
    }
    if (is_digit(c) || (c == '.' && i + 1 < s.size() && is_digit(s[i + 1]))) {
      // Digits, a decimal point, an exponent with its sign, then suffix letters (u, f, lf, h, ...).
      while (i < s.size()) {
        const char d = s[i];
        if (is_digit(d) || d == '.' || is_ident_char(d)) {
          if ((d == 'e' || d == 'E') && i + 1 < s.size() && (s[i + 1] == '+' || s[i + 1] == '-')) ++i;
          ++i;
        } else {
          break;
        }
      }
      push(TokenKind::number, begin, i);
      continue;
    }
    std::size_t len = 1;
    for (std::string_view op : kOperators) {
      if (s.substr(i, op.size()) == op) {
        len = op.size();
        break;
      }
    }
    i += len;
    push(TokenKind::punctuation, begin, i);
  }
  return out;
}

std::string join(const std::vector<Token>& tokens, std::size_t begin, std::size_t end) {
  std::string out;
  if (end > tokens.size()) end = tokens.size();
  for (std::size_t k = begin; k < end; ++k) out += tokens[k].text;
  return out;
}

}  // namespace shadelab::shaders
