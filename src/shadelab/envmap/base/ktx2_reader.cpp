#include "shadelab/envmap/base/ktx2_reader.h"

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <system_error>

#include "shadelab/envmap/base/texel_format.h"

namespace shadelab {

namespace {

constexpr std::array<unsigned char, 12> kIdentifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{1} << 30;

std::uint32_t u32(const std::vector<char>& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);  // little-endian host (the project's platforms)
  return v;
}
std::uint64_t u64(const std::vector<char>& b, std::size_t at) {
  std::uint64_t v = 0;
  std::memcpy(&v, b.data() + at, 8);
  return v;
}

struct Format {
  std::uint32_t bytes = 0;  // per texel
  bool ok = false;
};
Format format_of(std::uint32_t vk) {
  switch (vk) {
    case 97: return {8, true};    // R16G16B16A16_SFLOAT
    case 109: return {16, true};  // R32G32B32A32_SFLOAT
    case 122: return {4, true};   // B10G11R11_UFLOAT_PACK32
    case 123: return {4, true};   // E5B9G9R9_UFLOAT_PACK32
    case 83: return {4, true};    // R16G16_SFLOAT
    default: return {};
  }
}

// Decodes `count` texels of the format into RGBA floats.
void decode(const char* p, std::size_t count, std::uint32_t vk, float* out) {
  if (vk == 83) {
    for (std::size_t i = 0; i < count; ++i) {
      std::uint16_t r = 0, g = 0;
      std::memcpy(&r, p + 4 * i, 2);
      std::memcpy(&g, p + 4 * i + 2, 2);
      Imath::half hr, hg;
      hr.setBits(r);
      hg.setBits(g);
      out[4 * i] = static_cast<float>(hr);
      out[4 * i + 1] = static_cast<float>(hg);
      out[4 * i + 2] = 0.0f;
      out[4 * i + 3] = 1.0f;
    }
    return;
  }
  if (vk == 97) {  // keep the stored alpha
    for (std::size_t i = 0; i < 4 * count; ++i) {
      std::uint16_t v = 0;
      std::memcpy(&v, p + 2 * i, 2);
      Imath::half h;
      h.setBits(v);
      out[i] = static_cast<float>(h);
    }
    return;
  }
  if (vk == 109) {
    std::memcpy(out, p, 16 * count);
    return;
  }
  const TexelFormat f = vk == 122 ? TexelFormat::rg11b10f : TexelFormat::rgb9e5;
  const std::vector<float> rgb = decode_texels(p, count, f);
  for (std::size_t i = 0; i < count; ++i) {
    out[4 * i] = rgb[3 * i];
    out[4 * i + 1] = rgb[3 * i + 1];
    out[4 * i + 2] = rgb[3 * i + 2];
    out[4 * i + 3] = 1.0f;
  }
}

}  // namespace

std::string Ktx2Texture::value(const std::string& key) const {
  for (const auto& [k, v] : metadata) {
    if (k == key) return v;
  }
  return {};
}

