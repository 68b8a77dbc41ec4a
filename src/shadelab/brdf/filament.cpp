#include "shadelab/brdf/filament.h"

#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"

namespace shadelab {

static_assert(static_cast<int>(Filament::Diffuse::burley) == kernel::FILAMENT_DIFFUSE_BURLEY);

namespace {

kernel::FilamentParams kernel_params(const Filament::Params& p) {
  return {p.base_color, p.metallic, p.perceptual_roughness, p.reflectance, static_cast<int>(p.diffuse),
          p.energy_compensation ? 1 : 0};
}

}  // namespace

Filament::Filament(const Params& p) : LobeMixtureBrdf(Rgb{}, 0.0), m_p(p), m_k(kernel::filament_prepare(kernel_params(p))) {
  m_diffuse = Rgb(m_k.diffuse_colour) * inv_pi;
  // The specular lobe's average albedo is about Schlick's F_avg = (20 f0 + 1) / 21 (fresnel.sl).
  const Rgb f_avg = kernel::F_average_by_kind_rgb(kernel::FRESNEL_SCHLICK, kernel::rgb(1.0), kernel::rgb(0.0), m_k.f0);
  m_p_diffuse = lobe_probability(Rgb(m_k.diffuse_colour).average(), f_avg.average());
}

std::optional<KernelBinding> Filament::kernel_binding() const {
  const kernel::FilamentParams p = kernel_params(m_p);  // the parameters m_k was prepared from
  return KernelBinding{"filament", {}}
      .add("base_color", p.base_color)
      .add("metallic", p.metallic)
      .add("perceptual_roughness", p.perceptual_roughness)
      .add("reflectance", p.reflectance)
      .add("diffuse", p.diffuse)
      .add("energy_compensation", p.energy_compensation);
}

// The split sum's inputs (brdf.h SplitSumInputs): roughness sqrt(alpha), its f0 and f90 = 1, and the
// multiplicative energy compensation when it is on.
// The model's kernel writes it (kernels/filament.sl filament_split_sum), so the exported shaders read the same.
std::optional<SplitSumInputs> Filament::split_sum_inputs() const { return SplitSumInputs{kernel::filament_split_sum(m_k)}; }

bool Filament::is_reciprocal() const { return !(m_p.energy_compensation && Rgb(m_k.f0).max_component() > 0.0); }

double Filament::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  return ggx_vndf_bounded_pdf(wi, wo, m_k.alpha, m_k.alpha);
}

Vec3 Filament::specular_sample(const Vec3& wo, Vec2 u, double) const {
  return reflect(wo, sample_ggx_vndf_bounded(wo, u, m_k.alpha, m_k.alpha));
}

ModelInfo filament_model() {
  ModelInfo info;
  info.name = "filament";
  info.split_sum_sweep = SplitSumSweep{"perceptual_roughness", "metallic", "1"};
  info.summary = "(1-metallic) base_color Fd + D_GGX V_SmithGGXCorrelated F_Schlick(f0) [x (1 + f0 (1/E(N.V) - 1))]";
  info.source = "Filament documentation, 'Material system' (standard model, energy compensation)";
  info.params = {
      {"base_color", ParamKind::color, "0.8", 0.0, 1.0, {}, "base colour (diffuse albedo of dielectrics, f0 of metals)", 0, {}},
      {"metallic", ParamKind::scalar, "0", 0.0, 1.0, {}, "0 dielectric, 1 metal", 0, {}},
      {"perceptual_roughness", ParamKind::scalar, "0.5", 0.01, 1.0, {}, "perceptual roughness, alpha = its square", 0, {}},
      {"reflectance", ParamKind::scalar, "0.5", 0.0, 1.0, {}, "dielectric f0 = 0.16 reflectance^2 (0.5: f0 = 0.04)", 0, {}},
      {"diffuse", ParamKind::choice, "lambert", 0, 0, {"lambert", "burley"}, "diffuse BRDF", 0, {}},
      {"energy_compensation", ParamKind::choice, "on", 0, 0, {"on", "off"}, "scale the specular lobe by 1 + f0 (1/E - 1)", 0, {}},
  };
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    Filament::Params q;
    q.base_color = p.color("base_color");
    q.metallic = p.scalar("metallic");
    q.perceptual_roughness = p.scalar("perceptual_roughness");
    q.reflectance = p.scalar("reflectance");
    q.diffuse = p.choice("diffuse") == "burley" ? Filament::Diffuse::burley : Filament::Diffuse::lambert;
    q.energy_compensation = p.choice("energy_compensation") == "on";
    return BrdfPtr(new Filament(q));
  };
  return info;
}

}  // namespace shadelab
