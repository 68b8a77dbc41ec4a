// shadelab image files: OpenEXR through the OpenEXR library, PNG and RGBE writing through stb, RGBE reading
// through rgbe.h (see image_io.h for the contract, docs/images.md for the reasons).
#include "shadelab/image/image_io.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <ImfArray.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <ImfThreading.h>
#include <Imath/half.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "shadelab/core/text.h"
#include "shadelab/image/rgbe.h"
#include "shadelab/image/srgb.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;

enum class Format { exr, hdr, png, unknown };

// Library messages may span lines (OpenEXR's do); an Error is one line.
std::string one_line(std::string_view text) {
  std::string s(text);
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  while (!s.empty() && s.back() == ' ') {
    s.pop_back();
  }
  return s.empty() ? std::string("unknown error") : printable(s, max_library_bytes);
}

Error read_error(const fs::path& path, std::string_view reason) {
  return make_error("read_image: '" + path.string() + "': " + one_line(reason));
}

Error file_error(const char* who, const fs::path& path, std::string_view reason) {
  return make_error(std::string(who) + ": '" + path.string() + "': " + one_line(reason));
}

Error write_error(const fs::path& path, std::string_view reason) { return file_error("write_image", path, reason); }

std::string errno_message(int err) { return std::system_category().message(err); }

Format format_of(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](char c) {
    return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  });
  if (ext == ".exr") {
    return Format::exr;
  }
  if (ext == ".hdr" || ext == ".pic") {
    return Format::hdr;
  }
  if (ext == ".png") {
    return Format::png;
  }
  return Format::unknown;
}

const char* unknown_extension_reason() {
  return "unknown image file extension (expected .exr, .hdr, .pic or .png)";
}

// Replaces NaN and +-Inf by 0 and counts them; counts negative values and keeps them.
// The first of each is recorded (its texel and channel) before the repair.
void repair_and_count(Image& image, ReadInfo& info) {
  int nonfinite = 0;
  int negative = 0;
  const auto texel = [&](std::size_t i, float v) {
    const std::size_t pixel = i / 3;
    const std::size_t w = static_cast<std::size_t>(std::max(image.width, 1));
    return ReadInfo::Texel{static_cast<int>(pixel % w), static_cast<int>(pixel / w), static_cast<int>(i % 3), v};
  };
  for (std::size_t i = 0; i < image.data.size(); ++i) {
    float& v = image.data[i];
    if (!std::isfinite(v)) {
      if (nonfinite == 0) info.first_nonfinite = texel(i, v);
      v = 0.0f;
      ++nonfinite;
    } else if (v < 0.0f) {
      if (negative == 0) info.first_negative = texel(i, v);
      ++negative;
    }
  }
  info.nonfinite_repaired = nonfinite;
  info.negative_values = negative;
}

// ---------------------------------------------------------------------------------------------- OpenEXR

long long box_width(const Imath::Box2i& b) { return static_cast<long long>(b.max.x) - b.min.x + 1; }
long long box_height(const Imath::Box2i& b) { return static_cast<long long>(b.max.y) - b.min.y + 1; }

bool box_contains(const Imath::Box2i& outer, const Imath::Box2i& inner) {
  return inner.min.x >= outer.min.x && inner.min.y >= outer.min.y && inner.max.x <= outer.max.x &&
         inner.max.y <= outer.max.y;
}

constexpr std::uint64_t bytes_per_pixel = 3 * sizeof(float);  // an Image pixel
constexpr std::uint64_t strip_bytes = 16ULL << 20;              // a strip buffer, when one is needed

std::string mib(std::uint64_t bytes) { return std::to_string((bytes + (1ULL << 20) - 1) >> 20) + " MiB"; }

// Refuses a read whose allocations (the image and the decoder's buffers) would exceed the budget.
Result<bool> check_budget(const fs::path& path, std::uint64_t bytes, const std::string& what, std::uint64_t budget) {
  if (bytes <= budget) {
    return true;
  }
  return read_error(path, what + " needs " + mib(bytes) + ", more than the image memory budget of " + mib(budget));
}

// OpenEXR allocates line-offset tables and tile buffers from the header before any pixel is read: bound the
// sizes it accepts (its sanity check then throws, which read_image reports).
void limit_openexr() {
  static std::once_flag once;
  std::call_once(once, [] {
    Imf::Header::setMaxImageSize(static_cast<int>(max_image_side), static_cast<int>(max_image_side));
    Imf::Header::setMaxTileSize(static_cast<int>(max_exr_tile_side), static_cast<int>(max_exr_tile_side));
  });
}

// The part of the data window inside the display window (empty when max < min).
Imath::Box2i overlap(const Imath::Box2i& display_window, const Imath::Box2i& data_window) {
  return Imath::Box2i(Imath::V2i(std::max(data_window.min.x, display_window.min.x),
                                 std::max(data_window.min.y, display_window.min.y)),
                      Imath::V2i(std::min(data_window.max.x, display_window.max.x),
                                 std::min(data_window.max.y, display_window.max.y)));
}

// Rows per strip for a buffer `row_bytes` wide: as many as fit in strip_bytes, at least one.
int strip_rows(std::uint64_t row_bytes, int rows) {
  return static_cast<int>(std::clamp<std::uint64_t>(strip_bytes / std::max<std::uint64_t>(row_bytes, 1), 1,
                                                    static_cast<std::uint64_t>(std::max(rows, 1))));
}

// Copies rows [y0, y1] of an RGB float strip over the data window's columns into `image` (pixel (0, 0) is
// display_window.min), keeping only the columns of `keep` (the overlap).
void copy_strip(const std::vector<float>& strip, const Imath::Box2i& data_window, int y0, int y1,
                const Imath::Box2i& keep, const Imath::Box2i& display_window, Image& image) {
  const auto strip_width = static_cast<std::size_t>(box_width(data_window));
  const auto row_floats = static_cast<std::size_t>(keep.max.x - keep.min.x + 1) * 3;
  for (int y = y0; y <= y1; ++y) {
    const std::size_t src = (static_cast<std::size_t>(y - y0) * strip_width +
                             static_cast<std::size_t>(keep.min.x - data_window.min.x)) * 3;
    const std::size_t dst = image.index(keep.min.x - display_window.min.x, y - display_window.min.y);
    std::copy_n(strip.begin() + static_cast<std::ptrdiff_t>(src), row_floats,
                image.data.begin() + static_cast<std::ptrdiff_t>(dst));
  }
}

// Luminance/chroma files (Y, RY, BY, subsampled chroma) hold half data; RgbaInputFile converts them to RGB.
// Read in strips of the overlapping rows, so the buffers follow the data window and a strip budget.
Result<Image> read_exr_luminance_chroma(const fs::path& path, const Imath::Box2i& display_window,
                                        ReadInfo& info, std::uint64_t budget) {
  Imf::RgbaInputFile file(path.c_str());
  const Imath::Box2i data_window = file.dataWindow();
  const Imath::Box2i keep = overlap(display_window, data_window);
  const auto w = static_cast<std::size_t>(box_width(data_window));
  const int rows = keep.max.y - keep.min.y + 1;
  const int per_strip = strip_rows(w * sizeof(Imf::Rgba), rows);
  const std::uint64_t image_bytes =
      static_cast<std::uint64_t>(box_width(display_window)) * box_height(display_window) * bytes_per_pixel;
  if (auto ok = check_budget(path, image_bytes + w * static_cast<std::uint64_t>(per_strip) * (sizeof(Imf::Rgba) + bytes_per_pixel),
                             "reading it", budget);
      !ok) {
    return ok.error();
  }
  Image image(static_cast<int>(box_width(display_window)), static_cast<int>(box_height(display_window)));
  info.sample_type = "half";
  info.grey = false;
  if (keep.max.x < keep.min.x || rows <= 0) {
    return image;
  }
  std::vector<Imf::Rgba> pixels(w * static_cast<std::size_t>(per_strip));
  std::vector<float> strip(w * static_cast<std::size_t>(per_strip) * 3);
  for (int y0 = keep.min.y; y0 <= keep.max.y; y0 += per_strip) {
    const int y1 = std::min(keep.max.y, y0 + per_strip - 1);
    const Imath::Box2i window(Imath::V2i(data_window.min.x, y0), Imath::V2i(data_window.max.x, y1));
    file.setFrameBuffer(Imf::ComputeBasePointer(pixels.data(), window), 1, w);
    file.readPixels(y0, y1);
    const std::size_t n = w * static_cast<std::size_t>(y1 - y0 + 1);
    for (std::size_t i = 0; i < n; ++i) {
      strip[3 * i] = static_cast<float>(pixels[i].r);
      strip[3 * i + 1] = static_cast<float>(pixels[i].g);
      strip[3 * i + 2] = static_cast<float>(pixels[i].b);
    }
    copy_strip(strip, data_window, y0, y1, keep, display_window, image);
  }
  return image;
}

