// shadelab piecewise-constant distributions in 1D and 2D (Pharr, Jakob, Humphreys, PBR 4th ed., A.4.2 and
// A.5.6): sample a continuous x in [0,1) with density proportional to a non-negative table, its pdf, and
// the inverse (x -> u). Used for importance-sampling environment maps and tabulated functions.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/core/vec.h"

namespace shadelab {

class Distribution1D {
 public:
  // The values must be finite and non-negative; if they sum to zero the distribution is uniform.
  static Result<Distribution1D> create(std::span<const double> values);

  struct Sample {
    double x = 0.0;       // continuous position in [0, 1)
    double pdf = 0.0;     // density with respect to x
    std::size_t index = 0;
  };
  Sample sample(double u) const;
  double pdf(double x) const;
  double invert(double x) const;

  std::size_t size() const { return m_func.size(); }
  double integral() const { return m_integral; }  // mean of the table times 1 (the domain length)
  double value(std::size_t i) const { return m_func[i]; }

 private:
  std::vector<double> m_func;
  std::vector<double> m_cdf;  // size() + 1 entries, m_cdf[0] = 0, m_cdf.back() = 1
  double m_integral = 0.0;
};

// 2D over [0,1)^2 with values[y * width + x]: a marginal over rows and one conditional per row.
class Distribution2D {
 public:
  static Result<Distribution2D> create(std::span<const double> values, std::size_t width, std::size_t height);

  struct Sample {
    Vec2 p;
    double pdf = 0.0;
  };
  Sample sample(Vec2 u) const;
  double pdf(Vec2 p) const;
  Vec2 invert(Vec2 p) const;

  std::size_t width() const { return m_width; }
  std::size_t height() const { return m_height; }

 private:
  Distribution2D(std::vector<Distribution1D> rows, Distribution1D marginal, std::size_t width, std::size_t height)
      : m_rows(std::move(rows)), m_marginal(std::move(marginal)), m_width(width), m_height(height) {}
  std::vector<Distribution1D> m_rows;
  Distribution1D m_marginal;
  std::size_t m_width = 0;
  std::size_t m_height = 0;
};

}  // namespace shadelab
