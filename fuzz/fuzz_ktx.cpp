// Fuzz harness: the KTX 1.1 cube-map reader (decode_ktx_cubemap, from memory). Contract checked (ktx.h): an
// error is one printable line; a decoded chain is non-empty, level i has faces of max(1, size0 >> i)
// texels, and it survives an exact round trip through the RGBA32F encoder (every value, NaN as NaN).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "harness.h"
#include "shadelab/envmap/base/ktx.h"

using namespace shadelab;

namespace {

bool same_value(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<char> bytes(reinterpret_cast<const char*>(data), reinterpret_cast<const char*>(data) + size);
  auto levels = decode_ktx_cubemap(bytes);
  if (!levels) {
    fuzz::require_one_line(levels.error().message, "");
    return 0;
  }
  if (levels->empty()) fuzz::finding("empty mip chain", "");
  const int size0 = (*levels)[0].size;
  for (std::size_t i = 0; i < levels->size(); ++i) {
    const CubeMap& level = (*levels)[i];
    const int expected = std::max(1, size0 >> i);
    if (level.size != expected) fuzz::finding("level size", std::to_string(i) + ": " + std::to_string(level.size));
    for (const Image& face : level.faces) {
      if (!face.is_valid() || face.width != expected || face.height != expected) fuzz::finding("face size", std::to_string(i));
    }
  }
  auto encoded = encode_ktx_cubemap(*levels, KtxPixelType::float32);
  if (!encoded) fuzz::finding("a decoded chain does not encode", encoded.error().message);
  auto again = decode_ktx_cubemap(*encoded);
  if (!again || again->size() != levels->size()) fuzz::finding("the RGBA32F round trip fails", again ? "" : again.error().message);
  for (std::size_t i = 0; i < levels->size(); ++i) {
    for (std::size_t f = 0; f < 6; ++f) {
      const auto& a = (*levels)[i].faces[f].data;
      const auto& b = (*again)[i].faces[f].data;
      for (std::size_t k = 0; k < a.size(); ++k) {
        if (!same_value(a[k], b[k])) fuzz::finding("the RGBA32F round trip changes a value", std::to_string(i));
      }
    }
  }
  return 0;
}
