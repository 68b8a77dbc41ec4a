// shadelab shininess conversion: the microfacet roughness that best matches a Phong-family specular lobe of
// exponent n, and what the published mappings give beside it.
//
// The lobes compared: the source model (phong, blinn-phong or blinn-phong-modified, with the registry's default
// normalization, "exact", the zoo's; or blinn-phong-microfacet: the registry's cook-torrance with d = blinn-phong,
// g = smith, f = none, Blinn-Phong's D inside the microfacet model) with kd = 0 and ks = 1; the target (ggx: the registry's ggx; beckmann: the
// registry's cook-torrance with d = beckmann, g = smith, form = microfacet) with kd = 0, ks = 1 and Fresnel off
// (f = none: F = 1, so that only the lobe's shape and the target's own masking-shadowing differ), its roughness
// alpha the one free parameter, fitted by fit_model under a metric (fit/metric.h) on the fitter's grid.
//
// The published mappings, each as its source writes it (r: a perceptual roughness, alpha = r^2):
//   walter:  alpha = sqrt(2 / (n + 2))                 Walter, Marschner, Li & Torrance 2007, eq. 29 (Beckmann vs
//                                                      Phong-style D; used for GGX too)
//   cod:     g = log(n) / log(8192), r = 1 - g         Lazarov 2013, "Getting More Physical in Call of Duty: Black Ops
//                                                      II" (n = 8192^g), read as roughness = 1 - gloss; g clamped to [0, 1]
//   godot:   r = 1 - sqrt(1 - log2(n) / 9)             Godot's Collada importer since PR #17840; undefined for n > 512
//   babylon: t = (min(n, 1024) / 1300)^(1/3), r = 0.1 + 0.9 (1 - t)^3
//                                                      Babylon.js glTF exporter: its cubic Bezier (control ordinates 1,
//                                                      0.1, 0.1, 0.1) at t
// Each mapping's alpha is clamped into the target's range before its residual is measured.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/fit/fit.h"

namespace shadelab {

struct ShininessMapping {
  std::string name;    // walter, cod, godot, babylon
  std::string source;  // one line: where it comes from
  std::optional<double> alpha;  // unset where the mapping is undefined at n
  double residual = 0.0;
  double relative_residual = 0.0;  // residual / the lobe's own size (ShininessConversion::relative_residual's scale)
  double excess = 0.0;  // residual / best residual - 1
};

struct ShininessConversion {
  std::string from, to;
  double n = 0.0;
  FitMetric metric = FitMetric::cosine_l2;
  double alpha = 0.0;     // the best fit
  double residual = 0.0;  // its residual
  double relative_residual = 0.0;  // residual / the data's own size in the metric (E of a black BRDF)
  bool at_bound = false;  // the best fit sits on the target's range's end
  std::vector<ShininessMapping> mappings;
};

// The names accepted: from phong | blinn-phong | blinn-phong-modified | blinn-phong-microfacet; to ggx | beckmann.
Result<ShininessConversion> convert_shininess(const std::string& from, const std::string& to, double n,
                                              FitMetric metric = FitMetric::cosine_l2,
                                              const FitGridOptions& grid = {});

// The published mappings' alpha at n (unset where undefined), in the order above.
std::vector<std::pair<std::string, std::optional<double>>> published_shininess_mappings(double n);

}  // namespace shadelab
