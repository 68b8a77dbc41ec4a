#include "shadelab/brdf/ggx.h"

#include <cmath>
#include <utility>

#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"

namespace shadelab {

namespace {

static_assert(static_cast<int>(Ggx::Geometry::smith_correlated) == kernel::GGX_ENERGY_G_CORRELATED &&
              static_cast<int>(Ggx::Geometry::smith_separable) == kernel::GGX_ENERGY_G_SEPARABLE);
static_assert(static_cast<int>(Ggx::FresnelKind::dielectric) == kernel::FRESNEL_DIELECTRIC &&
              static_cast<int>(Ggx::FresnelKind::conductor) == kernel::FRESNEL_CONDUCTOR &&
              static_cast<int>(Ggx::FresnelKind::schlick) == kernel::FRESNEL_SCHLICK &&
              static_cast<int>(Ggx::FresnelKind::none) == kernel::FRESNEL_NONE);
static_assert(static_cast<int>(Ggx::MultipleScattering::kulla_conty) == kernel::GGX_MS_KULLA_CONTY);

kernel::GgxParams kernel_params(const Ggx::Params& p) {
  return {p.kd, p.ks, p.alpha_x, p.alpha_y, static_cast<int>(p.f), p.f0, p.ior, p.k, static_cast<int>(p.g), static_cast<int>(p.ms)};
}

// The albedo estimates behind p_d of the one-sample MIS: the cosine lobe carries the diffuse base and the
// (diffuse-like) multiple-scattering lobe, whose albedo is about F_ms (1 - E_avg); the specular sampler
// carries about F_avg.
std::pair<double, double> lobe_albedos(const Ggx::Params& p, const kernel::GgxState& k) {
  const kernel::rgb f_avg = kernel::F_average_by_kind_rgb(static_cast<int>(p.f), p.ior, p.k, p.f0);
  double ms = 0.0;
  if (p.ms == Ggx::MultipleScattering::kulla_conty) {
    const Rgb scale = k.ms_scale;  // F_ms / (pi (1 - E_avg))
    const double e_avg = kernel::ggx_energy_average_at(k.ms_rows);
    ms = scale.average() * pi * (1.0 - e_avg) * (1.0 - e_avg);
  }
  return {p.kd.average() + ms, (p.ks * Rgb(f_avg)).average()};
}

}  // namespace

Ggx::Ggx(const Params& p)
    : LobeMixtureBrdf(p.kd * inv_pi, 0.0), m_p(p), m_k(kernel::ggx_prepare(kernel_params(p))) {
  const auto [diffuse, specular] = lobe_albedos(m_p, m_k);
  m_p_diffuse = lobe_probability(diffuse, specular);
}

std::optional<KernelBinding> Ggx::kernel_binding() const {
  const kernel::GgxParams& p = m_k.p;  // the parameters m_k was prepared from
  return KernelBinding{"ggx", {}}
      .add("kd", p.kd)
      .add("ks", p.ks)
      .add("alpha_x", p.alpha_x)
      .add("alpha_y", p.alpha_y)
      .add("f", p.f)
      .add("f0", p.f0)
      .add("ior", p.ior)
      .add("k", p.k)
      .add("g", p.g)
      .add("ms", p.ms);
}

// The split sum's inputs (brdf.h SplitSumInputs): roughness sqrt(sqrt(alpha_x alpha_y)); f0 the model's own
// Fresnel at normal incidence (fresnel.sl F_by_kind_rgb at cos = 1: Schlick's f0, 1 for f = none, the exact F(0)
// of a dielectric or conductor, for which the DFG table's Schlick is then an approximation) times ks; f90 = ks;
// the Kulla-Conty lobe when it is on. The DFG table is the height-correlated G2: with g = smith-separable the
// split sum uses it anyway (an approximation).
// The model's kernel writes it (kernels/ggx.sl ggx_split_sum), so the exported shaders read the same.
std::optional<SplitSumInputs> Ggx::split_sum_inputs() const { return SplitSumInputs{kernel::ggx_split_sum(m_k)}; }

double Ggx::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  switch (m_p.sampler) {
    case Sampler::ndf: return ggx_ndf_pdf(wi, wo, m_p.alpha_x, m_p.alpha_y);
    case Sampler::vndf:
    case Sampler::vndf_caps: return ggx_vndf_pdf(wi, wo, m_p.alpha_x, m_p.alpha_y);
    case Sampler::vndf_bounded: return ggx_vndf_bounded_pdf(wi, wo, m_p.alpha_x, m_p.alpha_y);
  }
  return 0.0;
}

Vec3 Ggx::specular_sample(const Vec3& wo, Vec2 u, double) const {
  Vec3 h;
  switch (m_p.sampler) {
    case Sampler::ndf: h = sample_ggx_ndf(u, m_p.alpha_x, m_p.alpha_y); break;
    case Sampler::vndf: h = sample_ggx_vndf_heitz(wo, u, m_p.alpha_x, m_p.alpha_y); break;
    case Sampler::vndf_caps: h = sample_ggx_vndf_caps(wo, u, m_p.alpha_x, m_p.alpha_y); break;
    case Sampler::vndf_bounded: h = sample_ggx_vndf_bounded(wo, u, m_p.alpha_x, m_p.alpha_y); break;
  }
  return reflect(wo, h);
}

