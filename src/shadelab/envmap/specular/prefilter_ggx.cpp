// shadelab prefiltered GGX cube mip chain (prefilter_ggx.h): filtered importance sampling of the split-sum lobe.
#include "shadelab/envmap/specular/prefilter_ggx.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/envmap/base/downsample.h"
#include "shadelab/envmap/base/simd.h"
#include "shadelab/envmap/specular/lobe_near_far.h"
#include "shadelab/envmap/specular/lobe_sum.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/sampling/sobol.h"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace shadelab {

double GgxMipMapping::roughness(int level) const {
  if (levels <= 1) return 0.0;
  const double t = static_cast<double>(level) / (levels - 1);
  switch (kind) {
    case GgxRoughnessMapping::filament: return 1.0 - std::sqrt(std::max(0.0, 1.0 - t));  // inverse of t = r (2 - r)
    default: return t;  // t = r
  }
}

double GgxMipMapping::lod(double r) const {
  const double scale = levels > 1 ? levels - 1.0 : 0.0;
  switch (kind) {
    case GgxRoughnessMapping::filament: return scale * r * (2.0 - r);
    default: return scale * r;
  }
}

const char* GgxMipMapping::name() const { return kind == GgxRoughnessMapping::filament ? "filament" : "linear"; }

std::string GgxMipMapping::formula() const {
  const std::string l = std::to_string(levels > 1 ? levels - 1 : 0);
  return kind == GgxRoughnessMapping::filament ? "lod = r * (2 - r) * " + l : "lod = r * " + l;
}

GgxRoughnessMapping parse_ggx_roughness_mapping(const std::string& name) {
  if (name == "linear") return GgxRoughnessMapping::linear;
  if (name == "filament") return GgxRoughnessMapping::filament;
  throw std::invalid_argument("mapping: unknown roughness-to-mip mapping '" + name + "' (linear, filament)");
}

GgxFilterMethod parse_ggx_filter_method(const std::string& name) {
  if (name == "sum") return GgxFilterMethod::sum;
  if (name == "sampled") return GgxFilterMethod::sampled;
  throw std::invalid_argument("method: unknown GGX filter method '" + name + "' (sum, sampled)");
}

const char* ggx_filter_method_name(GgxFilterMethod method) { return method == GgxFilterMethod::sampled ? "sampled" : "sum"; }

const char* ggx_level_method_name(GgxLevelMethod method) {
  switch (method) {
    case GgxLevelMethod::input: return "input";
    case GgxLevelMethod::exact: return "exact";
    case GgxLevelMethod::near_far: return "near-far";
    default: return "sampled";
  }
}

Rgb prefilter_ggx_brute_force(const CubeMap& radiance, const Vec3& r, double roughness) {
  const CubeTexelTable& t = CubeTexelTable::get(radiance.size);
  const auto n2 = static_cast<std::size_t>(radiance.size) * static_cast<std::size_t>(radiance.size);
  const double alpha = kernel::alpha_from_roughness(roughness);
  Rgb sum;
  double weight = 0.0;
  for (std::size_t k = 0; k < t.direction.size(); ++k) {
    const Vec3& l = t.direction[k];
    const double rl = dot(r, l);
    if (rl <= 0.0) continue;
    const Vec3 h = normalize(r + l);
    const double w = kernel::D_ggx(dot(r, h), alpha) * rl * t.solid_angle[k];  // D(h) max(R.l, 0) dOmega
    const std::size_t p = k % n2;
    const auto size = static_cast<std::size_t>(radiance.size);
    sum += radiance.faces[k / n2].at(static_cast<int>(p % size), static_cast<int>(p / size)) * w;
    weight += w;
  }
  return weight > 0.0 ? sum / weight : Rgb{};
}

GgxChainTexels::GgxChainTexels(const GgxPrefilteredCube& chain) {
  cubes.reserve(chain.levels.size());
  for (const CubeMap& level : chain.levels) cubes.push_back(cube_texels(level));
  mapping = chain.mapping.kind == GgxRoughnessMapping::filament ? kernel::GGX_MIP_MAPPING_FILAMENT
                                                                 : kernel::GGX_MIP_MAPPING_LINEAR;
}

