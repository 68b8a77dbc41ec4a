#include "shadelab/brdf/fresnel_materials.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "shadelab/brdf/fresnel.h"

namespace shadelab {
namespace {

constexpr const char* k_required[] = {"water",  "glass",  "fused_silica", "diamond", "gold",
                                      "silver", "copper", "aluminium",    "iron",    "titanium",
                                      "chromium", "platinum", "nickel"};

const FresnelMaterial& get(std::string_view name) {
  const FresnelMaterial* m = find_fresnel_material(name);
  if (m == nullptr) ADD_FAILURE() << "missing material " << name;
  static const FresnelMaterial empty{};
  return m != nullptr ? *m : empty;
}

TEST(FresnelMaterials, EveryMaterialIsPresentAndWellFormed) {
  const auto all = fresnel_materials();
  EXPECT_EQ(all.size(), std::size(k_required));
  for (const char* name : k_required) EXPECT_NE(find_fresnel_material(name), nullptr) << name;

  std::set<std::string> names;
  for (const auto& m : all) {
    const std::string name(m.name);
    EXPECT_TRUE(names.insert(name).second) << "duplicate " << name;
    for (char c : name) EXPECT_TRUE((c >= 'a' && c <= 'z') || c == '_') << name;
    EXPECT_EQ(m.wavelengths, "650, 550, 450 nm") << name;
    EXPECT_EQ(m.wavelengths, fresnel_material_wavelengths) << name;
    const bool has_year = m.source.find("(19") != std::string_view::npos ||  // "(1972)"
                          m.source.find(", 20") != std::string_view::npos;    // ", 2017-01-20"
    EXPECT_TRUE(has_year) << name << ": the source names no year";
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(m.n[c]) && m.n[c] > 0.0) << name << " n[" << c << "]";
      EXPECT_TRUE(std::isfinite(m.k[c]) && m.k[c] >= 0.0) << name << " k[" << c << "]";
      if (m.conductor) {
        EXPECT_GT(m.k[c], 1.0) << name << ": a metal absorbs strongly in the visible";
      } else {
        EXPECT_EQ(m.k[c], 0.0) << name << ": dielectrics have k = 0";
        EXPECT_GT(m.n[c], 1.0) << name;
      }
    }
    if (!m.conductor) {
      // Normal dispersion in the visible: the index rises toward the blue.
      EXPECT_LE(m.n.r, m.n.g) << name;
      EXPECT_LT(m.n.g, m.n.b) << name;
    }
  }
}

TEST(FresnelMaterials, LookupByName) {
  const auto all = fresnel_materials();
  for (const auto& m : all) {
    const FresnelMaterial* found = find_fresnel_material(m.name);
    ASSERT_NE(found, nullptr) << m.name;
    EXPECT_EQ(found, &m) << "lookup returns the table entry itself";
  }
  ASSERT_NE(find_fresnel_material("Gold"), nullptr);
  EXPECT_EQ(find_fresnel_material("GOLD")->name, "gold");
  EXPECT_EQ(find_fresnel_material("Fused_Silica")->name, "fused_silica");
  for (const char* unknown : {"", "unobtainium", "gol", "golden", "gold ", " gold", "aluminum", "glass2"}) {
    EXPECT_EQ(find_fresnel_material(unknown), nullptr) << "'" << unknown << "'";
  }
}

TEST(FresnelMaterials, DielectricIndicesBracketTheSodiumDLine) {
  // Independent single-wavelength values at the sodium D line (589 nm), which lies between the R (650 nm)
  // and G (550 nm) entries: N-BK7 n_d = 1.5168 (SCHOTT catalogue), fused silica 1.4585 (Malitson 1965),
  // diamond 2.417 (CRC Handbook), water 1.333 (CRC Handbook, 20-25 C).
  struct Case {
    const char* name;
    double n_d;
  };
  for (const Case& c : {Case{"glass", 1.5168}, Case{"fused_silica", 1.4585}, Case{"diamond", 2.417},
                        Case{"water", 1.333}}) {
    const FresnelMaterial& m = get(c.name);
    EXPECT_LE(m.n.r, c.n_d) << c.name;
    EXPECT_GE(m.n.g, c.n_d) << c.name;
  }
}

