// Tests of image file I/O: round trips per format, hand-written EXR and PNG files that exercise what our
// own writer never produces (data windows, tiles, 16-bit and grey PNG), Blender's real HDR worlds, bad
// input of every kind, non-finite repair, and the atomic write.
#include "shadelab/image/image_io.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <thread>
#include <string>
#include <vector>

#include "shadelab/image/srgb.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;

// ------------------------------------------------------------------------------------------------ helpers

class ImageIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() /
            ("shadelab_image_test_" + std::to_string(::getpid()) + "_" + std::string(test->name()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }

  fs::path path(const std::string& name) const { return m_dir / name; }

  // Names of the entries in the test directory, sorted.
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(m_dir)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path m_dir;
};

// Deterministic uniform floats in [lo, hi).
class Uniform {
 public:
  explicit Uniform(std::uint32_t seed) : m_engine(seed) {}
  float operator()(float lo, float hi) {
    const double u = static_cast<double>(m_engine() >> 8) * 0x1p-24;  // 24 random bits -> [0, 1)
    return static_cast<float>(static_cast<double>(lo) + u * static_cast<double>(hi - lo));
  }
  std::uint32_t bits() { return static_cast<std::uint32_t>(m_engine()); }

 private:
  std::mt19937 m_engine;
};

Image random_image(int w, int h, std::uint32_t seed, float lo, float hi) {
  Image image(w, h);
  Uniform uniform(seed);
  for (float& v : image.data) {
    v = uniform(lo, hi);
  }
  return image;
}

void write_file(const fs::path& p, const std::vector<unsigned char>& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::vector<unsigned char> read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The failure must be an Error of one line that names the file.
template <typename T>
void expect_error_naming(const Result<T>& result, const fs::path& p) {
  ASSERT_FALSE(result.has_value()) << p;
  const std::string& message = result.error().message;
  EXPECT_NE(message.find(p.filename().string()), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

void put_u8(std::vector<unsigned char>& out, unsigned v) { out.push_back(static_cast<unsigned char>(v & 0xFFu)); }
void put_le32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) {
    put_u8(out, v >> (8 * i));
  }
}
void put_le64(std::vector<unsigned char>& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) {
    put_u8(out, static_cast<unsigned>(v >> (8 * i)));
  }
}
void put_be32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int i = 3; i >= 0; --i) {
    put_u8(out, v >> (8 * i));
  }
}
void put_f32(std::vector<unsigned char>& out, float v) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  put_le32(out, bits);
}
void put_string(std::vector<unsigned char>& out, const std::string& s) {
  out.insert(out.end(), s.begin(), s.end());
  out.push_back(0);
}

// ------------------------------------------------------------------ a minimal OpenEXR writer, for tests
//
// Uncompressed FLOAT channels, scan lines (one per chunk) or one-level tiles, any data and display window:
// the layout of the OpenEXR file format specification ("OpenEXR File Layout"), written independently of the
// library so that the reader is checked against the format rather than against itself.

struct RawExr {
  int data_window[4] = {0, 0, 0, 0};     // xmin, ymin, xmax, ymax
  int display_window[4] = {0, 0, 0, 0};  // xmin, ymin, xmax, ymax
  std::vector<std::string> channels;     // sorted, as the format requires
  int tile_size = 0;                     // 0: scan lines; otherwise square tiles of this size
  std::function<float(const std::string&, int, int)> value;  // channel, x, y -> value
};

void put_attribute(std::vector<unsigned char>& out, const std::string& name, const std::string& type,
                   const std::vector<unsigned char>& value) {
  put_string(out, name);
  put_string(out, type);
  put_le32(out, static_cast<std::uint32_t>(value.size()));
  out.insert(out.end(), value.begin(), value.end());
}

std::vector<unsigned char> box2i(const int b[4]) {
  std::vector<unsigned char> v;
  for (int i = 0; i < 4; ++i) {
    put_le32(v, static_cast<std::uint32_t>(b[i]));
  }
  return v;
}

std::vector<unsigned char> encode_raw_exr(const RawExr& exr) {
  std::vector<unsigned char> out;
  put_le32(out, 20000630);                                     // magic number
  put_le32(out, 2u | (exr.tile_size > 0 ? 0x200u : 0u));      // version 2, bit 9: single-part tiled
  std::vector<unsigned char> chlist;
  for (const std::string& c : exr.channels) {
    put_string(chlist, c);
    put_le32(chlist, 2);  // pixel type FLOAT
    put_le32(chlist, 0);  // pLinear + 3 reserved bytes
    put_le32(chlist, 1);  // xSampling
    put_le32(chlist, 1);  // ySampling
  }
  chlist.push_back(0);
  put_attribute(out, "channels", "chlist", chlist);
  put_attribute(out, "compression", "compression", {0});
  put_attribute(out, "dataWindow", "box2i", box2i(exr.data_window));
  put_attribute(out, "displayWindow", "box2i", box2i(exr.display_window));
  put_attribute(out, "lineOrder", "lineOrder", {0});
  std::vector<unsigned char> one;
  put_f32(one, 1.0f);
  put_attribute(out, "pixelAspectRatio", "float", one);
  std::vector<unsigned char> center;
  put_f32(center, 0.0f);
  put_f32(center, 0.0f);
  put_attribute(out, "screenWindowCenter", "v2f", center);
  put_attribute(out, "screenWindowWidth", "float", one);
  if (exr.tile_size > 0) {
    std::vector<unsigned char> tiles;
    put_le32(tiles, static_cast<std::uint32_t>(exr.tile_size));
    put_le32(tiles, static_cast<std::uint32_t>(exr.tile_size));
    tiles.push_back(0);  // ONE_LEVEL, round down
    put_attribute(out, "tiles", "tiledesc", tiles);
  }
  out.push_back(0);  // end of header

  const int x0 = exr.data_window[0];
  const int y0 = exr.data_window[1];
  const int x1 = exr.data_window[2];
  const int y1 = exr.data_window[3];
  // Chunks: (tile or scan line) rectangles in file order, each with its coordinates header.
  struct Chunk {
    std::vector<int> coordinates;
    int cx0, cy0, cx1, cy1;
  };
  std::vector<Chunk> chunks;
  if (exr.tile_size > 0) {
    const int t = exr.tile_size;
    for (int ty = 0; y0 + ty * t <= y1; ++ty) {
      for (int tx = 0; x0 + tx * t <= x1; ++tx) {
        chunks.push_back({{tx, ty, 0, 0}, x0 + tx * t, y0 + ty * t, std::min(x1, x0 + tx * t + t - 1),
                          std::min(y1, y0 + ty * t + t - 1)});
      }
    }
  } else {
    for (int y = y0; y <= y1; ++y) {
      chunks.push_back({{y}, x0, y, x1, y});
    }
  }
  const std::size_t table_at = out.size();
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    put_le64(out, 0);  // patched below
  }
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    const std::uint64_t offset = out.size();
    for (int b = 0; b < 8; ++b) {
      out[table_at + 8 * i + static_cast<std::size_t>(b)] = static_cast<unsigned char>(offset >> (8 * b));
    }
    const Chunk& c = chunks[i];
    for (int v : c.coordinates) {
      put_le32(out, static_cast<std::uint32_t>(v));
    }
    std::vector<unsigned char> pixels;  // per scan line: per channel: the line's samples
    for (int y = c.cy0; y <= c.cy1; ++y) {
      for (const std::string& name : exr.channels) {
        for (int x = c.cx0; x <= c.cx1; ++x) {
          put_f32(pixels, exr.value(name, x, y));
        }
      }
    }
    put_le32(out, static_cast<std::uint32_t>(pixels.size()));
    out.insert(out.end(), pixels.begin(), pixels.end());
  }
  return out;
}

// A value that identifies channel and position: R -> 1000 + ..., G -> 2000 + ..., B -> 3000 + ...
float channel_value(const std::string& name, int x, int y) {
  const float base = name == "R" ? 1000.0f : name == "G" ? 2000.0f : name == "B" ? 3000.0f : 4000.0f;
  return base + static_cast<float>(x) + 0.25f * static_cast<float>(y);
}

