#include "shadelab/brdf/gloss.h"

#include <algorithm>
#include <cmath>

namespace shadelab {

Result<GlossEncoding> GlossEncoding::validated() const {
  if (!std::isfinite(n_black) || !std::isfinite(n_white) || n_black <= 0.0 || n_white <= n_black) {
    return make_error("gloss encoding: need 0 < n_black < n_white (got n_black = " + std::to_string(n_black) +
                      ", n_white = " + std::to_string(n_white) + ")");
  }
  return *this;
}

double GlossEncoding::exponent_from_gloss(double g) const {
  g = std::clamp(g, 0.0, 1.0);
  return n_black * std::pow(n_white / n_black, g);  // logarithmic encoding, zoo article
}

double GlossEncoding::gloss_from_exponent(double n) const {
  if (!(n > n_black)) return 0.0;
  return std::clamp(std::log(n / n_black) / std::log(n_white / n_black), 0.0, 1.0);
}

std::uint8_t GlossEncoding::texel_from_exponent(double n) const {
  return static_cast<std::uint8_t>(std::lround(gloss_from_exponent(n) * 255.0));
}

}  // namespace shadelab