const char* sample_type_name(Imf::PixelType type) {
  switch (type) {
    case Imf::HALF:
      return "half";
    case Imf::FLOAT:
      return "float";
    case Imf::UINT:
      return "uint";
    default:
      return "unknown";
  }
}

Result<Image> read_exr(const fs::path& path, ReadInfo& info, std::uint64_t budget) {
  limit_openexr();
  if (auto ok = check_exr_header(path); !ok) return ok.error();
  Imf::InputFile file(path.c_str());
  const Imf::Header& header = file.header();
  const Imath::Box2i display_window = header.displayWindow();
  const Imath::Box2i data_window = header.dataWindow();
  const long long width = box_width(display_window);
  const long long height = box_height(display_window);
  if (width <= 0 || height <= 0 || box_width(data_window) <= 0 || box_height(data_window) <= 0) {
    return read_error(path, "image has zero size");
  }
  if (width * height > max_image_pixels || width > max_image_side || height > max_image_side ||
      box_width(data_window) * box_height(data_window) > max_image_pixels) {
    return read_error(path, "image is too large (" + std::to_string(width) + " x " + std::to_string(height) +
                                " display window; the limit is " + std::to_string(max_image_pixels) + " pixels)");
  }
  if (!file.isComplete()) {
    return read_error(path, "file is truncated or incomplete: some scan lines or tiles are missing");
  }
  info.partial_data_window = !(data_window == display_window);

  const Imf::ChannelList& channels = header.channels();
  std::string names;
  for (auto it = channels.begin(); it != channels.end(); ++it) {
    ++info.channels;
    names += (names.empty() ? "" : ", ") + std::string(it.name());
  }
  const Imf::Channel* r = channels.findChannel("R");
  const Imf::Channel* g = channels.findChannel("G");
  const Imf::Channel* b = channels.findChannel("B");
  const Imf::Channel* y = channels.findChannel("Y");
  info.had_alpha = channels.findChannel("A") != nullptr;
  const bool rgb = r != nullptr || g != nullptr || b != nullptr;
  if (!rgb && y == nullptr) {
    return read_error(path, "no R, G, B or Y channel (channels: " + (names.empty() ? "none" : names) + ")");
  }
  if (!rgb && (channels.findChannel("RY") != nullptr || channels.findChannel("BY") != nullptr)) {
    return read_exr_luminance_chroma(path, display_window, info, budget);
  }
  const Imf::Channel* used[3] = {r, g, b};
  if (!rgb) {
    used[0] = y;
    used[1] = used[2] = nullptr;
    info.grey = true;
  }
  for (const Imf::Channel* c : used) {
    if (c != nullptr && (c->xSampling != 1 || c->ySampling != 1)) {
      return read_error(path, "subsampled R, G, B or Y channels are not supported");
    }
  }
  info.sample_type = sample_type_name((used[0] != nullptr ? used[0] : (used[1] != nullptr ? used[1] : used[2]))->type);

  // Read straight into the image when the data window lies inside the display window (the usual case);
  // otherwise only the rows that overlap the display window, in strips over the data window's columns.
  const bool direct = box_contains(display_window, data_window);
  const Imath::Box2i keep = overlap(display_window, data_window);
  const int rows = keep.max.y - keep.min.y + 1;
  const auto data_width = static_cast<std::uint64_t>(box_width(data_window));
  const int per_strip = direct ? 0 : strip_rows(data_width * bytes_per_pixel, rows);
  const std::uint64_t image_bytes = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) * bytes_per_pixel;
  if (auto ok = check_budget(path, image_bytes + data_width * static_cast<std::uint64_t>(per_strip) * bytes_per_pixel,
                             "reading its " + std::to_string(width) + " x " + std::to_string(height) + " display window",
                             budget);
      !ok) {
    return ok.error();
  }
  Image image(static_cast<int>(width), static_cast<int>(height));
  const char* names_rgb[3] = {"R", "G", "B"};
  const std::size_t x_stride = 3 * sizeof(float);
  // A frame buffer whose pixel `origin` is at `base`, `w` pixels per row.
  auto frame_buffer = [&](float* base, const Imath::V2i& origin, long long w, long long h) {
    Imf::FrameBuffer fb;
    for (int c = 0; c < 3; ++c) {
      const char* name = rgb ? names_rgb[c] : (c == 0 ? "Y" : nullptr);
      if (name == nullptr) {
        continue;
      }
      // A channel named here but absent from the file is filled with 0 by OpenEXR.
      fb.insert(name, Imf::Slice::Make(Imf::FLOAT, base + c, origin, w, h, x_stride,
                                       x_stride * static_cast<std::size_t>(w), 1, 1, 0.0));
    }
    return fb;
  };
  if (direct) {
    file.setFrameBuffer(frame_buffer(image.data.data(), display_window.min, width, height));
    file.readPixels(data_window.min.y, data_window.max.y);
  } else if (keep.max.x >= keep.min.x && rows > 0) {
    std::vector<float> strip(static_cast<std::size_t>(data_width) * static_cast<std::size_t>(per_strip) * 3);
    for (int y0 = keep.min.y; y0 <= keep.max.y; y0 += per_strip) {
      const int y1 = std::min(keep.max.y, y0 + per_strip - 1);
      file.setFrameBuffer(frame_buffer(strip.data(), Imath::V2i(data_window.min.x, y0), box_width(data_window), y1 - y0 + 1));
      file.readPixels(y0, y1);
      copy_strip(strip, data_window, y0, y1, keep, display_window, image);
    }
  }
  if (!rgb) {
    for (std::size_t i = 0; i < image.data.size(); i += 3) {
      image.data[i + 1] = image.data[i + 2] = image.data[i];
    }
  }
  return image;
}

// An OpenEXR output stream into memory, so that the file is written by write_atomically like the others.
class MemoryOStream final : public Imf::OStream {
 public:
  MemoryOStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    const auto count = static_cast<std::size_t>(n);
    if (m_bytes.size() < m_position + count) {
      m_bytes.resize(m_position + count);
    }
    std::memcpy(m_bytes.data() + m_position, c, count);
    m_position += count;
  }
  std::uint64_t tellp() override { return m_position; }
  void seekp(std::uint64_t pos) override { m_position = static_cast<std::size_t>(pos); }
  std::vector<char>& bytes() { return m_bytes; }

 private:
  std::vector<char> m_bytes;
  std::size_t m_position = 0;
};

