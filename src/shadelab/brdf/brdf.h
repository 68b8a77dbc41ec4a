// shadelab BRDF interface: every model has eval, pdf and sample, in the local shading frame (normal = +Z).
//
// Contract (docs/conventions.md):
// - wi points from the surface toward the light, wo toward the viewer; both unit length.
// - eval(wi, wo) returns f_r in 1/sr, RGB, WITHOUT the cosine factor. If either direction is on or below
//   the horizon (z <= 0) it returns 0, never NaN.
// - sample(wo, u, u_lobe) draws wi from a distribution over the whole sphere of directions whose density per
//   unit solid angle is pdf(wi, wo); that density integrates to 1 over the sphere. A sampled wi may fall
//   below the horizon (a glossy lobe about the mirror direction near grazing); its weight is then 0.
// - weight = f_r(wi, wo) cos(theta_i) / pdf, the Monte Carlo estimator's factor; 0 where pdf is 0.
// - If wo is on or below the horizon, sample returns pdf 0 and weight 0.
// - eval_batch(wi, wo, out, n) is eval over n pairs of contiguous arrays, the same bits as n calls;
//   eval_batch_checked also checks that every direction is unit length (is_unit_direction).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shadelab/color/rgb.h"
#include "shadelab/core/vec.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

struct BrdfSample {
  Vec3 wi{0.0, 0.0, 1.0};
  double pdf = 0.0;  // per unit solid angle
  Rgb weight;        // f cos(theta_i) / pdf
};

// The shading kernel a model's eval is (src/shadelab/kernels/*.sl): the kernel's name K (the .sl text defines
// `KState K_prepare(KParams)` and `rgb K_eval(KState, vec3 wi, vec3 wo)`) and the values of the KParams
// fields, in declaration order, taken from the same KParams the C++ eval was prepared from. The shader
// exporter bakes these values into a shader (or packs them into a uniform block); it checks every name and
// size against the struct it reads from the kernel text, so a binding that drifts from the kernel fails there.
struct KernelField {
  std::string name;
  std::vector<double> values;  // real or int: 1 value; rgb: 3; real[N]: N
};

struct KernelBinding {
  std::string kernel;
  std::vector<KernelField> fields;

  KernelBinding& add(std::string name, double v) { return add_values(std::move(name), {v}); }
  KernelBinding& add(std::string name, int v) { return add_values(std::move(name), {static_cast<double>(v)}); }
  KernelBinding& add(std::string name, const Rgb& c) { return add_values(std::move(name), {c.r, c.g, c.b}); }
  template <std::size_t N>
  KernelBinding& add(std::string name, const double (&a)[N]) {
    return add_values(std::move(name), std::vector<double>(a, a + N));
  }
  KernelBinding& add_values(std::string name, std::vector<double> v) {
    fields.push_back({std::move(name), std::move(v)});
    return *this;
  }
};

// What the split-sum environment lighting (kernels/game_ibl.sl) needs of a microfacet-GGX BRDF, read from the
// BRDF itself (so a textured hit's own roughness and f0 are used): the model's kernel description
// (kernels/split_sum.sl SplitSumMaterial: diffuse albedo, perceptual roughness, f0, f90 and the energy terms,
// written by the model's own kernel, e.g. ggx.sl ggx_split_sum), the text the exported shaders run too.
struct SplitSumInputs {
  kernel::SplitSumMaterial material;
  double roughness() const { return material.roughness; }
  Rgb f0() const { return Rgb(material.f0); }
  Rgb f90() const { return Rgb(material.f90); }
};

// The direction test of eval_batch_checked and of the Python module's direction rule: |v|^2 within 4 ulp of
// 1 (dividing such a vector by its length would move each component by at most an ulp); false for NaN and
// infinities.
inline constexpr double unit_direction_tolerance = 4.0 * std::numeric_limits<double>::epsilon();
inline bool is_unit_direction(const Vec3& v) {
  const double n2 = dot(v, v);
  return std::abs(n2 - 1.0) <= unit_direction_tolerance;
}

class Brdf {
 public:
  Brdf() = default;
  Brdf(const Brdf&) = default;
  Brdf& operator=(const Brdf&) = default;
  virtual ~Brdf() = default;

  virtual Rgb eval(const Vec3& wi, const Vec3& wo) const = 0;
  // out[i] = eval(wi[i], wo[i]) for i < n, bit for bit, with the loop inside the model: one virtual call for
  // the whole batch, the model's state read once and its kernel inlined into the loop. This is how to
  // evaluate many pairs (bench/python_eval_baseline.cpp measures it against the per-pair loop).
  void eval_batch(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n) const {
    (void)eval_pairs(wi, wo, out, n, false);
  }
  // The same, checking first that wi[i] and wo[i] are unit length (is_unit_direction): it stops at the first
  // pair where one is not and returns its index (n when every pair passed), with out written for the pairs
  // before it only. The check runs on blocks of 64 pairs ahead of their eval (vectorized where the CPU has
  // AVX2: brdf/unit_check.cpp); the Python module's Brdf.eval calls this on NumPy's arrays in place.
  [[nodiscard]] std::size_t eval_batch_checked(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n) const {
    return eval_pairs(wi, wo, out, n, true);
  }
  virtual double pdf(const Vec3& wi, const Vec3& wo) const = 0;
  // u picks the direction within a lobe, u_lobe picks the lobe; all three in [0, 1).
  virtual BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const = 0;