// ------------------------------------------------------------------- a minimal PNG writer, for tests
//
// Stored (uncompressed) deflate blocks; any bit depth 8 or 16 and colour type 0, 2, 4, 6. stb_image_write
// writes only 8-bit RGB(A), so 16-bit and grey files are made here (PNG specification, ISO/IEC 15948).

std::uint32_t crc32(const unsigned char* data, std::size_t n) {
  std::uint32_t crc = 0xFFFFFFFFu;  // CRC-32 of the PNG specification, annex D, bit by bit
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) {
      crc = (crc & 1u) != 0 ? 0xEDB88320u ^ (crc >> 1) : crc >> 1;
    }
  }
  return crc ^ 0xFFFFFFFFu;
}

void put_png_chunk(std::vector<unsigned char>& out, const char* type, const std::vector<unsigned char>& data) {
  put_be32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_be32(out, crc32(out.data() + start, out.size() - start));
}

// samples: rows top to bottom, channel-interleaved, each sample < 2^bit_depth.
std::vector<unsigned char> encode_raw_png(int w, int h, int bit_depth, int colour_type,
                                          const std::vector<std::uint16_t>& samples) {
  const int channels = colour_type == 0 ? 1 : colour_type == 2 ? 3 : colour_type == 4 ? 2 : 4;
  std::vector<unsigned char> raw;  // filter byte 0 (None) then the row's big-endian samples
  std::size_t s = 0;
  for (int y = 0; y < h; ++y) {
    raw.push_back(0);
    for (int i = 0; i < w * channels; ++i, ++s) {
      if (bit_depth == 16) {
        put_u8(raw, samples[s] >> 8u);
      }
      put_u8(raw, samples[s]);
    }
  }
  std::vector<unsigned char> zlib = {0x78, 0x01};  // deflate, 32 KiB window, no dictionary
  for (std::size_t at = 0; at < raw.size() || at == 0;) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    zlib.push_back(at + n == raw.size() ? 1 : 0);  // BFINAL, BTYPE = 00 (stored)
    put_u8(zlib, static_cast<unsigned>(n));
    put_u8(zlib, static_cast<unsigned>(n >> 8));
    put_u8(zlib, static_cast<unsigned>(~n));
    put_u8(zlib, static_cast<unsigned>(~n >> 8));
    zlib.insert(zlib.end(), raw.begin() + static_cast<std::ptrdiff_t>(at),
                raw.begin() + static_cast<std::ptrdiff_t>(at + n));
    at += n;
    if (n == 0) {
      break;
    }
  }
  std::uint32_t a = 1;  // Adler-32 (RFC 1950)
  std::uint32_t b = 0;
  for (unsigned char c : raw) {
    a = (a + c) % 65521u;
    b = (b + a) % 65521u;
  }
  put_be32(zlib, (b << 16) | a);

  std::vector<unsigned char> out = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  std::vector<unsigned char> ihdr;
  put_be32(ihdr, static_cast<std::uint32_t>(w));
  put_be32(ihdr, static_cast<std::uint32_t>(h));
  ihdr.push_back(static_cast<unsigned char>(bit_depth));
  ihdr.push_back(static_cast<unsigned char>(colour_type));
  ihdr.push_back(0);  // deflate
  ihdr.push_back(0);  // adaptive filtering
  ihdr.push_back(0);  // no interlace
  put_png_chunk(out, "IHDR", ihdr);
  put_png_chunk(out, "IDAT", zlib);
  put_png_chunk(out, "IEND", {});
  return out;
}

// ------------------------------------------------------------------------------------------ round trips

TEST_F(ImageIo, ExrFloatRoundTripIsExactForEveryCompression) {
  // Odd sizes cross the 16-line ZIP and 32-line PIZ blocks; values span signs and 60 orders of magnitude.
  Image image = random_image(37, 23, 1, -4.0f, 4.0f);
  Uniform uniform(2);
  for (float& v : image.data) {
    v = std::ldexp(v, static_cast<int>(uniform(-100.0f, 100.0f)));
  }
  image.data[0] = std::numeric_limits<float>::denorm_min();
  image.data[1] = std::numeric_limits<float>::max();
  image.data[2] = -0.0f;
  for (ExrCompression c : {ExrCompression::none, ExrCompression::rle, ExrCompression::zips, ExrCompression::zip,
                           ExrCompression::piz}) {
    const fs::path p = path("float_" + std::to_string(static_cast<int>(c)) + ".exr");
    WriteOptions options;
    options.exr_compression = c;
    ASSERT_TRUE(write_image(image, p, options)) << p;
    ReadInfo info;
    const Result<Image> back = read_image(p, &info);
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(back->width, 37);
    EXPECT_EQ(back->height, 23);
    EXPECT_EQ(info.format, "exr");
    EXPECT_EQ(info.sample_type, "float");
    EXPECT_EQ(info.channels, 3);
    EXPECT_EQ(info.nonfinite_repaired, 0);
    ASSERT_EQ(back->data.size(), image.data.size());
    EXPECT_EQ(std::memcmp(back->data.data(), image.data.data(), image.data.size() * sizeof(float)), 0)
        << "compression " << static_cast<int>(c);
  }
}

TEST_F(ImageIo, ExrHalfRoundTripIsWithinHalfPrecision) {
  Image image = random_image(64, 33, 3, -1000.0f, 1000.0f);
  image.data[0] = 1e-6f;     // a half subnormal (below 2^-14)
  image.data[1] = 1e6f;      // beyond the half range: clamped to 65504
  image.data[2] = -70000.0f;
  for (ExrCompression c : {ExrCompression::zip, ExrCompression::piz}) {
    WriteOptions options;
    options.exr_pixel_type = ExrPixelType::half;
    options.exr_compression = c;
    const fs::path p = path("half.exr");
    ASSERT_TRUE(write_image(image, p, options));
    ReadInfo info;
    const Result<Image> back = read_image(p, &info);
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(info.sample_type, "half");
    EXPECT_NEAR(back->data[0], 1e-6f, 0x1p-25);    // half subnormal spacing 2^-24, rounding error 2^-25
    EXPECT_EQ(back->data[1], 65504.0f);
    EXPECT_EQ(back->data[2], -65504.0f);
    double worst = 0.0;
    for (std::size_t i = 3; i < image.data.size(); ++i) {
      const double v = static_cast<double>(image.data[i]);
      const double r = static_cast<double>(back->data[i]);
      // Round to nearest with a 10-bit mantissa: relative error at most 2^-11 for normal halves.
      const double bound = std::max(std::abs(v) * 0x1p-11, 0x1p-25);
      ASSERT_LE(std::abs(r - v), bound) << "value " << v << " read " << r;
      worst = std::max(worst, std::abs(r - v) / std::max(std::abs(v), 1e-30));
    }
    EXPECT_GT(worst, 0x1p-13);  // it really is half, not float
  }
}

TEST_F(ImageIo, HdrRoundTripIsWithinRgbePrecision) {
  Image image = random_image(45, 19, 4, 0.0f, 1.0f);
  Uniform uniform(5);
  for (float& v : image.data) {
    v = std::ldexp(v, static_cast<int>(uniform(-20.0f, 20.0f)));
  }
  for (const char* name : {"a.hdr", "b.pic"}) {
    const fs::path p = path(name);
    ASSERT_TRUE(write_image(image, p));
    ReadInfo info;
    const Result<Image> back = read_image(p, &info);
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(info.format, "hdr");
    EXPECT_EQ(info.sample_type, "rgbe");
    ASSERT_EQ(back->width, 45);
    ASSERT_EQ(back->height, 19);
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const Rgb v = image.at(x, y);
        const Rgb r = back->at(x, y);
        // RGBE: an 8-bit mantissa per channel with the exponent of the largest channel; encoding truncates,
        // so each channel is off by less than 2^-7 of the largest (about 0.8%).
        const double bound = v.max_component() * 0x1p-7;
        for (int c = 0; c < 3; ++c) {
          ASSERT_LE(std::abs(r[c] - v[c]), bound) << x << "," << y << " channel " << c;
        }
        ASSERT_LE(std::abs(r.max_component() - v.max_component()), v.max_component() * 0.01);
      }
    }
  }
}