Result<Ktx2Texture> parse_ktx2(const std::vector<char>& b, const std::string& name) {
  const auto fail = [&](const std::string& what) { return make_error(name + ": " + what); };
  if (b.size() < 80 || std::memcmp(b.data(), kIdentifier.data(), kIdentifier.size()) != 0) {
    return fail("not a KTX 2 file (no KTX 20 identifier)");
  }
  Ktx2Texture t;
  t.vk_format = u32(b, 12);
  const std::uint32_t width = u32(b, 20), height = u32(b, 24), depth = u32(b, 28);
  const std::uint32_t layers = u32(b, 32), faces = u32(b, 36), level_count = u32(b, 40), scheme = u32(b, 44);
  const Format fmt = format_of(t.vk_format);
  if (!fmt.ok) return fail("vkFormat " + std::to_string(t.vk_format) + " is not one this reader decodes (97, 109, 122, 123, 83)");
  if (scheme != 0) return fail("supercompressionScheme " + std::to_string(scheme) + " is not supported (only 0, none)");
  if (depth != 0) return fail("pixelDepth " + std::to_string(depth) + ": only 2D textures are read");
  if (layers != 0) return fail("layerCount " + std::to_string(layers) + ": array textures are not read");
  if (faces != 1 && faces != 6) return fail("faceCount " + std::to_string(faces) + " (must be 1 or 6)");
  if (width < 1 || width > 16384 || height < 1 || height > 16384) {
    return fail("pixelWidth x pixelHeight " + std::to_string(width) + " x " + std::to_string(height) + " is out of range [1, 16384]");
  }
  if (faces == 6 && width != height) return fail("a cube map's faces must be square");
  const std::uint32_t levels = std::max<std::uint32_t>(1, level_count);
  if (levels > 32 || (1ull << (levels - 1)) > std::max(width, height)) {
    return fail("levelCount " + std::to_string(level_count) + " is more than the size allows");
  }
  const std::size_t index_end = 80 + 24 * static_cast<std::size_t>(levels);
  if (b.size() < index_end) return fail("truncated level index");
  // Key/value data.
  const std::uint32_t kvd_offset = u32(b, 56), kvd_length = u32(b, 60);
  if (kvd_length > 0) {
    if (static_cast<std::uint64_t>(kvd_offset) + kvd_length > b.size()) return fail("kvdByteOffset + kvdByteLength is beyond the file");
    std::size_t at = kvd_offset;
    const std::size_t end = static_cast<std::size_t>(kvd_offset) + kvd_length;
    while (at + 4 <= end) {
      const std::uint32_t len = u32(b, at);
      if (len > end - at - 4) return fail("a key/value entry runs past kvdByteLength");
      const char* kv = b.data() + at + 4;
      const auto* nul = static_cast<const char*>(std::memchr(kv, '\0', len));
      if (nul == nullptr) return fail("a key/value entry has no NUL after its key");
      std::string key(kv, nul);
      std::string value(nul + 1, kv + len);
      while (!value.empty() && value.back() == '\0') value.pop_back();
      t.metadata.emplace_back(std::move(key), std::move(value));
      at += 4 + (static_cast<std::size_t>(len) + 3) / 4 * 4;
    }
  }
  t.width = static_cast<int>(width);
  t.height = static_cast<int>(height);
  t.faces = static_cast<int>(faces);
  for (std::uint32_t l = 0; l < levels; ++l) {
    const std::size_t at = 80 + 24 * static_cast<std::size_t>(l);
    const std::uint64_t offset = u64(b, at), length = u64(b, at + 8);
    const std::uint64_t w = t.level_width(static_cast<int>(l)), h = t.level_height(static_cast<int>(l));
    const std::uint64_t count = w * h * faces;
    if (length != count * fmt.bytes) {
      return fail("level " + std::to_string(l) + " byteLength " + std::to_string(length) + " is not " +
                  std::to_string(count * fmt.bytes) + " (" + std::to_string(faces) + " face(s) of " + std::to_string(w) +
                  " x " + std::to_string(h) + ")");
    }
    if (offset > b.size() || length > b.size() - offset) return fail("level " + std::to_string(l) + " lies beyond the file");
    std::vector<float> texels(4 * count);
    decode(b.data() + offset, count, t.vk_format, texels.data());
    t.levels.push_back(std::move(texels));
  }
  return t;
}

Result<Ktx2Texture> read_ktx2(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(path.string() + ": cannot read (" + ec.message() + ")");
  if (size > kMaxFileBytes) return make_error(path.string() + ": larger than 1 GiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(path.string() + ": cannot open");
  std::vector<char> bytes(static_cast<std::size_t>(size));
  if (size > 0 && !in.read(bytes.data(), static_cast<std::streamsize>(size))) return make_error(path.string() + ": read failed");
  return parse_ktx2(bytes, path.string());
}

}  // namespace shadelab