  // True when f(wi, wo) == f(wo, wi) for every pair. Some published forms are not reciprocal by design
  // (the original Phong and Blinn-Phong, which divide by N.L; wrapped diffuse with w > 0).
  virtual bool is_reciprocal() const { return true; }

  // True when eval is a Monte Carlo estimate (the layered ground truth, brdf/layered.h): a deterministic
  // function of the pair, but noisy. Such a model has no shader kernel and is reciprocal in expectation only;
  // the analysis measures it by sampling where quadrature would chase the noise (analysis/check.h).
  virtual bool is_stochastic() const { return false; }
  // True when eval interpolates a measured table (brdf/measured.h): continuous, with kinks along every bin
  // boundary, and within the table's interpolation error (about 1e-3) of what was measured. Adaptive quadrature
  // of such a function to 1e-10 subdivides along every kink (100 s for one albedo); the analysis integrates it to
  // tabulated_rel_tol (analysis/albedo.h).
  virtual bool is_tabulated() const { return false; }
  // For a stochastic model, the standard error of eval(wi, wo)'s own estimate (from the same random numbers:
  // eval's value is the mean it belongs to); nullopt for an exact model, or when one sample gives no spread.
  virtual std::optional<Rgb> eval_standard_error(const Vec3& /*wi*/, const Vec3& /*wo*/) const { return std::nullopt; }

  // False when the sampler's density jumps across a curve below the horizon (the support edge of the visible-
  // normal samplers, the cut of the bounded one), which quadrature over the sphere cannot resolve. The
  // analysis then integrates the density over the upper hemisphere only and checks the mass below the horizon
  // against the sampler's share of samples there (analysis/chi_square.h). Samples below carry weight 0.
  virtual bool pdf_smooth_below_horizon() const { return true; }

  // The albedo of the model's Lambertian (view-independent) part, pi times its constant f: what a game
  // multiplies by diffuse irradiance / pi. Black for a model without one.
  virtual Rgb diffuse_albedo() const { return {}; }

  // The kernel this model's eval is and its parameter values (see KernelBinding); every registered model
  // has one (the shader tests check), test doubles need none.
  virtual std::optional<KernelBinding> kernel_binding() const { return std::nullopt; }

  // What game shading's environment lighting asks of a model (render/game_renderer.h, brdf/game_lobe.h), each
  // answered by the model itself so that no renderer or front end switches on a model's name:
  // - game_phong_exponent(): the Phong exponent n whose lobe (R.L)^n matches the model's specular lobe, which
  //   picks the Phong chain's level (the conversions per model: brdf/game_lobe.h); 0 for no specular lobe.
  // - gloss_exponent_is_blinn_phong(): whether a gloss map's exponent is a Blinn-Phong (N.H)^n one (the
  //   renderer then takes n/4 for the Phong chain, brdf/gloss.h).
  // - game_wrap(): the wrap w of a wrapped diffuse lobe, which the SH9 ambient applies by its band factors.
  // - split_sum_inputs(): the split-sum description of a microfacet-GGX model (f0, f90, roughness, energy
  //   terms; SplitSumInputs below), nullopt for a model that engines shade with the Phong chain.
  virtual double game_phong_exponent() const { return 0.0; }
  virtual bool gloss_exponent_is_blinn_phong() const { return false; }
  virtual double game_wrap() const { return 0.0; }
  virtual std::optional<SplitSumInputs> split_sum_inputs() const { return std::nullopt; }

 protected:
  // eval_batch (check_unit false) and eval_batch_checked (true). Every registered model overrides it with
  // eval_kernel_batch (below); this default, for test doubles, calls eval once per pair.
  virtual std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const;
};

inline std::size_t Brdf::eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const {
  for (std::size_t i = 0; i < n; ++i) {
    if (check_unit && (!is_unit_direction(wi[i]) || !is_unit_direction(wo[i]))) return i;
    out[i] = eval(wi[i], wo[i]);
  }
  return n;
}

using BrdfPtr = std::unique_ptr<const Brdf>;

namespace brdf_detail {
// True when is_unit_direction(wi[i]) and is_unit_direction(wo[i]) for every i < n (brdf/unit_check.cpp:
// the same test, vectorized).
bool all_unit_directions(const Vec3* wi, const Vec3* wo, std::size_t n);
}  // namespace brdf_detail

// The loop of every model's eval_pairs: out[i] = Kernel(state, wi[i], wo[i]), the same call the model's eval
// makes. The state is copied into a local once, so the stores to out cannot alias it and it stays in
// registers; Kernel is a template argument, so the call is direct and inlines (one call site, so the
// compiler inlines it however large). With check_unit, each block of 64 pairs is checked first, without a
// branch per pair and in cache for the eval that follows, so the eval loop is the same as without.
template <auto Kernel, typename State>
std::size_t eval_kernel_batch(const State& state, const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n,
                              bool check_unit) {
  const State s = state;
  constexpr std::size_t block = 64;
  for (std::size_t b = 0; b < n; b += block) {
    std::size_t end = n - b < block ? n : b + block;
    bool stop = false;
    if (check_unit) {
      if (!brdf_detail::all_unit_directions(wi + b, wo + b, end - b)) {
        end = b;
        while (is_unit_direction(wi[end]) && is_unit_direction(wo[end])) ++end;
        stop = true;
      }
    }
    for (std::size_t i = b; i < end; ++i) out[i] = Kernel(s, wi[i], wo[i]);
    if (stop) return end;
  }
  return n;
}

}  // namespace shadelab
