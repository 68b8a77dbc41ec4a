// shadelab game lobes: what game shading's environment lighting needs to know of a material's BRDF
// (render/game_renderer.h, "specular ambient"; kernels/game_ambient.sl), computed once per material and
// shared by the game renderer and the browser explorer (web/), so that both light a material from the same
// numbers.
//
// Contract:
// - game_phong_exponent(model, p): the Phong exponent whose lobe (R.L)^n matches the model's specular lobe,
//   which picks the prefiltered cube's level. Blinn-Phong-like lobes (N.H)^n have n/4
//   (phong_exponent_from_blinn_phong, brdf/gloss.h); Beckmann roughness m and Ward's alpha convert to a
//   Blinn-Phong exponent by n = 2/m^2 - 2 (exponent_from_beckmann_m, microfacet.h), the anisotropic Ward by
//   the mean of its two alphas; Lafortune by its first lobe's exponent; GGX by its alpha (the geometric mean
//   of alpha_x and alpha_y) as a Beckmann m; Filament by alpha = perceptual_roughness^2. 0 for a model without a specular lobe
//   (no specular ambient then).
// - game_lobe(model, p, f): that exponent; whether a gloss map's exponent is a Blinn-Phong one (blinn_like);
//   the wrap of wrapped diffuse (0 otherwise); and the specular lobe's directional albedo rho_s at
//   cos(theta_o) = (b + 0.5) / GAME_ALBEDO_BINS for each bin b: the mean of f's sample weights over 4096
//   draws of its own sampler (PCG32 seeded (1234, b), so the table is the same on every run and machine)
//   minus the diffuse albedo, clamped at 0.
// - ggx_split_sum_lobe(f): the split-sum description of a ggx or filament BRDF (below).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "shadelab/brdf/brdf.h"
#include "shadelab/brdf/params.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

struct GameLobe {
  double exponent = 0.0;
  bool blinn_like = false;
  double wrap = 0.0;
  double roughness_factor = 1.0;  // perceptual roughness that a metallic-roughness texture multiplies (renderer)
  std::array<Rgb, kernel::GAME_ALBEDO_BINS> specular_albedo{};
};

double game_phong_exponent(const std::string& model, const ParamValues& p);

// The prefiltered level's Phong exponent for a GGX-like lobe of perceptual roughness r (alpha = r^2).
double phong_exponent_from_alpha(double perceptual_roughness);

GameLobe game_lobe(const std::string& model, const ParamValues& p, const Brdf& f);

// The table as the kernel takes it.
kernel::GameSpecularAlbedo game_specular_albedo_table(const GameLobe& lobe);

// What the split-sum specular ambient (kernels/game_ambient.sl game_split_sum_specular) needs of a
// microfacet-GGX BRDF (the ggx and filament models), read from the BRDF itself (so a textured hit's own
// roughness and f0 are used):
// - roughness: the perceptual roughness sqrt(alpha), alpha = sqrt(alpha_x alpha_y) for an anisotropic ggx (an
//   approximation, as engines do);
// - f0, f90: Schlick's reflectance at normal incidence and at grazing, times ggx's ks tint. ggx: f = schlick
//   gives f0, f = none gives f0 = 1, f = dielectric / conductor their exact F at normal incidence (the DFG
//   table's Schlick is then an approximation of the exact Fresnel curve); f90 = ks. filament: its f0, f90 = 1;
// - the energy terms the model adds: filament's compensation (filament_energy_compensation) or ggx's Kulla-Conty
//   lobe (ggx_ms_albedo), which the renderer evaluates with E = A + B of its DFG table.
// The DFG table is the height-correlated Smith G2: for ggx with g = smith-separable the split sum uses it
// anyway (an approximation). nullopt for any other BRDF.
struct GgxSplitSumLobe {
  double roughness = 0.0;
  Rgb f0;
  Rgb f90;
  const kernel::FilamentState* filament = nullptr;  // energy compensation on: its state
  const kernel::GgxState* ggx_ms = nullptr;          // Kulla-Conty lobe on: its state
};
std::optional<GgxSplitSumLobe> ggx_split_sum_lobe(const Brdf& f);

}  // namespace shadelab
