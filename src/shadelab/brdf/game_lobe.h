// shadelab game lobes: what game shading's environment lighting needs to know of a material's BRDF
// (render/game_renderer.h, "specular ambient"; kernels/game_ambient.sl), computed once per material and
// shared by the game renderer and the browser explorer (web/), so that both light a material from the same
// numbers. Each number is the model's own answer (brdf.h: game_phong_exponent, gloss_exponent_is_blinn_phong,
// game_wrap, split_sum_inputs): nothing here or in a renderer knows a model by its name.
//
// Contract:
// - game_lobe(f): the Phong exponent whose lobe (R.L)^n matches the model's specular lobe, which picks the
//   prefiltered cube's level (each model's conversion: Blinn-Phong-like lobes (N.H)^n have n/4
//   (phong_exponent_from_blinn_phong, brdf/gloss.h); Beckmann roughness m and Ward's alpha convert to a
//   Blinn-Phong exponent by n = 2/m^2 - 2 (exponent_from_beckmann_m, microfacet.h), the anisotropic Ward by
//   the mean of its two alphas; Lafortune by its first lobe's exponent; GGX by its alpha (the geometric mean
//   of alpha_x and alpha_y) as a Beckmann m; Filament by alpha = perceptual_roughness^2; 0 for a model
//   without a specular lobe: no specular ambient then); whether a gloss map's exponent is a Blinn-Phong one
//   (blinn_like); the wrap of wrapped diffuse (0 otherwise); and the specular lobe's directional albedo
//   rho_s at cos(theta_o) = (b + 0.5) / GAME_ALBEDO_BINS for each bin b: the mean of f's sample weights over
//   4096 draws of its own sampler (PCG32 seeded (1234, b), so the table is the same on every run and
//   machine) minus the diffuse albedo, clamped at 0.
// - the split sum's inputs of a microfacet-GGX model: f.split_sum_inputs() (brdf.h SplitSumInputs).
#pragma once

#include <array>

#include "shadelab/brdf/brdf.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

struct GameLobe {
  double exponent = 0.0;
  bool blinn_like = false;
  double wrap = 0.0;
  double roughness_factor = 1.0;  // perceptual roughness that a metallic-roughness texture multiplies (renderer)
  std::array<Rgb, kernel::GAME_ALBEDO_BINS> specular_albedo{};
};

// The Phong chain's exponent for a GGX-like lobe of perceptual roughness r (alpha = r^2, microfacet.h).
double phong_exponent_from_alpha(double perceptual_roughness);

GameLobe game_lobe(const Brdf& f);

// The table as the kernel takes it.
kernel::GameSpecularAlbedo game_specular_albedo_table(const GameLobe& lobe);

}  // namespace shadelab
