// Tests of core/text.h: messages are one printable line of bounded length (issue 16, 5).
#include "shadelab/core/text.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace shadelab {
namespace {

bool printable_ascii_or_utf8(const std::string& s) {
  return std::none_of(s.begin(), s.end(), [](char c) {
    const auto b = static_cast<unsigned char>(c);
    return b < 0x20 || b == 0x7f;
  });
}

TEST(Text, ControlBytesAndBadUtf8AreEscaped) {
  EXPECT_EQ(printable("a\nb\tc\x1b[31m"), "a\\x0ab\\x09c\\x1b[31m");
  EXPECT_EQ(printable(std::string("nul\0x", 5)), "nul\\x00x");
  EXPECT_EQ(printable("\x7f"), "\\x7f");
  // Valid UTF-8 is kept: e acute, the euro sign, a 4-byte emoji.
  EXPECT_EQ(printable("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80");
  // Invalid: a lone continuation byte, an overlong encoding of '/', a surrogate, a truncated sequence.
  EXPECT_EQ(printable("\x80"), "\\x80");
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");
  EXPECT_EQ(printable("ab\xe2\x82"), "ab\\xe2\\x82");
}

TEST(Text, LongTextIsCutAtACharacterBoundary) {
  const std::string name(100000, 'n');
  const std::string cut = printable(name);
  EXPECT_EQ(cut.size(), max_quoted_bytes + 3);
  EXPECT_EQ(cut.substr(cut.size() - 3), "...");
  // A cut never splits an escape or a UTF-8 sequence.
  const std::string euros = printable(std::string(100, '\xe2') + "x", 10);
  EXPECT_EQ(euros, "\\xe2\\xe2...");
  std::string utf8;
  for (int i = 0; i < 50; ++i) utf8 += "\xc3\xa9";
  const std::string e = printable(utf8, 11);
  EXPECT_EQ(e.size(), 10u + 3u);  // five whole characters, then "..."
}

TEST(Text, WholeMessagesKeepTheirStartAndEnd) {
  const std::string message = "scene.json: /materials/" + std::string(100000, 'x') + "\x1b: unknown key 'z'";
  const std::string line = printable_message(message);
  EXPECT_LE(line.size(), max_message_bytes);
  EXPECT_EQ(line.rfind("scene.json: /materials/xxx", 0), 0u);
  EXPECT_EQ(line.substr(line.size() - 15), "unknown key 'z'");
  EXPECT_NE(line.find(" ... "), std::string::npos);
  EXPECT_NE(line.find("\\x1b"), std::string::npos);
  EXPECT_TRUE(printable_ascii_or_utf8(line));
  EXPECT_EQ(printable_message("short"), "short");
}

}  // namespace
}  // namespace shadelab

// xml_escape against its inverse: decoding the five entities gives back the input with the forbidden control
// bytes as spaces, and the output holds none of & < > " ' unescaped nor any forbidden control byte.
TEST(Text, XmlEscapeDecodesBackAndLeavesNoMarkup) {
  std::string all;
  for (int b = 1; b < 256; ++b) all += static_cast<char>(b);
  all += "a&amp;b<c>\"'";
  const std::string out = shadelab::xml_escape(all);
  std::string decoded, expected;
  for (std::size_t i = 0; i < out.size();) {
    const auto c = static_cast<unsigned char>(out[i]);
    ASSERT_NE(c, '<');
    ASSERT_NE(c, '>');
    ASSERT_NE(c, '"');
    ASSERT_NE(c, '\'');
    ASSERT_FALSE(c < 0x20 && c != '\t' && c != '\n' && c != '\r') << "control byte " << int(c) << " kept";
    if (c == '&') {
      const std::size_t semi = out.find(';', i);
      ASSERT_NE(semi, std::string::npos);
      const std::string entity = out.substr(i, semi + 1 - i);
      if (entity == "&amp;") decoded += '&';
      else if (entity == "&lt;") decoded += '<';
      else if (entity == "&gt;") decoded += '>';
      else if (entity == "&quot;") decoded += '"';
      else if (entity == "&apos;") decoded += '\'';
      else FAIL() << "unknown entity " << entity;
      i = semi + 1;
    } else {
      decoded += out[i++];
    }
  }
  for (const char c : all) {
    const auto b = static_cast<unsigned char>(c);
    expected += (b < 0x20 && c != '\t' && c != '\n' && c != '\r') ? ' ' : c;
  }
  EXPECT_EQ(decoded, expected);
}
