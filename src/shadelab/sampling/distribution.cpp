#include "shadelab/sampling/distribution.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace shadelab {

Result<Distribution1D> Distribution1D::create(std::span<const double> values) {
  if (values.empty()) return make_error("distribution: the table is empty");
  Distribution1D d;
  d.m_func.assign(values.begin(), values.end());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]) || values[i] < 0.0) {
      return make_error("distribution: value " + std::to_string(i) + " is negative or not finite");
    }
  }
  const auto n = static_cast<double>(values.size());
  d.m_cdf.resize(values.size() + 1);
  d.m_cdf[0] = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) d.m_cdf[i + 1] = d.m_cdf[i] + values[i] / n;
  d.m_integral = d.m_cdf.back();
  if (d.m_integral == 0.0) {
    // An all-zero table samples uniformly, so callers never divide by a zero integral.
    for (std::size_t i = 0; i <= values.size(); ++i) d.m_cdf[i] = static_cast<double>(i) / n;
    d.m_integral = 0.0;
  } else {
    for (auto& c : d.m_cdf) c /= d.m_integral;
  }
  d.m_cdf.back() = 1.0;
  return d;
}

Distribution1D::Sample Distribution1D::sample(double u) const {
  // The last cdf entry <= u; ties on zero-width bins resolve to the first bin with non-zero mass.
  const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), u);
  std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - m_cdf.begin()) - 1));
  i = std::min(i, m_func.size() - 1);
  const double width = m_cdf[i + 1] - m_cdf[i];
  double t = width > 0.0 ? (u - m_cdf[i]) / width : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const auto n = static_cast<double>(m_func.size());
  double x = std::min((static_cast<double>(i) + t) / n, std::nextafter(1.0, 0.0));
  // pdf() puts x in bin floor(x n). Rounding can move x across an edge of bin i (t rounding to 1 just below
  // a CDF step, or (i / n) n < i), which would give it the density of a neighbour, 0 if that one is empty:
  // step x by ulps back into bin i (one or two steps at most).
  while (x > 0.0 && static_cast<std::size_t>(x * n) > i) x = std::nextafter(x, 0.0);
  while (static_cast<std::size_t>(x * n) < i) x = std::nextafter(x, 1.0);
  Sample s;
  s.index = i;
  s.x = x;
  s.pdf = pdf(s.x);
  return s;
}

double Distribution1D::pdf(double x) const {
  if (x < 0.0 || x >= 1.0) return 0.0;
  const auto n = static_cast<double>(m_func.size());
  const auto i = std::min(static_cast<std::size_t>(x * n), m_func.size() - 1);
  return (m_cdf[i + 1] - m_cdf[i]) * n;
}

double Distribution1D::invert(double x) const {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const auto n = static_cast<double>(m_func.size());
  const auto i = std::min(static_cast<std::size_t>(x * n), m_func.size() - 1);
  const double t = x * n - static_cast<double>(i);
  return m_cdf[i] + t * (m_cdf[i + 1] - m_cdf[i]);
}

Result<Distribution2D> Distribution2D::create(std::span<const double> values, std::size_t width,
                                              std::size_t height) {
  if (width == 0 || height == 0) return make_error("distribution: width and height must be positive");
  if (values.size() != width * height) return make_error("distribution: table size is not width x height");
  std::vector<Distribution1D> rows;
  rows.reserve(height);
  std::vector<double> marginal(height);
  for (std::size_t y = 0; y < height; ++y) {
    auto row = Distribution1D::create(values.subspan(y * width, width));
    if (!row) return make_error(row.error().message + " (row " + std::to_string(y) + ")");
    marginal[y] = row->integral();
    rows.push_back(std::move(row).value());
  }
  auto m = Distribution1D::create(marginal);
  if (!m) return m.error();
  return Distribution2D(std::move(rows), std::move(m).value(), width, height);
}

Distribution2D::Sample Distribution2D::sample(Vec2 u) const {
  const auto my = m_marginal.sample(u.y);
  const auto mx = m_rows[my.index].sample(u.x);
  return {{mx.x, my.x}, mx.pdf * my.pdf};
}

double Distribution2D::pdf(Vec2 p) const {
  if (p.x < 0.0 || p.x >= 1.0 || p.y < 0.0 || p.y >= 1.0) return 0.0;
  const auto iy = std::min(static_cast<std::size_t>(p.y * static_cast<double>(m_height)), m_height - 1);
  return m_marginal.pdf(p.y) * m_rows[iy].pdf(p.x);
}

Vec2 Distribution2D::invert(Vec2 p) const {
  const auto iy = std::min(static_cast<std::size_t>(std::clamp(p.y, 0.0, 1.0) * static_cast<double>(m_height)),
                           m_height - 1);
  return {m_rows[iy].invert(p.x), m_marginal.invert(p.y)};
}

}  // namespace shadelab
