// shadelab sRGB decode tables (see srgb.h for the contract).
#include "shadelab/image/srgb.h"

namespace shadelab {

const std::array<float, 256>& srgb8_to_linear_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int k = 0; k < 256; ++k) {
      t[static_cast<std::size_t>(k)] = static_cast<float>(srgb_to_linear(k / 255.0));  // code k -> V = k / 255
    }
    return t;
  }();
  return table;
}

const std::vector<float>& srgb16_to_linear_table() {
  static const std::vector<float> table = [] {
    std::vector<float> t(65536);
    for (int k = 0; k < 65536; ++k) {
      t[static_cast<std::size_t>(k)] = static_cast<float>(srgb_to_linear(k / 65535.0));  // code k -> V = k / 65535
    }
    return t;
  }();
  return table;
}

}  // namespace shadelab
