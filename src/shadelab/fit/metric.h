// shadelab fitting metrics: how far a model's BRDF is from data, over a set of configurations (fit/samples.h).
// Each metric compares a transform T of the reflected quantity f cos(theta_i) (the radiance a unit directional
// light at wi reflects toward wo), per channel, in the weighted root mean square
//   E = sqrt( sum_k w_k sum_c (T(f_model,c(k) cos_i(k)) - T(f_data,c(k) cos_i(k)))^2 / (3 sum_k w_k) )
// with w_k the configuration's measure (dw_i dw_o, fit/samples.h), so that E is a discretized L2 norm over the
// configuration space, normalized by its measure. The transforms:
//   cosine-l2: T(x) = x                 (Ngan, Durand & Matusik 2005, "Experimental Analysis of BRDF Models", EGSR:
//                                         the cosine-weighted L2 difference of the BRDFs)
//   cube-root: T(x) = cbrt(x)           (Fores, Ferwerda & Gu 2012, "Toward a Perceptually Based Metric for BRDF
//                                         Modeling", CIC: the cube root, after lightness scales)
//   log:       T(x) = ln(1 + x)         (Low, Kronander, Ynnerman & Unger 2012, "BRDF Models for Accurate and
//                                         Efficient Rendering of Glossy Surfaces", ACM TOG 31(1))
#pragma once

#include <string>
#include <string_view>

#include "shadelab/core/error.h"

namespace shadelab {

enum class FitMetric { cosine_l2, cube_root, log };

// The metric's name as the CLI and JSON spell it ("cosine-l2", "cube-root", "log").
const char* fit_metric_name(FitMetric m);
// Parses a name; the error lists the names.
Result<FitMetric> parse_fit_metric(std::string_view name);
// "cosine-l2, cube-root, log": for messages and help.
std::string fit_metric_names();

// T(x) of the metric (above), x = f cos(theta_i) >= 0.
double fit_metric_transform(FitMetric m, double x);

}  // namespace shadelab
