#include "shadelab/brdf/game_lobe.h"

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/microfacet.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {

double phong_exponent_from_alpha(double perceptual_roughness) {
  return phong_exponent_from_ggx_alpha(alpha_from_perceptual_roughness(perceptual_roughness));
}

GameLobe game_lobe(const Brdf& f) {
  GameLobe info;
  info.exponent = f.game_phong_exponent();
  info.blinn_like = f.gloss_exponent_is_blinn_phong();
  info.wrap = f.game_wrap();
  constexpr int bins = kernel::GAME_ALBEDO_BINS;
  for (int b = 0; b < bins; ++b) {
    const double c = (b + 0.5) / bins;
    const Vec3 wo{std::sqrt(1.0 - c * c), 0.0, c};
    Pcg32 rng(1234, static_cast<std::uint64_t>(b));
    Rgb sum;
    const int samples = 4096;
    for (int s = 0; s < samples; ++s) {
      sum += f.sample(wo, {rng.next_double(), rng.next_double()}, rng.next_double()).weight;
    }
    const Rgb spec = sum / samples - f.diffuse_albedo();
    info.specular_albedo[static_cast<std::size_t>(b)] = {std::max(0.0, spec.r), std::max(0.0, spec.g), std::max(0.0, spec.b)};
  }
  return info;
}

kernel::GameSpecularAlbedo game_specular_albedo_table(const GameLobe& lobe) {
  kernel::GameSpecularAlbedo t;
  for (std::size_t b = 0; b < lobe.specular_albedo.size(); ++b) t.bin[b] = lobe.specular_albedo[b];
  return t;
}

}  // namespace shadelab
