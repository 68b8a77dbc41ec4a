// shadelab image files: OpenEXR through the OpenEXR library, PNG and RGBE writing through stb, RGBE reading
// through rgbe.h (see image_io.h for the contract, docs/images.md for the reasons).
#include "shadelab/image/image_io.h"

#include <fcntl.h>
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
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <memory>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

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
  return s.empty() ? std::string("unknown error") : s;
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
void repair_and_count(Image& image, ReadInfo& info) {
  int nonfinite = 0;
  int negative = 0;
  for (float& v : image.data) {
    if (!std::isfinite(v)) {
      v = 0.0f;
      ++nonfinite;
    } else if (v < 0.0f) {
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

// Copies the part of an RGB float buffer covering `data_window` that lies inside `display_window` into
// `image`, whose pixel (0, 0) is display_window.min.
void copy_into_display(const std::vector<float>& buffer, const Imath::Box2i& data_window,
                       const Imath::Box2i& display_window, Image& image) {
  const int x0 = std::max(data_window.min.x, display_window.min.x);
  const int x1 = std::min(data_window.max.x, display_window.max.x);
  const int y0 = std::max(data_window.min.y, display_window.min.y);
  const int y1 = std::min(data_window.max.y, display_window.max.y);
  if (x0 > x1 || y0 > y1) {
    return;
  }
  const auto buffer_width = static_cast<std::size_t>(box_width(data_window));
  const auto row_floats = static_cast<std::size_t>(x1 - x0 + 1) * 3;
  for (int y = y0; y <= y1; ++y) {
    const std::size_t src = (static_cast<std::size_t>(y - data_window.min.y) * buffer_width +
                             static_cast<std::size_t>(x0 - data_window.min.x)) * 3;
    const std::size_t dst = image.index(x0 - display_window.min.x, y - display_window.min.y);
    std::copy_n(buffer.begin() + static_cast<std::ptrdiff_t>(src), row_floats,
                image.data.begin() + static_cast<std::ptrdiff_t>(dst));
  }
}

// Luminance/chroma files (Y, RY, BY, subsampled chroma) hold half data; RgbaInputFile converts them to RGB.
Result<Image> read_exr_luminance_chroma(const fs::path& path, const Imath::Box2i& display_window,
                                        ReadInfo& info) {
  Imf::RgbaInputFile file(path.c_str());
  const Imath::Box2i data_window = file.dataWindow();
  const auto w = static_cast<std::size_t>(box_width(data_window));
  const auto h = static_cast<std::size_t>(box_height(data_window));
  std::vector<Imf::Rgba> pixels(w * h);
  file.setFrameBuffer(Imf::ComputeBasePointer(pixels.data(), data_window), 1, w);
  file.readPixels(data_window.min.y, data_window.max.y);
  std::vector<float> buffer(w * h * 3);
  for (std::size_t i = 0; i < w * h; ++i) {
    buffer[3 * i] = static_cast<float>(pixels[i].r);
    buffer[3 * i + 1] = static_cast<float>(pixels[i].g);
    buffer[3 * i + 2] = static_cast<float>(pixels[i].b);
  }
  Image image(static_cast<int>(box_width(display_window)), static_cast<int>(box_height(display_window)));
  copy_into_display(buffer, data_window, display_window, image);
  info.sample_type = "half";
  info.grey = false;
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

Result<Image> read_exr(const fs::path& path, ReadInfo& info) {
  Imf::InputFile file(path.c_str());
  const Imf::Header& header = file.header();
  const Imath::Box2i display_window = header.displayWindow();
  const Imath::Box2i data_window = header.dataWindow();
  const long long width = box_width(display_window);
  const long long height = box_height(display_window);
  if (width <= 0 || height <= 0 || box_width(data_window) <= 0 || box_height(data_window) <= 0) {
    return read_error(path, "image has zero size");
  }
  if (width * height > max_image_pixels ||
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
    return read_exr_luminance_chroma(path, display_window, info);
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

  Image image(static_cast<int>(width), static_cast<int>(height));
  // Read straight into the image when the data window lies inside the display window (the usual case);
  // otherwise into a buffer over the data window, copied afterwards.
  const bool direct = box_contains(display_window, data_window);
  std::vector<float> buffer;
  if (!direct) {
    buffer.assign(static_cast<std::size_t>(box_width(data_window) * box_height(data_window)) * 3, 0.0f);
  }
  float* base = direct ? image.data.data() : buffer.data();
  const Imath::Box2i& base_window = direct ? display_window : data_window;
  const std::size_t x_stride = 3 * sizeof(float);
  const std::size_t y_stride = x_stride * static_cast<std::size_t>(box_width(base_window));
  Imf::FrameBuffer frame_buffer;
  const char* names_rgb[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    const char* name = rgb ? names_rgb[c] : (c == 0 ? "Y" : nullptr);
    if (name == nullptr) {
      continue;
    }
    // A channel named here but absent from the file is filled with 0 by OpenEXR.
    frame_buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, base + c, base_window.min, box_width(base_window),
                                               box_height(base_window), x_stride, y_stride, 1, 1, 0.0));
  }
  file.setFrameBuffer(frame_buffer);
  file.readPixels(data_window.min.y, data_window.max.y);
  if (!direct) {
    copy_into_display(buffer, data_window, display_window, image);
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

std::vector<std::uint16_t> to_half_bits(const std::vector<float>& values) {
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
Result<Image> read_hdr(const fs::path& path, ReadInfo& info) {
  auto bytes = read_bytes(path);
  if (!bytes) {
    return bytes.error();
  }
  Result<Image> image = decode_rgbe(bytes->data(), bytes->size(), max_image_pixels);
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

Result<Image> read_png(const fs::path& path, ReadInfo& info) {
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
  Image image;
  if (sixteen) {
    std::unique_ptr<stbi_us, StbiFree> pixels(stbi_load_16_from_memory(bytes->data(), size, &w, &h, &n, 0));
    if (!pixels) {
      return read_error(path, "corrupt or truncated PNG file (" + stb_reason() + ")");
    }
    image = Image(w, h);
    decode_srgb(pixels.get(), n, srgb16_to_linear_table().data(), image);
  } else {
    std::unique_ptr<stbi_uc, StbiFree> pixels(stbi_load_from_memory(bytes->data(), size, &w, &h, &n, 0));
    if (!pixels) {
      return read_error(path, "corrupt or truncated PNG file (" + stb_reason() + ")");
    }
    image = Image(w, h);
    decode_srgb(pixels.get(), n, srgb8_to_linear_table().data(), image);
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

Result<std::vector<char>> encode_png(const Image& image, const fs::path& path, double exposure) {
  const double scale = std::exp2(exposure);  // exposure in stops: a factor of 2^exposure
  std::vector<std::uint8_t> codes(image.data.size());
  std::transform(image.data.begin(), image.data.end(), codes.begin(),
                 [scale](float v) { return linear_to_srgb8(static_cast<double>(v) * scale); });
  std::vector<char> bytes;
  if (stbi_write_png_to_func(append_bytes, &bytes, image.width, image.height, 3, codes.data(), image.width * 3) ==
      0) {
    return write_error(path, "cannot encode PNG data");
  }
  return bytes;
}

// ---------------------------------------------------------------------------------------------- atomic write

// Writes `bytes` to a new temporary file beside `target` (created exclusively, flushed with fsync), then
// renames it over `target`. On any failure the temporary is removed and `target` is untouched. `who` starts
// the error message.
Result<bool> write_atomically(const fs::path& target, const std::vector<char>& bytes, const char* who) {
  static std::atomic<unsigned> counter{0};
  const auto ticks = static_cast<unsigned long long>(std::chrono::steady_clock::now().time_since_epoch().count());
  const std::string tmp_name = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                               std::to_string(counter.fetch_add(1)) + "-" + std::to_string(ticks % 1000000007ULL);
  const fs::path tmp = target.parent_path() / tmp_name;

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
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    ::unlink(tmp.c_str());
    return file_error(who, target, "cannot replace the file: " + ec.message());
  }
  return true;
}

}  // namespace

Result<Image> read_image(const fs::path& path, ReadInfo* info) {
  const Format format = format_of(path);
  if (format == Format::unknown) {
    return read_error(path, unknown_extension_reason());
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
        image = read_exr(path, local);
        break;
      case Format::hdr:
        local.format = "hdr";
        image = read_hdr(path, local);
        break;
      case Format::png:
        local.format = "png";
        image = read_png(path, local);
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
  } catch (const std::exception& e) {
    // OpenEXR reports corrupt and truncated files by throwing (Iex::BaseExc derives from std::exception).
    return read_error(path, e.what());
  } catch (...) {
    return read_error(path, "unknown error while decoding");
  }
}

Result<bool> write_file_atomically(const fs::path& path, const std::vector<char>& bytes) {
  try {
    return write_atomically(path, bytes, "write_file_atomically");
  } catch (const std::exception& e) {  // std::bad_alloc from the path strings, at worst
    return file_error("write_file_atomically", path, e.what());
  }
}

Result<bool> write_image(const Image& image, const fs::path& path, const WriteOptions& options) {
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
    std::vector<char> bytes;
    switch (format) {
      case Format::exr:
        bytes = encode_exr(image, options);
        break;
      case Format::hdr: {
        auto encoded = encode_hdr(image, path);
        if (!encoded) {
          return encoded.error();
        }
        bytes = std::move(encoded.value());
        break;
      }
      case Format::png: {
        auto encoded = encode_png(image, path, options.exposure);
        if (!encoded) {
          return encoded.error();
        }
        bytes = std::move(encoded.value());
        break;
      }
      case Format::unknown:
        break;
    }
    return write_atomically(path, bytes, "write_image");
  } catch (const std::exception& e) {
    return write_error(path, e.what());
  } catch (...) {
    return write_error(path, "unknown error while encoding");
  }
}

}  // namespace shadelab