TEST_F(ImageIo, HdrWritesNegativeAndNonFiniteAsZero) {
  Image image(2, 1);
  image.set(0, 0, {-1.0, std::nan(""), 0.5});
  image.set(1, 0, {INFINITY, 2.0, -INFINITY});
  const fs::path p = path("clean.hdr");
  ASSERT_TRUE(write_image(image, p));
  const Result<Image> back = read_image(p);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->at(0, 0).r, 0.0);
  EXPECT_EQ(back->at(0, 0).g, 0.0);
  EXPECT_NEAR(back->at(0, 0).b, 0.5, 0.5 / 128);
  EXPECT_EQ(back->at(1, 0).r, 0.0);
  EXPECT_NEAR(back->at(1, 0).g, 2.0, 2.0 / 128);
  EXPECT_EQ(back->at(1, 0).b, 0.0);
}

TEST_F(ImageIo, PngRoundTripIsWithinHalfACodeInSrgb) {
  const Image image = random_image(50, 31, 6, 0.0f, 1.0f);
  const fs::path p = path("rt.png");
  ASSERT_TRUE(write_image(image, p));
  ReadInfo info;
  const Result<Image> back = read_image(p, &info);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(info.format, "png");
  EXPECT_EQ(info.sample_type, "uint8");
  EXPECT_EQ(info.channels, 3);
  ASSERT_EQ(back->data.size(), image.data.size());
  for (std::size_t i = 0; i < image.data.size(); ++i) {
    const double written = linear_to_srgb(static_cast<double>(image.data[i]));
    const double read = linear_to_srgb(static_cast<double>(back->data[i]));
    // Rounding to the nearest code: at most half a code, i.e. well within the 1/255 asked for.
    ASSERT_LE(std::abs(read - written), 0.5 / 255.0 + 1e-6) << "float " << i;
  }
}

TEST_F(ImageIo, PngExposureClampAndNonFinite) {
  Image image(6, 1);
  image.set(0, 0, Rgb::gray(0.25));
  image.set(1, 0, Rgb::gray(2.0));
  image.set(2, 0, Rgb::gray(-1.0));
  image.set(3, 0, {std::nan(""), INFINITY, -INFINITY});
  image.set(4, 0, Rgb::gray(0.0625));
  image.set(5, 0, Rgb::gray(0.001));
  const fs::path p = path("exposure.png");
  WriteOptions options;
  options.exposure = 1.0;  // x2
  ASSERT_TRUE(write_image(image, p, options));
  const Result<Image> back = read_image(p);
  ASSERT_TRUE(back) << back.error().message;
  const auto code_of = [](double linear) { return static_cast<double>(linear_to_srgb8(linear)); };
  EXPECT_EQ(code_of(back->at(0, 0).r), code_of(0.5));
  EXPECT_EQ(back->at(1, 0).r, 1.0);
  EXPECT_EQ(back->at(2, 0).r, 0.0);
  EXPECT_EQ(back->at(3, 0).r, 0.0);  // NaN
  EXPECT_EQ(back->at(3, 0).g, 1.0);  // +Inf clamps to 1
  EXPECT_EQ(back->at(3, 0).b, 0.0);  // -Inf clamps to 0
  EXPECT_EQ(code_of(back->at(4, 0).r), code_of(0.125));
  EXPECT_EQ(code_of(back->at(5, 0).r), code_of(0.002));  // on the linear segment: code round(255*12.92*0.002) = 7
  EXPECT_EQ(linear_to_srgb8(back->at(5, 0).r), 7);

  options.exposure = std::nan("");
  expect_error_naming(write_image(image, path("bad_exposure.png"), options), path("bad_exposure.png"));
}

TEST_F(ImageIo, ExtensionsAreCaseInsensitive) {
  const Image image = random_image(5, 4, 7, 0.0f, 1.0f);
  for (const char* name : {"a.EXR", "b.Hdr", "c.PNG", "d.PiC"}) {
    ASSERT_TRUE(write_image(image, path(name))) << name;
    const Result<Image> back = read_image(path(name));
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(back->width, 5);
    EXPECT_EQ(back->height, 4);
  }
}

// ------------------------------------------------------------------------- EXR layout (hand-written files)

TEST_F(ImageIo, ExrDataWindowInsideTheDisplayWindow) {
  RawExr exr;
  exr.display_window[2] = 7;  // 8 x 6
  exr.display_window[3] = 5;
  exr.data_window[0] = 2;  // data (2,1)-(5,3)
  exr.data_window[1] = 1;
  exr.data_window[2] = 5;
  exr.data_window[3] = 3;
  exr.channels = {"B", "G", "R"};
  exr.value = channel_value;
  const fs::path p = path("window.exr");
  write_file(p, encode_raw_exr(exr));
  ReadInfo info;
  const Result<Image> image = read_image(p, &info);
  ASSERT_TRUE(image) << image.error().message;
  ASSERT_EQ(image->width, 8);
  ASSERT_EQ(image->height, 6);
  EXPECT_TRUE(info.partial_data_window);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 8; ++x) {
      const bool inside = x >= 2 && x <= 5 && y >= 1 && y <= 3;
      const Rgb c = image->at(x, y);
      EXPECT_EQ(c.r, inside ? static_cast<double>(channel_value("R", x, y)) : 0.0) << x << "," << y;
      EXPECT_EQ(c.g, inside ? static_cast<double>(channel_value("G", x, y)) : 0.0) << x << "," << y;
      EXPECT_EQ(c.b, inside ? static_cast<double>(channel_value("B", x, y)) : 0.0) << x << "," << y;
    }
  }
}

TEST_F(ImageIo, ExrDataWindowBeyondTheDisplayWindowIsCropped) {
  RawExr exr;
  const int display[4] = {-3, 10, 4, 14};  // 8 x 5, at a negative x and positive y origin
  const int data[4] = {-5, 8, 6, 15};      // overscan on every side
  std::copy(display, display + 4, exr.display_window);
  std::copy(data, data + 4, exr.data_window);
  exr.channels = {"B", "G", "R"};
  exr.value = channel_value;
  const fs::path p = path("overscan.exr");
  write_file(p, encode_raw_exr(exr));
  const Result<Image> image = read_image(p);
  ASSERT_TRUE(image) << image.error().message;
  ASSERT_EQ(image->width, 8);
  ASSERT_EQ(image->height, 5);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 8; ++x) {
      EXPECT_EQ(image->at(x, y).r, static_cast<double>(channel_value("R", x - 3, y + 10)));
      EXPECT_EQ(image->at(x, y).b, static_cast<double>(channel_value("B", x - 3, y + 10)));
    }
  }
}

TEST_F(ImageIo, ExrTiledWithAlpha) {
  RawExr exr;
  const int window[4] = {0, 0, 9, 6};  // 10 x 7 in 4 x 4 tiles: partial tiles on the right and bottom
  std::copy(window, window + 4, exr.display_window);
  std::copy(window, window + 4, exr.data_window);
  exr.channels = {"A", "B", "G", "R"};
  exr.tile_size = 4;
  exr.value = channel_value;
  const fs::path p = path("tiled.exr");
  write_file(p, encode_raw_exr(exr));
  ReadInfo info;
  const Result<Image> image = read_image(p, &info);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_TRUE(info.had_alpha);
  EXPECT_EQ(info.channels, 4);
  EXPECT_FALSE(info.partial_data_window);
  ASSERT_EQ(image->width, 10);
  ASSERT_EQ(image->height, 7);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 10; ++x) {
      EXPECT_EQ(image->at(x, y).r, static_cast<double>(channel_value("R", x, y)));
      EXPECT_EQ(image->at(x, y).g, static_cast<double>(channel_value("G", x, y)));
      EXPECT_EQ(image->at(x, y).b, static_cast<double>(channel_value("B", x, y)));
    }
  }
}

