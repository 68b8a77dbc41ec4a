// The game renderer's split-sum specular ambient for the microfacet-GGX models (game_renderer.h):
//   L_spec = prefiltered_ggx(R, r) (f0 A(N.V, r) + f90 B(N.V, r)).
// Oracles, each computed independently of the renderer's table lookups:
// - a constant environment L: integral L f cos = L (f0 A + B) by the definition of A and B (dfg.h), for
//   Schlick's Fresnel and the height-correlated G2, so the split sum is exact there up to the DFG table's
//   bilinear interpolation; A and B here come from the adaptive quadrature dfg_quadrature at the exact
//   (N.V, alpha) of each pixel, not from the table;
// - the same sphere path-traced (the environment alone, no occlusion on a convex sphere: one bounce is
//   everything), agreeing within its standard error and the table's interpolation error;
// - a real environment: the prefiltered factor against the brute-force GGX convolution of the baked cube
//   (prefilter_ggx_brute_force, every texel with its solid angle) at a roughness on a level of the chain.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "shadelab/brdf/registry.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/envmap/specular/prefilter_ggx.h"
#include "shadelab/image/image_io.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/render/test_scenes.h"

namespace shadelab {
namespace {

// The split sum is opt-in for now (GameOptions::ggx_specular defaults to phong: docs/renderer.md says why).
GameOptions split_sum_options() {
  GameOptions o;
  o.ggx_specular = GameGgxSpecular::split_sum;
  return o;
}

using testing::add_material;

// A unit sphere at the origin under a constant environment L = 0.5, seen along -Z from (x, 0, 4): the hit
// normal is (x, 0, sqrt(1 - x^2)), so N.V = sqrt(1 - x^2).
Scene constant_sphere(const std::string& model, ParamAssignments params) {
  return testing::furnace_sphere(model, std::move(params));
}

const double offsets[] = {0.0, 0.5, 0.8, 0.95, 0.99};  // N.V = 1, 0.866, 0.6, 0.312, 0.141

TEST(GameSplitSum, AConstantEnvironmentGivesTheDfgIntegralPerPixel) {
  // ggx with f = schlick: L (f0 A + B); with f = none (F = 1): L (A + B) = L E_ss(N.V). The bilinear read of
  // the 64 x 64 table is the only error: the largest relative difference seen was 0.275%; 0.5% is allowed.
  // Dropping B in the renderer fails it (measured below in the commit message).
  struct Case {
    double roughness;
    double f0;  // < 0: f = none
  };
  const Case cases[] = {{0.2, 0.04}, {0.5, 0.04}, {0.8, 0.04}, {0.2, -1.0}, {0.5, 0.9}, {0.9, -1.0}};
  // A constant environment is constant in a chain of any size: small faces, a quick bake per call.
  GameOptions small = split_sum_options();
  small.environment_size = small.specular_size = 16;
  double worst = 0.0;
  for (const Case& c : cases) {
    ParamAssignments p{{"kd", "0"}, {"roughness", std::to_string(c.roughness)}};
    if (c.f0 < 0.0) {
      p.push_back({"f", "none"});
    } else {
      p.push_back({"f", "schlick"});
      p.push_back({"f0", std::to_string(c.f0)});
    }
    const Scene s = constant_sphere("ggx", p);
    for (const double x : offsets) {
      const double mu = std::sqrt(1.0 - x * x);
      const DfgValue v = dfg_quadrature(mu, c.roughness * c.roughness, 1e-9);
      const double f0 = c.f0 < 0.0 ? 1.0 : c.f0;
      const double expected = 0.5 * (f0 * v.a + v.b);
      const Rgb game = game_radiance(s, {x, 0, 4}, {0, 0, -1}, small).value();
      const double rel = std::abs(game.g - expected) / expected;
      worst = std::max(worst, rel);
      EXPECT_LE(rel, 5e-3) << "r " << c.roughness << " f0 " << c.f0 << " N.V " << mu << ": game " << game.g
                           << ", L (f0 A + B) " << expected;
    }
  }
  std::printf("split sum vs L (f0 A + B) by quadrature: worst relative difference %.3g%%\n", 100.0 * worst);
  RecordProperty("worst_relative", std::to_string(worst));
}

TEST(GameSplitSum, AConstantEnvironmentAgreesWithThePathTracer) {
  // The path tracer sees the same sphere (environment only, one bounce, BRDF sampling): its pixel estimates
  // L integral f cos, which the split sum reproduces exactly for a constant environment (above), so the two
  // agree within 4 sigma plus the table's 0.5%. Filament's compensation scales by 1 + f0 (1/E - 1): the
  // BRDF reads E from kernels/ggx_energy.sl, the renderer uses A + B of its DFG table (two quadratures of
  // the same integral, within 3e-4 of each other), and a metal of f0 = 1 reflects L (the white furnace).
  struct Case {
    std::string model;
    ParamAssignments params;
  };
  const Case cases[] = {
      {"ggx", {{"kd", "0"}, {"roughness", "0.3"}}},
      {"ggx", {{"kd", "0"}, {"roughness", "0.7"}, {"f", "schlick"}, {"f0", "0.9"}}},
      {"filament", {{"base_color", "0.9,0.6,0.3"}, {"metallic", "1"}, {"perceptual_roughness", "0.6"}}},
      {"filament", {{"base_color", "0"}, {"metallic", "0"}, {"perceptual_roughness", "0.4"}}},
  };
  for (const Case& c : cases) {
    const Scene s = constant_sphere(c.model, c.params);
    for (const double x : offsets) {
      const Vec3 o{x, 0, 4};
      const Rgb game = game_radiance(s, o, {0, 0, -1}, split_sum_options()).value();
      const auto ref = estimate_radiance(s, o, {0, 0, -1}, 20000, SamplingMode::brdf, 1, 7).value();
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(game[ch], ref.mean[ch], 4.0 * ref.standard_error[ch] + 5e-3 * ref.mean[ch] + 1e-9)
            << c.model << " x " << x << " channel " << ch;
      }
    }
  }
}

// Under real environments (Blender's sunrise, studio and forest, the sun in the lat-long) the GGX chain the
// renderer bakes (64 x 64, 7 levels, linear mapping r_i = i / 6, the default 1024 samples) against the GGX
// lobe's convolution of the baked cube over every texel (prefilter_ggx_brute_force, itself checked against
// the envmap test's own sum), at the roughness of levels 2, 3 and 4 (faces 16, 8, 4):
// - at the texel centres: the levels of face 16 and below are exact sums (prefilter_ggx.h, 3 n^2 <= 1024),
//   so the chain is the convolution up to float storage. With 512 samples the face-16 level was sampled
//   and missed the sun by 45.8% (sunrise) and 65% (studio) at its worst texel;
// - at ten directions off the centres: the bilinear read between centres 5.6 to 22.5 degrees apart of a
//   convolution that still peaks at the sun (measured worst: sunrise 73.9%, studio 49.8%, forest 9.1% with
//   the supersampled environment cube, which keeps the sun's flux; 66.2%, 50.2%, 8.8% with the point-sampled
//   one); the storage's error, the same for any bake of a 64 x 64 chain, held here at 80%;
// - the renderer's pixel of a ggx sphere (F = 1, N.V = 1, r = 1/2) is the chain's value times A + B of its
//   DFG table, to 1e-5 (measured 6e-16), and that A + B is within 0.1% of the quadrature (8e-4);
// - at those five sphere points the Phong chain the renderer used before (GameGgxSpecular::phong) misses by
//   more than twice as much as the GGX chain on every map (measured 80.2% / 6.2%, 221% / 19.3%,
//   69.5% / 7.0%). 9.9 s on 2 cores (each of the 15 renderer calls bakes its environment again).
TEST(GameSplitSum, ThePrefilteredFactorIsTheGgxConvolutionOfTheEnvironment) {
  const std::filesystem::path dir = SHADELAB_BLENDER_WORLDS;
  if (!std::filesystem::is_directory(dir)) GTEST_FAIL() << dir << " is missing (scripts/setup.sh installs blender-data)";
  const Vec3 dirs[] = {Vec3{0, -1, 0}, Vec3{1, 0, 0}, normalize(Vec3{0.3, 0.8, -0.5}), Vec3{0, 0, -1},
                       normalize(Vec3{-1, 0.2, 0.4})};
  double worst_centre = 0.0;
  double worst_dir = 0.0;
  double worst_phong = 0.0;
  double worst_render = 0.0;
  double worst_table = 0.0;
  for (const char* name : {"sunrise", "studio", "forest"}) {
    Scene s;
    s.environment.kind = Environment::Kind::image;
    s.environment.latlong = read_image(dir / (std::string(name) + ".exr")).value();
    s.settings.max_depth = 1;
    GameOptions g = split_sum_options();
    g.diffuse = GameAmbient::none;
    g.split_sum_lookup = GameSplitSumLookup::mirror;  // the chain read once along R, as published
    const GameEnvironment baked = bake_game_environment(s, g).value();
    ASSERT_EQ(baked.specular_ggx.levels.size(), 7u);
    double map_centre = 0.0;
    double map_dir = 0.0;
    double map_phong = 0.0;
    for (const int level : {2, 3, 4}) {
      const double r = level / 6.0;
      const int n = baked.specular_ggx.levels[static_cast<std::size_t>(level)].size;
      for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x) {
            const Vec3 d = texel_direction(f, x, y, n);
            const double want = prefilter_ggx_brute_force(baked.radiance, d, r).g;
            const double got = sample_ggx_chain(baked.specular_ggx, d, r).g;
            map_centre = std::max(map_centre, std::abs(got - want) / want);
          }
      for (const Vec3& d0 : dirs) {
        for (const Vec3& d : {d0, -d0}) {
          const double want = prefilter_ggx_brute_force(baked.radiance, d, r).g;
          map_dir = std::max(map_dir, std::abs(sample_ggx_chain(baked.specular_ggx, d, r).g - want) / want);
        }
      }
    }
    // The renderer, at the roughness of level 3: a sphere point whose normal is -d, seen head on (R = -d).
    // The chain and the Phong chain at those five points (the Phong side renders each, on every map; the
    // split-sum renderer is compared with the chain on sunrise, each call bakes the chain again).
    const double r = 0.5;
    Scene sr = s;
    sr.spheres.push_back({{0, 0, 0}, 1.0, add_material(sr, "ggx", {{"kd", "0"}, {"f", "none"}, {"roughness", "0.5"}})});
    const DfgAb ab = dfg_lookup(game_dfg_table(g.dfg_size), 1.0, r);
    const DfgValue q = dfg_quadrature(1.0, r * r, 1e-9);
    worst_table = std::max(worst_table, std::abs((ab.a + ab.b) - (q.a + q.b)) / (q.a + q.b));
    GameOptions phong = g;
    phong.ggx_specular = GameGgxSpecular::phong;
    double map_half = 0.0;
    for (const Vec3& d : dirs) {
      const Vec3 eye = d * -3.0;
      const Vec3 n_hit = -d;
      const double chain = sample_ggx_chain(baked.specular_ggx, n_hit, r).g * (ab.a + ab.b);
      const double want = prefilter_ggx_brute_force(baked.radiance, n_hit, r).g * (q.a + q.b);
      map_half = std::max(map_half, std::abs(chain - want) / want);
      if (std::string(name) == "sunrise") {
        const Rgb game = game_radiance(sr, eye, d, g).value();
        worst_render = std::max(worst_render, std::abs(game.g - chain) / chain);
      }
      const Rgb old = game_radiance(sr, eye, d, phong).value();
      map_phong = std::max(map_phong, std::abs(old.g - want) / want);
    }
    EXPECT_GT(map_phong, 2.0 * map_half) << name;
    std::printf("%s: the GGX chain vs the brute-force convolution, r = 1/3, 1/2, 2/3: texel centres worst %.3g%%, "
                "ten directions worst %.3g%%; at r = 1/2 on the sphere: the GGX chain %.3g%%, the Phong chain %.3g%%\n",
                name, 100.0 * map_centre, 100.0 * map_dir, 100.0 * map_half, 100.0 * map_phong);
    worst_centre = std::max(worst_centre, map_centre);
    worst_dir = std::max(worst_dir, map_dir);
    worst_phong = std::max(worst_phong, map_phong);
  }
  std::printf("renderer vs chain x (A + B) of its table: worst %.3g; that A + B vs quadrature: %.3g\n", worst_render,
              worst_table);
  EXPECT_LE(worst_render, 1e-5);
  EXPECT_LE(worst_table, 1e-3);
  EXPECT_LE(worst_centre, 1e-6);
  EXPECT_LE(worst_dir, 0.80);
  RecordProperty("worst_relative_texel_centres", std::to_string(worst_centre));
  RecordProperty("worst_relative_directions", std::to_string(worst_dir));
  RecordProperty("worst_relative_phong", std::to_string(worst_phong));
}