Imf::Compression exr_compression(ExrCompression c) {
  switch (c) {
    case ExrCompression::none:
      return Imf::NO_COMPRESSION;
    case ExrCompression::rle:
      return Imf::RLE_COMPRESSION;
    case ExrCompression::zips:
      return Imf::ZIPS_COMPRESSION;
    case ExrCompression::zip:
      return Imf::ZIP_COMPRESSION;
    case ExrCompression::piz:
      return Imf::PIZ_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}

constexpr float half_max = 65504.0f;  // largest finite half: (2 - 2^-10) 2^15

std::vector<std::uint16_t> to_half_bits(const FloatBuffer& values) {
  std::vector<std::uint16_t> bits(values.size());
  std::transform(values.begin(), values.end(), bits.begin(), [](float v) {
    return Imath::half(std::isfinite(v) ? std::clamp(v, -half_max, half_max) : v).bits();
  });
  return bits;
}

std::vector<char> encode_exr(const Image& image, const WriteOptions& options) {
  const bool half = options.exr_pixel_type == ExrPixelType::half;
  const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;
  Imf::Header header(image.width, image.height);
  header.compression() = exr_compression(options.exr_compression);
  for (const char* name : {"R", "G", "B"}) {
    header.channels().insert(name, Imf::Channel(type));
  }
  // Half data as the bits of Imath::half values; finite values beyond the half range are clamped.
  const std::vector<std::uint16_t> halves = half ? to_half_bits(image.data) : std::vector<std::uint16_t>{};
  const char* base =
      half ? reinterpret_cast<const char*>(halves.data()) : reinterpret_cast<const char*>(image.data.data());
  const std::size_t x_stride = 3 * (half ? sizeof(std::uint16_t) : sizeof(float));
  const std::size_t y_stride = x_stride * static_cast<std::size_t>(image.width);
  const std::size_t channel_size = half ? sizeof(std::uint16_t) : sizeof(float);
  Imf::FrameBuffer frame_buffer;
  int c = 0;
  for (const char* name : {"R", "G", "B"}) {
    // OpenEXR's Slice takes a mutable pointer for both directions; an output file only reads through it.
    frame_buffer.insert(name, Imf::Slice(type, const_cast<char*>(base + static_cast<std::size_t>(c) * channel_size),
                                         x_stride, y_stride));
    ++c;
  }
  MemoryOStream stream;
  {
    Imf::OutputFile file(stream, header, Imf::globalThreadCount());
    file.setFrameBuffer(frame_buffer);
    file.writePixels(image.height);
  }  // the destructor writes the line offset table
  return std::move(stream.bytes());
}

// ---------------------------------------------------------------------------------------------- stb

struct StbiFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

Result<std::vector<unsigned char>> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) {
    return read_error(path, "cannot open file");
  }
  const std::streamoff size = in.tellg();
  if (size <= 0) {
    return read_error(path, "file is empty");
  }
  if (size > INT_MAX) {
    return read_error(path, "file is too large (over 2 GiB)");
  }
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) {
    return read_error(path, "cannot read file");
  }
  return bytes;
}

std::string stb_reason() {
  const char* reason = stbi_failure_reason();
  return reason != nullptr ? std::string(reason) : std::string("unknown error");
}

// Size check through stbi_info before stb allocates the pixels.
Result<bool> check_stb_size(const fs::path& path, const std::vector<unsigned char>& bytes, const char* what) {
  int w = 0;
  int h = 0;
  int n = 0;
  if (stbi_info_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &n) == 0) {
    return read_error(path, std::string("corrupt or unsupported ") + what + " file (" + stb_reason() + ")");
  }
  if (w <= 0 || h <= 0) {
    return read_error(path, "image has zero size");
  }
  if (static_cast<long long>(w) * h > max_image_pixels) {
    return read_error(path, "image is too large (" + std::to_string(w) + " x " + std::to_string(h) + ")");
  }
  return true;
}

// Radiance RGBE through our own decoder (rgbe.h says why not stb_image).
Result<Image> read_hdr(const fs::path& path, ReadInfo& info, std::uint64_t budget) {
  auto bytes = read_bytes(path);
  if (!bytes) {
    return bytes.error();
  }
  // The image is 12 bytes a pixel and the decoder's scan-line buffer one row: the budget bounds the pixels.
  const long long budget_pixels = static_cast<long long>(budget / bytes_per_pixel);
  Result<Image> image = decode_rgbe(bytes->data(), bytes->size(), std::min(max_image_pixels, budget_pixels));
  if (!image) {
    return read_error(path, image.error().message);
  }
  info.sample_type = "rgbe";
  info.channels = 3;
  return image;
}

// Walks the PNG chunk list (PNG specification, section 5.3: length, type, data, CRC) up to IEND. stb_image
// decodes a file whose last chunk is cut short without complaint; this makes every truncation an error.
Result<bool> check_png_chunks(const fs::path& path, const std::vector<unsigned char>& bytes) {
  std::size_t at = 8;  // after the signature
  for (;;) {
    if (bytes.size() - at < 12) {
      return read_error(path, "PNG file is truncated (no complete IEND chunk)");
    }
    const std::size_t length = (std::size_t{bytes[at]} << 24) | (std::size_t{bytes[at + 1]} << 16) |
                               (std::size_t{bytes[at + 2]} << 8) | std::size_t{bytes[at + 3]};
    if (length > bytes.size() - at - 12) {
      return read_error(path, "PNG file is truncated inside a chunk");
    }
    const bool iend = std::memcmp(bytes.data() + at + 4, "IEND", 4) == 0;
    at += 12 + length;
    if (iend) {
      return true;
    }
  }
}

// Decodes stb's interleaved 8- or 16-bit samples (1 to 4 channels) through an sRGB table into RGB.
template <typename T>
void decode_srgb(const T* samples, int channels, const float* table, Image& image) {
  const std::size_t count = image.pixel_count();
  const auto nc = static_cast<std::size_t>(channels);
  float* out = image.data.data();
  if (channels <= 2) {  // grey or grey + alpha
    for (std::size_t i = 0; i < count; ++i) {
      out[3 * i] = out[3 * i + 1] = out[3 * i + 2] = table[samples[i * nc]];
    }
  } else {  // RGB or RGBA
    for (std::size_t i = 0; i < count; ++i) {
      out[3 * i] = table[samples[i * nc]];
      out[3 * i + 1] = table[samples[i * nc + 1]];
      out[3 * i + 2] = table[samples[i * nc + 2]];
    }
  }
}

// The alpha channel of stb's interleaved samples (grey + alpha or RGBA) through `table` (code / max) into R, G and B;
// 1 where the image has no alpha channel.
template <typename T>
void decode_alpha(const T* samples, int channels, const float* table, Image& image) {
  const std::size_t count = image.pixel_count();
  const auto nc = static_cast<std::size_t>(channels);
  float* out = image.data.data();
  const bool has_alpha = channels == 2 || channels == 4;
  for (std::size_t i = 0; i < count; ++i) {
    out[3 * i] = out[3 * i + 1] = out[3 * i + 2] = has_alpha ? table[samples[i * nc + nc - 1]] : 1.0f;
  }
}

std::uint32_t be32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}

void put_be32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>((v >> shift) & 0xFF));
}

// CRC-32 of PNG chunks (PNG specification, annex D: polynomial 0xEDB88320, reflected, inverted).
std::uint32_t png_crc(const unsigned char* data, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= data[i];
    for (int k = 0; k < 8; ++k) c = (c & 1u) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xFFFFFFFFu;
}