TEST_F(ImageIo, ExrLuminanceOnlyBecomesGrey) {
  RawExr exr;
  const int window[4] = {0, 0, 4, 2};
  std::copy(window, window + 4, exr.display_window);
  std::copy(window, window + 4, exr.data_window);
  exr.channels = {"Y"};
  exr.value = [](const std::string&, int x, int y) { return 0.5f + static_cast<float>(x * 10 + y); };
  const fs::path p = path("grey.exr");
  write_file(p, encode_raw_exr(exr));
  ReadInfo info;
  const Result<Image> image = read_image(p, &info);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_TRUE(info.grey);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      const double v = 0.5 + x * 10 + y;
      EXPECT_EQ(image->at(x, y).r, v);
      EXPECT_EQ(image->at(x, y).g, v);
      EXPECT_EQ(image->at(x, y).b, v);
    }
  }
}

TEST_F(ImageIo, ExrWithoutColourChannelsOrTooLargeIsAnError) {
  RawExr exr;
  exr.display_window[2] = exr.data_window[2] = 3;
  exr.display_window[3] = exr.data_window[3] = 3;
  exr.channels = {"Z"};
  exr.value = channel_value;
  const fs::path depth = path("depth.exr");
  write_file(depth, encode_raw_exr(exr));
  const Result<Image> image = read_image(depth);
  expect_error_naming(image, depth);
  EXPECT_NE(image.error().message.find("channels: Z"), std::string::npos) << image.error().message;

  // A 100001^2 display window around one pixel of data: refused before anything is allocated.
  exr.channels = {"R"};
  exr.display_window[2] = exr.display_window[3] = 100000;
  exr.data_window[2] = exr.data_window[3] = 0;
  const fs::path huge = path("huge.exr");
  write_file(huge, encode_raw_exr(exr));
  const Result<Image> big = read_image(huge);
  expect_error_naming(big, huge);
  EXPECT_NE(big.error().message.find("too large"), std::string::npos) << big.error().message;
}

// ------------------------------------------------------------------------- PNG decoding (hand-written files)

TEST_F(ImageIo, Png16BitRgbDecodesTheExactCurve) {
  const int w = 7;
  const int h = 3;
  std::vector<std::uint16_t> samples(static_cast<std::size_t>(w * h * 3));
  Uniform uniform(8);
  for (auto& s : samples) {
    s = static_cast<std::uint16_t>(uniform.bits() & 0xFFFFu);
  }
  samples[0] = 0;
  samples[1] = 65535;
  samples[2] = 2651;  // 2651 / 65535 = 0.04045: the breakpoint
  const fs::path p = path("rgb16.png");
  write_file(p, encode_raw_png(w, h, 16, 2, samples));
  ReadInfo info;
  const Result<Image> image = read_image(p, &info);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(info.sample_type, "uint16");
  EXPECT_EQ(info.channels, 3);
  ASSERT_EQ(image->width, w);
  ASSERT_EQ(image->height, h);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    ASSERT_EQ(image->data[i], static_cast<float>(srgb_to_linear(samples[i] / 65535.0))) << "sample " << i;
  }
}

TEST_F(ImageIo, PngGreyAndAlphaBecomeRgbWithAlphaDropped) {
  // 8-bit grey, 8-bit grey + alpha, 16-bit grey + alpha, 8-bit RGBA; alpha 0 must not darken the colour.
  struct Case {
    int bit_depth;
    int colour_type;
    int channels;
  };
  for (const Case c : {Case{8, 0, 1}, Case{8, 4, 2}, Case{16, 4, 2}, Case{8, 6, 4}}) {
    const int w = 4;
    const int h = 2;
    std::vector<std::uint16_t> samples;
    const int max_code = (1 << c.bit_depth) - 1;
    for (int i = 0; i < w * h; ++i) {
      for (int k = 0; k < c.channels; ++k) {
        const bool alpha = (c.channels == 2 && k == 1) || (c.channels == 4 && k == 3);
        samples.push_back(static_cast<std::uint16_t>(alpha ? 0 : (i * 37 + k * 11) * max_code / 300));
      }
    }
    const fs::path p = path("grey_" + std::to_string(c.bit_depth) + "_" + std::to_string(c.colour_type) + ".png");
    write_file(p, encode_raw_png(w, h, c.bit_depth, c.colour_type, samples));
    ReadInfo info;
    const Result<Image> image = read_image(p, &info);
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_EQ(info.channels, c.channels);
    EXPECT_EQ(info.had_alpha, c.channels == 2 || c.channels == 4);
    EXPECT_EQ(info.grey, c.channels <= 2);
    for (int i = 0; i < w * h; ++i) {
      const std::size_t s = static_cast<std::size_t>(i * c.channels);
      for (int k = 0; k < 3; ++k) {
        const std::uint16_t code = samples[s + (c.channels <= 2 ? 0u : static_cast<std::size_t>(k))];
        EXPECT_EQ(image->data[static_cast<std::size_t>(3 * i + k)],
                  static_cast<float>(srgb_to_linear(code / static_cast<double>(max_code))))
            << p << " pixel " << i << " channel " << k;
      }
    }
  }
}

TEST_F(ImageIo, RowZeroIsTheTopRowOfTheFile) {
  // Row 0 of a hand-written PNG is its first row; our PNG and EXR writers keep it first.
  const std::vector<std::uint16_t> samples = {255, 0};  // 1 x 2 grey: white on top of black
  const fs::path p = path("top.png");
  write_file(p, encode_raw_png(1, 2, 8, 0, samples));
  const Result<Image> image = read_image(p);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->at(0, 0).r, 1.0);
  EXPECT_EQ(image->at(0, 1).r, 0.0);
  for (const char* name : {"top.exr", "top.hdr"}) {
    ASSERT_TRUE(write_image(*image, path(name)));
    const Result<Image> back = read_image(path(name));
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(back->at(0, 0).r, 1.0) << name;
    EXPECT_EQ(back->at(0, 1).r, 0.0) << name;
  }
}

// ------------------------------------------------------------------------------------- Blender's worlds

TEST(ImageIoBlender, EveryWorldLoads) {
  // Sizes and means (over all pixels and the three channels) measured with this reader on Debian 12's
  // blender-data; a reader that mishandles windows, channels or compression cannot match them. The means
  // are pinned to 1e-5 relative (they are printed to 6 decimals).
  struct Expected {
    int width;
    int height;
    double mean;
  };
  const std::map<std::string, Expected> expected = {
      {"city.exr", {1024, 512, 1.047794}},      {"courtyard.exr", {1024, 512, 0.557858}},
      {"forest.exr", {1024, 512, 0.561491}},    {"interior.exr", {1024, 512, 0.950692}},
      {"night.exr", {1024, 512, 0.131402}},     {"studio.exr", {1024, 512, 0.256111}},
      {"sunrise.exr", {1024, 512, 0.468848}},   {"sunset.exr", {1024, 512, 0.464407}},
  };
  const fs::path dir = SHADELAB_BLENDER_WORLDS;
  ASSERT_TRUE(fs::is_directory(dir)) << dir << " is missing: install blender-data (scripts/setup.sh)";
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".exr") {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 8u);
  int checked = 0;
  for (const fs::path& file : files) {
    const auto start = std::chrono::steady_clock::now();
    ReadInfo info;
    const Result<Image> image = read_image(file, &info);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_GT(image->width, 0);
    EXPECT_GT(image->height, 0);
    double sum[3] = {0.0, 0.0, 0.0};
    double max = 0.0;
    for (std::size_t i = 0; i < image->data.size(); ++i) {
      const double v = static_cast<double>(image->data[i]);
      ASSERT_TRUE(std::isfinite(v)) << file;
      sum[i % 3] += v;
      max = std::max(max, v);
    }
    const double n = static_cast<double>(image->pixel_count());
    const double mean = (sum[0] + sum[1] + sum[2]) / (3.0 * n);
    std::printf("[ world    ] %-14s %5d x %-5d %-5s %d ch  mean %.6f (R %.6f G %.6f B %.6f)  max %10.3f  "
                "repaired %d negative %d  read %.1f ms\n",
                file.filename().string().c_str(), image->width, image->height, info.sample_type.c_str(),
                info.channels, mean, sum[0] / n, sum[1] / n, sum[2] / n, max, info.nonfinite_repaired,
                info.negative_values, ms);
    // Their negative values (DWAB noise) are within radiance_negative_tolerance: every command that reads an
    // environment takes them (issue 40).
    EXPECT_TRUE(check_radiance(file, *image, info)) << check_radiance(file, *image, info).error().message;
    const auto it = expected.find(file.filename().string());
    if (it != expected.end()) {
      EXPECT_EQ(image->width, it->second.width) << file;
      EXPECT_EQ(image->height, it->second.height) << file;
      EXPECT_NEAR(mean, it->second.mean, 1e-5 * it->second.mean) << file;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 8) << "all eight worlds of blender-data should be present";
}