// A sphere of ggx under a lat-long whose radiance varies with direction (a sky brighter toward +Y and +X),
// seen from +Z at 32 x 32.
Scene varying_sphere(double roughness) {
  Scene s = constant_sphere("ggx", {{"kd", "0"}, {"roughness", std::to_string(roughness)}});
  s.environment.kind = Environment::Kind::image;
  s.environment.latlong = Image(64, 32);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 64; ++x) s.environment.latlong.set(x, y, Rgb{0.2 + 3.0 * (32 - y) / 32.0, 0.5 + x / 64.0, 0.3});
  }
  s.camera.position = {0, 0, 4};
  s.camera.look_at = {0, 0, 0};
  s.camera.vfov_deg = 32.0;
  s.camera.width = s.camera.height = 32;
  return s;
}

TEST(GameSplitSum, ABakeGivenByTheCallerRendersAsTheRenderersOwn) {
  const Scene s = varying_sphere(0.6);
  GameOptions o = split_sum_options();
  o.specular_size = 16;
  o.environment_size = 16;
  const RenderResult own = render_game(s, o).value();
  const GameEnvironment baked = bake_game_environment(s, o).value();
  const RenderResult given = render_game(s, o, baked).value();
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      ASSERT_EQ(own.beauty.at(x, y).r, given.beauty.at(x, y).r) << x << ", " << y;
      ASSERT_EQ(own.beauty.at(x, y).g, given.beauty.at(x, y).g) << x << ", " << y;
      ASSERT_EQ(own.beauty.at(x, y).b, given.beauty.at(x, y).b) << x << ", " << y;
    }
  // A bake without what the options read is an error naming it, not a silently darker image.
  GameOptions phong = o;
  phong.ggx_specular = GameGgxSpecular::phong;
  const GameEnvironment no_ggx = bake_game_environment(s, phong).value();
  const auto r = render_game(s, o, no_ggx);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("no GGX chain"), std::string::npos) << r.error().message;
  GameOptions irr = o;
  irr.diffuse = GameAmbient::irradiance_map;
  EXPECT_NE(render_game(s, irr, baked).error().message.find("no irradiance cube"), std::string::npos);
  EXPECT_NE(render_game(s, o, GameEnvironment{}).error().message.find("empty"), std::string::npos);
}