// Reference reflectances below are measured normal-incidence values of fresh, opaque films and clean
// surfaces as commonly quoted (reflectance-versus-wavelength curves of Ag, Al, Au, Cu in optics texts and
// handbooks), not values computed from the n, k in the table, so they check the table, not the arithmetic.
// Tolerances: published measurements of the same metal differ by a few percent (film preparation, oxide,
// roughness), and a channel is one wavelength, so for metals the bands are 0.03-0.06 wide where the
// reflectance is flat and wider where it changes fast (gold and copper around 450-550 nm); for dielectrics
// the reflectance follows from a well-known index to three digits, so the bands are 0.001-0.01.
TEST(FresnelMaterials, NormalIncidenceMatchesPublishedReflectance) {
  const Rgb au = fresnel_f0(get("gold"));
  EXPECT_GE(au.r, 0.93);  // ~0.95-0.97 in the red
  EXPECT_LE(au.r, 0.98);
  EXPECT_GE(au.g, 0.70);  // the steep edge around 500-550 nm
  EXPECT_LE(au.g, 0.85);
  EXPECT_GE(au.b, 0.33);  // ~0.4 at 450 nm
  EXPECT_LE(au.b, 0.45);
  EXPECT_GT(au.r, au.g);
  EXPECT_GT(au.g, au.b);  // yellow

  const Rgb ag = fresnel_f0(get("silver"));
  for (int c = 0; c < 3; ++c) {
    EXPECT_GE(ag[c], 0.95) << c;  // > 0.95 across the visible
    EXPECT_LE(ag[c], 0.995) << c;
  }

  const Rgb al = fresnel_f0(get("aluminium"));
  for (int c = 0; c < 3; ++c) {
    EXPECT_GE(al[c], 0.88) << c;  // ~0.91-0.92, dipping toward 0.87 only near 800 nm
    EXPECT_LE(al[c], 0.94) << c;
  }

  const Rgb cu = fresnel_f0(get("copper"));
  EXPECT_GE(cu.r, 0.90);  // high in the red
  EXPECT_LE(cu.r, 0.98);
  EXPECT_GE(cu.b, 0.45);  // ~0.5-0.6 in the blue
  EXPECT_LE(cu.b, 0.65);
  EXPECT_GT(cu.r, cu.g);
  EXPECT_GT(cu.g, cu.b);

  // The grey transition metals reflect about half to three quarters of visible light.
  for (const char* name : {"iron", "titanium", "chromium", "nickel", "platinum"}) {
    const Rgb f = fresnel_f0(get(name));
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(f[c], 0.45) << name << " " << c;
      EXPECT_LE(f[c], 0.75) << name << " " << c;
    }
  }

  const Rgb water = fresnel_f0(get("water"));
  const Rgb glass = fresnel_f0(get("glass"));
  const Rgb silica = fresnel_f0(get("fused_silica"));
  const Rgb diamond = fresnel_f0(get("diamond"));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(water[c], 0.020, 0.001) << c;    // 2 % (n = 1.333)
    EXPECT_NEAR(glass[c], 0.042, 0.002) << c;    // ~4 % (n = 1.52)
    EXPECT_NEAR(silica[c], 0.035, 0.002) << c;   // 3.5 % (n = 1.46)
    EXPECT_NEAR(diamond[c], 0.172, 0.005) << c;  // 17 % (n = 2.42)
  }
}

TEST(FresnelMaterials, ReflectanceAcrossAngles) {
  for (const auto& m : fresnel_materials()) {
    const Rgb f0 = fresnel_f0(m);
    const Rgb at_normal = fresnel_reflectance(m, 1.0);
    const Rgb at_grazing = fresnel_reflectance(m, 0.0);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(at_normal[c], f0[c], 1e-12) << m.name << " " << c;
      EXPECT_NEAR(at_grazing[c], 1.0, 1e-12) << m.name << " " << c;  // every interface is a mirror at grazing
      // Direct evaluation of the definitions in brdf/fresnel.h.
      const double expected_f0 = m.conductor ? f0_from_ior(m.n[c], m.k[c]) : f0_from_ior(m.n[c]);
      EXPECT_NEAR(f0[c], expected_f0, 1e-15) << m.name << " " << c;
    }
    for (int i = 0; i <= 20; ++i) {
      const double cos_i = i / 20.0;
      const Rgb f = fresnel_reflectance(m, cos_i);
      for (int c = 0; c < 3; ++c) {
        const double expected =
            m.conductor ? F_conductor(cos_i, m.n[c], m.k[c]) : F_dielectric(cos_i, m.n[c]);
        EXPECT_EQ(f[c], expected) << m.name << " cos " << cos_i;
        EXPECT_TRUE(f[c] >= 0.0 && f[c] <= 1.0) << m.name << " cos " << cos_i;
      }
    }
  }
}

}  // namespace
}  // namespace shadelab
