// shadelab message text: every error is one printable line of bounded length (docs/testing.md, "Classes of
// bad input").
//
// - printable(text, max_bytes): control bytes (below 0x20, 0x7f) and bytes that are not part of valid UTF-8
//   are written as \xNN; valid UTF-8 is kept; the result is cut at a character boundary to at most
//   max_bytes bytes plus "...". Used for anything quoted from a file or the command line (names, keys,
//   library messages).
// - printable_message(text): the whole line the CLI prints; a message longer than max_message_bytes keeps
//   its start (file, field) and its end (the reason) and drops the middle.
// - xml_escape(text): text for XML or HTML content and attribute values (SVG <title>, report pages): & < > " '
//   escaped, the control characters XML 1.0 forbids (all below 0x20 but tab, line feed, carriage return)
//   replaced by spaces.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>

namespace shadelab {

inline constexpr std::size_t max_quoted_bytes = 80;     // a name or key quoted in a message
inline constexpr std::size_t max_library_bytes = 240;   // a third-party library's message inside ours
inline constexpr std::size_t max_message_bytes = 1000;  // a whole message line

namespace text_detail {

// Length of the valid UTF-8 sequence starting at s[i] (RFC 3629: no overlongs, no surrogates, <= U+10FFFF),
// or 0 when the bytes there are not one.
inline std::size_t utf8_sequence(std::string_view s, std::size_t i) {
  const auto b0 = static_cast<unsigned char>(s[i]);
  std::size_t n = 0;
  unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    n = 2;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    n = 3;
    if (b0 == 0xE0) lo = 0xA0;
    if (b0 == 0xED) hi = 0x9F;
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    n = 4;
    if (b0 == 0xF0) lo = 0x90;
    if (b0 == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const auto b = static_cast<unsigned char>(s[i + k]);
    if (b < (k == 1 ? lo : 0x80u) || b > (k == 1 ? hi : 0xBFu)) return 0;
  }
  return n;
}

inline void append_hex(std::string& out, unsigned char b) {
  static constexpr char digits[] = "0123456789abcdef";
  out += "\\x";
  out += digits[b >> 4];
  out += digits[b & 15];
}

}  // namespace text_detail

inline std::string printable(std::string_view text, std::size_t max_bytes = max_quoted_bytes) {
  std::string out;
  out.reserve(std::min(text.size(), max_bytes) + 8);
  std::size_t i = 0;
  while (i < text.size()) {
    const auto b = static_cast<unsigned char>(text[i]);
    std::string piece;
    std::size_t used = 1;
    if (b >= 0x20 && b < 0x7f) {
      piece.assign(1, static_cast<char>(b));
    } else if (b >= 0x80 && (used = text_detail::utf8_sequence(text, i)) > 0) {
      piece.assign(text.substr(i, used));
    } else {
      used = 1;
      text_detail::append_hex(piece, b);
    }
    if (out.size() + piece.size() > max_bytes) {
      out += "...";
      return out;
    }
    out += piece;
    i += used;
  }
  return out;
}

inline std::string printable_message(std::string_view text, std::size_t max_bytes = max_message_bytes) {
  const std::string all = printable(text, std::string::npos - 8);
  if (all.size() <= max_bytes) return all;
  // Cut the middle: the start names the file and field, the end usually says what is wrong.
  const std::size_t tail = max_bytes / 4;
  std::size_t head_end = max_bytes - tail - 5;
  std::size_t tail_start = all.size() - tail;
  // Do not split a UTF-8 sequence or a \xNN escape.
  auto continuation = [&](std::size_t k) { return (static_cast<unsigned char>(all[k]) & 0xC0) == 0x80; };
  while (head_end > 0 && continuation(head_end)) --head_end;
  while (tail_start < all.size() && continuation(tail_start)) ++tail_start;
  for (std::size_t k = head_end >= 3 ? head_end - 3 : 0; k < head_end; ++k) {
    if (all[k] == '\\' && k + 1 < all.size() && all[k + 1] == 'x') head_end = k;
  }
  for (std::size_t k = tail_start >= 3 ? tail_start - 3 : 0; k < tail_start; ++k) {
    if (all[k] == '\\' && k + 1 < all.size() && all[k + 1] == 'x') tail_start = k + 4;
  }
  return all.substr(0, head_end) + " ... " + all.substr(tail_start);
}

inline std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // XML 1.0 section 2.2: no control characters but tab, line feed and carriage return.
        out += (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') ? ' ' : c;
    }
  }
  return out;
}

}  // namespace shadelab
