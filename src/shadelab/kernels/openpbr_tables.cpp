// The openpbr kernel's dielectric albedo table (openpbr.sl, openpbr.h): E_d(mu, alpha, e) of the GGX reflection lobe
// with the exact dielectric Fresnel of eta = (1 + e)/(1 - e), by the library's deterministic quadrature: a tensor
// Gauss-Legendre rule (numeric's gauss_legendre_rule) over the visible normals, mapped by the spherical-cap
// sampler of Dupuy & Benyoub 2023 ("Sampling Visible GGX Normals with Spherical Caps", listing 3), whose density is
// the VNDF D_o(h) = G1(wo) max(0, wo.h) D(h) / mu_o (Heitz 2018 eq. 1), so that
//   E_d(mu_o) = integral over the unit square of F(wo.h, eta) G2(wi, wo) / G1(wo) [wi.z > 0],  wi = reflect(wo, h).
// One pass of the geometry serves every slice e_k (only F depends on e). Rows on up to 8 threads, each texel
// computed alone: the same numbers whatever the number of threads.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "shadelab/kernels/openpbr.h"
#include "shadelab/numeric/quadrature.h"

namespace shadelab::kernel {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kRule = 48;  // Gauss-Legendre nodes per axis (and per piece along u1)

// E_d at (mu, alpha) for every slice at once (out[k], k < slices), with n-node rules. The azimuth of the cap is
// folded to [0, pi] (wo in the xz-plane: the integrand is even in phi) and integrated by Gauss-Legendre; along the
// cap's height u1 the part where wi falls below the horizon is cut off first (scanned on 512 cells, the sign changes
// of wi.z refined by bisection), so that each Gauss-Legendre piece integrates a smooth function: G2 -> 0 linearly at
// wi.z = 0, a kink a rule across it would resolve only as n^-2.
void directional_albedo_slices(double mu, double alpha, int n, const double* e, int slices, double* out) {
  const GaussLegendreRule& g = gauss_legendre_rule(n);
  const double m = std::clamp(mu, GGX_ENERGY_MU_MIN, 1.0);
  const vec3 wo(std::sqrt(std::max(0.0, (1.0 - m) * (1.0 + m))), 0.0, m);
  const double g1 = G1_ggx(wo, alpha, alpha);
  const vec3 ws = normalize(vec3(alpha * wo.x, 0.0, wo.z));  // the view in the stretched (alpha = 1) space
  std::vector<double> eta(static_cast<std::size_t>(slices));
  for (int k = 0; k < slices; ++k) {
    out[k] = 0.0;
    eta[static_cast<std::size_t>(k)] = e[k] > 0.0 && e[k] < 1.0 ? openpbr_eta_from_e(e[k]) : 0.0;
  }
  for (std::size_t b = 0; b < g.nodes.size(); ++b) {
    const double phi = 0.5 * kPi * (g.nodes[b] + 1.0);
    const double cp = std::cos(phi), sp = std::sin(phi);
    // The half vector, its cosine to wo and wi at cap height parameter u1 (z = (1 - u1)(1 + ws.z) - ws.z).
    const auto at = [&](double u1, vec3& h, double& oh, vec3& wi) {
      const double z = (1.0 - u1) * (1.0 + ws.z) - ws.z;
      const double sin_t = std::sqrt(std::clamp(1.0 - z * z, 0.0, 1.0));
      const vec3 hs = vec3(sin_t * cp, sin_t * sp, z) + ws;
      const vec3 hv(alpha * hs.x, alpha * hs.y, hs.z);
      if (dot(hv, hv) == 0.0) {  // the cap's lowest point at normal incidence (u1 = 1, ws = +Z): no normal there
        h = vec3(0.0, 0.0, 1.0);
        oh = 0.0;
        wi = vec3(0.0, 0.0, -1.0);  // outside the integrand (it was 0/0, a NaN that every test read as outside)
        return;
      }
      h = normalize(hv);
      oh = dot(wo, h);
      wi = h * (2.0 * oh) - wo;
    };
    const auto height = [&](double u1) {
      vec3 h, wi;
      double oh = 0.0;
      at(u1, h, oh, wi);
      return wi.z;
    };
    constexpr int cells = 512;
    double lo = 0.0;
    double f_lo = height(0.0);
    double start = f_lo > 0.0 ? 0.0 : -1.0;
    const auto piece = [&](double a0, double a1) {
      // u1 = a0 + (a1 - a0) s^2 (3 - 2 s): nodes crowd both ends (the layer near the cut, where G2 rises from 0
      // within wi.z ~ alpha, is thin for sharp lobes), with the Jacobian 6 s (1 - s).
      const double len = a1 - a0;
      for (std::size_t a = 0; a < g.nodes.size(); ++a) {
        const double sv = 0.5 * (g.nodes[a] + 1.0);
        const double u1 = a0 + len * sv * sv * (3.0 - 2.0 * sv);
        const double half = 0.5 * len * 6.0 * sv * (1.0 - sv);
        vec3 h, wi;
        double oh = 0.0;
        at(u1, h, oh, wi);
        if (!(oh > 0.0) || !(wi.z > 0.0)) continue;
        const double w = 0.5 * g.weights[b] * half * g.weights[a] * G2_ggx_correlated(wi, wo, alpha, alpha) / g1;
        for (int k = 0; k < slices; ++k) {
          const double f = e[k] <= 0.0 ? 0.0 : (e[k] >= 1.0 ? 1.0 : F_dielectric(oh, eta[static_cast<std::size_t>(k)]));
          out[k] += w * f;
        }
      }
    };
    for (int c = 1; c <= cells; ++c) {
      const double hi = static_cast<double>(c) / cells;
      const double f_hi = height(hi);
      if ((f_lo > 0.0) != (f_hi > 0.0)) {
        double x0 = lo, x1 = hi;  // bisection to the crossing
        for (int it = 0; it < 60 && x1 - x0 > 1e-15; ++it) {
          const double xm = 0.5 * (x0 + x1);
          if ((height(xm) > 0.0) == (f_lo > 0.0)) {
            x0 = xm;
          } else {
            x1 = xm;
          }
        }
        const double cross = 0.5 * (x0 + x1);
        if (f_lo > 0.0) {
          piece(start, cross);
          start = -1.0;
        } else {
          start = cross;
        }
      }
      lo = hi;
      f_lo = f_hi;
    }
    if (start >= 0.0) piece(start, 1.0);
  }
}

double slice_e(int k) { return openpbr_de_slice_e(k); }

// The inverse of openpbr_de_column: mu = kappa ((1 + 1/kappa)^(x^2) - 1), kappa = max(alpha_j, 0.1).
double column_mu(int j, int i) {
  const double alpha = std::max(ggx_energy_row_alpha(j), OPENPBR_DE_KAPPA_MIN);
  const double x = static_cast<double>(i) / (GGX_ENERGY_COLS - 1);
  return i == GGX_ENERGY_COLS - 1 ? 1.0 : alpha * std::expm1(x * x * std::log1p(1.0 / alpha));
}

struct Texels {
  std::vector<double> e;
  double seconds = 0.0;
};

Texels compute_texels() {
  const auto start = std::chrono::steady_clock::now();
  const int slices = OPENPBR_DE_SLICES, rows = GGX_ENERGY_ROWS, cols = GGX_ENERGY_COLS;
  Texels t;
  t.e.assign(static_cast<std::size_t>(slices * rows * cols), 0.0);
  double e_nodes[OPENPBR_DE_SLICES];
  for (int k = 0; k < slices; ++k) e_nodes[k] = slice_e(k);
#ifdef __EMSCRIPTEN__
  const unsigned threads = 1;
#else
  const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 8u);
#endif
  const auto work = [&](unsigned first) {
    double fine[OPENPBR_DE_SLICES];
    for (int j = 1 + static_cast<int>(first); j < rows; j += static_cast<int>(threads)) {
      const double alpha = ggx_energy_row_alpha(j);
      for (int i = 0; i < cols; ++i) {
        const double mu = column_mu(j, i);
        directional_albedo_slices(mu, alpha, kRule, e_nodes, slices, fine);
        for (int k = 0; k < slices; ++k) {
          t.e[static_cast<std::size_t>((k * rows + j) * cols + i)] = std::clamp(fine[k], 0.0, 1.0);
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned w = 1; w < threads; ++w) pool.emplace_back(work, w);
  work(0);
  for (auto& th : pool) th.join();
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

const Texels& texels() {
  static const Texels t = compute_texels();
  return t;
}

// The averages: row 0 the hemispherical Fresnel average 2 integral F(mu, eta_k) mu d(mu); rows j > 0 the exact
// integral of the row's interpolant (the kernel's openpbr_de_row over the texels above) times 2 mu, cell by cell.
std::vector<double> compute_averages() {
  const int slices = OPENPBR_DE_SLICES, rows = GGX_ENERGY_ROWS, cols = GGX_ENERGY_COLS;
  std::vector<double> avg(static_cast<std::size_t>(slices * rows), 0.0);
  QuadratureOptions o;
  o.rel_tol = 1e-12;
  o.abs_tol = 1e-14;
  for (int k = 0; k < slices; ++k) {
    const double e = slice_e(k);
    avg[static_cast<std::size_t>(k * rows)] =
        integrate([&](double mu) { return 2.0 * mu * openpbr_fresnel_e(mu, e); }, 0.0, 1.0, o).value;
    for (int j = 1; j < rows; ++j) {
      const double alpha_j = ggx_energy_row_alpha(j);
      double sum = 0.0;
      for (int i = 0; i + 1 < cols; ++i) {
        const double a = i == 0 ? 0.0 : column_mu(j, i);
        const double b = column_mu(j, i + 1);
        sum += integrate([&](double mu) { return 2.0 * mu * openpbr_de_row(k, j, openpbr_de_column(alpha_j, mu), mu); },
                         a, b, o)
                   .value;
      }
      avg[static_cast<std::size_t>(k * rows + j)] = sum;
    }
  }
  return avg;
}

}  // namespace

std::pair<double, double> dielectric_directional_albedo(double mu, double alpha, double e, int n) {
  const int rule = n > 0 ? n : kRule;
  double fine = 0.0, coarse = 0.0;
  directional_albedo_slices(mu, alpha, rule, &e, 1, &fine);
  directional_albedo_slices(mu, alpha, std::max(2, rule / 2), &e, 1, &coarse);
  return {fine, std::abs(fine - coarse)};
}

const double* dielectric_energy_texels() { return texels().e.data(); }

const double* dielectric_energy_average_texels() {
  static const std::vector<double> avg = compute_averages();
  return avg.data();
}

const DielectricEnergyTable& dielectric_energy_table() {
  static const DielectricEnergyTable table = [] {
    DielectricEnergyTable t;
    t.slices = OPENPBR_DE_SLICES;
    t.rows = GGX_ENERGY_ROWS;
    t.cols = GGX_ENERGY_COLS;
    t.e = texels().e;
    t.seconds = texels().seconds;
    const double* a = dielectric_energy_average_texels();
    t.e_avg.assign(a, a + t.slices * t.rows);
    return t;
  }();
  return table;
}

}  // namespace shadelab::kernel