// ------------------------------------------------------------------------------------------- bad input

TEST_F(ImageIo, MissingFile) {
  for (const char* name : {"missing.exr", "missing.hdr", "missing.png"}) {
    const Result<Image> image = read_image(path(name));
    expect_error_naming(image, path(name));
    EXPECT_NE(image.error().message.find("no such file"), std::string::npos) << image.error().message;
  }
}

TEST_F(ImageIo, EmptyFile) {
  for (const char* name : {"empty.exr", "empty.hdr", "empty.png"}) {
    write_file(path(name), {});
    const Result<Image> image = read_image(path(name));
    expect_error_naming(image, path(name));
    EXPECT_NE(image.error().message.find("empty"), std::string::npos) << image.error().message;
  }
}

TEST_F(ImageIo, UnknownExtension) {
  const Image image(2, 2);
  for (const char* name : {"photo.jpg", "notes.txt", "no_extension", "archive.exr.gz"}) {
    write_file(path(name), {1, 2, 3});
    const Result<Image> read = read_image(path(name));
    expect_error_naming(read, path(name));
    EXPECT_NE(read.error().message.find("extension"), std::string::npos) << read.error().message;
    expect_error_naming(write_image(image, path(std::string("out_") + name)), path(std::string("out_") + name));
  }
}

TEST_F(ImageIo, TruncatedFilesAreErrors) {
  const Image image = random_image(64, 48, 9, 0.0f, 8.0f);
  struct Case {
    const char* name;
    ExrCompression compression;
  };
  for (const Case c : {Case{"t_none.exr", ExrCompression::none}, Case{"t_zip.exr", ExrCompression::zip},
                       Case{"t_piz.exr", ExrCompression::piz}, Case{"t.hdr", ExrCompression::zip},
                       Case{"t.png", ExrCompression::zip}}) {
    WriteOptions options;
    options.exr_compression = c.compression;
    const fs::path full = path(std::string("full_") + c.name);
    ASSERT_TRUE(write_image(image, full, options));
    ASSERT_TRUE(read_image(full));
    const std::vector<unsigned char> bytes = read_file(full);
    // Cut inside the header, in the offset table, at half, and one byte short of the end.
    for (const std::size_t keep : {std::size_t{20}, std::size_t{400}, bytes.size() / 2, bytes.size() - 1}) {
      const fs::path cut = path(std::to_string(keep) + "_" + c.name);
      write_file(cut, std::vector<unsigned char>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(keep)));
      const Result<Image> read = read_image(cut);
      expect_error_naming(read, cut);
    }
  }
}

TEST_F(ImageIo, RandomBytesAreErrors) {
  Uniform uniform(10);
  std::vector<unsigned char> noise(4096);
  for (auto& b : noise) {
    b = static_cast<unsigned char>(uniform.bits() & 0xFFu);
  }
  for (const char* name : {"noise.exr", "noise.hdr", "noise.png", "noise.pic"}) {
    write_file(path(name), noise);
    expect_error_naming(read_image(path(name)), path(name));
  }
  // The right signature followed by noise reaches the decoders themselves.
  const std::vector<std::vector<unsigned char>> signatures = {
      {0x76, 0x2f, 0x31, 0x01, 0x02, 0x00, 0x00, 0x00},
      {'#', '?', 'R', 'A', 'D', 'I', 'A', 'N', 'C', 'E', '\n'},
      {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A}};
  const char* names[3] = {"signed.exr", "signed.hdr", "signed.png"};
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::uint32_t seed = 0; seed < 20; ++seed) {
      Uniform u(100 + seed);
      std::vector<unsigned char> bytes = signatures[i];
      for (int k = 0; k < 2048; ++k) {
        bytes.push_back(static_cast<unsigned char>(u.bits() & 0xFFu));
      }
      write_file(path(names[i]), bytes);
      expect_error_naming(read_image(path(names[i])), path(names[i]));
    }
  }
  // A valid PNG named .exr, a valid EXR named .png: the content must match the extension.
  ASSERT_TRUE(write_image(Image(3, 3), path("real.png")));
  ASSERT_TRUE(write_image(Image(3, 3), path("real.exr")));
  fs::copy_file(path("real.png"), path("png_inside.exr"));
  fs::copy_file(path("real.exr"), path("exr_inside.png"));
  expect_error_naming(read_image(path("png_inside.exr")), path("png_inside.exr"));
  expect_error_naming(read_image(path("exr_inside.png")), path("exr_inside.png"));
}

TEST_F(ImageIo, NonFiniteTexelsAreRepairedAndCounted) {
  for (const ExrPixelType type : {ExrPixelType::float32, ExrPixelType::half}) {
    Image image = random_image(8, 4, 11, 0.0f, 1.0f);
    image.set(1, 1, {std::nan(""), 0.5, INFINITY});
    image.set(7, 3, {-INFINITY, -0.5, 0.25});
    const fs::path p = path("nan.exr");
    WriteOptions options;
    options.exr_pixel_type = type;
    ASSERT_TRUE(write_image(image, p, options));
    ReadInfo info;
    const Result<Image> back = read_image(p, &info);
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(info.nonfinite_repaired, 3);
    EXPECT_EQ(info.negative_values, 1);
    EXPECT_EQ(back->at(1, 1).r, 0.0);
    EXPECT_EQ(back->at(1, 1).g, 0.5);
    EXPECT_EQ(back->at(1, 1).b, 0.0);
    EXPECT_EQ(back->at(7, 3).r, 0.0);
    EXPECT_EQ(back->at(7, 3).g, -0.5);  // negative values are kept
    for (float v : back->data) {
      ASSERT_TRUE(std::isfinite(v));
    }
    // The first of each, as stored (issue 40): NaN at (1, 1) R, the negative at (7, 3) G.
    EXPECT_EQ(info.first_nonfinite.x, 1);
    EXPECT_EQ(info.first_nonfinite.y, 1);
    EXPECT_EQ(info.first_nonfinite.channel, 0);
    EXPECT_TRUE(std::isnan(info.first_nonfinite.value));
    EXPECT_EQ(info.first_negative.x, 7);
    EXPECT_EQ(info.first_negative.y, 3);
    EXPECT_EQ(info.first_negative.channel, 1);
    EXPECT_EQ(info.first_negative.value, -0.5f);
  }
}

