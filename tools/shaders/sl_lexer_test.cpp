// The lexer gives the text back exactly (so a token map keeps comments and line numbers), and splits the
// dialect's constructs into the right tokens.
#include "sl_lexer.h"

#include <gtest/gtest.h>

#include "kernel_library.h"

namespace shadelab::shaders {
namespace {

TEST(SlLexer, EveryKernelFileRoundTripsExactly) {
  for (const auto& f : embedded_kernel_files()) EXPECT_EQ(join(lex(f.text)), f.text) << f.name;
  for (const auto& f : embedded_support_files()) EXPECT_EQ(join(lex(f.text)), f.text) << f.name;
}

TEST(SlLexer, TokenKindsAndLines) {
  const std::string text = "// real rgb\nreal x = 1.5e-3; /* mix\n atan2 */ x += 2.0f;\n#define A 1\nint y=x<=3;";
  const auto t = lex(text);
  std::vector<std::pair<TokenKind, std::string>> code;
  for (const auto& tok : t) {
    if (tok.kind != TokenKind::whitespace) code.emplace_back(tok.kind, tok.text);
  }
  ASSERT_GE(code.size(), 14u);
  EXPECT_EQ(code[0], std::make_pair(TokenKind::comment, std::string("// real rgb")));
  EXPECT_EQ(code[1], std::make_pair(TokenKind::identifier, std::string("real")));
  EXPECT_EQ(code[4], std::make_pair(TokenKind::number, std::string("1.5e-3")));
  EXPECT_EQ(code[6], std::make_pair(TokenKind::comment, std::string("/* mix\n atan2 */")));
  EXPECT_EQ(code[8], std::make_pair(TokenKind::punctuation, std::string("+=")));
  EXPECT_EQ(code[9], std::make_pair(TokenKind::number, std::string("2.0f")));
  EXPECT_EQ(code[11], std::make_pair(TokenKind::preprocessor, std::string("#define A 1")));
  // "x<=3": identifier, "<=", number
  EXPECT_EQ(code[code.size() - 3], std::make_pair(TokenKind::punctuation, std::string("<=")));
  // Line numbers count the newlines inside comments.
  for (const auto& tok : t) {
    if (tok.text == "2.0f") {
      EXPECT_EQ(tok.line, 3);
    }
    if (tok.text == "y") {
      EXPECT_EQ(tok.line, 5);
    }
  }
}

TEST(SlLexer, HashInsideALineIsNotADirective) {
  const auto t = lex("a # b\n  #line 1\n");
  int directives = 0;
  for (const auto& tok : t) directives += tok.kind == TokenKind::preprocessor ? 1 : 0;
  EXPECT_EQ(directives, 1);
}

}  // namespace
}  // namespace shadelab::shaders