TEST(GameSplitSum, TheDominantDirectionChangesOnlyWhatDependsOnDirection) {
  // Under a constant environment the lookup direction cannot matter: mirror and dominant agree to rounding.
  // Under the varying sky they differ at oblique view (the rim) and agree head on (R = n there).
  GameOptions mirror = split_sum_options();
  mirror.environment_size = mirror.specular_size = 16;  // a quick bake per call
  mirror.split_sum_lookup = GameSplitSumLookup::mirror;
  GameOptions dominant = mirror;
  dominant.split_sum_lookup = GameSplitSumLookup::dominant;
  const Scene c = constant_sphere("ggx", {{"kd", "0"}, {"roughness", "0.7"}});
  for (const double x : offsets) {
    const Rgb a = game_radiance(c, {x, 0, 4}, {0, 0, -1}, mirror).value();
    const Rgb b = game_radiance(c, {x, 0, 4}, {0, 0, -1}, dominant).value();
    EXPECT_NEAR(a.g, b.g, 1e-6 * a.g) << x;
  }
  const Scene v = varying_sphere(0.7);
  const Rgb head_m = game_radiance(v, {0, 0, 4}, {0, 0, -1}, mirror).value();
  const Rgb head_d = game_radiance(v, {0, 0, 4}, {0, 0, -1}, dominant).value();
  EXPECT_NEAR(head_m.g, head_d.g, 1e-9 * head_m.g);
  const Rgb rim_m = game_radiance(v, {0, 0.95, 4}, {0, 0, -1}, mirror).value();
  const Rgb rim_d = game_radiance(v, {0, 0.95, 4}, {0, 0, -1}, dominant).value();
  EXPECT_GT(std::abs(rim_m.r - rim_d.r), 0.02 * rim_m.r) << rim_m.r << " vs " << rim_d.r;
}

