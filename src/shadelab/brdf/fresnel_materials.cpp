#include "shadelab/brdf/fresnel_materials.h"

#include <array>
#include <cstddef>

#include "shadelab/brdf/fresnel.h"

namespace shadelab {

namespace {

constexpr std::string_view k_wl = fresnel_material_wavelengths;  // "650, 550, 450 nm" for every entry

constexpr std::string_view k_johnson_christy_1972 =
    "P. B. Johnson and R. W. Christy, \"Optical constants of the noble metals\", "
    "Phys. Rev. B 6, 4370-4379 (1972)";
constexpr std::string_view k_johnson_christy_1974 =
    "P. B. Johnson and R. W. Christy, \"Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, "
    "and Pd\", Phys. Rev. B 9, 5056-5070 (1974)";
constexpr std::string_view k_rakic_1998 =
    "A. D. Rakic, A. B. Djurisic, J. M. Elazar, M. L. Majewski, \"Optical properties of metallic films for "
    "vertical-cavity optoelectronic devices\", Appl. Opt. 37, 5271-5283 (1998), Lorentz-Drude model";

// How the numbers were obtained (wavelengths in micrometres, "lerp a-b" = linear interpolation in wavelength
// between the table rows at a and b; 4 decimals kept). Sellmeier: n^2 = 1 + sum B_i l^2 / (l^2 - C_i).
constexpr std::array<FresnelMaterial, 13> k_materials{{
    // Water, liquid, 25 C: Hale & Querry 1973, tabulated rows 0.650, 0.550, 0.450 (no interpolation needed);
    // their k there is 1.6e-8, 2.0e-9, 1.0e-9, dropped.
    {"water", false, {1.331, 1.333, 1.337}, {0.0, 0.0, 0.0}, k_wl,
     "G. M. Hale and M. R. Querry, \"Optical constants of water in the 200-nm to 200-um wavelength region\", "
     "Appl. Opt. 12, 555-563 (1973)"},
    // Glass = SCHOTT N-BK7 borosilicate crown, from its Sellmeier formula: B = 1.03961212, 0.231792344,
    // 1.01046945; C = 0.00600069867, 0.0200179144, 103.560653 um^2 (SCHOTT data sheet, catalogue of 2017).
    {"glass", false, {1.51452, 1.51852, 1.52532}, {0.0, 0.0, 0.0}, k_wl,
     "SCHOTT AG, \"Optical Glass - Data Sheets\", N-BK7 Sellmeier coefficients (SCHOTT Zemax catalogue, "
     "2017-01-20)"},
    // Fused silica (SiO2), from Malitson's Sellmeier formula: B = 0.6961663, 0.4079426, 0.8974794;
    // sqrt(C) = 0.0684043, 0.1162414, 9.896161 um.
    {"fused_silica", false, {1.45653, 1.45991, 1.46557}, {0.0, 0.0, 0.0}, k_wl,
     "I. H. Malitson, \"Interspecimen comparison of the refractive index of fused silica\", "
     "J. Opt. Soc. Am. 55, 1205-1209 (1965)"},
    // Diamond, from Peter's two-term Sellmeier formula: B = 0.3306, 4.3356; sqrt(C) = 0.1750, 0.1060 um.
    {"diamond", false, {2.41050, 2.42295, 2.44536}, {0.0, 0.0, 0.0}, k_wl,
     "F. Peter, \"Ueber Brechungsindizes und Absorptionskonstanten des Diamanten zwischen 644 und 226 mu\", "
     "Z. Phys. 15, 358-368 (1923)"},

    // Gold: Johnson & Christy 1972, lerp 0.6168-0.6595, 0.5486-0.5821, 0.4305-0.4509.
    {"gold", true, {0.1556, 0.4241, 1.3831}, {3.6024, 2.4721, 1.9155}, k_wl, k_johnson_christy_1972},
    // Silver: Johnson & Christy 1972, same rows as gold.
    {"silver", true, {0.0522, 0.0596, 0.0400}, {4.4094, 3.5974, 2.6484}, k_wl, k_johnson_christy_1972},
    // Copper: Johnson & Christy 1972, same rows as gold.
    {"copper", true, {0.2378, 1.0066, 1.2404}, {3.6264, 2.5823, 2.3929}, k_wl, k_johnson_christy_1972},
    // Aluminium (evaporated films): Rakic 1995 tabulated n, k, lerp 0.61993-0.65225, 0.51660-0.56357,
    // 0.44280-0.47687.
    {"aluminium", true, {1.5580, 1.0152, 0.6332}, {7.7124, 6.6273, 5.4544}, k_wl,
     "A. D. Rakic, \"Algorithm for the determination of intrinsic optical constants of metal films: "
     "application to aluminum\", Appl. Opt. 34, 4755-4767 (1995)"},
    // Iron: Johnson & Christy 1974 (Rakic et al. 1998 has no iron), lerp 0.617-0.659, 0.549-0.582,
    // 0.431-0.451.
    {"iron", true, {2.9114, 2.9497, 2.5845}, {3.0893, 2.9318, 2.7670}, k_wl, k_johnson_christy_1974},
    // Titanium and chromium: Johnson & Christy 1974's measured table, lerp 0.617-0.659, 0.549-0.582,
    // 0.431-0.451, as for iron. (Until issue 16 these came from Rakic et al. 1998's Lorentz-Drude fit, which
    // the numbers matched, but whose fit misses the visible for these two: Ti's F0 rose toward the blue,
    // 0.577 / 0.574 / 0.592, and Cr's was 0.64-0.65, where the measurements give 0.616 / 0.582 / 0.545 and a
    // flat 0.555, the values published material tables list.)
    {"titanium", true, {2.7407, 2.5418, 2.2670}, {3.8143, 3.4345, 3.0385}, k_wl, k_johnson_christy_1974},
    {"chromium", true, {3.1071, 3.1812, 2.3230}, {3.3314, 3.3291, 3.1350}, k_wl, k_johnson_christy_1974},
    // Nickel, platinum: the Lorentz-Drude model of Rakic et al. 1998 (their fitted parameters, which
    // reproduce the measured data they compiled), evaluated on a fine grid and interpolated between the two
    // grid points around each wavelength (the grid steps are under 4 nm).
    // Nickel: lerp 0.64983-0.65193, 0.54958-0.55136, 0.44862-0.45006.
    {"nickel", true, {2.0587, 1.8145, 1.6493}, {3.7635, 3.2587, 2.6705}, k_wl, k_rakic_1998},
    // Platinum: lerp 0.64977-0.65232, 0.54908-0.55123, 0.44967-0.45144.
    {"platinum", true, {2.3699, 2.0908, 1.8511}, {4.2536, 3.7036, 3.1398}, k_wl, k_rakic_1998},
}};

constexpr char ascii_lower(char c) {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}

constexpr bool equal_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (ascii_lower(a[i]) != ascii_lower(b[i])) return false;
  }
  return true;
}

}  // namespace

std::span<const FresnelMaterial> fresnel_materials() { return k_materials; }

const FresnelMaterial* find_fresnel_material(std::string_view name) {
  for (const auto& m : k_materials) {
    if (equal_ignoring_case(m.name, name)) return &m;
  }
  return nullptr;
}

Rgb fresnel_reflectance(const FresnelMaterial& m, double cos_i) {
  if (m.conductor) return F_conductor(cos_i, m.n, m.k);  // complex Fresnel, brdf/fresnel.h
  return {F_dielectric(cos_i, m.n.r), F_dielectric(cos_i, m.n.g), F_dielectric(cos_i, m.n.b)};
}

Rgb fresnel_f0(const FresnelMaterial& m) {
  // ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2), brdf/fresnel.h f0_from_ior (k = 0 for dielectrics).
  return {f0_from_ior(m.n.r, m.k.r), f0_from_ior(m.n.g, m.k.g), f0_from_ior(m.n.b, m.k.b)};
}

}  // namespace shadelab
