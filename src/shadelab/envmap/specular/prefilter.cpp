#include "shadelab/envmap/specular/prefilter.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/base/downsample.h"
#include "shadelab/envmap/base/simd.h"
#include "shadelab/envmap/specular/lobe_sum.h"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace shadelab {

double prefilter_exponent(int level, int mip_count, double gloss_scale, double gloss_bias) {
  const double t = mip_count > 1 ? static_cast<double>(level) / (mip_count - 1) : 0.0;
  return std::exp2(gloss_scale * (1.0 - t) + gloss_bias);  // cmft-style gloss scale and bias
}

Rgb prefilter_brute_force(const CubeMap& radiance, const Vec3& r, double n) {
  const CubeTexelTable& t = CubeTexelTable::get(radiance.size);
  const auto size = static_cast<std::size_t>(radiance.size);
  Rgb sum;
  double weight = 0.0;
  for (std::size_t k = 0; k < t.direction.size(); ++k) {
    const double c = dot(r, t.direction[k]);
    if (c <= 0.0) continue;
    const double w = std::pow(c, n) * t.solid_angle[k];  // (n+1)/(2pi) cancels in the ratio
    const std::size_t face = k / (size * size);
    const std::size_t p = k % (size * size);
    sum += radiance.faces[face].at(static_cast<int>(p % size), static_cast<int>(p / size)) * w;
    weight += w;
  }
  return weight > 0.0 ? sum / weight : Rgb{};
}

namespace {

using namespace simd;
using namespace lobe_sum;

// Lobes: the weight K(t) up to a constant factor as a function of d = 1 - t (8 lanes), and the cosine
// below which K < 1e-9 K(1).
struct PhongLobe {
  static constexpr bool row_sums_in_double = false;  // narrow caps: short float sums (lobe_sum.h)
  float n_log2e = 0.0f;  // n / ln 2: t^n = 2^(n log2(e) ln t)
  int terms = 10;        // terms of the series of ln(1 - d) (narrow caps), 0: range-reduced log (wide caps)
  double cos_cutoff = 0.0;

  // ln t = ln(1 - d). Narrow caps (d <= 1/4) use the series -(d + d^2/2 + ... + d^K/K), no division, with the
  // fewest terms K (4 .. 10) whose remainder, below d^(K+1)/(K+1) / (1 - d), changes n ln t by less than 1e-6
  // at the cap's edge (a relative weight error of 1e-6 where the weight is 1e-9 of its peak, less nearer R).
  explicit PhongLobe(double n) : n_log2e(static_cast<float>(n / 0.69314718055994531)), cos_cutoff(std::pow(1e-9, 1.0 / n)) {
    const double d_max = 1.0 - cos_cutoff;
    if (d_max > 0.25) {
      terms = 0;
    } else {
      terms = 4;
      while (terms < 10 && n * std::pow(d_max, terms + 1) / ((terms + 1) * (1.0 - d_max)) > 1e-6) ++terms;
    }
  }

  template <int K>
  SHADELAB_INLINE static f8 log1m_series(const f8& d) {
    f8 p = splat8(1.0f / K);
    for (int k = K - 1; k >= 1; --k) p = p * d + 1.0f / static_cast<float>(k);
    return -(p * d);
  }
  template <int K>
  SHADELAB_INLINE f8 weight(const f8& d) const {
    if constexpr (K == 0) {
      return exp2_8(n_log2e * log1m_8(d));
    } else {
      return exp2_8(n_log2e * log1m_series<K>(d));
    }
  }
};

SHADELAB_INLINE void convolve_rows_phong(const LevelJob& job, const PhongLobe& lobe, int begin, int end) {
  switch (lobe.terms) {
    case 0: convolve_rows_k<0>(job, lobe, begin, end); break;
    case 4: convolve_rows_k<4>(job, lobe, begin, end); break;
    case 5: convolve_rows_k<5>(job, lobe, begin, end); break;
    case 6: convolve_rows_k<6>(job, lobe, begin, end); break;
    case 7: convolve_rows_k<7>(job, lobe, begin, end); break;
    case 8: convolve_rows_k<8>(job, lobe, begin, end); break;
    case 9: convolve_rows_k<9>(job, lobe, begin, end); break;
    default: convolve_rows_k<10>(job, lobe, begin, end); break;
  }
}
SHADELAB_TARGET_AVX2 void convolve_rows_phong_avx2(const LevelJob& job, const PhongLobe& lobe, int begin, int end) {
  convolve_rows_phong(job, lobe, begin, end);
}
void convolve_rows_phong_base(const LevelJob& job, const PhongLobe& lobe, int begin, int end) {
  convolve_rows_phong(job, lobe, begin, end);
}

}  // namespace