kernel::IblTexels GgxChainTexels::texels(const DfgTable* dfg) const {
  kernel::IblTexels t{cubes.data(), static_cast<int>(cubes.size()), nullptr, 0};
  if (dfg != nullptr) {
    t.dfg = dfg->texels.data();
    t.dfg_size = dfg->size;
  }
  return t;
}

double ggx_chain_roughness(double roughness) { return std::clamp(std::isfinite(roughness) ? roughness : 0.0, 0.0, 1.0); }

GgxFilter::GgxFilter(const CubeMap& radiance, int samples, double lod_bias)
    : pyramid_{radiance}, samples_(samples), lod_bias_(lod_bias) {
  while (pyramid_.back().size > 1 && pyramid_.back().size % 2 == 0) pyramid_.push_back(downsample_cube(pyramid_.back()));
}

// The fixed sample set of one roughness: l = reflect(-R, h) for Hammersley h drawn from D(h) (n.h), kept where
// R.l > 0.
std::vector<GgxFilter::Sample> GgxFilter::make_samples(double roughness) const {
  const double alpha = kernel::alpha_from_roughness(roughness);
  const int count = samples_;
  const int input_size = pyramid_.front().size;
  const double max_lod = static_cast<double>(pyramid_.size() - 1);
  std::vector<Sample> out;
  out.reserve(static_cast<std::size_t>(count));
  const double omega_p = 4.0 * pi / (6.0 * input_size * input_size);  // mean input texel solid angle
  for (int k = 0; k < count; ++k) {
    const double u = (k + 0.5) / count;
    const double phi = two_pi * radical_inverse(static_cast<std::uint32_t>(k));
    // GGX sampling of h (Walter et al. 2007 eq. 35-36): cos^2(theta_h) = (1 - u) / (1 + (alpha^2 - 1) u).
    const double c2 = (1.0 - u) / (1.0 + (alpha * alpha - 1.0) * u);
    const double ch = std::sqrt(c2);
    const double sh = std::sqrt(std::max(0.0, 1.0 - c2));
    const Vec3 h{sh * std::cos(phi), sh * std::sin(phi), ch};
    const Vec3 l = 2.0 * ch * h - Vec3{0.0, 0.0, 1.0};  // reflect(-R, h) with R = +Z
    if (l.z <= 0.0) continue;
    const double pdf = kernel::D_ggx(ch, alpha) / 4.0;  // l-space pdf D (n.h) / (4 v.h) with n = v
    const double omega_s = 1.0 / (count * pdf);
    // Krivanek & Colbert 2008 eq. 8: the level whose texel solid angle matches the sample's, plus a bias.
    const double lod = std::clamp(0.5 * std::log2(omega_s / omega_p) + lod_bias_, 0.0, max_lod);
    out.push_back({l, l.z, lod});
  }
  return out;
}

Rgb GgxFilter::eval(const Vec3& r, const std::vector<Sample>& samples) const {
  const Frame frame = Frame::from_normal(r);
  const int max_lod = static_cast<int>(pyramid_.size()) - 1;
  Rgb sum;
  double weight = 0.0;
  for (const Sample& s : samples) {
    const Vec3 d = frame.to_world(s.l);
    const int l0 = static_cast<int>(s.lod);
    const double f = s.lod - l0;
    Rgb v = sample_cube_seamless(pyramid_[static_cast<std::size_t>(l0)], d);
    if (f > 0.0 && l0 < max_lod) v = v * (1.0 - f) + sample_cube_seamless(pyramid_[static_cast<std::size_t>(l0 + 1)], d) * f;
    sum += v * s.weight;
    weight += s.weight;
  }
  return weight > 0.0 ? sum / weight : Rgb{};
}