// A palette image (colour type 3) whose pixels index past its PLTE would make stb_image read palette
// entries it never filled (uninitialised memory: the image would differ from run to run). The indices are
// found by decoding a copy of the file whose PLTE is replaced by the identity palette (entry i = (i, 0, 0)),
// so the red channel is the index; any index >= the file's palette size is an error. tRNS may not be longer
// than PLTE (PNG specification 11.3.2.1).
Result<bool> check_palette_indices(const fs::path& path, const std::vector<unsigned char>& bytes) {
  if (bytes.size() < 33 || std::memcmp(bytes.data() + 12, "IHDR", 4) != 0) {
    return true;  // stb reports it
  }
  const int bit_depth = bytes[24];
  const int colour_type = bytes[25];
  if (colour_type != 3 || bit_depth < 1 || bit_depth > 8) {
    return true;
  }
  std::vector<unsigned char> copy(bytes.begin(), bytes.begin() + 8);
  std::size_t entries = 0;
  bool have_palette = false;
  std::size_t at = 8;
  while (at + 12 <= bytes.size()) {  // check_png_chunks has validated the chunk lengths
    const std::uint32_t length = be32(bytes.data() + at);
    const unsigned char* type = bytes.data() + at + 4;
    if (std::memcmp(type, "PLTE", 4) == 0 && !have_palette) {
      have_palette = true;
      entries = length / 3;
      const std::size_t identity = std::size_t{1} << bit_depth;
      std::vector<unsigned char> chunk{'P', 'L', 'T', 'E'};
      for (std::size_t i = 0; i < identity; ++i) chunk.insert(chunk.end(), {static_cast<unsigned char>(i), 0, 0});
      put_be32(copy, static_cast<std::uint32_t>(chunk.size() - 4));
      copy.insert(copy.end(), chunk.begin(), chunk.end());
      put_be32(copy, png_crc(chunk.data(), chunk.size()));
    } else {
      if (std::memcmp(type, "tRNS", 4) == 0 && have_palette && length > entries) {
        return read_error(path, "PNG tRNS chunk has " + std::to_string(length) + " entries, more than the " +
                                    std::to_string(entries) + " of its palette");
      }
      copy.insert(copy.end(), bytes.begin() + static_cast<std::ptrdiff_t>(at),
                  bytes.begin() + static_cast<std::ptrdiff_t>(at + 12 + length));
    }
    if (std::memcmp(type, "IEND", 4) == 0) {
      break;
    }
    at += 12 + length;
  }
  if (!have_palette) {
    return true;  // stb reports the missing PLTE
  }
  int w = 0;
  int h = 0;
  int n = 0;
  std::unique_ptr<stbi_uc, StbiFree> indices(
      stbi_load_from_memory(copy.data(), static_cast<int>(copy.size()), &w, &h, &n, 3));
  if (!indices) {
    return true;  // the real decode reports why
  }
  const std::size_t count = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::size_t largest = 0;
  for (std::size_t i = 0; i < count; ++i) largest = std::max<std::size_t>(largest, indices.get()[3 * i]);
  if (largest >= entries) {
    return read_error(path, "PNG pixels index palette entry " + std::to_string(largest) + ", but its PLTE has " +
                                std::to_string(entries) + " entries");
  }
  return true;
}

// code / (2^bits - 1): the linear tables of PngSamples::linear.
const std::vector<float>& linear_code_table(int bits) {
  static const std::vector<float> t8 = [] {
    std::vector<float> t(256);
    for (int k = 0; k < 256; ++k) t[static_cast<std::size_t>(k)] = static_cast<float>(k / 255.0);
    return t;
  }();
  static const std::vector<float> t16 = [] {
    std::vector<float> t(65536);
    for (int k = 0; k < 65536; ++k) t[static_cast<std::size_t>(k)] = static_cast<float>(k / 65535.0);
    return t;
  }();
  return bits == 8 ? t8 : t16;
}

Result<Image> read_png(const fs::path& path, ReadInfo& info, std::uint64_t budget, PngSamples png) {
  auto bytes = read_bytes(path);
  if (!bytes) {
    return bytes.error();
  }
  static constexpr unsigned char signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};  // PNG spec 5.2
  if (bytes->size() < sizeof(signature) || !std::equal(signature, signature + 8, bytes->begin())) {
    return read_error(path, "not a PNG file (bad signature)");
  }
  if (auto ok = check_png_chunks(path, *bytes); !ok) {
    return ok.error();
  }
  if (auto ok = check_stb_size(path, *bytes, "PNG"); !ok) {
    return ok.error();
  }
  const int size = static_cast<int>(bytes->size());
  int w = 0;
  int h = 0;
  int n = 0;
  const bool sixteen = stbi_is_16_bit_from_memory(bytes->data(), size) != 0;
  if (stbi_info_from_memory(bytes->data(), size, &w, &h, &n) == 0 || n < 1 || n > 4) {
    return read_error(path, "unsupported PNG channel count " + std::to_string(n));
  }
  // The image, stb's samples and its inflated scan lines (about as large as the samples).
  const auto pixels_count = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
  if (auto ok = check_budget(path, pixels_count * (bytes_per_pixel + 2ULL * static_cast<std::uint64_t>(n) * (sixteen ? 2 : 1)),
                             "decoding its " + std::to_string(w) + " x " + std::to_string(h) + " pixels", budget);
      !ok) {
    return ok.error();
  }
  if (auto ok = check_palette_indices(path, *bytes); !ok) {
    return ok.error();
  }
  Image image;
  if (sixteen) {
    std::unique_ptr<stbi_us, StbiFree> pixels(stbi_load_16_from_memory(bytes->data(), size, &w, &h, &n, 0));
    if (!pixels) {
      return read_error(path, "corrupt or truncated PNG file (" + stb_reason() + ")");
    }
    image = Image(w, h);
    if (png == PngSamples::alpha) {
      decode_alpha(pixels.get(), n, linear_code_table(16).data(), image);
    } else {
      decode_srgb(pixels.get(), n, png == PngSamples::linear ? linear_code_table(16).data() : srgb16_to_linear_table().data(),
                  image);
    }
  } else {
    std::unique_ptr<stbi_uc, StbiFree> pixels(stbi_load_from_memory(bytes->data(), size, &w, &h, &n, 0));
    if (!pixels) {
      return read_error(path, "corrupt or truncated PNG file (" + stb_reason() + ")");
    }
    image = Image(w, h);
    if (png == PngSamples::alpha) {
      decode_alpha(pixels.get(), n, linear_code_table(8).data(), image);
    } else {
      decode_srgb(pixels.get(), n, png == PngSamples::linear ? linear_code_table(8).data() : srgb8_to_linear_table().data(),
                  image);
    }
  }
  info.sample_type = sixteen ? "uint16" : "uint8";
  info.channels = n;
  info.grey = n <= 2;
  info.had_alpha = n == 2 || n == 4;
  return image;
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<char>*>(context);
  const auto* p = static_cast<const char*>(data);
  out->insert(out->end(), p, p + size);
}

Result<std::vector<char>> encode_hdr(const Image& image, const fs::path& path) {
  // RGBE holds neither negative nor non-finite values: they become 0 (image_io.h).
  std::vector<float> clean(image.data.size());
  std::transform(image.data.begin(), image.data.end(), clean.begin(),
                 [](float v) { return std::isfinite(v) && v > 0.0f ? v : 0.0f; });
  std::vector<char> bytes;
  if (stbi_write_hdr_to_func(append_bytes, &bytes, image.width, image.height, 3, clean.data()) == 0) {
    return write_error(path, "cannot encode Radiance RGBE data");
  }
  return bytes;
}