ModelInfo ggx_model() {
  ModelInfo info;
  info.name = "ggx";
  info.split_sum_sweep = SplitSumSweep{"roughness", "kd", "0"};
  info.summary = "kd/pi + ks F D_GGX G2 / (4 N.L N.V)  [+ (1-E(mu_o))(1-E(mu_i)) F_ms / (pi (1-E_avg)) with ms=kulla-conty]";
  info.source = "Walter et al. 2007; Heitz 2014 (Smith G); Kulla & Conty 2017 (ms); Heitz 2018, Dupuy & Benyoub 2023, "
                "Eto & Tokuyoshi 2023 (samplers)";
  info.params = {
      kd_param("0.2"),
      {"ks", ParamKind::color, "1", 0.0, 1.0, {}, "tint of the specular lobe (1: the plain model)", 0, {}},
      {"alpha", ParamKind::scalar, "0.25", 1e-4, 1.0, {}, "GGX roughness (perceptual roughness squared); or give roughness, or alpha_x and alpha_y", 0, {}},
      {"roughness", ParamKind::scalar, "0.5", 0.01, 1.0, {}, "perceptual roughness, alpha = roughness^2", 0, {}},
      {"alpha_x", ParamKind::scalar, "0.25", 1e-4, 1.0, {}, "anisotropic roughness along the tangent (+X), with alpha_y", 0, {}},
      {"alpha_y", ParamKind::scalar, "0.25", 1e-4, 1.0, {}, "anisotropic roughness along the bitangent (+Y), with alpha_x", 0, {}},
      {"f", ParamKind::choice, "schlick", 0, 0, {"schlick", "dielectric", "conductor", "none"}, "Fresnel term", 0, {}},
      {"f0", ParamKind::color, "0.04", 0.0, 1.0, {}, "reflectance at normal incidence (schlick)", 0, {}},
      {"ior", ParamKind::color, "1.5", 1e-3, 100.0, {}, "real part of the relative IOR (dielectric, conductor)", 0, {}},
      {"k", ParamKind::color, "0", 0.0, 100.0, {}, "imaginary part of the IOR (conductor)", 0, {}},
      {"g", ParamKind::choice, "smith-correlated", 0, 0, {"smith-correlated", "smith-separable"}, "Smith masking-shadowing: height-correlated or separable", 0, {}},
      {"ms", ParamKind::choice, "none", 0, 0, {"none", "kulla-conty"}, "multiple-scattering energy compensation", 0, {}},
      {"sampling", ParamKind::choice, "vndf-bounded", 0, 0, {"ndf", "vndf", "vndf-caps", "vndf-bounded"}, "specular sampler", 0, {}},
  };
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    Ggx::Params q;
    q.kd = p.color("kd");
    q.ks = p.color("ks");
    const bool axy = p.is_set("alpha_x") || p.is_set("alpha_y");
    if (p.is_set("alpha") && p.is_set("roughness")) {
      return make_error("brdf ggx: give parameter 'alpha' or 'roughness', not both (alpha = roughness^2)");
    }
    if (axy && (p.is_set("alpha") || p.is_set("roughness"))) {
      return make_error("brdf ggx: give 'alpha_x' and 'alpha_y', or 'alpha' or 'roughness', not both kinds");
    }
    if (p.is_set("alpha_x") != p.is_set("alpha_y")) {
      return make_error("brdf ggx: give both 'alpha_x' and 'alpha_y' (anisotropic), or 'alpha' alone");
    }
    if (axy) {
      q.alpha_x = p.scalar("alpha_x");
      q.alpha_y = p.scalar("alpha_y");
    } else if (p.is_set("roughness")) {
      q.alpha_x = q.alpha_y = alpha_from_perceptual_roughness(p.scalar("roughness"));
    } else {
      q.alpha_x = q.alpha_y = p.scalar("alpha");
    }
    q.f = pick_choice<Ggx::FresnelKind>(p.choice("f"), {{"schlick", Ggx::FresnelKind::schlick},
                                                 {"dielectric", Ggx::FresnelKind::dielectric},
                                                 {"conductor", Ggx::FresnelKind::conductor},
                                                 {"none", Ggx::FresnelKind::none}});
    q.f0 = p.color("f0");
    q.ior = p.color("ior");
    q.k = p.color("k");
    q.g = p.choice("g") == "smith-separable" ? Ggx::Geometry::smith_separable : Ggx::Geometry::smith_correlated;
    q.ms = p.choice("ms") == "kulla-conty" ? Ggx::MultipleScattering::kulla_conty : Ggx::MultipleScattering::none;
    q.sampler = pick_choice<Ggx::Sampler>(p.choice("sampling"), {{"vndf-bounded", Ggx::Sampler::vndf_bounded},
                                                          {"ndf", Ggx::Sampler::ndf},
                                                          {"vndf", Ggx::Sampler::vndf},
                                                          {"vndf-caps", Ggx::Sampler::vndf_caps}});
    return BrdfPtr(new Ggx(q));
  };
  return info;
}

}  // namespace shadelab