// Radiance (an environment map) is finite and not negative: read_radiance_image refuses the first texel that
// is not, naming the file, the texel and the channel (issue 40); negatives within lossy-compression noise
// (radiance_negative_tolerance of the map's mean) are kept; a clean file reads as read_image reads it.
TEST_F(ImageIo, RadianceReadsRefuseNegativeAndNonFiniteTexels) {
  Image image(8, 4);
  for (float& v : image.data) v = 0.5f;
  image.set(1, 0, {0.5, -0.02, 0.5});  // 4% of the mean: noise, kept
  image.set(6, 2, {0.5, 0.5, -0.25});
  const fs::path neg = path("negative.exr");
  ASSERT_TRUE(write_image(image, neg));
  const Result<Image> a = read_radiance_image(neg);
  ASSERT_FALSE(a);
  EXPECT_NE(a.error().message.find("negative.exr': texel (6, 2) channel B is -0.25, below -0.05 x the map's mean"),
            std::string::npos) << a.error().message;
  image.set(6, 2, {0.5, 0.5, 0.5});
  const fs::path noise = path("noise.exr");
  ASSERT_TRUE(write_image(image, noise));
  ReadInfo noise_info;
  const Result<Image> kept = read_radiance_image(noise, &noise_info);
  ASSERT_TRUE(kept) << kept.error().message;
  EXPECT_EQ(kept->at(1, 0).g, -0.02f);
  EXPECT_EQ(noise_info.negative_values, 1);
  // A map whose mean is not above 0: any negative value.
  Image dark(8, 4);
  dark.set(3, 1, {0.0, 0.0, -1e-6});
  const fs::path dark_path = path("dark.exr");
  ASSERT_TRUE(write_image(dark, dark_path));
  const Result<Image> d = read_radiance_image(dark_path);
  ASSERT_FALSE(d);
  EXPECT_NE(d.error().message.find("texel (3, 1) channel B is -1e-06"), std::string::npos) << d.error().message;
  image.set(6, 2, {0.5, -std::numeric_limits<double>::infinity(), 0.5});
  const fs::path inf = path("inf.exr");
  ASSERT_TRUE(write_image(image, inf));
  const Result<Image> b = read_radiance_image(inf);
  ASSERT_FALSE(b);
  EXPECT_NE(b.error().message.find("inf.exr': texel (6, 2) channel G is -Inf"), std::string::npos) << b.error().message;
  image.set(6, 2, {0.0, 0.0, 0.0});  // black is light
  const fs::path ok = path("ok.exr");
  ASSERT_TRUE(write_image(image, ok));
  ReadInfo info;
  const Result<Image> c = read_radiance_image(ok, &info);
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->data, read_image(ok).value().data);
  EXPECT_EQ(info.format, "exr");
}

// ------------------------------------------------------------------------------------------- atomic write

TEST_F(ImageIo, WriteIntoAMissingDirectoryFailsCleanly) {
  const Image image(4, 4);
  for (const char* name : {"a.exr", "a.hdr", "a.png"}) {
    const fs::path p = m_dir / "does_not_exist" / name;
    expect_error_naming(write_image(image, p), p);
  }
  EXPECT_TRUE(listing().empty());
}

TEST_F(ImageIo, ExistingOutputIsReplacedOnlyOnSuccess) {
  const Image first = random_image(6, 5, 12, 0.0f, 1.0f);
  const Image second = random_image(6, 5, 13, 0.0f, 1.0f);
  for (const char* name : {"out.exr", "out.hdr", "out.png"}) {
    const fs::path p = path(name);
    ASSERT_TRUE(write_image(first, p));
    const std::vector<unsigned char> first_bytes = read_file(p);
    ASSERT_TRUE(write_image(second, p));
    const std::vector<unsigned char> second_bytes = read_file(p);
    EXPECT_NE(first_bytes, second_bytes) << name;  // replaced on success

    Image wrong_size = second;
    wrong_size.data.pop_back();
    expect_error_naming(write_image(Image{}, p), p);
    expect_error_naming(write_image(Image(0, 7), p), p);
    expect_error_naming(write_image(wrong_size, p), p);
    WriteOptions bad;
    bad.exposure = INFINITY;
    expect_error_naming(write_image(second, p, bad), p);
    EXPECT_EQ(read_file(p), second_bytes) << name;  // untouched by every failure
  }
  // The target is a directory: the temporary is written, the rename fails, the temporary is removed.
  fs::create_directory(path("dir.exr"));
  expect_error_naming(write_image(first, path("dir.exr")), path("dir.exr"));
  EXPECT_TRUE(fs::is_directory(path("dir.exr")));
  EXPECT_EQ(listing(), (std::vector<std::string>{"dir.exr", "out.exr", "out.hdr", "out.png"}));
}

TEST_F(ImageIo, WriteFileAtomicallyWritesExactlyTheBytes) {
  const std::vector<char> first = {'a', 'b', '\0', 'c'};
  const std::vector<char> second(100000, 'z');
  ASSERT_TRUE(write_file_atomically(path("f.bin"), first));
  EXPECT_EQ(read_file(path("f.bin")), std::vector<unsigned char>({'a', 'b', 0, 'c'}));
  ASSERT_TRUE(write_file_atomically(path("f.bin"), second));
  EXPECT_EQ(read_file(path("f.bin")).size(), second.size());
  ASSERT_TRUE(write_file_atomically(path("empty.bin"), {}));
  EXPECT_TRUE(fs::exists(path("empty.bin")));
  EXPECT_EQ(fs::file_size(path("empty.bin")), 0u);
  const fs::path missing = m_dir / "nope" / "g.bin";
  const Result<bool> failed = write_file_atomically(missing, first);
  expect_error_naming(failed, missing);
  EXPECT_NE(failed.error().message.find("write_file_atomically"), std::string::npos) << failed.error().message;
  EXPECT_EQ(listing(), (std::vector<std::string>{"empty.bin", "f.bin"}));
}


// --------------------------------------------------------------------------- bad input that cost memory

// issue 16, 2: a 6.7 KB EXR whose display window is 16384 x 8192 made the reader allocate 1.6 GB before any
// pixel was checked. The display window alone needs 1.5 GiB of floats: over the 1 GiB budget, an error.
TEST_F(ImageIo, ExrDisplayWindowBeyondTheMemoryBudgetIsAnError) {
  RawExr exr;
  exr.channels = {"R"};
  exr.display_window[2] = 16383;
  exr.display_window[3] = 8191;
  exr.value = channel_value;  // data window: the one pixel (0, 0)
  const fs::path p = path("wide.exr");
  write_file(p, encode_raw_exr(exr));
  ASSERT_LT(fs::file_size(p), 1000u);
  const Result<Image> image = read_image(p);
  expect_error_naming(image, p);
  EXPECT_NE(image.error().message.find("memory budget"), std::string::npos) << image.error().message;
  // The budget is stated in one place and the check agrees with it.
  EXPECT_LT(image_read_budget_bytes, 16384ULL * 8192ULL * 12ULL);
}

// The buffers follow the data window: a data window wider than the display window (overscan) is read in
// strips of the overlapping rows. 8192 x 300 data around a 4096 x 200 display: two strips of 16 MiB.
TEST_F(ImageIo, ExrOverscanIsReadInStripsOfTheOverlap) {
  RawExr exr;
  exr.channels = {"R"};
  const int display[4] = {0, 0, 4095, 199};
  const int data[4] = {-2048, -50, 6143, 249};
  std::copy(display, display + 4, exr.display_window);
  std::copy(data, data + 4, exr.data_window);
  exr.value = [](const std::string&, int x, int y) { return static_cast<float>(x) + 10000.0f * static_cast<float>(y); };
  const fs::path p = path("overscan_strips.exr");
  write_file(p, encode_raw_exr(exr));
  const Result<Image> image = read_image(p);
  ASSERT_TRUE(image) << image.error().message;
  ASSERT_EQ(image->width, 4096);
  ASSERT_EQ(image->height, 200);
  int wrong = 0;
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 4096; ++x) {
      wrong += image->at(x, y).r == static_cast<double>(static_cast<float>(x) + 10000.0f * static_cast<float>(y)) ? 0 : 1;
      wrong += image->at(x, y).g == 0.0 ? 0 : 1;
    }
  }
  EXPECT_EQ(wrong, 0);
}

// A data window that misses the display window entirely: a black image, nothing read.
TEST_F(ImageIo, ExrDataWindowOutsideTheDisplayWindowIsBlack) {
  RawExr exr;
  exr.channels = {"G"};
  const int display[4] = {0, 0, 15, 7};
  const int data[4] = {100, 100, 101, 101};
  std::copy(display, display + 4, exr.display_window);
  std::copy(data, data + 4, exr.data_window);
  exr.value = channel_value;
  const fs::path p = path("outside.exr");
  write_file(p, encode_raw_exr(exr));
  const Result<Image> image = read_image(p);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(*std::max_element(image->data.begin(), image->data.end()), 0.0f);
}