namespace {

// A bilinear lookup's taps at a face: texels x0, x0 + 1 (weights 1 - ax, ax) by y0, y0 + 1, x and y one
// texel outside the face at most (texel_across_edges), as sample_cube_seamless finds them.
struct Taps {
  int face = 0, x0 = 0, y0 = 0;
  double ax = 0.0, ay = 0.0;
};
inline Taps taps_at(int n, const Vec3& dir) {
  const CubeCoord c = cube_coord(dir);
  const double fx = c.s * n - 0.5;  // texel centres at integer fx
  const double fy = c.t * n - 0.5;
  Taps t;
  t.face = c.face;
  t.x0 = std::clamp(static_cast<int>(std::floor(fx)), -1, n - 1);
  t.y0 = std::clamp(static_cast<int>(std::floor(fy)), -1, n - 1);
  t.ax = std::clamp(fx - t.x0, 0.0, 1.0);
  t.ay = std::clamp(fy - t.y0, 0.0, 1.0);
  return t;
}
// The taps read on `face` with x and / or y mirrored (x -> n - 1 - x): the same weights at the mirror
// texels, combined in the same order as sample_cube_seamless (identity: its value bit for bit).
inline Rgb read_taps(const CubeMap& cube, const Taps& t, int face, bool flip_x, bool flip_y) {
  const int n = cube.size;
  if (t.x0 >= 0 && t.x0 + 1 < n && t.y0 >= 0 && t.y0 + 1 < n) {
    // All four taps inside the face (the common case): read them where they lie, the same floats as
    // texel_across_edges gives, combined in the same order.
    const float* data = cube.faces[static_cast<std::size_t>(face)].data.data();
    const int xa = flip_x ? n - 1 - t.x0 : t.x0, xb = flip_x ? xa - 1 : xa + 1;
    const int ya = flip_y ? n - 1 - t.y0 : t.y0, yb = flip_y ? ya - 1 : ya + 1;
    const auto at = [&](int x, int y) {
      const float* p = data + 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x));
      return Rgb{p[0], p[1], p[2]};
    };
    return (at(xa, ya) * (1 - t.ax) + at(xb, ya) * t.ax) * (1 - t.ay) + (at(xa, yb) * (1 - t.ax) + at(xb, yb) * t.ax) * t.ay;
  }
  const auto tx = [&](int x) { return flip_x ? n - 1 - x : x; };
  const auto ty = [&](int y) { return flip_y ? n - 1 - y : y; };
  return (texel_across_edges(cube, face, tx(t.x0), ty(t.y0)) * (1 - t.ax) + texel_across_edges(cube, face, tx(t.x0 + 1), ty(t.y0)) * t.ax) *
             (1 - t.ay) +
         (texel_across_edges(cube, face, tx(t.x0), ty(t.y0 + 1)) * (1 - t.ax) + texel_across_edges(cube, face, tx(t.x0 + 1), ty(t.y0 + 1)) * t.ax) *
             t.ay;
}

}  // namespace

void GgxFilter::eval_mirrored(const Vec3& r, const std::vector<Sample>& samples, const int (&axes)[2], Rgb (&out)[4]) const {
  // Each input face's image under the four reflections (lobe_sum::reflect: the face and the flips).
  lobe_sum::Partner image[4][6];
  for (int g = 0; g < 6; ++g)
    for (int o = 0; o < 4; ++o) {
      lobe_sum::Partner p;
      p.face = g;
      if (o & 1) p = lobe_sum::reflect(axes[0], p);
      if (o & 2) p = lobe_sum::reflect(axes[1], p);
      image[o][g] = p;
    }
  const Frame frame = Frame::from_normal(r);
  const int max_lod = static_cast<int>(pyramid_.size()) - 1;
  Rgb sum[4];
  double weight = 0.0;
  for (const Sample& s : samples) {
    const Vec3 d = frame.to_world(s.l);
    const int l0 = static_cast<int>(s.lod);
    const double f = s.lod - l0;
    const bool second = f > 0.0 && l0 < max_lod;
    const CubeMap& c0 = pyramid_[static_cast<std::size_t>(l0)];
    const Taps t0 = taps_at(c0.size, d);
    Taps t1;
    if (second) t1 = taps_at(pyramid_[static_cast<std::size_t>(l0 + 1)].size, d);
    for (int o = 0; o < 4; ++o) {
      const lobe_sum::Partner& p0 = image[o][t0.face];
      Rgb v = read_taps(c0, t0, p0.face, p0.flip_x, p0.flip_y);
      if (second) {
        const lobe_sum::Partner& p1 = image[o][t1.face];
        v = v * (1.0 - f) + read_taps(pyramid_[static_cast<std::size_t>(l0 + 1)], t1, p1.face, p1.flip_x, p1.flip_y) * f;
      }
      sum[o] += v * s.weight;
    }
    weight += s.weight;
  }
  for (int o = 0; o < 4; ++o) out[o] = weight > 0.0 ? sum[o] / weight : Rgb{};
}