Result<std::vector<char>> encode_png(const Image& image, const fs::path& path, double exposure, PngSamples png) {
  const double scale = std::exp2(exposure);  // exposure in stops: a factor of 2^exposure
  std::vector<std::uint8_t> codes(image.data.size());
  if (png == PngSamples::linear) {
    std::transform(image.data.begin(), image.data.end(), codes.begin(), [scale](float v) {
      const double x = static_cast<double>(v) * scale;
      return static_cast<std::uint8_t>(std::isfinite(x) ? std::lround(std::clamp(x, 0.0, 1.0) * 255.0) : 0);
    });
  } else {
    std::transform(image.data.begin(), image.data.end(), codes.begin(),
                   [scale](float v) { return linear_to_srgb8(static_cast<double>(v) * scale); });
  }
  std::vector<char> bytes;
  if (stbi_write_png_to_func(append_bytes, &bytes, image.width, image.height, 3, codes.data(), image.width * 3) ==
      0) {
    return write_error(path, "cannot encode PNG data");
  }
  return bytes;
}

// ---------------------------------------------------------------------------------------------- atomic write

// Signals that end a process by default (SIGINT, SIGTERM, SIGHUP) are held while any atomic write is in
// progress, in any thread, and raised again when the last one is done: Ctrl-C then lands after the rename
// (or the temporary's removal), never between, so it leaves neither a temporary nor a lost output behind.
// A program's own handler (the render command's) is restored first, so it sees the signal as usual.
std::mutex g_hold_mutex;
int g_hold_depth = 0;
constexpr int held_signals[3] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_saved_actions[3];
volatile std::sig_atomic_t g_held_signal = 0;

extern "C" void hold_signal(int sig) { g_held_signal = sig; }

class SignalHold {
 public:
  SignalHold() {
    const std::lock_guard<std::mutex> lock(g_hold_mutex);
    if (g_hold_depth++ == 0) {
      g_held_signal = 0;
      struct sigaction hold {};
      hold.sa_handler = hold_signal;
      sigemptyset(&hold.sa_mask);
      for (int i = 0; i < 3; ++i) ::sigaction(held_signals[i], &hold, &g_saved_actions[i]);
    }
  }
  ~SignalHold() {
    const std::lock_guard<std::mutex> lock(g_hold_mutex);
    if (--g_hold_depth == 0) {
      for (int i = 0; i < 3; ++i) ::sigaction(held_signals[i], &g_saved_actions[i], nullptr);
      const int sig = g_held_signal;
      g_held_signal = 0;
      if (sig != 0) std::raise(sig);
    }
  }
  SignalHold(const SignalHold&) = delete;
  SignalHold& operator=(const SignalHold&) = delete;
};

// ---------------------------------------------------------------------------------------------- output sets
//
// Every file shadelab writes goes through publish(): one mechanism for a single file and for a set of files
// that belong together (issue 40, findings 5 and 7; docs/design.md, "Output sets").
//  1. The folder of every target is locked (flock on the folder itself, LOCK_EX, in the order of the folders'
//     real paths, so two writers never wait on each other crosswise). Concurrent writers to one folder are
//     serialised: each publishes a whole set, the last one wins, no mix.
//  2. Under the lock, what a dead run left is settled (settle_folder): a committed journal is rolled forward,
//     every other temporary of ours is removed; nobody else can own one, since a live writer holds the lock.
//  3. Every file is written to its temporary beside its target (".NAME.set-ID.tmp", created exclusively,
//     fsync'd); an existing target gets a hard link ".NAME.set-ID.old" so that a failed rename can undo.
//  4. With more than one change, the journal ".shadelab-set-ID.journal" is written (fsync'd, ending in a line
//     "end"): a copy in every other folder of the set first, then the one in the first folder, the commit point.
//  5. The renames, then the removals (the files of an older output of the same name), then the journals go.
// A kill -9 before the commit leaves temporaries only: the next writer into that folder removes them and the
// old set stands. A kill -9 after it leaves a journal: the next writer into that folder completes the set.
// A failed rename (after every target was checked to be no folder: an I/O error) puts the renamed targets back.

constexpr const char* set_marker = ".set-";
constexpr const char* journal_prefix = ".shadelab-set-";
constexpr const char* journal_suffix = ".journal";