Result<PrefilteredCube> prefilter_specular(const CubeMap& radiance, const PrefilterOptions& o) {
  if (o.size < 1 || (o.size & (o.size - 1)) != 0) {
    return make_error("prefilter: size " + std::to_string(o.size) + " is not a power of two");
  }
  int max_levels = 1;
  while ((o.size >> (max_levels - 1)) > 1) ++max_levels;
  const int levels = o.mip_count == 0 ? max_levels : o.mip_count;
  if (levels < 1 || levels > max_levels) {
    return make_error("prefilter: mip count " + std::to_string(o.mip_count) + " is out of range [1, " +
                      std::to_string(max_levels) + "] for size " + std::to_string(o.size));
  }
  if (!std::isfinite(o.gloss_scale) || !std::isfinite(o.gloss_bias) || o.gloss_scale < 0.0) {
    return make_error("prefilter: gloss scale must be finite and >= 0, gloss bias finite");
  }
  if (radiance.size < 1) return make_error("prefilter: the input cube map is empty");

  // The input pyramid, finest first: sizes now, levels halved on demand.
  std::vector<int> sizes{radiance.size};
  while (sizes.back() % 2 == 0 && sizes.back() > 1) sizes.push_back(sizes.back() / 2);
  std::vector<CubeMap> pyramid(sizes.size());
  std::vector<Input> prepared(sizes.size());
  const bool avx = cpu_has_avx2_fma();

  PrefilteredCube out;
  long long total_rows = 0;
  for (int i = 0; i < levels; ++i) total_rows += level_items(std::max(1, o.size >> i));
  long long rows_done = 0;
  for (int i = 0; i < levels; ++i) {
    const int size = std::max(1, o.size >> i);
    const double n = prefilter_exponent(i, levels, o.gloss_scale, o.gloss_bias);
    const PhongLobe lobe(n);
    const double kappa = std::max(0.0, lobe.cos_cutoff);  // caps wider than a hemisphere are cut at t = 0
    // The finest input level within 2e9 weight evaluations (outputs x texels in the cap, a (1 - kappa)/2
    // fraction of the sphere), but never one whose texels (about (pi/2)/N) exceed half the lobe width.
    const double outputs = 6.0 * size * size;
    std::size_t pick = sizes.size() - 1;
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      const double texels = 6.0 * sizes[k] * sizes[k] * (1.0 - kappa) / 2.0;
      if (outputs * texels <= 2e9) {
        pick = k;
        break;
      }
    }
    while (pick > 0 && (pi / 2.0) / sizes[pick] > 0.5 / std::sqrt(n)) --pick;
    if (prepared[pick].cube == nullptr) {
      for (std::size_t k = 1; k <= pick; ++k) {
        if (pyramid[k].size == 0) pyramid[k] = downsample_cube(k == 1 ? radiance : pyramid[k - 1]);
      }
      prepared[pick] = make_input(pick == 0 ? radiance : pyramid[pick]);
    }

    CubeMap level(size);
    const LevelJob job = level_job(prepared[pick], level, kappa);
    const int rows = level_items(size);
    const int chunk = std::max(1, rows / 20);
    for (int start = 0; start < rows; start += chunk) {
      const int end = std::min(rows, start + chunk);
      tbb::parallel_for(tbb::blocked_range<int>(start, end), [&](const tbb::blocked_range<int>& range) {
        if (avx) {
          convolve_rows_phong_avx2(job, lobe, range.begin(), range.end());
        } else {
          convolve_rows_phong_base(job, lobe, range.begin(), range.end());
        }
      });
      rows_done += end - start;
      if (o.progress) o.progress(static_cast<double>(rows_done) / static_cast<double>(total_rows));
    }
    out.levels.push_back(std::move(level));
    out.exponents.push_back(n);
  }
  return out;
}

}  // namespace shadelab