namespace {

// Whether the level of face n is the exact sum over the input (header: "Coarse levels"). Cost: 6 n^2 output
// texels x 6 N^2 input texels, summed over the exact levels (n, n/2, ...) at most 36 n^2 N^2 4/3; sampling
// the whole chain costs about 8 taps x samples x 6 (N/2)^2 4/3 = 16 samples N^2: 3 n^2 <= samples keeps the
// exact sums below the sampling's cost, whatever the input size.
bool exact_level(int n, int samples) { return 3.0 * n * n <= static_cast<double>(samples); }

// The lobe of prefilter_ggx_brute_force, D(h) max(R.l, 0), as lobe_sum reads it: a function of d = 1 - t,
// t = R.l, up to the constant 1/pi. With h = normalize(R + l), (R.h)^2 = (1 + t)/2 = 1 - d/2, so D's
// denominator (R.h)^2 (alpha^2 - 1) + 1 is alpha^2 + (d/2)(1 - alpha^2) (Walter et al. 2007 eq. 33):
// K(d) = (1 - d) alpha^2 / (alpha^2 + (d/2)(1 - alpha^2))^2, in float. The hemisphere t >= 0 is the cap
// (d <= 1), where K >= 0. PrefilterGgx.CoarseLevelsAreSummedExactlyAndHoldASmallBrightSource holds every
// texel of the exact levels to the tests' own double brute force.
struct GgxLobe {
  static constexpr bool row_sums_in_double = true;  // a hemisphere of texels (lobe_sum.h)
  float a2 = 1.0f;    // alpha^2
  float half = 0.0f;  // (1 - alpha^2) / 2
  explicit GgxLobe(double alpha) : a2(static_cast<float>(alpha * alpha)), half(static_cast<float>(0.5 * (1.0 - alpha * alpha))) {}
  template <int K>
  SHADELAB_INLINE simd::f8 weight(const simd::f8& d) const {
    const simd::f8 den = a2 + half * d;
    return (1.0f - d) * a2 / (den * den);
  }
};

SHADELAB_TARGET_AVX2 void ggx_rows_avx2(const lobe_sum::LevelJob& job, const GgxLobe& lobe, int begin, int end) {
  lobe_sum::convolve_rows_k<0>(job, lobe, begin, end);
}
void ggx_rows_base(const lobe_sum::LevelJob& job, const GgxLobe& lobe, int begin, int end) {
  lobe_sum::convolve_rows_k<0>(job, lobe, begin, end);
}
SHADELAB_TARGET_AVX2 void ggx_near_far_avx2(const lobe_sum::NearFarJob& job, const GgxLobe& lobe, int begin, int end) {
  lobe_sum::convolve_rows_near_far<0>(job, lobe, begin, end);
}
void ggx_near_far_base(const lobe_sum::NearFarJob& job, const GgxLobe& lobe, int begin, int end) {
  lobe_sum::convolve_rows_near_far<0>(job, lobe, begin, end);
}

// GgxFilterMethod::sum: the levels summed exactly over every input texel (header: Method). Cost n^2 N^2 for a
// level of face n: 2^24 is the level of face 16 of a 256 input, about 0.05 s of CPU.
bool exact_sum_level(int n, int input_size) {
  return input_size < 8 || static_cast<double>(n) * n * input_size * input_size <= 16777216.0;
}

}  // namespace