// A palette PNG (colour type 3) with its indices, one byte each.
std::vector<unsigned char> encode_palette_png(int w, int h, const std::vector<unsigned char>& indices,
                                              const std::vector<unsigned char>& palette_rgb) {
  std::vector<std::uint16_t> samples(indices.begin(), indices.end());
  // encode_raw_png's grey 8-bit layout is the palette layout (one byte per pixel): patch the colour type
  // and add PLTE before IDAT.
  std::vector<unsigned char> grey = encode_raw_png(w, h, 8, 0, samples);
  std::vector<unsigned char> out(grey.begin(), grey.begin() + 8);
  std::vector<unsigned char> ihdr(grey.begin() + 16, grey.begin() + 29);
  ihdr[9] = 3;
  put_png_chunk(out, "IHDR", ihdr);
  put_png_chunk(out, "PLTE", palette_rgb);
  out.insert(out.end(), grey.begin() + 33, grey.end());  // IDAT and IEND as they were
  return out;
}

// issue 16, 3: a palette PNG whose pixels index past its PLTE read uninitialised palette entries (valgrind),
// so the image differed from run to run. Such a file is an error; one that stays inside its palette decodes.
TEST_F(ImageIo, PngPaletteIndexPastThePaletteIsAnError) {
  const std::vector<unsigned char> palette = {255, 0, 0, 0, 255, 0};  // two entries: red, green
  const fs::path good = path("palette_ok.png");
  write_file(good, encode_palette_png(3, 2, {0, 1, 0, 1, 1, 0}, palette));
  const Result<Image> ok = read_image(good);
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_EQ(ok->at(0, 0).r, 1.0);
  EXPECT_EQ(ok->at(1, 0).g, 1.0);
  EXPECT_EQ(ok->at(1, 0).r, 0.0);

  const fs::path bad = path("palette_past.png");
  write_file(bad, encode_palette_png(3, 2, {0, 1, 0, 1, 200, 0}, palette));
  const Result<Image> image = read_image(bad);
  expect_error_naming(image, bad);
  EXPECT_NE(image.error().message.find("palette entry 200"), std::string::npos) << image.error().message;
}

// issue 16, 4: kill -9 during a write left ".x.exr.tmp-*" behind. The next write beside it removes
// temporaries of our naming whose process is gone, and leaves those of live processes and other files alone.
// Issue 40, 7: those of other targets too (".y.exr.tmp-DEADPID-..."): no later run wrote y.exr, so before
// output sets nothing ever removed them; every write now settles its whole folder under the folder's lock.
TEST_F(ImageIo, StaleTemporariesOfDeadProcessesAreRemoved) {
  // A pid that is not running: the largest pid Linux hands out is 4194304.
  const std::string dead = ".x.exr.tmp-4194999-0-1";
  const std::string live = ".x.exr.tmp-" + std::to_string(::getpid()) + "-77-1";
  const std::string other = ".x.exr.tmp-notapid";
  const std::string other_file = ".y.exr.tmp-4194999-0-1";
  for (const auto& name : {dead, live, other, other_file}) write_file(path(name), {1, 2, 3});
  ASSERT_TRUE(write_image(Image(2, 2), path("x.exr")));
  EXPECT_FALSE(fs::exists(path(dead)));
  EXPECT_TRUE(fs::exists(path(live)));
  EXPECT_TRUE(fs::exists(path(other)));
  EXPECT_FALSE(fs::exists(path(other_file)));
}

// issue 16, 4: Ctrl-C while the output was being written lost the image and left ".x.tmp-*" behind. A
// child process with the default SIGINT action writes 256 MiB; the parent interrupts it once the temporary
// exists. The signal is held until the rename, then ends the child: the file is whole, no temporary is left.
TEST_F(ImageIo, SigintDuringAWriteEndsTheProcessOnlyAfterTheRename) {
  const fs::path target = path("big.bin");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGINT, SIG_DFL);
    const std::vector<char> big(256u << 20, 'x');
    const Result<bool> ok = write_file_atomically(target, big);
    ::_exit(ok ? 0 : 1);
  }
  // Wait for the temporary to appear, then interrupt.
  bool seen = false;
  for (int i = 0; i < 20000 && !seen; ++i) {
    for (const auto& entry : fs::directory_iterator(m_dir)) {
      seen = seen || entry.path().filename().string().rfind(".big.bin.set-", 0) == 0;
    }
    if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ::kill(child, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(seen) << "the child never created its temporary";
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
  ASSERT_TRUE(fs::exists(target));
  EXPECT_EQ(fs::file_size(target), 256u << 20);
  EXPECT_EQ(listing(), std::vector<std::string>{"big.bin"});
}

// Several files as one step: all written, or none changed. A directory in the way of the third file makes
// its rename fail after the first two were renamed; they are put back (the existing one from its hard link,
// the new one removed) and no temporary or backup is left.
TEST_F(ImageIo, WriteFilesAtomicallyIsAllOrNothing) {
  auto read_all = [](const fs::path& p) {
    const std::vector<unsigned char> b = read_file(p);
    return std::string(b.begin(), b.end());
  };
  auto bytes = [](const std::string& s) { return std::vector<char>(s.begin(), s.end()); };
  std::ofstream(path("a.bin"), std::ios::binary) << "old a";
  fs::create_directories(path("c.bin"));
  const Result<bool> failed = write_files_atomically(
      {{path("a.bin"), bytes("new a")}, {path("b.bin"), bytes("new b")}, {path("c.bin"), bytes("new c")}});
  ASSERT_FALSE(failed.has_value());
  EXPECT_NE(failed.error().message.find("c.bin"), std::string::npos) << failed.error().message;
  EXPECT_EQ(read_all(path("a.bin")), "old a");
  EXPECT_EQ(listing(), (std::vector<std::string>{"a.bin", "c.bin"}));
  // A target in a missing directory fails before any rename: nothing changes either.
  ASSERT_FALSE(write_files_atomically({{path("a.bin"), bytes("new a")}, {path("none/d.bin"), bytes("d")}}).has_value());
  EXPECT_EQ(read_all(path("a.bin")), "old a");
  EXPECT_EQ(listing(), (std::vector<std::string>{"a.bin", "c.bin"}));
  fs::remove(path("c.bin"));
  // Issue 40: the folder in the way is now refused before anything is written; a rename that fails after the
  // commit (the folder appears then) still puts the renamed targets back and removes the journal.
  PublishOptions late;
  late.after_step = [&](const char* step) {
    if (std::string(step) == "committed") fs::create_directories(path("c.bin"));
  };
  const Result<bool> late_fail = write_files_atomically(
      {{path("a.bin"), bytes("new a")}, {path("b.bin"), bytes("new b")}, {path("c.bin"), bytes("new c")}}, late);
  ASSERT_FALSE(late_fail.has_value());
  EXPECT_NE(late_fail.error().message.find("c.bin"), std::string::npos) << late_fail.error().message;
  EXPECT_EQ(read_all(path("a.bin")), "old a");
  EXPECT_EQ(listing(), (std::vector<std::string>{"a.bin", "c.bin"}));
  fs::remove(path("c.bin"));
  ASSERT_TRUE(write_files_atomically({{path("a.bin"), bytes("new a")}, {path("b.bin"), bytes("new b")}}).has_value());
  EXPECT_EQ(read_all(path("a.bin")), "new a");
  EXPECT_EQ(read_all(path("b.bin")), "new b");
  EXPECT_EQ(listing(), (std::vector<std::string>{"a.bin", "b.bin"}));
}

// ------------------------------------------------------------------------------------- output sets (issue 40)

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<char> text_bytes(const std::string& s) { return std::vector<char>(s.begin(), s.end()); }

// Runs write_files_atomically(files) in a child process that ends itself with SIGKILL at `step`, as a kill -9
// there would; returns true when the child died there.
bool killed_at(const std::vector<std::pair<fs::path, std::vector<char>>>& files, const std::string& step,
               const PublishOptions& base = {}) {
  const pid_t child = ::fork();
  if (child == 0) {
    PublishOptions o = base;
    o.after_step = [&step](const char* s) {
      if (step == s) ::kill(::getpid(), SIGKILL);
    };
    (void)write_files_atomically(files, o);
    ::_exit(0);
  }
  int status = 0;
  if (::waitpid(child, &status, 0) != child) return false;
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

// Finding 7: a kill -9 between the renames of a set (merge's EXR and PNG) left a new EXR beside an old PNG.
// After the commit point the set is completed by the next writer into the folder; the temporaries go.
TEST_F(ImageIo, OutputSetKilledAfterItsCommitIsCompletedByTheNextWriter) {
  write_file(path("x.exr"), {'o', 'l', 'd'});
  write_file(path("x.png"), {'o', 'l', 'd'});
  ASSERT_TRUE(killed_at({{path("x.exr"), text_bytes("new exr")}, {path("x.png"), text_bytes("new png")}}, "renamed-first"));
  EXPECT_EQ(file_text(path("x.exr")), "new exr");  // the kill -9 came between the renames
  EXPECT_EQ(file_text(path("x.png")), "old");
  EXPECT_GT(listing().size(), 3u) << "the journal and the temporaries stay for the next writer";
  ASSERT_TRUE(write_file_atomically(path("other.txt"), text_bytes("x")));  // any write into the folder
  EXPECT_EQ(file_text(path("x.exr")), "new exr");
  EXPECT_EQ(file_text(path("x.png")), "new png");
  EXPECT_EQ(listing(), (std::vector<std::string>{"other.txt", "x.exr", "x.png"}));
}

// Before the commit point a kill -9 leaves only temporaries: the old set stands and the next writer removes them.
TEST_F(ImageIo, OutputSetKilledBeforeItsCommitLeavesTheOldSet) {
  write_file(path("x.exr"), {'o', 'l', 'd'});
  write_file(path("x.png"), {'o', 'l', 'd'});
  ASSERT_TRUE(killed_at({{path("x.exr"), text_bytes("new exr")}, {path("x.png"), text_bytes("new png")}}, "written"));
  EXPECT_EQ(file_text(path("x.exr")), "old");
  EXPECT_EQ(file_text(path("x.png")), "old");
  ASSERT_TRUE(write_file_atomically(path("other.txt"), text_bytes("x")));
  EXPECT_EQ(file_text(path("x.exr")), "old");
  EXPECT_EQ(file_text(path("x.png")), "old");
  EXPECT_EQ(listing(), (std::vector<std::string>{"other.txt", "x.exr", "x.png"}));
}

// A set over two folders: the copy of the journal in the second folder is written before the commit record in
// the first; killed between, the set never happened, whichever folder is written next.
TEST_F(ImageIo, OutputSetOverTwoFoldersIsAllOrNothing) {
  fs::create_directories(path("a"));
  fs::create_directories(path("b"));
  write_file(path("a/x.exr"), {'o', 'l', 'd'});
  write_file(path("b/x.png"), {'o', 'l', 'd'});
  const std::vector<std::pair<fs::path, std::vector<char>>> set = {{path("a/x.exr"), text_bytes("new exr")},
                                                                     {path("b/x.png"), text_bytes("new png")}};
  ASSERT_TRUE(killed_at(set, "prepared"));
  ASSERT_TRUE(write_file_atomically(path("b/other.txt"), text_bytes("x")));  // the second folder settles first
  ASSERT_TRUE(write_file_atomically(path("a/other.txt"), text_bytes("x")));
  EXPECT_EQ(file_text(path("a/x.exr")), "old");
  EXPECT_EQ(file_text(path("b/x.png")), "old");
  // Killed after the commit: the first folder's next writer completes both folders.
  ASSERT_TRUE(killed_at(set, "renamed-first"));
  EXPECT_EQ(file_text(path("b/x.png")), "old");
  ASSERT_TRUE(write_file_atomically(path("a/other.txt"), text_bytes("y")));
  EXPECT_EQ(file_text(path("a/x.exr")), "new exr");
  EXPECT_EQ(file_text(path("b/x.png")), "new png");
  for (const char* d : {"a", "b"}) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path(d))) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"other.txt", d == std::string("a") ? "x.exr" : "x.png"})) << d;
  }
}

