#include "shadelab/brdf/lafortune.h"

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

namespace {
// Albedo estimate of lobe j used for lobe selection: |s|^n * 2 pi / (n + 1) (its integral over the sphere).
double lobe_weight(double s_len, double n) { return std::pow(s_len, n) * two_pi / (n + 1.0); }

kernel::LafortuneParams kernel_params(const Rgb& kd, const Rgb& ks, const std::vector<Lafortune::Lobe>& lobes) {
  kernel::LafortuneParams p{};
  p.kd = kd;
  p.ks = ks;
  p.count = static_cast<int>(std::min<std::size_t>(lobes.size(), kernel::LAFORTUNE_MAX_LOBES));
  for (int j = 0; j < p.count; ++j) {
    const auto& l = lobes[static_cast<std::size_t>(j)];
    p.cx[j] = l.cx;
    p.cy[j] = l.cy;
    p.cz[j] = l.cz;
    p.n[j] = l.n;
  }
  return p;
}
}  // namespace

Lafortune::Lafortune(const Rgb& kd, const Rgb& ks, std::vector<Lobe> lobes)
    : LobeMixtureBrdf(kd * inv_pi, [&] {
        // Specular estimate at normal incidence: s = Cz V with V = N.
        double spec = 0.0;
        for (const auto& l : lobes) spec += lobe_weight(std::abs(l.cz), l.n);
        return lobe_probability(kd.average(), ks.average() * spec);
      }()),
      m_lobes(std::move(lobes)),
      m_k(kernel::lafortune_prepare(kernel_params(kd, ks, m_lobes))) {}

std::optional<KernelBinding> Lafortune::kernel_binding() const {
  const kernel::LafortuneParams& p = m_k.p;  // the parameters m_k was prepared from
  return KernelBinding{"lafortune", {}}
      .add("kd", p.kd)
      .add("ks", p.ks)
      .add("count", p.count)
      .add("cx", p.cx)
      .add("cy", p.cy)
      .add("cz", p.cz)
      .add("n", p.n);
}

Lafortune::Axes Lafortune::axes(const Vec3& wo) const {
  Axes a;
  a.axis.resize(m_lobes.size());
  a.probability.resize(m_lobes.size());
  double total = 0.0;
  for (std::size_t j = 0; j < m_lobes.size(); ++j) {
    const auto& l = m_lobes[j];
    a.axis[j] = {l.cx * wo.x, l.cy * wo.y, l.cz * wo.z};
    const double len = length(a.axis[j]);
    a.probability[j] = len > 0.0 ? lobe_weight(len, l.n) : 0.0;
    total += a.probability[j];
  }
  for (auto& p : a.probability) p = total > 0.0 ? p / total : 1.0 / static_cast<double>(m_lobes.size());
  return a;
}

double Lafortune::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  const Axes a = axes(wo);
  double p = 0.0;
  for (std::size_t j = 0; j < m_lobes.size(); ++j) {
    const double len = length(a.axis[j]);
    if (a.probability[j] == 0.0 || len == 0.0) continue;
    const double c = dot(a.axis[j], wi) / len;
    if (c > 0.0) p += a.probability[j] * (m_lobes[j].n + 1.0) * inv_two_pi * std::pow(c, m_lobes[j].n);
  }
  return p;
}

Vec3 Lafortune::specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  const Axes a = axes(wo);
  std::size_t j = 0;
  double acc = a.probability[0];
  while (j + 1 < m_lobes.size() && u_lobe >= acc) acc += a.probability[++j];
  const double len = length(a.axis[j]);
  if (len == 0.0) return sample_uniform_sphere(u);  // unreachable: such a lobe has probability 0
  return Frame::from_normal(a.axis[j] / len).to_world(sample_power_cosine(u, m_lobes[j].n));
}

ModelInfo lafortune_model() {
  ModelInfo info;
  info.name = "lafortune";
  info.summary = "kd/pi + ks sum_j max(0, Cx Lx Vx + Cy Ly Vy + Cz Lz Vz)^n_j";
  info.source = "Lafortune, Foo, Torrance & Greenberg 1997 eq. 4; lecture 5 'Empirical BRDF Representation'";
  info.params = {kd_param("0.3"),
                 ks_param("1"),
                 {"lobes", ParamKind::lobes, "-1,-1,1,20", -1e3, 1e3, {},
                  "lobes Cx,Cy,Cz,n separated by ';' (n in [0, 1e6]; 1 to 8 lobes)", 4,
                  {{-1e3, 1e3}, {-1e3, 1e3}, {-1e3, 1e3}, {0.0, 1e6}}}};
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    std::vector<Lafortune::Lobe> lobes;
    for (const auto& g : p.lobes("lobes")) lobes.push_back({g[0], g[1], g[2], g[3]});
    if (lobes.empty()) return make_error("brdf lafortune: parameter 'lobes' needs at least one lobe");
    if (lobes.size() > static_cast<std::size_t>(kernel::LAFORTUNE_MAX_LOBES)) {
      return make_error("brdf lafortune: parameter 'lobes' has " + std::to_string(lobes.size()) + " lobes; at most " +
                        std::to_string(kernel::LAFORTUNE_MAX_LOBES) + " are supported");
    }
    return BrdfPtr(new Lafortune(p.color("kd"), p.color("ks"), std::move(lobes)));
  };
  return info;
}

}  // namespace shadelab
