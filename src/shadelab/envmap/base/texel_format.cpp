#include "shadelab/envmap/base/texel_format.h"

#include <Imath/half.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace shadelab {

const char* texel_format_name(TexelFormat f) {
  switch (f) {
    case TexelFormat::rgba16f: return "rgba16f";
    case TexelFormat::rgba32f: return "rgba32f";
    case TexelFormat::rg11b10f: return "rg11b10f";
    case TexelFormat::rgb9e5: return "rgb9e5";
  }
  return "?";
}

std::optional<TexelFormat> parse_texel_format(const std::string& name) {
  for (TexelFormat f : all_texel_formats) {
    if (name == texel_format_name(f)) return f;
  }
  return std::nullopt;
}

std::uint32_t texel_bytes(TexelFormat f) {
  switch (f) {
    case TexelFormat::rgba16f: return 8;
    case TexelFormat::rgba32f: return 16;
    case TexelFormat::rg11b10f:
    case TexelFormat::rgb9e5: return 4;
  }
  return 0;
}

// VkFormat enumerants (Vulkan 1.3, VkFormat).
std::uint32_t vk_format(TexelFormat f) {
  switch (f) {
    case TexelFormat::rgba16f: return 97;
    case TexelFormat::rgba32f: return 109;
    case TexelFormat::rg11b10f: return 122;
    case TexelFormat::rgb9e5: return 123;
  }
  return 0;
}

const char* vk_format_name(TexelFormat f) {
  switch (f) {
    case TexelFormat::rgba16f: return "VK_FORMAT_R16G16B16A16_SFLOAT";
    case TexelFormat::rgba32f: return "VK_FORMAT_R32G32B32A32_SFLOAT";
    case TexelFormat::rg11b10f: return "VK_FORMAT_B10G11R11_UFLOAT_PACK32";
    case TexelFormat::rgb9e5: return "VK_FORMAT_E5B9G9R9_UFLOAT_PACK32";
  }
  return "?";
}

// DXGI_FORMAT enumerants (dxgiformat.h).
std::uint32_t dxgi_format(TexelFormat f) {
  switch (f) {
    case TexelFormat::rgba16f: return 10;
    case TexelFormat::rgba32f: return 2;
    case TexelFormat::rg11b10f: return 26;
    case TexelFormat::rgb9e5: return 67;
  }
  return 0;
}

const char* dxgi_format_name(TexelFormat f) {
  switch (f) {
    case TexelFormat::rgba16f: return "DXGI_FORMAT_R16G16B16A16_FLOAT";
    case TexelFormat::rgba32f: return "DXGI_FORMAT_R32G32B32A32_FLOAT";
    case TexelFormat::rg11b10f: return "DXGI_FORMAT_R11G11B10_FLOAT";
    case TexelFormat::rgb9e5: return "DXGI_FORMAT_R9G9B9E5_SHAREDEXP";
  }
  return "?";
}

// Float32 -> unsigned float with 5 exponent bits (bias 15) and m mantissa bits, round to nearest even
// (Vulkan 1.3 "Unsigned 11-Bit Floating-Point Numbers"; texel_format.h for the special values).
std::uint32_t encode_ufloat(float v, int m) {
  const std::uint32_t exp_all = 31u << m;
  if (std::isnan(v)) return exp_all | 1u;
  if (!(v > 0.0f)) return 0;  // zero, negative, -inf
  if (std::isinf(v)) return exp_all;
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
  const int e = static_cast<int>((bits >> 23) & 0xFF) - 127;  // unbiased float32 exponent (v > 0 is normal or subnormal)
  const std::uint32_t mant = bits & 0x7FFFFF;
  std::uint32_t val = 0;
  std::uint32_t rem = 0;
  int shift = 0;
  if (e >= -14) {  // normal in the target: E = e + 15
    shift = 23 - m;
    val = (static_cast<std::uint32_t>(e + 15) << m) | (mant >> shift);
    rem = mant & ((1u << shift) - 1u);
  } else {  // subnormal in the target: M = v 2^(14 + m), v = (2^23 + mant) 2^(e - 23)
    if (((bits >> 23) & 0xFF) == 0) return 0;  // float32 subnormals are far below the smallest target value
    const std::uint32_t full = mant | 0x800000u;
    shift = 9 - m - e;  // -(e - 23 + 14 + m)
    if (shift >= 25) return 0;  // below half the smallest subnormal
    val = full >> shift;
    rem = full & ((1u << shift) - 1u);
  }
  const std::uint32_t half = 1u << (shift - 1);
  if (rem > half || (rem == half && (val & 1u) != 0)) ++val;  // a carry moves into the exponent correctly
  if (val >= exp_all) val = exp_all - 1u;                      // finite overflow: the largest finite value
  return val;
}

