#include "shadelab/kernels/tables.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>

#include "shadelab/kernels/kernels.h"
#include "shadelab/numeric/quadrature.h"

namespace shadelab::kernel {

namespace {

// The texels alone: what ggx_energy_texel reads, and what the averages are integrated from.
struct EnergyTexels {
  std::vector<double> alpha;
  std::vector<double> mu;
  std::vector<double> e;
  std::vector<double> e_error;
};

// The azimuthal integral of D_GGX at fixed theta_i, theta_o: A = integral_0^{2 pi} D(h) d(phi_i). With
// h.z^2 = p^2 / |wi + wo|^2, p = cos(theta_i) + cos(theta_o), and |wi + wo|^2 = 2 (1 + cos theta_i cos theta_o +
// sin theta_i sin theta_o cos(phi)), D = (alpha^2 / pi) ((c2 + d cos phi) + Delta)^2 / (c2 + d cos phi)^2 with
// Delta = (1 - alpha^2) p^2, so A = 2 alpha^2 (1 + 2 Delta / sqrt(c2^2 - d^2) + Delta^2 c2 / (c2^2 - d^2)^(3/2))
// by integral dphi/(c + d cos) = 2 pi / sqrt(c^2 - d^2) and integral dphi/(c + d cos)^2 = 2 pi c / (c^2 - d^2)^(3/2)
// (Gradshteyn & Ryzhik 3.613.2 and its derivative in c). c2 -/+ d are written as products of half-angle terms,
// 4 cos^2(S/2) (alpha^2 cos^2(T/2) + sin^2(T/2)) and 4 cos^2(T/2) (alpha^2 cos^2(S/2) + sin^2(S/2)),
// S = theta_i + theta_o, T = theta_i - theta_o, so that nothing cancels near the mirror configuration.
double azimuthal_ggx_integral(double theta_i, double theta_o, double alpha) {
  const double a2 = alpha * alpha;
  const double cs = std::cos(0.5 * (theta_i + theta_o));
  const double ss = std::sin(0.5 * (theta_i + theta_o));
  const double cd = std::cos(0.5 * (theta_i - theta_o));
  const double sd = std::sin(0.5 * (theta_i - theta_o));
  const double lo = 4.0 * cs * cs * (a2 * cd * cd + sd * sd);  // c2 - d > 0
  const double hi = 4.0 * cd * cd * (a2 * cs * cs + ss * ss);  // c2 + d > 0
  if (!(lo > 0.0) || !(hi > 0.0)) return 0.0;                  // wi on the horizon at the antipode: measure 0
  const double c2 = 0.5 * (lo + hi);
  const double p = std::cos(theta_i) + std::cos(theta_o);
  const double delta = (1.0 - a2) * p * p;
  const double q = lo * hi;
  const double sq = std::sqrt(q);
  return 2.0 * a2 * (1.0 + 2.0 * delta / sq + delta * delta * c2 / (q * sq));
}

// E(mu_o, alpha) with F = 1: integral over theta_i of sin(theta_i) G2(theta_i, theta_o) A(theta_i, theta_o) /
// (4 mu_o) (f cos(theta_i) = D G2 / (4 mu_o), G2 isotropic: a function of the two polar angles only, the
// kernel's G2_ggx_* of microfacet.sl). Adaptive Gauss-Kronrod (numeric/quadrature.h) on [0, theta_o] and
// [theta_o, pi/2], so that the mirror peak sits at a breakpoint.
std::pair<double, double> directional_albedo_f1(int g, double mu_o, double alpha) {
  const Vec3 wo{std::sqrt(std::max(0.0, (1.0 - mu_o) * (1.0 + mu_o))), 0.0, mu_o};
  const double theta_o = std::atan2(wo.x, mu_o);
  const auto f = [&](double theta_i) {
    const Vec3 wi{std::sin(theta_i), 0.0, std::cos(theta_i)};
    const double g2 = g == GGX_ENERGY_G_CORRELATED ? G2_ggx_correlated(wi, wo, alpha, alpha)
                                                   : G2_ggx_separable(wi, wo, alpha, alpha);
    return wi.x * g2 * azimuthal_ggx_integral(theta_i, theta_o, alpha) / (4.0 * mu_o);
  };
  QuadratureOptions o;
  o.rel_tol = 1e-11;
  o.abs_tol = 1e-13;
  const QuadratureResult a = integrate(f, 0.0, theta_o, o);
  const QuadratureResult b = integrate(f, theta_o, 0.5 * 3.14159265358979323846, o);
  return {a.value + b.value, a.error + b.error};
}

EnergyTexels compute_texels(int g) {
  EnergyTexels t;
  const int rows = GGX_ENERGY_ROWS;
  const int cols = GGX_ENERGY_COLS;
  t.alpha.resize(rows);
  t.mu.resize(static_cast<std::size_t>(rows * cols));
  t.e.resize(t.mu.size());
  t.e_error.resize(t.mu.size());
  for (int j = 0; j < rows; ++j) {
    const double alpha = j == 0 ? 0.0 : ggx_energy_row_alpha(j);
    t.alpha[static_cast<std::size_t>(j)] = alpha;
    for (int i = 0; i < cols; ++i) {
      const auto k = static_cast<std::size_t>(j * cols + i);
      if (j == 0) {  // alpha = 0: a mirror with F = 1 reflects everything
        t.mu[k] = static_cast<double>(i) / (cols - 1);
        t.e[k] = 1.0;
        continue;
      }
      // The inverse of ggx_energy_column: mu = kappa ((1 + 1/kappa)^(x^2) - 1), kappa = alpha_j.
      const double x = static_cast<double>(i) / (cols - 1);
      const double mu = i == cols - 1 ? 1.0 : alpha * std::expm1(x * x * std::log1p(1.0 / alpha));
      t.mu[k] = mu;
      const auto [e, err] = directional_albedo_f1(g, std::max(mu, GGX_ENERGY_MU_MIN), alpha);
      t.e[k] = std::min(e, 1.0);  // E <= 1 (G2 <= 1); the clamp removes quadrature noise above it
      t.e_error[k] = err;
    }
  }
  return t;
}

// Each table is computed the first time it is read (a function-local static: thread-safe, once).
const EnergyTexels& texels(int g) {
  if (g == GGX_ENERGY_G_SEPARABLE) {
    static const EnergyTexels separable = compute_texels(GGX_ENERGY_G_SEPARABLE);
    return separable;
  }
  static const EnergyTexels correlated = compute_texels(GGX_ENERGY_G_CORRELATED);
  return correlated;
}

GgxEnergyTable compute_table(int g) {
  const EnergyTexels& t = texels(g);
  GgxEnergyTable table;
  table.g = g;
  table.rows = GGX_ENERGY_ROWS;
  table.cols = GGX_ENERGY_COLS;
  table.alpha = t.alpha;
  table.mu = t.mu;
  table.e = t.e;
  table.e_error = t.e_error;
  table.e_avg.resize(static_cast<std::size_t>(table.rows));
  // E_avg_j: the integral of row j's interpolant (the kernel's ggx_energy_row, which reads the texels above)
  // times 2 mu, cell by cell between the nodes, where it is a smooth function of mu.
  for (int j = 0; j < table.rows; ++j) {
    if (j == 0) {
      table.e_avg[0] = 1.0;
      continue;
    }
    QuadratureOptions o;
    o.rel_tol = 1e-13;
    o.abs_tol = 1e-15;
    double sum = 0.0;
    for (int i = 0; i + 1 < table.cols; ++i) {
      const double a = t.mu[static_cast<std::size_t>(j * table.cols + i)];
      const double b = t.mu[static_cast<std::size_t>(j * table.cols + i + 1)];
      sum += integrate([&](double mu) { return 2.0 * mu * ggx_energy_row(g, j, mu); }, a, b, o).value;
    }
    table.e_avg[static_cast<std::size_t>(j)] = sum;
  }
  table.mapping =
      "rows j = 0.." + std::to_string(table.rows - 1) + ": alpha_j = c ((1 + amax/c)^(j/(rows-1)) - 1), c = " +
      std::to_string(GGX_ENERGY_C) + ", amax = " + std::to_string(GGX_ENERGY_ALPHA_MAX) +
      "; columns i = 0.." + std::to_string(table.cols - 1) +
      ": mu_i = alpha_j ((1 + 1/alpha_j)^((i/(cols-1))^2) - 1) (row 0: E = 1); texel (j, i) = e[j * cols + i]; "
      "Catmull-Rom in both coordinates as ggx_energy.sl writes it";
  return table;
}

// ---- The sheen lobe's directional albedo (sheen.sl).

constexpr double kPi = 3.14159265358979323846;

// The azimuthal integral of D_charlie at fixed theta_i, theta_o: integral_0^{2 pi} D(h) d(phi_i), with cos(theta_h) =
// (cos theta_i + cos theta_o) / |wi + wo| and |wi + wo|^2 = 2 (1 + cos theta_i cos theta_o + sin theta_i sin theta_o
// cos phi). D is even in phi, so twice the integral over [0, pi], by 48-point Gauss-Legendre (its nodes crowd the
// ends, where the lobe peaks at low roughness: phi = 0, wi and wo on the same side; numeric/quadrature.h's rule).
double azimuthal_charlie_integral(double theta_i, double theta_o, double alpha) {
  const GaussLegendreRule& g = gauss_legendre_rule(48);
  const double ci = std::cos(theta_i);
  const double si = std::sin(theta_i);
  const double co = std::cos(theta_o);
  const double so = std::sin(theta_o);
  const double p = ci + co;
  double sum = 0.0;
  for (std::size_t k = 0; k < g.nodes.size(); ++k) {
    const double phi = 0.5 * kPi * (g.nodes[k] + 1.0);
    const double n2 = 2.0 * (1.0 + ci * co + si * so * std::cos(phi));
    if (!(n2 > 0.0)) continue;  // wi antipodal to wo: measure zero
    sum += g.weights[k] * D_charlie(p / std::sqrt(n2), alpha);
  }
  return 2.0 * 0.5 * kPi * sum;
}

}  // namespace

SheenAlbedo sheen_directional_albedo(double mu, double sheen_roughness) {
  const double alpha = sheen_alpha(sheen_roughness);
  const double m = std::clamp(mu, 1e-9, 1.0);
  const double theta_o = std::acos(m);
  // E = integral over theta_i of sin cos V(theta_i, theta_o) A(theta_i, theta_o) (V does not depend on the azimuth).
  const auto f = [&](double theta_i, std::span<double> out) {
    const double ci = std::cos(theta_i);
    const double a = std::sin(theta_i) * ci * azimuthal_charlie_integral(theta_i, theta_o, alpha);
    out[0] = a * V_sheen_charlie(ci, m, alpha);
    out[1] = a * V_sheen_ashikhmin(ci, m);
  };
  QuadratureOptions o;
  o.rel_tol = 1e-8;
  o.abs_tol = 1e-9;
  o.initial_intervals = 4;
  const VectorQuadratureResult q = integrate_vector(f, 2, 0.0, 0.5 * kPi, o);
  SheenAlbedo r;
  for (int v = 0; v < 2; ++v) {
    r.e[v] = q.value[static_cast<std::size_t>(v)];
    r.error[v] = q.error[static_cast<std::size_t>(v)];
  }
  return r;
}

namespace {

SheenEnergyTable compute_sheen_table() {
  SheenEnergyTable t;
  t.rows = SHEEN_ENERGY_ROWS;
  t.cols = SHEEN_ENERGY_COLS;
  const auto cells = static_cast<std::size_t>(t.rows * t.cols);
  t.roughness.resize(static_cast<std::size_t>(t.rows));
  t.mu.resize(cells);
  t.e.resize(2 * cells);
  t.e_error.resize(2 * cells);
  for (int j = 0; j < t.rows; ++j) {
    const double r = sheen_energy_row_roughness(j);
    t.roughness[static_cast<std::size_t>(j)] = r;
    const double k = 2.0 * r;  // sheen.sl's column scale k_j
    for (int i = 0; i < t.cols; ++i) {
      const double x = static_cast<double>(i) / (t.cols - 1);
      // The inverse of sheen_energy_row's column coordinate: mu = mu_min + k ((1 + (1 - mu_min)/k)^(x^2) - 1).
      t.mu[static_cast<std::size_t>(j * t.cols + i)] =
          i == t.cols - 1 ? 1.0 : SHEEN_ENERGY_MU_MIN + k * std::expm1(x * x * std::log1p((1.0 - SHEEN_ENERGY_MU_MIN) / k));
    }
  }
  // Rows on up to 8 threads, each texel computed alone: the same numbers whatever the thread count.
#ifdef __EMSCRIPTEN__
  const unsigned threads = 1;  // the explorer's WebAssembly build has no threads
#else
  const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 8u);
#endif
  const auto work = [&](unsigned first) {
    for (int j = static_cast<int>(first); j < t.rows; j += static_cast<int>(threads)) {
      for (int i = 0; i < t.cols; ++i) {
        const auto c = static_cast<std::size_t>(j * t.cols + i);
        const SheenAlbedo a = sheen_directional_albedo(t.mu[c], t.roughness[static_cast<std::size_t>(j)]);
        for (std::size_t v = 0; v < 2; ++v) {
          t.e[v * cells + c] = a.e[v];
          t.e_error[v * cells + c] = a.error[v];
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned w = 1; w < threads; ++w) pool.emplace_back(work, w);
  work(0);
  for (auto& th : pool) th.join();
  t.mapping = "rows j = 0.." + std::to_string(t.rows - 1) +
              ": sheen roughness r_j = r_min + c ((1 + (1 - r_min)/c)^(j/(rows-1)) - 1), r_min = 0.07, c = 0.1; columns "
              "i = 0.." + std::to_string(t.cols - 1) +
              ": mu_i = mu_min + k ((1 + (1 - mu_min)/k)^((i/(cols-1))^2) - 1), k = 2 r_j, mu_min = cos(89 deg); texel "
              "(v, j, i) = e[(v * rows + j) * cols + i], v = 0 charlie, 1 ashikhmin; Catmull-Rom in both coordinates "
              "with quadratic ghosts, as sheen.sl writes it";
  return t;
}

}  // namespace

const SheenEnergyTable& sheen_energy_table() {
  static const SheenEnergyTable table = compute_sheen_table();
  return table;
}

const double* sheen_energy_texels() { return sheen_energy_table().e.data(); }

const GgxEnergyTable& ggx_energy_table(int g) {
  if (g == GGX_ENERGY_G_SEPARABLE) {
    static const GgxEnergyTable separable = compute_table(GGX_ENERGY_G_SEPARABLE);
    return separable;
  }
  static const GgxEnergyTable correlated = compute_table(GGX_ENERGY_G_CORRELATED);
  return correlated;
}

// Both Smith forms side by side, as kernels.h's fetches index them. Built from the per-form tables, each
// computed at its first use; the texels alone first, since the averages integrate the interpolated texels.
const double* ggx_energy_texels() {
  static const std::vector<double> all = [] {
    static_assert(GGX_ENERGY_ROWS == 32 && GGX_ENERGY_COLS == 32, "kernels.h indexes 32 x 32 tables");
    std::vector<double> v(texels(GGX_ENERGY_G_SEPARABLE).e);
    const std::vector<double>& c = texels(GGX_ENERGY_G_CORRELATED).e;
    v.insert(v.end(), c.begin(), c.end());
    return v;
  }();
  return all.data();
}

const double* ggx_energy_average_texels() {
  static const std::vector<double> all = [] {
    std::vector<double> v(ggx_energy_table(GGX_ENERGY_G_SEPARABLE).e_avg);
    const std::vector<double>& c = ggx_energy_table(GGX_ENERGY_G_CORRELATED).e_avg;
    v.insert(v.end(), c.begin(), c.end());
    return v;
  }();
  return all.data();
}

}  // namespace shadelab::kernel
