// shadelab Radiance RGBE decoding (see rgbe.h). Format: G. Ward, "Real Pixels", Graphics Gems II (1991),
// and the Radiance file format notes (radsite.lbl.gov, "Radiance File Formats").
#include "shadelab/image/rgbe.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace shadelab {
namespace {

// A bounded cursor over the input bytes.
class Cursor {
 public:
  Cursor(const unsigned char* begin, std::size_t size) : m_p(begin), m_end(begin + size) {}
  std::size_t left() const { return static_cast<std::size_t>(m_end - m_p); }
  const unsigned char* peek() const { return m_p; }
  unsigned char next() { return *m_p++; }  // callers check left() first
  void skip(std::size_t n) { m_p += n; }
  // The next line without its '\n'; false when no '\n' remains.
  bool line(std::string_view& out) {
    for (const unsigned char* q = m_p; q != m_end; ++q) {
      if (*q == '\n') {
        out = std::string_view(reinterpret_cast<const char*>(m_p), static_cast<std::size_t>(q - m_p));
        m_p = q + 1;
        return true;
      }
    }
    return false;
  }

 private:
  const unsigned char* m_p;
  const unsigned char* m_end;
};

// One axis of the resolution line: "-Y 512" and the like.
struct Axis {
  char sign = 0;
  char letter = 0;
  int size = 0;
};

bool parse_axis(std::string_view& s, Axis& axis) {
  while (!s.empty() && s.front() == ' ') {
    s.remove_prefix(1);
  }
  if (s.size() < 2 || (s[0] != '+' && s[0] != '-') || (s[1] != 'X' && s[1] != 'Y')) {
    return false;
  }
  axis.sign = s[0];
  axis.letter = s[1];
  s.remove_prefix(2);
  while (!s.empty() && s.front() == ' ') {
    s.remove_prefix(1);
  }
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), axis.size);
  if (ec != std::errc() || axis.size <= 0) {
    return false;
  }
  s.remove_prefix(static_cast<std::size_t>(end - s.data()));
  return true;
}

// Reads one scan line of `length` RGBE texels into `scan` (4 bytes each). Returns an empty string on
// success, else the reason.
std::string read_scanline(Cursor& in, int length, unsigned char* scan) {
  const auto n = static_cast<std::size_t>(length);
  const unsigned char* p = in.peek();
  // Per-component run-length encoding: marker 2, 2, then the length as 15 bits, big-endian; used only for
  // lengths 8 to 32767 (Ward, "Real Pixels").
  if (length >= 8 && length <= 0x7fff && in.left() >= 4 && p[0] == 2 && p[1] == 2 && (p[2] & 0x80) == 0) {
    const int encoded = (p[2] << 8) | p[3];
    if (encoded != length) {
      return "scan line length " + std::to_string(encoded) + " does not match " + std::to_string(length);
    }
    in.skip(4);
    for (std::size_t k = 0; k < 4; ++k) {
      std::size_t i = 0;
      while (i < n) {
        if (in.left() == 0) {
          return "file is truncated inside the pixel data";
        }
        const unsigned code = in.next();
        if (code > 128) {  // a run: code - 128 copies of the next byte
          const std::size_t run = code - 128;
          if (run > n - i) {
            return "run-length data overruns the scan line";
          }
          if (in.left() == 0) {
            return "file is truncated inside the pixel data";
          }
          const unsigned char value = in.next();
          for (std::size_t z = 0; z < run; ++z, ++i) {
            scan[4 * i + k] = value;
          }
        } else {  // `code` literal bytes
          if (code == 0) {
            return "zero-length run in run-length data";
          }
          if (code > n - i) {
            return "run-length data overruns the scan line";
          }
          if (in.left() < code) {
            return "file is truncated inside the pixel data";
          }
          for (std::size_t z = 0; z < code; ++z, ++i) {
            scan[4 * i + k] = in.next();
          }
        }
      }
    }
    return {};
  }
  // Flat texels, where (1, 1, 1, c) repeats the previous texel c << shift times, the shift growing by 8
  // with each consecutive repeat texel (the original Radiance encoding).
  std::size_t i = 0;
  unsigned shift = 0;
  while (i < n) {
    if (in.left() < 4) {
      return "file is truncated inside the pixel data";
    }
    const unsigned char* t = in.peek();
    in.skip(4);
    if (t[0] == 1 && t[1] == 1 && t[2] == 1) {
      if (i == 0) {
        return "repeat texel at the start of a scan line";
      }
      if (shift > 16) {
        return "repeat count overflows the scan line";
      }
      const std::size_t count = static_cast<std::size_t>(t[3]) << shift;
      if (count > n - i) {
        return "repeat count overruns the scan line";
      }
      for (std::size_t z = 0; z < count; ++z, ++i) {
        for (std::size_t k = 0; k < 4; ++k) {
          scan[4 * i + k] = scan[4 * (i - 1) + k];
        }
      }
      shift += 8;
    } else {
      for (std::size_t k = 0; k < 4; ++k) {
        scan[4 * i + k] = t[k];
      }
      ++i;
      shift = 0;
    }
  }
  return {};
}

}  // namespace