float decode_ufloat(std::uint32_t bits, int m) {
  const std::uint32_t e = (bits >> m) & 31u;
  const std::uint32_t mant = bits & ((1u << m) - 1u);
  const double scale = std::ldexp(1.0, m);
  if (e == 31) return mant == 0 ? INFINITY : NAN;
  if (e == 0) return static_cast<float>(std::ldexp(mant / scale, -14));
  return static_cast<float>(std::ldexp(1.0 + mant / scale, static_cast<int>(e) - 15));
}

std::uint32_t encode_rg11b10(float r, float g, float b) {
  return encode_ufloat(r, 6) | (encode_ufloat(g, 6) << 11) | (encode_ufloat(b, 5) << 22);
}

std::array<float, 3> decode_rg11b10(std::uint32_t p) {
  return {decode_ufloat(p & 0x7FFu, 6), decode_ufloat((p >> 11) & 0x7FFu, 6), decode_ufloat(p >> 22, 5)};
}

// The shared-exponent encoding of the Vulkan 1.3 specification ("Shared Exponent"), N = 9, B = 15, Emax = 31.
std::uint32_t encode_rgb9e5(float r, float g, float b) {
  constexpr int n = 9;
  constexpr int bias = 15;
  auto clamp_c = [](float c) { return std::isnan(c) ? 0.0 : std::clamp(static_cast<double>(c), 0.0, static_cast<double>(rgb9e5_max)); };
  const double rc = clamp_c(r);
  const double gc = clamp_c(g);
  const double bc = clamp_c(b);
  const double maxc = std::max({rc, gc, bc});
  int floor_log2 = -bias - 1;
  if (maxc > 0.0) {
    int ex = 0;
    std::frexp(maxc, &ex);  // maxc = f 2^ex, f in [0.5, 1): floor(log2 maxc) = ex - 1, exactly
    floor_log2 = std::max(-bias - 1, ex - 1);
  }
  int exp_shared = floor_log2 + 1 + bias;
  const double max_s = std::floor(std::ldexp(maxc, -(exp_shared - bias - n)) + 0.5);
  if (max_s >= 512.0) ++exp_shared;
  auto mant = [&](double c) { return static_cast<std::uint32_t>(std::floor(std::ldexp(c, -(exp_shared - bias - n)) + 0.5)); };
  return mant(rc) | (mant(gc) << 9) | (mant(bc) << 18) | (static_cast<std::uint32_t>(exp_shared) << 27);
}

std::array<float, 3> decode_rgb9e5(std::uint32_t p) {
  const int e = static_cast<int>(p >> 27) - 15 - 9;
  return {static_cast<float>(std::ldexp(p & 0x1FFu, e)), static_cast<float>(std::ldexp((p >> 9) & 0x1FFu, e)),
          static_cast<float>(std::ldexp((p >> 18) & 0x1FFu, e))};
}

namespace {

template <typename T>
void put(std::vector<char>& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.insert(out.end(), b, b + sizeof(T));
}

}  // namespace

