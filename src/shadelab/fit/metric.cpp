#include "shadelab/fit/metric.h"

#include <cmath>

namespace shadelab {

const char* fit_metric_name(FitMetric m) {
  switch (m) {
    case FitMetric::cosine_l2: return "cosine-l2";
    case FitMetric::cube_root: return "cube-root";
    case FitMetric::log: return "log";
  }
  return "?";
}

std::string fit_metric_names() { return "cosine-l2, cube-root, log"; }

Result<FitMetric> parse_fit_metric(std::string_view name) {
  for (FitMetric m : {FitMetric::cosine_l2, FitMetric::cube_root, FitMetric::log}) {
    if (name == fit_metric_name(m)) return m;
  }
  return Error{"--metric: '" + std::string(name) + "' is not one of " + fit_metric_names()};
}

double fit_metric_transform(FitMetric m, double x) {
  switch (m) {
    case FitMetric::cosine_l2: return x;              // Ngan et al. 2005: the cosine-weighted value itself
    case FitMetric::cube_root: return std::cbrt(x);   // Fores et al. 2012: cube root
    case FitMetric::log: return std::log1p(x);        // Low et al. 2012: ln(1 + f cos)
  }
  return x;
}

}  // namespace shadelab