// A folder, locked for as long as this object lives (or not, where the file system refuses flock).
class FolderLock {
 public:
  explicit FolderLock(const fs::path& dir) {
    m_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (m_fd < 0) return;
    while (::flock(m_fd, LOCK_EX) != 0) {
      if (errno == EINTR) continue;
      ::close(m_fd);  // no locks on this file system: written unlocked, nothing settled
      m_fd = -1;
      return;
    }
  }
  // Non-blocking: locked() says whether it was free.
  FolderLock(const fs::path& dir, bool /*try_only*/) {
    m_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (m_fd >= 0 && ::flock(m_fd, LOCK_EX | LOCK_NB) != 0) {
      ::close(m_fd);
      m_fd = -1;
    }
  }
  ~FolderLock() {
    if (m_fd >= 0) ::close(m_fd);  // closing the last descriptor releases the lock
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  bool locked() const { return m_fd >= 0; }
  void sync() const {
    if (m_fd >= 0) ::fsync(m_fd);
  }

 private:
  int m_fd = -1;
};

void sync_folder(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

// Percent-escapes the bytes a journal line cannot hold (control bytes, '%').
std::string escape_path(const std::string& s) {
  std::string out;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || c == '%' || u == 0x7f) {
      static const char* hex = "0123456789ABCDEF";
      out += '%';
      out += hex[u >> 4];
      out += hex[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

std::string unescape_path(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size()) {
      int v = 0;
      const auto [p, err] = std::from_chars(s.data() + i + 1, s.data() + i + 3, v, 16);
      if (err == std::errc() && p == s.data() + i + 3) {
        out += static_cast<char>(v);
        i += 2;
        continue;
      }
    }
    out += s[i];
  }
  return out;
}

struct Journal {
  std::string id;
  fs::path primary;              // the folder whose copy is the commit record
  std::vector<fs::path> folders;  // every folder of the set (the primary first)
  std::vector<std::pair<fs::path, fs::path>> renames;  // temporary -> target
  std::vector<fs::path> backups;                       // hard links of replaced targets
  std::vector<fs::path> removals;                      // files of an older output of the same name
  bool complete = false;                               // ends in "end": it was written whole
};

std::string journal_text(const Journal& j) {
  std::string t = "shadelab output set 1\nid " + j.id + "\nprimary " + escape_path(j.primary.string()) + "\n";
  for (const fs::path& d : j.folders) t += "folder " + escape_path(d.string()) + "\n";
  for (const auto& [tmp, target] : j.renames) {
    t += "rename " + escape_path(tmp.string()) + "\n";
    t += "to " + escape_path(target.string()) + "\n";
  }
  for (const fs::path& b : j.backups) t += "backup " + escape_path(b.string()) + "\n";
  for (const fs::path& r : j.removals) t += "remove " + escape_path(r.string()) + "\n";
  return t + "end\n";
}

Journal read_journal(const fs::path& path) {
  Journal j;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  fs::path pending;
  bool header = false;
  while (std::getline(in, line)) {
    const std::size_t sp = line.find(' ');
    const std::string key = line.substr(0, sp);
    const std::string value = sp == std::string::npos ? std::string() : unescape_path(line.substr(sp + 1));
    if (!header) {
      if (line != "shadelab output set 1") return j;
      header = true;
    } else if (key == "id") {
      j.id = value;
    } else if (key == "primary") {
      j.primary = value;
    } else if (key == "folder") {
      j.folders.emplace_back(value);
    } else if (key == "rename") {
      pending = value;
    } else if (key == "to") {
      j.renames.emplace_back(pending, fs::path(value));
    } else if (key == "backup") {
      j.backups.emplace_back(value);
    } else if (key == "remove") {
      j.removals.emplace_back(value);
    } else if (line == "end") {
      j.complete = !j.primary.empty();
      return j;
    }
  }
  return j;
}

fs::path journal_path(const fs::path& dir, const std::string& id) { return dir / (journal_prefix + id + journal_suffix); }

bool is_journal_name(const std::string& name) {
  return name.rfind(journal_prefix, 0) == 0 && name.size() > std::strlen(journal_prefix) + std::strlen(journal_suffix) &&
         name.compare(name.size() - std::strlen(journal_suffix), std::string::npos, journal_suffix) == 0;
}

// ".NAME.set-ID.tmp" / ".NAME.set-ID.old": the set's id, or "" for another name.
std::string set_file_id(const std::string& name) {
  if (name.size() < 2 || name[0] != '.' || is_journal_name(name)) return "";
  const bool tmp = name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0;
  const bool old = name.size() > 4 && name.compare(name.size() - 4, 4, ".old") == 0;
  if (!tmp && !old) return "";
  const std::size_t at = name.rfind(set_marker);
  if (at == std::string::npos || at == 0) return "";
  const std::size_t from = at + std::strlen(set_marker);
  return from < name.size() - 4 ? name.substr(from, name.size() - 4 - from) : "";
}

// The same folder, compared by real path.
bool same_folder(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec);
}

// Applies the part of a committed set that lies in `dir` (idempotent: a temporary already renamed is gone).
void roll_forward_in(const Journal& j, const fs::path& dir) {
  std::error_code ec;
  for (const auto& [tmp, target] : j.renames) {
    if (same_folder(target.parent_path(), dir) && fs::exists(fs::symlink_status(tmp, ec))) fs::rename(tmp, target, ec);
  }
  for (const fs::path& r : j.removals) {
    if (same_folder(r.parent_path(), dir)) fs::remove(r, ec);
  }
  for (const fs::path& b : j.backups) {
    if (same_folder(b.parent_path(), dir)) fs::remove(b, ec);
  }
  sync_folder(dir);
}

// Settles what dead runs left in `dir`, which this process holds locked; `held` are all the folders it holds.
void settle_folder(const fs::path& dir, const std::vector<fs::path>& held) {
  std::error_code ec;
  std::vector<fs::path> journals;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (is_journal_name(it->path().filename().string())) journals.push_back(it->path());
  }
  std::vector<std::string> kept;  // ids whose files must stay (a set another folder has yet to settle)
  for (const fs::path& jp : journals) {
    const Journal j = read_journal(jp);
    std::error_code rm;
    if (!j.complete) {  // torn while being written: never committed
      fs::remove(jp, rm);
      continue;
    }
    const bool primary = same_folder(j.primary, dir);
    const bool committed = primary || fs::exists(journal_path(j.primary, j.id), rm);
    if (!committed) {  // a copy written before the commit: the set never happened
      fs::remove(jp, rm);
      continue;
    }
    roll_forward_in(j, dir);
    if (!primary) {
      fs::remove(jp, rm);
      continue;
    }
    // The commit record goes last, once no other folder's copy is left.
    bool all = true;
    for (const fs::path& other : j.folders) {
      if (same_folder(other, dir) || !fs::exists(journal_path(other, j.id), rm)) continue;
      const bool held_here = std::any_of(held.begin(), held.end(), [&](const fs::path& h) { return same_folder(h, other); });
      std::unique_ptr<FolderLock> lock;
      if (!held_here) lock = std::make_unique<FolderLock>(other, true);
      if (!held_here && !lock->locked()) {
        all = false;
        continue;
      }
      roll_forward_in(j, other);
      fs::remove(journal_path(other, j.id), rm);
      sync_folder(other);
    }
    if (all) {
      fs::remove(jp, rm);
    } else {
      kept.push_back(j.id);
    }
  }
  // Every other temporary and backup of ours here is a dead run's; so are ".NAME.tmp-PID-..." of dead PIDs
  // (the naming before output sets).
  bool changed = !journals.empty();
  std::vector<fs::path> stale;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::string id = set_file_id(name);
    if (!id.empty()) {
      if (std::find(kept.begin(), kept.end(), id) == kept.end()) stale.push_back(it->path());
      continue;
    }
    const std::size_t at = name.find(".tmp-");
    if (name.empty() || name[0] != '.' || at == std::string::npos) continue;
    long long pid = 0;
    const char* first = name.data() + at + 5;
    const auto [p, err] = std::from_chars(first, name.data() + name.size(), pid);
    if (err != std::errc() || p == first || *p != '-' || pid <= 0 || pid > INT_MAX) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) stale.push_back(it->path());
  }
  for (const fs::path& p : stale) {  // removed after the walk: a folder changed while iterated may skip entries
    std::error_code rm;
    fs::remove(p, rm);
    changed = true;
  }
  if (changed) sync_folder(dir);
}

// Writes `bytes` to `tmp` (created exclusively, fsync'd); on failure nothing is left. The Error names `target`.
Result<bool> write_new_file(const fs::path& tmp, const fs::path& target, const std::vector<char>& bytes, const char* who) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    return file_error(who, target, "cannot create a temporary file in its directory: " + errno_message(errno));
  }
  auto fail = [&](const std::string& what, int err) -> Result<bool> {
    ::close(fd);
    ::unlink(tmp.c_str());
    return file_error(who, target, what + ": " + errno_message(err));
  };
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) {
        continue;
      }
      return fail("cannot write", errno);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    return fail("cannot flush", errno);
  }
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    return file_error(who, target, "cannot close: " + errno_message(err));
  }
  return true;
}

std::string new_set_id() {
  static std::atomic<unsigned> counter{0};
  const auto ticks = static_cast<unsigned long long>(std::chrono::steady_clock::now().time_since_epoch().count());
  return std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1)) + "-" +
         std::to_string(ticks % 1000000007ULL);
}

using FileRefs = std::vector<std::pair<fs::path, const std::vector<char>*>>;