Result<Image> decode_rgbe(const unsigned char* bytes, std::size_t size, long long max_pixels) {
  Cursor in(bytes, size);
  if (size < 2 || bytes[0] != '#' || bytes[1] != '?') {
    return make_error("not a Radiance RGBE file (no #? signature)");
  }
  std::string_view line;
  for (;;) {
    if (!in.line(line)) {
      return make_error("file is truncated inside the header");
    }
    if (line.empty()) {
      break;
    }
    if (line.substr(0, 7) == "FORMAT=") {
      std::string_view value = line.substr(7);
      while (!value.empty() && (value.back() == ' ' || value.back() == '\r')) {
        value.remove_suffix(1);
      }
      if (value != "32-bit_rle_rgbe") {
        return make_error("unsupported Radiance FORMAT=" + std::string(value) + " (only 32-bit_rle_rgbe)");
      }
    }
  }
  if (!in.line(line)) {
    return make_error("file is truncated before the resolution line");
  }
  const std::string resolution(line);
  Axis major;
  Axis minor;
  if (!parse_axis(line, major) || !parse_axis(line, minor) || major.letter == minor.letter) {
    return make_error("bad resolution line '" + resolution + "'");
  }
  const bool y_major = major.letter == 'Y';
  const int width = y_major ? minor.size : major.size;
  const int height = y_major ? major.size : minor.size;
  if (static_cast<long long>(width) * height > max_pixels) {
    return make_error("image is too large (" + std::to_string(width) + " x " + std::to_string(height) + ")");
  }

  // 2^(e - 136) for every exponent byte: the mantissa byte m stands for m / 256, the exponent is biased by 128.
  std::array<float, 256> scale{};
  for (int e = 1; e < 256; ++e) {
    scale[static_cast<std::size_t>(e)] = std::ldexp(1.0f, e - 136);
  }
  Image image(width, height);
  std::vector<unsigned char> scan(static_cast<std::size_t>(minor.size) * 4);
  for (int j = 0; j < major.size; ++j) {
    const std::string reason = read_scanline(in, minor.size, scan.data());
    if (!reason.empty()) {
      return make_error(reason + " (scan line " + std::to_string(j) + " of " + std::to_string(major.size) + ")");
    }
    for (int i = 0; i < minor.size; ++i) {
      // Radiance's Y axis points up: "-Y" scan lines run from the top, "+X" texels from the left.
      int x = 0;
      int y = 0;
      if (y_major) {
        y = major.sign == '-' ? j : major.size - 1 - j;
        x = minor.sign == '+' ? i : minor.size - 1 - i;
      } else {
        x = major.sign == '+' ? j : major.size - 1 - j;
        y = minor.sign == '-' ? i : minor.size - 1 - i;
      }
      const unsigned char* t = scan.data() + 4 * static_cast<std::size_t>(i);
      const float f = scale[t[3]];  // 0 for e = 0
      float* out = image.data.data() + image.index(x, y);
      out[0] = static_cast<float>(t[0]) * f;  // value = m * 2^(e - 136)
      out[1] = static_cast<float>(t[1]) * f;
      out[2] = static_cast<float>(t[2]) * f;
    }
  }
  return image;
}

}  // namespace shadelab
