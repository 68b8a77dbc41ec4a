#include "shadelab/envmap/diffuse/sh_error.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <tuple>

#include "shadelab/color/rgb.h"
#include "shadelab/envmap/diffuse/irradiance.h"
#include "shadelab/envmap/diffuse/sh_bands.h"
#include "shadelab/envmap/diffuse/zh3.h"

namespace shadelab {

namespace {

ShBands truncate(const ShBands& sh, int bands) {
  ShBands out(bands);
  for (std::size_t i = 0; i < out.c.size(); ++i) out.c[i] = sh.c[i];
  return out;
}

}  // namespace

std::vector<ShEncodingError> sh_encoding_errors(const CubeMap& env, int eval_size) {
  const CubeMap exact = irradiance_cube(env, eval_size, RadianceUnits::radiometric);
  const CubeTexelTable& t = CubeTexelTable::get(eval_size);
  const ShBands full = project_sh_bands(env, sh_max_bands);  // lower bands are the same projection, truncated
  const auto n2 = static_cast<std::size_t>(eval_size) * static_cast<std::size_t>(eval_size);

  auto measure = [&](const std::string& name, int coefficients, const std::function<Rgb(const Vec3&)>& e) {
    ShEncodingError r{name, coefficients, 0.0, 0.0, 0.0};
    double total = 0.0;
    for (std::size_t k = 0; k < t.direction.size(); ++k) {
      const std::size_t p = k % n2;
      const Rgb truth = exact.texel(static_cast<int>(k / n2), static_cast<int>(p) % eval_size, static_cast<int>(p) / eval_size);
      const Rgb got = e(t.direction[k]);
      const double y = luminance(truth);
      const double rel = y > 0.0 ? std::abs(luminance(got) - y) / y : 0.0;
      r.mean_relative += rel * t.solid_angle[k];
      total += t.solid_angle[k];
      r.max_relative = std::max(r.max_relative, rel);
      if (got.r < 0.0 || got.g < 0.0 || got.b < 0.0) r.negative_solid_angle += t.solid_angle[k];
    }
    r.mean_relative /= total;
    return r;
  };

  std::vector<ShEncodingError> out;
  const std::pair<ShWindow, const char*> windows[] = {{ShWindow::none, ""}, {ShWindow::hanning, " hanning"}, {ShWindow::lanczos, " lanczos"}};
  for (int bands = 2; bands <= sh_max_bands; ++bands) {
    const ShBands sh = truncate(full, bands);
    for (const auto& [window, suffix] : windows) {
      const std::vector<double> f = sh_irradiance_factors(bands, false, window);
      out.push_back(measure("L" + std::to_string(bands - 1) + suffix, bands * bands,
                            [&](const Vec3& n) { return sh_bands_evaluate(sh, n, f); }));
    }
  }
  const ShBands l2 = truncate(full, 3);
  for (const auto& [mode, name, count] : {std::tuple{Zh3Mode::stored, "ZH3 stored", 5}, std::tuple{Zh3Mode::hallucinated, "ZH3 hallucinated", 4}}) {
    const Zh3 z = zh3_from_sh(l2, mode);
    out.push_back(measure(name, count, [&](const Vec3& n) { return zh3_irradiance(z, n); }));
  }
  return out;
}

}  // namespace shadelab