Result<bool> publish(const FileRefs& files, const PublishOptions& options, const char* who) {
  if (files.empty()) return true;
  auto step = [&](const char* name) {
    if (options.after_step) options.after_step(name);
  };
  // The folders, by real path; every target as its real folder / its name.
  std::vector<fs::path> folders;
  std::vector<fs::path> targets;
  for (const auto& f : files) {
    const fs::path& target = f.first;
    if (target.filename().empty() || target.filename() == "." || target.filename() == "..") {
      return file_error(who, target, "not a file name");
    }
    std::error_code ec;
    const fs::path dir = fs::canonical(target.parent_path().empty() ? fs::path(".") : target.parent_path(), ec);
    if (ec || !fs::is_directory(dir, ec)) {
      return file_error(who, target, "its folder does not exist (or is not a folder)");
    }
    const fs::path real = dir / target.filename();
    if (std::find(targets.begin(), targets.end(), real) != targets.end()) {
      return file_error(who, target, "named twice in one output set");
    }
    if (fs::is_directory(fs::symlink_status(real, ec))) {
      return file_error(who, target, "cannot replace the file: it is a folder");
    }
    targets.push_back(real);
    if (std::find(folders.begin(), folders.end(), dir) == folders.end()) folders.push_back(dir);
  }
  std::sort(folders.begin(), folders.end());
  std::vector<std::unique_ptr<FolderLock>> locks;
  for (const fs::path& d : folders) locks.push_back(std::make_unique<FolderLock>(d));
  const SignalHold hold;
  for (std::size_t i = 0; i < folders.size(); ++i) {
    if (locks[i]->locked()) settle_folder(folders[i], folders);
  }
  step("locked");

  Journal j;
  j.id = new_set_id();
  j.primary = folders.front();
  j.folders = folders;
  std::vector<fs::path> temps;
  auto remove_paths = [](const std::vector<fs::path>& paths) {
    for (const fs::path& p : paths) ::unlink(p.c_str());
  };
  for (std::size_t i = 0; i < files.size(); ++i) {
    const fs::path tmp = targets[i].parent_path() / ("." + targets[i].filename().string() + set_marker + j.id + ".tmp");
    if (auto ok = write_new_file(tmp, files[i].first, *files[i].second, who); !ok) {
      remove_paths(temps);
      return ok.error();
    }
    temps.push_back(tmp);
    j.renames.emplace_back(tmp, targets[i]);
  }
  step("written");
  // The files of an older output of the same name (the caller's test), found under the lock.
  if (options.remove_also) {
    for (const fs::path& d : folders) {
      std::error_code ec;
      for (fs::directory_iterator it(d, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path p = d / it->path().filename();
        const std::string name = p.filename().string();
        if (is_journal_name(name) || !set_file_id(name).empty()) continue;
        if (std::find(targets.begin(), targets.end(), p) != targets.end()) continue;
        std::error_code st;
        if (!fs::is_regular_file(fs::symlink_status(p, st))) continue;
        if (options.remove_also(p)) j.removals.push_back(p);
      }
    }
  }
  // Hard links of the targets that exist, so that a failed rename can put them back.
  std::vector<fs::path> backups(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(targets[i], ec))) continue;
    const fs::path b = targets[i].parent_path() / ("." + targets[i].filename().string() + set_marker + j.id + ".old");
    fs::create_hard_link(targets[i], b, ec);
    if (!ec) {
      backups[i] = b;
      j.backups.push_back(b);
    }
  }
  const bool journaled = files.size() > 1 || !j.removals.empty();
  std::vector<fs::path> journals;  // the copies written, the commit record last
  if (journaled) {
    const std::string text = journal_text(j);
    const std::vector<char> bytes(text.begin(), text.end());
    for (std::size_t k = folders.size(); k-- > 0;) {  // the other folders' copies first, the primary's last
      const fs::path jp = journal_path(folders[k], j.id);
      if (auto ok = write_new_file(jp, files.front().first, bytes, who); !ok) {
        remove_paths(journals);
        remove_paths(temps);
        for (const fs::path& b : backups) ::unlink(b.c_str());
        return ok.error();
      }
      sync_folder(folders[k]);
      journals.push_back(jp);
      if (k == 1) step("prepared");
    }
  }
  step("committed");
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    fs::rename(temps[i], targets[i], ec);
    if (!ec) {
      if (i == 0) step("renamed-first");
      continue;
    }
    // Undo: the targets renamed so far go back to what they were (or away, where there was none).
    for (std::size_t k = 0; k < i; ++k) {
      std::error_code undo;
      if (!backups[k].empty()) {
        fs::rename(backups[k], targets[k], undo);
      } else {
        fs::remove(targets[k], undo);
      }
    }
    remove_paths(std::vector<fs::path>(temps.begin() + static_cast<std::ptrdiff_t>(i), temps.end()));
    remove_paths(backups);
    for (auto it = journals.rbegin(); it != journals.rend(); ++it) ::unlink(it->c_str());  // the commit record first
    for (const fs::path& d : folders) sync_folder(d);
    return file_error(who, files[i].first, "cannot replace the file: " + ec.message());
  }
  step("renamed");
  for (const fs::path& r : j.removals) {
    std::error_code ec;
    fs::remove(r, ec);
  }
  remove_paths(backups);
  if (journaled) {
    for (const fs::path& d : folders) sync_folder(d);  // the renames are on disk before the journal goes
    for (const fs::path& jp : journals) ::unlink(jp.c_str());  // the other folders' copies first, the commit record last
  }
  for (const fs::path& d : folders) sync_folder(d);
  step("done");
  return true;
}

// Writes one file through the output-set mechanism above.
Result<bool> write_atomically(const fs::path& target, const std::vector<char>& bytes, const char* who) {
  return publish(FileRefs{{target, &bytes}}, {}, who);
}

}  // namespace

Result<bool> check_exr_header(const fs::path& path, const char* who) {
  if (std::string why = exr_header_problem(path); !why.empty()) return file_error(who, path, why);
  return true;
}

std::string exr_header_problem(const fs::path& path) {
  auto fail = [](const std::string& why) { return why; };
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("cannot open the file");
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return fail("cannot read file size: " + ec.message());
  std::uint64_t pos = 0;
  auto read_bytes = [&](unsigned char* out, std::size_t n) {
    if (!in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n))) return false;
    pos += n;
    return true;
  };
  unsigned char head[8];
  if (size < 8 || !read_bytes(head, 8)) return fail("not an OpenEXR file (shorter than its 8-byte magic number and version)");
  if (head[0] != 0x76 || head[1] != 0x2f || head[2] != 0x31 || head[3] != 0x01) return fail("not an OpenEXR file (no magic number)");
  const std::uint32_t flags = static_cast<std::uint32_t>(head[5]) | static_cast<std::uint32_t>(head[6]) << 8u |
                              static_cast<std::uint32_t>(head[7]) << 16u;
  const bool long_names = (flags & 0x4u) != 0;  // version bit 10: names up to 255 bytes, else 31
  const bool multipart = (flags & 0x10u) != 0;  // version bit 12: headers until an empty one
  const std::size_t max_name = long_names ? 255 : 31;
  // A NUL-terminated name or type of at most max_name bytes; "" at the end of a header.
  auto read_name = [&](std::string& out, const char* what, const std::string& attribute) -> std::string {
    out.clear();
    for (;;) {
      unsigned char c = 0;
      if (!read_bytes(&c, 1)) return fail(std::string("the header ends inside ") + what + attribute + " (a truncated file)");
      if (c == 0) return {};
      if (out.size() == max_name) {
        return fail(std::string(what) + attribute + " '" + printable(out, 80) + "...' is longer than " + std::to_string(max_name) + " bytes");
      }
      out.push_back(static_cast<char>(c));
    }
  };
  for (;;) {  // each header of the file
    int attributes = 0;
    for (;; ++attributes) {
      std::string name, type;
      if (auto why = read_name(name, "an attribute name", ""); !why.empty()) return why;
      if (name.empty()) break;
      const std::string quoted = " of attribute '" + printable(name, 80) + "'";
      if (auto why = read_name(type, "the type", quoted); !why.empty()) return why;
      unsigned char b[4];
      if (!read_bytes(b, 4)) return fail("the header ends inside the size" + quoted + " (a truncated file)");
      const auto claimed = static_cast<std::int32_t>(static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8u |
                                                     static_cast<std::uint32_t>(b[2]) << 16u | static_cast<std::uint32_t>(b[3]) << 24u);
      const std::uint64_t left = size > pos ? size - pos : 0;
      if (claimed < 0 || static_cast<std::uint64_t>(claimed) > left) {
        return fail("header attribute '" + printable(name, 80) + "' (type '" + printable(type, 80) + "') claims " +
                    std::to_string(claimed) + " bytes, but the file has " + std::to_string(left) + " left after it");
      }
      in.seekg(claimed, std::ios::cur);
      pos += static_cast<std::uint64_t>(claimed);
      if (!in) return fail("cannot read the header");
    }
    // A single-part file has one header; a multi-part file's list of headers ends with an empty one.
    if (!multipart || attributes == 0) break;
  }
  return {};
}

Result<Image> read_image(const fs::path& path, ReadInfo* info) { return read_image(path, info, image_read_budget_bytes); }