GgxPrefilteredCube prefilter_ggx(const CubeMap& radiance, const GgxPrefilterOptions& o) {
  const int size = radiance.size;
  if (size < 1) throw std::invalid_argument("radiance: the input cube map is empty");
  int max_levels = 1;
  while ((size >> (max_levels - 1)) > 1) ++max_levels;
  if (o.levels < 0 || o.levels > max_levels) {
    throw std::invalid_argument("levels: " + std::to_string(o.levels) + " is out of range [0, " +
                                std::to_string(max_levels) + "] for face size " + std::to_string(size));
  }
  const bool pow2 = (size & (size - 1)) == 0;
  const int levels = o.levels == 0 ? (pow2 ? max_levels : 1) : o.levels;
  if (levels > 1 && !pow2) {
    throw std::invalid_argument("size: face size " + std::to_string(size) + " is not a power of two (mips need one)");
  }
  if (o.samples < 1 || o.samples > (1 << 20)) {
    throw std::invalid_argument("samples: " + std::to_string(o.samples) + " is out of range [1, 2^20]");
  }
  if (!std::isfinite(o.lod_bias) || o.lod_bias < 0.0) {
    throw std::invalid_argument("lod_bias: must be finite and >= 0");
  }
  if (!std::isfinite(o.near_cells) || o.near_cells <= 0.0) {
    throw std::invalid_argument("near_cells: must be finite and > 0");
  }
  if (!std::isfinite(o.coarse_cells) || o.coarse_cells <= 0.0) {
    throw std::invalid_argument("coarse_cells: must be finite and > 0");
  }

  const bool sampled = o.method == GgxFilterMethod::sampled;
  const bool avx = simd::cpu_has_avx2_fma();
  lobe_sum::Input input;     // the input in lobe_sum's planar form, made for the first summed level
  lobe_sum::FarInput cells, coarse;  // its mid and coarse cells, made for the first near-far level
  const int block = std::max(4, size / 64);
  const int coarse_block = size % (4 * block) == 0 ? 4 * block : block;

  GgxPrefilteredCube out;
  out.mapping = {o.mapping, levels};
  out.filter = o.method;
  out.samples = sampled ? o.samples : 0;
  // The sampled method's input pyramid, built only for it.
  const std::optional<GgxFilter> filter = sampled ? std::optional<GgxFilter>(std::in_place, radiance, o.samples, o.lod_bias) : std::nullopt;
  // Work items: pairs of rows of a face (lobe_sum::level_items), exact or sampled.
  long long total_rows = 0;
  for (int i = 1; i < levels; ++i) total_rows += lobe_sum::level_items(std::max(1, size >> i));
  long long rows_done = 0;

  out.levels.push_back(radiance);  // r_0 = 0: the delta lobe, the input itself
  out.roughness.push_back(out.mapping.roughness(0));
  out.exact.push_back(false);
  out.method.push_back(GgxLevelMethod::input);
  out.near_angle.push_back(0.0);
  out.mid_angle.push_back(0.0);
  for (int i = 1; i < levels; ++i) {
    const int n = std::max(1, size >> i);
    const double r = out.mapping.roughness(i);
    // Exact summation over the input (header: Method): the lobe sum of prefilter_ggx_brute_force over every
    // input texel, 8 at a time in float with each row's sums added in double, output texels in groups of
    // four mirror images (lobe_sum.h); or that sum near R and by cells far from it (lobe_near_far.h).
    const bool exact = sampled ? exact_level(n, o.samples) : exact_sum_level(n, size);
    const bool near_far = !sampled && !exact;
    const std::vector<GgxFilter::Sample> samples = sampled && !exact ? filter->make_samples(r) : std::vector<GgxFilter::Sample>{};
    CubeMap level(n);
    if ((exact || near_far) && input.cube == nullptr) input = lobe_sum::make_input(radiance);
    if (near_far && cells.n == 0) {
      cells = lobe_sum::make_far_input(radiance, block);
      coarse = lobe_sum::make_far_input(radiance, coarse_block);
      out.far_block = block;
      out.coarse_block = coarse_block;
    }
    // The fields' radii (header: Method): at least near_cells mid cells and 2 lobe widths; at least
    // coarse_cells coarse cells, 8 lobe widths and a coarse cell beyond the near field (so that the near
    // cells' coarse cells are refined). The lobe width 2 alpha: the angle from R where D falls to 1/4.
    const double width = 2.0 * kernel::alpha_from_roughness(r);
    const double near_angle = near_far ? std::max(o.near_cells * 2.0 * block / size, 3.0 * width) : 0.0;
    const double mid_angle =
        near_far ? std::max({o.coarse_cells * 2.0 * coarse_block / size, 8.0 * width, near_angle + 2.0 * coarse_block / size}) : 0.0;
    const lobe_sum::LevelJob job = lobe_sum::level_job(input, level, 0.0);
    const lobe_sum::NearFarJob near_far_job{&input, &cells, &coarse, &level, near_angle, mid_angle};
    const GgxLobe lobe(kernel::alpha_from_roughness(r));
    const int rows = lobe_sum::level_items(n);
    const int chunk = std::max(1, rows / 20);
    for (int start = 0; start < rows; start += chunk) {
      const int end = std::min(rows, start + chunk);
      tbb::parallel_for(tbb::blocked_range<int>(start, end), [&](const tbb::blocked_range<int>& range) {
        if (near_far) {
          if (avx) {
            ggx_near_far_avx2(near_far_job, lobe, range.begin(), range.end());
          } else {
            ggx_near_far_base(near_far_job, lobe, range.begin(), range.end());
          }
          return;
        }
        if (exact) {
          if (avx) {
            ggx_rows_avx2(job, lobe, range.begin(), range.end());
          } else {
            ggx_rows_base(job, lobe, range.begin(), range.end());
          }
          return;
        }
        // Work item: face item / h, rows y and n - 1 - y (h = (n + 1) / 2), texels in groups of four mirror
        // images (eval_mirrored; the 1 x 1 level's single texel alone).
        const int h = (n + 1) / 2;
        for (int item = range.begin(); item != range.end(); ++item) {
          const int face = item / h;
          const int y = item % h;
          if (n == 1) {
            level.set(face, 0, 0, filter->eval(texel_direction(face, 0, 0, 1), samples));
            continue;
          }
          const int axes[2] = {lobe_sum::face_axis_of_local(face, 0), lobe_sum::face_axis_of_local(face, 1)};
          for (int x = 0; x < h; ++x) {
            Rgb v[4];
            filter->eval_mirrored(texel_direction(face, x, y, n), samples, axes, v);
            level.set(face, x, y, v[0]);
            level.set(face, n - 1 - x, y, v[1]);
            level.set(face, x, n - 1 - y, v[2]);
            level.set(face, n - 1 - x, n - 1 - y, v[3]);
          }
        }
      });
      rows_done += end - start;
      if (o.progress) o.progress(static_cast<double>(rows_done) / static_cast<double>(total_rows));
    }
    out.levels.push_back(std::move(level));
    out.roughness.push_back(r);
    out.exact.push_back(exact);
    out.method.push_back(exact ? GgxLevelMethod::exact : near_far ? GgxLevelMethod::near_far : GgxLevelMethod::sampled);
    out.near_angle.push_back(near_angle);
    out.mid_angle.push_back(mid_angle);
  }
  return out;
}

Rgb sample_ggx_chain(const GgxPrefilteredCube& chain, const Vec3& dir, double roughness) {
  if (chain.levels.empty()) return {};
  const GgxChainTexels c(chain);
  const kernel::IblTexels texels = c.texels();
  const kernel::IblBinding bind(texels);
  return kernel::ggx_chain_read(dir, ggx_chain_roughness(roughness), texels.cube_count, c.mapping);
}

}  // namespace shadelab