// Finding 5: a full disk part-way through a set (here a file size limit: the third file's write fails with
// EFBIG) left the files written before it. Now every target is untouched and no temporary is left.
TEST_F(ImageIo, WriteFilesAtomicallyFailingPartWayChangesNothing) {
  for (const char* n : {"c.ktx2", "c_m0.exr", "c_m1.exr"}) write_file(path(n), {'o', 'l', 'd'});
  const pid_t child = ::fork();
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    const Result<bool> r = write_files_atomically({{path("c.ktx2"), text_bytes("new")},
                                                   {path("c_m0.exr"), text_bytes("new")},
                                                   {path("c_m1.exr"), std::vector<char>(8192, 'x')}});
    const bool named = !r && r.error().message.find("c_m1.exr") != std::string::npos;
    ::_exit(named ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the write did not fail naming c_m1.exr";
  for (const char* n : {"c.ktx2", "c_m0.exr", "c_m1.exr"}) EXPECT_EQ(file_text(path(n)), "old") << n;
  EXPECT_EQ(listing(), (std::vector<std::string>{"c.ktx2", "c_m0.exr", "c_m1.exr"}));
}

// Finding 5: the files of an older output of the same name go in the same step (remove_also), and a kill -9
// after the commit removes them too once settled.
TEST_F(ImageIo, OutputSetRemovesTheOlderOutputsFiles) {
  for (const char* n : {"c_m0.exr", "c_m1.exr", "c_m2.exr", "keep.exr"}) write_file(path(n), {1});
  PublishOptions o;
  o.remove_also = [](const fs::path& p) { return p.filename().string().rfind("c_m", 0) == 0; };
  ASSERT_TRUE(killed_at({{path("c.ktx2"), text_bytes("c")}, {path("c_m0.exr"), text_bytes("m0")}}, "renamed", o));
  EXPECT_TRUE(fs::exists(path("c_m2.exr")));
  ASSERT_TRUE(write_file_atomically(path("other.txt"), text_bytes("x")));
  EXPECT_EQ(listing(), (std::vector<std::string>{"c.ktx2", "c_m0.exr", "keep.exr", "other.txt"}));
  EXPECT_EQ(file_text(path("c_m0.exr")), "m0");
  write_file(path("c_m1.exr"), {1});
  ASSERT_TRUE(write_files_atomically({{path("c.ktx2"), text_bytes("c2")}, {path("c_m0.exr"), text_bytes("m0b")}}, o));
  EXPECT_EQ(listing(), (std::vector<std::string>{"c.ktx2", "c_m0.exr", "keep.exr", "other.txt"}));
}

// Finding 7: concurrent writers of one set are serialised (a lock on the folder): every round ends with a
// pair from one writer, never a mix.
TEST_F(ImageIo, ConcurrentWritersOfOneSetNeverMix) {
  for (int round = 0; round < 8; ++round) {
    std::vector<pid_t> children;
    for (int w = 0; w < 2; ++w) {
      const pid_t child = ::fork();
      if (child == 0) {
        const std::string tag = std::to_string(w);
        for (int k = 0; k < 10; ++k) {
          if (!write_files_atomically({{path("x.exr"), text_bytes(tag)}, {path("x.png"), text_bytes(tag)}})) ::_exit(1);
        }
        ::_exit(0);
      }
      children.push_back(child);
    }
    for (const pid_t c : children) {
      int status = 0;
      ASSERT_EQ(::waitpid(c, &status, 0), c);
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
    ASSERT_EQ(file_text(path("x.exr")), file_text(path("x.png"))) << "round " << round;
    ASSERT_EQ(listing(), (std::vector<std::string>{"x.exr", "x.png"}));
  }
}

}  // namespace
}  // namespace shadelab