Result<bool> check_radiance(const fs::path& path, const Image& image, const ReadInfo& info) {
  static constexpr const char* channel_names[] = {"R", "G", "B"};
  const auto where = [](const ReadInfo::Texel& t) {
    return "texel (" + std::to_string(t.x) + ", " + std::to_string(t.y) + ") channel " +
           channel_names[std::clamp(t.channel, 0, 2)];
  };
  const auto number = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return std::string(text);
  };
  if (info.nonfinite_repaired > 0) {
    const float v = info.first_nonfinite.value;
    return read_error(path, where(info.first_nonfinite) + " is " + (std::isnan(v) ? "NaN" : v > 0 ? "+Inf" : "-Inf") +
                                " (" + std::to_string(info.nonfinite_repaired) +
                                " non-finite values); radiance must be finite and not negative");
  }
  if (info.negative_values == 0) return true;
  double sum = 0.0;
  for (const float v : image.data) sum += static_cast<double>(v);
  const double mean = image.data.empty() ? 0.0 : sum / static_cast<double>(image.data.size());
  const double floor = -radiance_negative_tolerance * std::max(mean, 0.0);
  const std::size_t w = static_cast<std::size_t>(std::max(image.width, 1));
  for (std::size_t i = 0; i < image.data.size(); ++i) {
    const double v = static_cast<double>(image.data[i]);
    if (!(v < floor) && !(v < 0.0 && mean <= 0.0)) continue;
    const ReadInfo::Texel t{static_cast<int>((i / 3) % w), static_cast<int>((i / 3) / w), static_cast<int>(i % 3),
                            image.data[i]};
    return read_error(path, where(t) + " is " + number(v) + ", below -" + number(radiance_negative_tolerance) +
                                " x the map's mean value " + number(mean) +
                                " (the most lossy compression leaves); radiance must be finite and not negative");
  }
  return true;
}

Result<Image> read_radiance_image(const fs::path& path, ReadInfo* info, std::uint64_t budget_bytes) {
  ReadInfo local;
  auto image = read_image(path, &local, budget_bytes);
  if (!image) return image;
  if (auto ok = check_radiance(path, *image, local); !ok) return ok.error();
  if (info != nullptr) *info = local;
  return image;
}

Result<Image> read_image(const fs::path& path, ReadInfo* info, std::uint64_t budget_bytes) {
  return read_image(path, info, budget_bytes, PngSamples::srgb);
}

Result<Image> read_image(const fs::path& path, ReadInfo* info, std::uint64_t budget_bytes, PngSamples png) {
  const std::uint64_t budget = std::min(budget_bytes, image_read_budget_bytes);
  const Format format = format_of(path);
  if (format == Format::unknown) {
    return read_error(path, unknown_extension_reason());
  }
  if (png == PngSamples::alpha && format != Format::png) {
    return read_error(path, "an alpha channel is read from PNG files only");
  }
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) {
    return read_error(path, "no such file");
  }
  if (!fs::is_regular_file(status)) {
    return read_error(path, "not a regular file");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) {
    return read_error(path, "cannot read file size: " + ec.message());
  }
  if (size == 0) {
    return read_error(path, "file is empty");
  }

  ReadInfo local;
  try {
    Result<Image> image = make_error("");
    switch (format) {
      case Format::exr:
        local.format = "exr";
        image = read_exr(path, local, budget);
        break;
      case Format::hdr:
        local.format = "hdr";
        image = read_hdr(path, local, budget);
        break;
      case Format::png:
        local.format = "png";
        image = read_png(path, local, budget, png);
        break;
      case Format::unknown:
        break;
    }
    if (!image) {
      return image;
    }
    repair_and_count(image.value(), local);
    if (info != nullptr) {
      *info = std::move(local);
    }
    return image;
  } catch (const std::bad_alloc&) {
    return read_error(path, "out of memory while decoding (the image is within the budget; the machine's memory is not)");
  } catch (const std::exception& e) {
    // OpenEXR reports corrupt and truncated files by throwing (Iex::BaseExc derives from std::exception).
    return read_error(path, e.what());
  } catch (...) {
    return read_error(path, "unknown error while decoding");
  }
}

Result<Rgba8Image> decode_rgba8(const std::vector<unsigned char>& bytes, const std::string& name) {
  const fs::path path(name);
  static constexpr unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};  // PNG spec 5.2
  const bool png = bytes.size() >= 8 && std::equal(png_signature, png_signature + 8, bytes.begin());
  const bool jpeg = bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;  // JPEG SOI + marker
  if (!png && !jpeg) return read_error(path, "not a PNG or JPEG image");
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) return read_error(path, "image is too large (over 2 GiB)");
  if (png) {
    if (auto ok = check_png_chunks(path, bytes); !ok) return ok.error();
  }
  if (auto ok = check_stb_size(path, bytes, png ? "PNG" : "JPEG"); !ok) return ok.error();
  if (png) {
    if (auto ok = check_palette_indices(path, bytes); !ok) return ok.error();
  }
  int w = 0;
  int h = 0;
  int n = 0;
  std::unique_ptr<stbi_uc, StbiFree> pixels(
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &n, 4));
  if (!pixels) return read_error(path, std::string("corrupt or truncated ") + (png ? "PNG" : "JPEG") + " (" + stb_reason() + ")");
  Rgba8Image image;
  image.width = w;
  image.height = h;
  image.rgba.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  return image;
}

Result<std::vector<char>> encode_png_rgba8(const Rgba8Image& image, const fs::path& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4) {
    return write_error(path, "RGBA image of inconsistent size");
  }
  std::vector<char> bytes;
  if (stbi_write_png_to_func(append_bytes, &bytes, image.width, image.height, 4, image.rgba.data(), image.width * 4) == 0) {
    return write_error(path, "cannot encode PNG data");
  }
  return bytes;
}

Result<bool> write_file_atomically(const fs::path& path, const std::vector<char>& bytes) {
  try {
    return write_atomically(path, bytes, "write_file_atomically");
  } catch (const std::exception& e) {  // std::bad_alloc from the path strings, at worst
    return file_error("write_file_atomically", path, e.what());
  }
}

Result<bool> write_files_atomically(const std::vector<std::pair<fs::path, std::vector<char>>>& files,
                                   const PublishOptions& options) {
  try {
    FileRefs refs;
    for (const auto& f : files) refs.emplace_back(f.first, &f.second);
    return publish(refs, options, "write_files_atomically");
  } catch (const std::exception& e) {  // std::bad_alloc from the path strings, at worst
    return file_error("write_files_atomically", files.empty() ? fs::path() : files.front().first, e.what());
  }
}

Result<std::vector<char>> encode_image(const Image& image, const fs::path& path, const WriteOptions& options) {
  const Format format = format_of(path);
  if (format == Format::unknown) {
    return write_error(path, unknown_extension_reason());
  }
  if (!image.is_valid()) {
    return write_error(path, "image is empty or its data size does not match " + std::to_string(image.width) +
                                 " x " + std::to_string(image.height) + " x 3");
  }
  if (!std::isfinite(options.exposure)) {
    return write_error(path, "exposure must be finite");
  }
  try {
    switch (format) {
      case Format::exr:
        return encode_exr(image, options);
      case Format::hdr:
        return encode_hdr(image, path);
      case Format::png:
        return encode_png(image, path, options.exposure, options.png_samples);
      case Format::unknown:
        break;
    }
    return write_error(path, unknown_extension_reason());
  } catch (const std::exception& e) {
    return write_error(path, e.what());
  } catch (...) {
    return write_error(path, "unknown error while encoding");
  }
}

Result<bool> write_image(const Image& image, const fs::path& path, const WriteOptions& options) {
  auto bytes = encode_image(image, path, options);
  if (!bytes) {
    return bytes.error();
  }
  try {
    return write_atomically(path, *bytes, "write_image");
  } catch (const std::exception& e) {
    return write_error(path, e.what());
  } catch (...) {
    return write_error(path, "unknown error while writing");
  }
}

}  // namespace shadelab