void append_texels(std::vector<char>& out, const Image& face, TexelFormat f, TexelEncodeInfo* info) {
  TexelEncodeInfo local;
  out.reserve(out.size() + face.pixel_count() * texel_bytes(f));
  for (std::size_t p = 0; p < face.pixel_count(); ++p) {
    const float* c = &face.data[3 * p];
    switch (f) {
      case TexelFormat::rgba16f:
        for (int k = 0; k < 4; ++k) {
          const float v = k < 3 ? c[k] : 1.0f;
          const float cv = std::isfinite(v) ? std::clamp(v, -half_max, half_max) : v;
          local.clamped_values += std::isfinite(v) && cv != v ? 1 : 0;
          put(out, Imath::half(cv).bits());
        }
        break;
      case TexelFormat::rgba32f:
        for (int k = 0; k < 4; ++k) put(out, k < 3 ? c[k] : 1.0f);
        break;
      case TexelFormat::rg11b10f:
      case TexelFormat::rgb9e5: {
        const bool packed11 = f == TexelFormat::rg11b10f;
        for (int k = 0; k < 3; ++k) {
          const float limit = packed11 ? (k < 2 ? ufloat11_max : ufloat10_max) : rgb9e5_max;
          if (c[k] < 0.0f || (!packed11 && std::isnan(c[k]))) {
            ++local.negative_values;
          } else if (std::isfinite(c[k]) && c[k] > limit) {
            ++local.clamped_values;
          }
        }
        put(out, packed11 ? encode_rg11b10(c[0], c[1], c[2]) : encode_rgb9e5(c[0], c[1], c[2]));
        break;
      }
    }
  }
  if (info != nullptr) {
    info->clamped_values += local.clamped_values;
    info->negative_values += local.negative_values;
  }
}

std::vector<float> decode_texels(const char* data, std::size_t count, TexelFormat f) {
  std::vector<float> rgb(3 * count);
  for (std::size_t p = 0; p < count; ++p) {
    const char* t = data + p * texel_bytes(f);
    switch (f) {
      case TexelFormat::rgba16f:
        for (int k = 0; k < 3; ++k) {
          std::uint16_t bits = 0;
          std::memcpy(&bits, t + 2 * k, 2);
          Imath::half h;
          h.setBits(bits);
          rgb[3 * p + static_cast<std::size_t>(k)] = static_cast<float>(h);
        }
        break;
      case TexelFormat::rgba32f:
        std::memcpy(&rgb[3 * p], t, 12);
        break;
      case TexelFormat::rg11b10f:
      case TexelFormat::rgb9e5: {
        std::uint32_t bits = 0;
        std::memcpy(&bits, t, 4);
        const auto v = f == TexelFormat::rg11b10f ? decode_rg11b10(bits) : decode_rgb9e5(bits);
        for (int k = 0; k < 3; ++k) rgb[3 * p + static_cast<std::size_t>(k)] = v[static_cast<std::size_t>(k)];
        break;
      }
    }
  }
  return rgb;
}

Result<bool> check_cube_chain(const std::vector<CubeMap>& levels, const std::string& what) {
  if (levels.empty() || levels[0].size < 1) return make_error(what + ": nothing to write (no mip levels)");
  if (levels.size() > 32) return make_error(what + ": " + std::to_string(levels.size()) + " mip levels, at most 32");
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const int expected = std::max(1, levels[0].size >> i);
    if (levels[i].size != expected) {
      return make_error(what + ": mip level " + std::to_string(i) + " has size " + std::to_string(levels[i].size) +
                        ", expected " + std::to_string(expected));
    }
    for (const Image& face : levels[i].faces) {
      if (face.width != expected || face.height != expected || face.data.size() != face.pixel_count() * 3) {
        return make_error(what + ": mip level " + std::to_string(i) + " has a face that is not " +
                          std::to_string(expected) + " x " + std::to_string(expected));
      }
    }
  }
  return true;
}

}  // namespace shadelab