// A model the renderer has never heard of: a new file's class that answers split_sum_inputs() (here by
// forwarding everything to a ggx BRDF, so the right image is known) and no registry name. The renderer gives
// it the split sum, with nothing in render/ naming it: the image is the ggx material's, bit for bit, and
// differs from the Phong chain's. Without the capability (a class that does not forward split_sum_inputs) the
// same BRDF falls back to the Phong chain.
class NewGgxLikeModel final : public Brdf {
 public:
  NewGgxLikeModel(BrdfPtr inner, bool answers) : m_inner(std::move(inner)), m_answers(answers) {}
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return m_inner->eval(wi, wo); }
  double pdf(const Vec3& wi, const Vec3& wo) const override { return m_inner->pdf(wi, wo); }
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override { return m_inner->sample(wo, u, u_lobe); }
  Rgb diffuse_albedo() const override { return m_inner->diffuse_albedo(); }
  double game_phong_exponent() const override { return m_inner->game_phong_exponent(); }
  std::optional<SplitSumInputs> split_sum_inputs() const override {
    return m_answers ? m_inner->split_sum_inputs() : std::nullopt;
  }

 private:
  BrdfPtr m_inner;
  bool m_answers;
};

TEST(GameSplitSum, ANewModelThatAnswersTheSplitSumGetsItWithNoRendererChange) {
  GameOptions o = split_sum_options();
  o.specular_size = o.environment_size = 16;
  const ParamAssignments p{{"kd", "0"}, {"roughness", "0.6"}};
  const Scene ggx = varying_sphere(0.6);
  Scene custom = ggx;
  Scene fallback = ggx;
  custom.materials[0].model.clear();
  custom.materials[0].brdf = std::make_shared<NewGgxLikeModel>(make_brdf("ggx", p).value(), true);
  fallback.materials[0].model.clear();
  fallback.materials[0].brdf = std::make_shared<NewGgxLikeModel>(make_brdf("ggx", p).value(), false);
  const RenderResult want = render_game(ggx, o).value();
  const RenderResult got = render_game(custom, o).value();
  const RenderResult phong = render_game(fallback, o).value();
  double differs = 0.0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      ASSERT_EQ(want.beauty.at(x, y).g, got.beauty.at(x, y).g) << x << ", " << y;
      differs = std::max(differs, std::abs(want.beauty.at(x, y).g - phong.beauty.at(x, y).g));
    }
  EXPECT_GT(differs, 0.01);  // the Phong chain's image is another image
}

TEST(GameSplitSum, ThePhongFamilyKeepsThePhongChain) {
  // A Phong-family material is shaded exactly as before whatever ggx_specular says.
  const Scene s = constant_sphere("blinn-phong", {});
  GameOptions phong;
  phong.ggx_specular = GameGgxSpecular::phong;
  for (const double x : offsets) {
    const Rgb a = game_radiance(s, {x, 0, 4}, {0, 0, -1}, split_sum_options()).value();
    const Rgb b = game_radiance(s, {x, 0, 4}, {0, 0, -1}, phong).value();
    EXPECT_EQ(a.g, b.g);
  }
}

}  // namespace
}  // namespace shadelab
