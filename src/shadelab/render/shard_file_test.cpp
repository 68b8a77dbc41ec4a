#include "shadelab/render/shard_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <variant>

#include "shadelab/image/image_io.h"
#include "shadelab/render/test_scenes.h"

namespace shadelab {
namespace {

using testing::add_material;
using testing::floor_quad;
namespace fs = std::filesystem;

// 40 x 24: 3 x 2 tiles of 16, the right and bottom ones partial; 16 spp.
Scene shard_scene() {
  Scene s;
  s.camera.width = 40;
  s.camera.height = 24;
  s.camera.position = {0, 1, 4};
  s.camera.look_at = {0, 0.5, 0};
  s.environment.kind = Environment::Kind::uniform;
  s.environment.uniform = Rgb{0.3, 0.4, 0.5};
  s.quads.push_back(floor_quad(5.0, 0.0, add_material(s, "lambert", {{"kd", "0.5"}})));
  s.spheres.push_back({{0, 0.7, 0}, 0.7, add_material(s, "cook-torrance", {})});
  s.lights.push_back(SphereLight{{2, 3, 1}, 0.5, Rgb::gray(20.0)});
  s.settings.spp = 16;
  s.settings.max_depth = 4;
  s.settings.seed = 11;
  s.source = "shard-scene";
  return s;
}

class ShardDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("shadelab_shard_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  // Renders shard `index`/`count` with `threads` threads and writes it to dir/name.
  fs::path part(const Scene& s, int index, int count, ShardSplit split, int threads, const std::string& name) {
    RenderOptions o;
    o.threads = threads;
    o.shard = {index, count, split};
    auto r = render_scene(s, o);
    EXPECT_TRUE(r) << r.error().message;
    ShardInfo info = make_shard_info(s, o, s.settings.spp, s.settings.max_depth);
    info.nonfinite_samples = r->stats.nonfinite_samples;
    const fs::path p = dir / name;
    auto w = write_shard(p, info, *r);
    EXPECT_TRUE(w) << w.error().message;
    return p;
  }
  std::vector<fs::path> parts(const Scene& s, int count, ShardSplit split) {
    std::vector<fs::path> v;
    for (int i = 0; i < count; ++i) v.push_back(part(s, i, count, split, 1 + i % 3, "p" + std::to_string(i) + ".exr"));
    return v;
  }

  fs::path dir;
};

// issue 17: the merged image is the single-machine image bit for bit, for N in {1, 2, 3, 7, 16} and both splits,
// whatever the thread count of each piece (1, 2 or 3 here; the whole render with 2). 16 shards of 16 spp by
// samples are one sample each; 16 by tiles leave 10 shards without a tile.
TEST_F(ShardDir, MergedPartsAreTheSingleRenderBitForBit) {
  const Scene s = shard_scene();
  RenderOptions whole;
  whole.threads = 2;
  const auto ref = render_scene(s, whole);
  ASSERT_TRUE(ref) << ref.error().message;
  for (ShardSplit split : {ShardSplit::samples, ShardSplit::tiles}) {
    for (int n : {1, 2, 3, 7, 16}) {
      const auto files = parts(s, n, split);
      // Any order of the parts.
      std::vector<fs::path> shuffled(files.rbegin(), files.rend());
      const auto merged = merge_shards(shuffled);
      ASSERT_TRUE(merged) << merged.error().message;
      EXPECT_TRUE(merged->result.sums == ref->sums) << n << (split == ShardSplit::tiles ? " tiles" : " samples");
      ASSERT_EQ(merged->result.beauty.data.size(), ref->beauty.data.size());
      EXPECT_EQ(std::memcmp(merged->result.beauty.data.data(), ref->beauty.data.data(), ref->beauty.data.size() * sizeof(float)), 0)
          << n << (split == ShardSplit::tiles ? " tiles" : " samples");
      for (const auto& f : files) fs::remove(f);
    }
  }
  // A part alone is not the image (the sums are split for real): shard 0 of 2 by samples has half the sum.
  const auto half = parts(s, 2, ShardSplit::samples);
  const auto sums = read_shard_sums(half[0], read_shard_info(half[0]).value()).value();
  EXPECT_FALSE(sums.sums == ref->sums);
}

TEST_F(ShardDir, ShardsSplitTheSamplesAndTilesDisjointly) {
  // Sample ranges tile [0, spp) in order; tiles go to exactly one shard.
  for (int spp : {1, 5, 16, 1000}) {
    for (int n : {1, 2, 3, 7, 16}) {
      int next = 0;
      for (int i = 0; i < n; ++i) {
        const auto [b, e] = shard_sample_range(spp, {i, n, ShardSplit::samples});
        EXPECT_EQ(b, next);
        EXPECT_LE(b, e);
        next = e;
        EXPECT_EQ(shard_sample_range(spp, {i, n, ShardSplit::tiles}), std::make_pair(0, spp));
      }
      EXPECT_EQ(next, spp);
      for (int t = 0; t < 50; ++t) {
        int owners = 0;
        for (int i = 0; i < n; ++i) owners += shard_owns_tile(t, {i, n, ShardSplit::tiles}) ? 1 : 0;
        EXPECT_EQ(owners, 1);
      }
    }
  }
}

// A missing, duplicated or foreign part is an error naming the file; nothing is merged.
TEST_F(ShardDir, MissingDuplicateAndForeignPartsAreErrorsNamingTheFile) {
  const Scene s = shard_scene();
  const auto files = parts(s, 3, ShardSplit::samples);
  auto missing = merge_shards({files[0], files[2]});
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("1 of 3 shards missing (index 1)"), std::string::npos) << missing.error().message;
  auto dup = merge_shards({files[0], files[1], files[2], files[1]});
  ASSERT_FALSE(dup);
  EXPECT_NE(dup.error().message.find("shard 1/3 again"), std::string::npos) << dup.error().message;
  EXPECT_NE(dup.error().message.find(files[1].string()), std::string::npos);

  // Foreign: another seed, another scene (one material parameter), another spp, another split or count.
  Scene seed = s;
  seed.settings.seed = 12;
  Scene material = s;
  material.materials[0].params[0].second = "0.51";
  Scene spp = s;
  spp.settings.spp = 15;
  const std::vector<std::pair<fs::path, std::string>> foreign{
      {part(seed, 1, 3, ShardSplit::samples, 1, "seed.exr"), "seed 12, but 11"},
      {part(material, 1, 3, ShardSplit::samples, 1, "material.exr"), "scene_hash"},
      {part(spp, 1, 3, ShardSplit::samples, 1, "spp.exr"), "spp 15, but 16"},
      {part(s, 1, 3, ShardSplit::tiles, 1, "tiles.exr"), "split tiles, but samples"},
      {part(s, 1, 4, ShardSplit::samples, 1, "four.exr"), "count 4, but 3"}};
  for (const auto& [file, why] : foreign) {
    auto r = merge_shards({files[0], file, files[2]});
    ASSERT_FALSE(r) << file;
    EXPECT_NE(r.error().message.find("'" + file.string() + "': from another render"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find(why), std::string::npos) << r.error().message;
  }
  EXPECT_NE(scene_fingerprint(s), scene_fingerprint(material));
  EXPECT_EQ(scene_fingerprint(s), scene_fingerprint(seed));  // the seed is a field of its own

  // Not a shard: a plain EXR, a file that is not an EXR, a truncated part, no file at all.
  const fs::path plain = dir / "plain.exr";
  ASSERT_TRUE(write_image(Image(4, 4), plain));
  const fs::path text = dir / "text.exr";
  std::ofstream(text) << "not an image\n";
  const fs::path cut = dir / "cut.exr";
  {
    std::ifstream in(files[1], std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
    bytes.resize(bytes.size() / 2);
    std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  const std::vector<std::pair<fs::path, std::string>> bad{
      {plain, "not a shadelab shard"}, {text, "not a readable EXR file"}, {cut, ""}, {dir / "none.exr", "no such file"}};
  for (const auto& [file, why] : bad) {
    auto r = merge_shards({files[0], file, files[2]});
    ASSERT_FALSE(r) << file;
    EXPECT_NE(r.error().message.find("'" + file.string() + "'"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find(why), std::string::npos) << r.error().message;
  }
}

// Every pixel's sums in a part are bounded by what its samples can give: a part whose sums were altered
// beyond that is refused (and the 128-bit merge cannot overflow).
TEST_F(ShardDir, ImpossibleSumsAreRefused) {
  const Scene s = shard_scene();
  RenderOptions o;
  o.shard = {0, 2, ShardSplit::samples};
  auto r = render_scene(s, o).value();
  ShardInfo info = make_shard_info(s, o, s.settings.spp, s.settings.max_depth);
  r.sums[5].c[1] = static_cast<Int128>(static_cast<UInt128>(1) << 126u);
  const fs::path p = dir / "huge.exr";
  ASSERT_TRUE(write_shard(p, info, r));
  auto sums = read_shard_sums(p, read_shard_info(p).value());
  ASSERT_FALSE(sums);
  EXPECT_NE(sums.error().message.find("pixel (5, 0) has a sum larger than its samples can give"), std::string::npos)
      << sums.error().message;
  // A header whose non-finite count disagrees with the channel.
  r = render_scene(s, o).value();
  info.nonfinite_samples = 3;
  ASSERT_TRUE(write_shard(p, info, r));
  sums = read_shard_sums(p, read_shard_info(p).value());
  ASSERT_FALSE(sums);
  EXPECT_NE(sums.error().message.find("nonfinite channel adds up to 0, the header says 3"), std::string::npos) << sums.error().message;
}

// NaN samples cannot enter the exact sums: they are counted per pixel, travel in the parts, and the merged
// image has NaN in the same pixels as the single render.
TEST_F(ShardDir, NonFiniteSamplesSurviveTheMerge) {
  Scene s = shard_scene();
  RenderOptions whole;
  auto ref = render_scene(s, whole).value();
  // Stand-in for a broken formula: mark pixels as a render with NaN samples would.
  ref.nonfinite[7] = 2;
  const Image img = image_from_sums(ref.sums, ref.nonfinite, s.camera.width, s.camera.height, 16);
  EXPECT_TRUE(std::isnan(img.data[7 * 3]));
  EXPECT_FALSE(std::isnan(img.data[8 * 3]));
  RenderOptions o;
  o.shard = {0, 2, ShardSplit::tiles};
  auto part0 = render_scene(s, o).value();
  part0.nonfinite[7] = 2;  // pixel 7 is in tile 0, shard 0's
  ShardInfo i0 = make_shard_info(s, o, 16, 4);
  i0.nonfinite_samples = 2;
  ASSERT_TRUE(write_shard(dir / "a.exr", i0, part0));
  o.shard = {1, 2, ShardSplit::tiles};
  const auto part1 = render_scene(s, o).value();
  ASSERT_TRUE(write_shard(dir / "b.exr", make_shard_info(s, o, 16, 4), part1));
  const auto merged = merge_shards({dir / "a.exr", dir / "b.exr"}).value();
  EXPECT_EQ(merged.status.nonfinite_samples, 2u);
  EXPECT_EQ(std::memcmp(merged.result.beauty.data.data(), img.data.data(), img.data.size() * sizeof(float)), 0);
}

// A scene path that is not UTF-8 (Linux allows any bytes but '/' and NUL in a name) is written, read back
// with U+FFFD in its place, and still merges: parts match by the scene's hash, not its name (found 2026-12-06:
// write_shard failed with the JSON library's "invalid UTF-8 byte").
TEST_F(ShardDir, ASceneNameThatIsNotUtf8IsWrittenAndMerges) {
  Scene s = shard_scene();
  s.source = "scenes/s\xff" "x.json";
  RenderOptions whole;
  const auto ref = render_scene(s, whole).value();
  std::vector<fs::path> files;
  for (int i = 0; i < 2; ++i) {
    RenderOptions o;
    o.shard = {i, 2, ShardSplit::samples};
    const auto r = render_scene(s, o).value();
    files.push_back(dir / ("u" + std::to_string(i) + ".exr"));
    auto w = write_shard(files.back(), make_shard_info(s, o, s.settings.spp, s.settings.max_depth), r);
    ASSERT_TRUE(w) << w.error().message;
  }
  const auto info = read_shard_info(files[0]);
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info->scene, "scenes/s\xef\xbf\xbdx.json");
  const auto merged = merge_shards(files);
  ASSERT_TRUE(merged) << merged.error().message;
  EXPECT_EQ(std::memcmp(merged->result.beauty.data.data(), ref.beauty.data.data(), ref.beauty.data.size() * sizeof(float)), 0);
}

// A scene with one of everything the fingerprint walks, every texture binding of material 0 set, so that each
// member can be changed alone (it is not rendered: indices need not suit the models).
Scene fingerprint_scene() {
  Scene s = shard_scene();
  for (int t = 0; t < 2; ++t) {
    Texture tex;
    tex.name = "tex" + std::to_string(t);
    tex.source = "textures/tex" + std::to_string(t) + ".png";
    tex.image = Image(4, 4);
    for (std::size_t k = 0; k < tex.image.data.size(); ++k) tex.image.data[k] = 0.01f * static_cast<float>(k + 7u * t);
    tex.data = t == 1;
    s.textures.push_back(std::move(tex));
  }
  Material& m = s.materials[0];
  m.kd_texture = 0, m.ks_texture = 1, m.gloss_texture = 1, m.normal_texture = 1;
  m.base_color_texture = 0, m.metallic_roughness_texture = 1;
  m.emission = Rgb{0.1, 0.2, 0.3};
  s.disks.push_back({{1, 0.1, 1}, {0, 1, 0}, 0.3, 1});
  MeshShape mesh;
  mesh.source = "meshes/tri.obj";
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.uvs = {{0, 0}, {1, 0}, {0, 1}};
  mesh.indices = {0, 1, 2};
  mesh.material = 1;
  s.meshes.push_back(mesh);
  s.lights.push_back(DirectionalLight{{0, 1, 0}, Rgb{1, 1, 1}, false});
  s.lights.push_back(PointLight{{1, 2, 3}, Rgb{4, 5, 6}});
  s.lights.push_back(SpotLight{{1, 2, 3}, {0, -1, 0}, Rgb{7, 8, 9}, 0.9, 0.8});
  s.lights.push_back(HemisphereLight{{0, 1, 0}, Rgb{0.5, 0.6, 0.7}, Rgb{0.1, 0.1, 0.1}});
  s.environment.kind = Environment::Kind::image;
  s.environment.latlong = Image(8, 4);
  for (std::size_t k = 0; k < s.environment.latlong.data.size(); ++k) s.environment.latlong.data[k] = 0.5f + 0.001f * static_cast<float>(k);
  s.environment.source = "env/sky.exr";
  return s;
}

// The members of every struct the fingerprint walks, named by structured bindings as in shard_file.cpp: a
// member added to any of them stops this test compiling until a change of it is added to the list below
// (and shard_file.cpp stops compiling until it is hashed there).
[[maybe_unused]] void every_member_is_in_the_list(Scene& s, Material& m, Texture& t, MeshShape& mesh, Environment& e,
                                                  SkyModel& sky, Camera& c, RenderSettings& r, ParamTexture& p,
                                                  UvTransform& u) {
  [[maybe_unused]] auto& [s0, s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11] = s;  // s11: warnings, not hashed
  [[maybe_unused]] auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13] = m;
  [[maybe_unused]] auto& [p0, p1, p2, p3, p4] = p;
  [[maybe_unused]] auto& [u0, u1, u2, u3, u4, u5] = u;
  [[maybe_unused]] auto& [t0, t1, t2, t3] = t;
  [[maybe_unused]] auto& [h0, h1, h2, h3, h4, h5] = mesh;
  [[maybe_unused]] auto& [e0, e1, e2, e3, e4, e5, e6] = e;
  [[maybe_unused]] auto& [k0, k1, k2, k3, k4, k5] = sky;
  [[maybe_unused]] auto& [c0, c1, c2, c3, c4, c5] = c;
  [[maybe_unused]] auto& [r0, r1, r2, r3, r4] = r;
  static_assert(std::variant_size_v<SceneLight> == 5, "a new light type: add changes of its members below");
}

// issue 40, finding 2: every member of every struct in the Scene that changes the image changes the
// fingerprint, each alone (the old hand-written list left out base_color_texture and
// metallic_roughness_texture), and every one of these changes gives a fingerprint of its own.
TEST(SceneFingerprint, EveryMemberThatChangesTheImageChangesIt) {
  const Scene base = fingerprint_scene();
  const std::string h0 = scene_fingerprint(base);
  EXPECT_EQ(h0.size(), 16u);
  const std::vector<std::pair<std::string, std::function<void(Scene&)>>> changes{
      {"camera.position", [](Scene& s) { s.camera.position.x += 0.5; }},
      {"camera.look_at", [](Scene& s) { s.camera.look_at.y += 0.5; }},
      {"camera.up", [](Scene& s) { s.camera.up = {0, 1, 1e-9}; }},
      {"camera.vfov_deg", [](Scene& s) { s.camera.vfov_deg = 41; }},
      {"camera.width", [](Scene& s) { s.camera.width = 41; }},
      {"camera.height", [](Scene& s) { s.camera.height = 25; }},
      {"texture.name", [](Scene& s) { s.textures[0].name = "other"; }},
      {"texture.image texel", [](Scene& s) { s.textures[0].image.data[5] = std::nextafter(s.textures[0].image.data[5], 1.0f); }},
      {"texture.image shape", [](Scene& s) { s.textures[0].image.width = 8, s.textures[0].image.height = 2; }},
      {"texture.image last texel", [](Scene& s) { s.textures[1].image.data.back() += 1.0f; }},
      {"texture.data", [](Scene& s) { s.textures[0].data = true; }},
      {"texture order", [](Scene& s) { std::swap(s.textures[0], s.textures[1]); }},
      {"material.name", [](Scene& s) { s.materials[0].name += "x"; }},
      {"material.model", [](Scene& s) { s.materials[0].model = "phong"; }},
      {"material.params value", [](Scene& s) { s.materials[0].params[0].second = "0.51"; }},
      {"material.params name", [](Scene& s) { s.materials[0].params[0].first = "ks"; }},
      {"material.params added", [](Scene& s) { s.materials[1].params.push_back({"n", "30"}); }},
      {"material.kd_texture", [](Scene& s) { s.materials[0].kd_texture = -1; }},
      {"material.ks_texture", [](Scene& s) { s.materials[0].ks_texture = -1; }},
      {"material.gloss_texture", [](Scene& s) { s.materials[0].gloss_texture = -1; }},
      {"material.normal_texture", [](Scene& s) { s.materials[0].normal_texture = -1; }},
      {"material.base_color_texture", [](Scene& s) { s.materials[0].base_color_texture = -1; }},
      {"material.metallic_roughness_texture", [](Scene& s) { s.materials[0].metallic_roughness_texture = -1; }},
      {"material.base_color_texture index", [](Scene& s) { s.materials[0].base_color_texture = 1; }},
      // Each member of a parameter texture: variants of one binding, all different from each other (seen, below).
      {"material.param_textures added", [](Scene& s) { s.materials[0].param_textures.push_back({"kd", 0, -1, ParamTexture::Use::multiply, {}}); }},
      {"param_texture.param", [](Scene& s) { s.materials[0].param_textures.push_back({"ks", 0, -1, ParamTexture::Use::multiply, {}}); }},
      {"param_texture.texture", [](Scene& s) { s.materials[0].param_textures.push_back({"kd", 1, -1, ParamTexture::Use::multiply, {}}); }},
      {"param_texture.channel", [](Scene& s) { s.materials[0].param_textures.push_back({"kd", 0, 1, ParamTexture::Use::multiply, {}}); }},
      {"param_texture.use", [](Scene& s) { s.materials[0].param_textures.push_back({"kd", 0, -1, ParamTexture::Use::anisotropy, {}}); }},
      {"param_texture.transform", [](Scene& s) {
         s.materials[0].param_textures.push_back({"kd", 0, -1, ParamTexture::Use::multiply, make_gltf_uv_transform({0.0, 0.5}, 0.0, {1.0, 1.0})});
       }},
      {"material.gloss_encoding.n_black", [](Scene& s) { s.materials[0].gloss_encoding.n_black = 3; }},
      {"material.gloss_encoding.n_white", [](Scene& s) { s.materials[0].gloss_encoding.n_white = 4096; }},
      {"material.uv_scale.x", [](Scene& s) { s.materials[0].uv_scale.x = 2; }},
      {"material.uv_scale.y", [](Scene& s) { s.materials[0].uv_scale.y = 2; }},
      {"material.emission", [](Scene& s) { s.materials[0].emission.b = 0.4; }},
      {"sphere.center", [](Scene& s) { s.spheres[0].center.z = 0.1; }},
      {"sphere.radius", [](Scene& s) { s.spheres[0].radius = 0.71; }},
      {"sphere.material", [](Scene& s) { s.spheres[0].material = 0; }},
      {"quad.corner", [](Scene& s) { s.quads[0].corner.y = 0.01; }},
      {"quad.u", [](Scene& s) { s.quads[0].u.z = 0.01; }},
      {"quad.v", [](Scene& s) { s.quads[0].v.x = 0.01; }},
      {"quad.material", [](Scene& s) { s.quads[0].material = 1; }},
      {"disk.center", [](Scene& s) { s.disks[0].center.x = 1.5; }},
      {"disk.normal", [](Scene& s) { s.disks[0].normal = {0, 0, 1}; }},
      {"disk.radius", [](Scene& s) { s.disks[0].radius = 0.4; }},
      {"disk.material", [](Scene& s) { s.disks[0].material = 0; }},
      {"shape added", [](Scene& s) { s.spheres.push_back({{0, 0, 0}, 1, 0}); }},
      {"mesh.positions", [](Scene& s) { s.meshes[0].positions[2].y = 1.5; }},
      {"mesh.normals", [](Scene& s) { s.meshes[0].normals[1] = {0, 1, 0}; }},
      {"mesh.normals removed", [](Scene& s) { s.meshes[0].normals.clear(); }},
      {"mesh.uvs", [](Scene& s) { s.meshes[0].uvs[1].x = 0.5; }},
      {"mesh.indices", [](Scene& s) { s.meshes[0].indices = {0, 2, 1}; }},
      {"mesh.material", [](Scene& s) { s.meshes[0].material = 0; }},
      {"sphere light.center", [](Scene& s) { std::get<SphereLight>(s.lights[0]).center.x = 2.5; }},
      {"sphere light.radius", [](Scene& s) { std::get<SphereLight>(s.lights[0]).radius = 0.6; }},
      {"sphere light.radiance", [](Scene& s) { std::get<SphereLight>(s.lights[0]).radiance.g = 21; }},
      {"directional.to_light", [](Scene& s) { std::get<DirectionalLight>(s.lights[1]).to_light = {0, 0, 1}; }},
      {"directional.irradiance", [](Scene& s) { std::get<DirectionalLight>(s.lights[1]).irradiance.r = 2; }},
      {"directional.game_sh", [](Scene& s) { std::get<DirectionalLight>(s.lights[1]).game_sh = true; }},
      {"point.position", [](Scene& s) { std::get<PointLight>(s.lights[2]).position.z = 4; }},
      {"point.intensity", [](Scene& s) { std::get<PointLight>(s.lights[2]).intensity.b = 7; }},
      {"spot.position", [](Scene& s) { std::get<SpotLight>(s.lights[3]).position.x = 0; }},
      {"spot.axis", [](Scene& s) { std::get<SpotLight>(s.lights[3]).axis = {0, 0, -1}; }},
      {"spot.intensity", [](Scene& s) { std::get<SpotLight>(s.lights[3]).intensity.r = 1; }},
      {"spot.cos_inner", [](Scene& s) { std::get<SpotLight>(s.lights[3]).cos_inner = 0.95; }},
      {"spot.cos_outer", [](Scene& s) { std::get<SpotLight>(s.lights[3]).cos_outer = 0.7; }},
      {"hemisphere.up", [](Scene& s) { std::get<HemisphereLight>(s.lights[4]).up = {0, 0, 1}; }},
      {"hemisphere.sky", [](Scene& s) { std::get<HemisphereLight>(s.lights[4]).sky.r = 0.55; }},
      {"hemisphere.ground", [](Scene& s) { std::get<HemisphereLight>(s.lights[4]).ground.g = 0.2; }},
      {"light type, same numbers", [](Scene& s) { s.lights[2] = SphereLight{{1, 2, 3}, 0.0, Rgb{4, 5, 6}}; }},
      {"light order", [](Scene& s) { std::swap(s.lights[1], s.lights[2]); }},
      {"environment.kind", [](Scene& s) { s.environment.kind = Environment::Kind::uniform; }},
      {"environment.uniform", [](Scene& s) { s.environment.uniform.r = 0.31; }},
      {"environment.latlong texel", [](Scene& s) { s.environment.latlong.data[40] += 1e-6f; }},
      {"environment.latlong size", [](Scene& s) { s.environment.latlong = Image(4, 2); }},
      {"environment.rotation_deg", [](Scene& s) { s.environment.rotation_deg = 90; }},
      {"environment.scale", [](Scene& s) { s.environment.scale = 2; }},
      {"sky.sun_direction", [](Scene& s) { s.environment.sky.sun_direction = {0, 1, 0}; }},
      {"sky.sun_angular_radius_deg", [](Scene& s) { s.environment.sky.sun_angular_radius_deg = 0.5; }},
      {"sky.sun_irradiance", [](Scene& s) { s.environment.sky.sun_irradiance.r = 4; }},
      {"sky.zenith", [](Scene& s) { s.environment.sky.zenith.g = 0.3; }},
      {"sky.horizon", [](Scene& s) { s.environment.sky.horizon.b = 0.8; }},
      {"sky.ground", [](Scene& s) { s.environment.sky.ground.r = 0.2; }},
      {"settings.rr_depth", [](Scene& s) { s.settings.rr_depth = 0; }},
  };
  std::map<std::string, std::string> seen{{h0, "the scene itself"}};
  for (const auto& [what, change] : changes) {
    Scene s = base;
    change(s);
    const std::string h = scene_fingerprint(s);
    EXPECT_NE(h, h0) << what << " leaves the fingerprint as it was";
    const auto [it, inserted] = seen.emplace(h, what);
    EXPECT_TRUE(inserted || it->second == what) << what << " gives the fingerprint of " << it->second;
  }
}

// What does not change the image leaves the fingerprint alone: paths (a scene moved to another folder or
// machine), the BRDF pointer (rebuilt from the parameters on every load), the thread count, and spp,
// max_depth and seed, which are fields of their own in ShardInfo (an option may override the scene's).
TEST(SceneFingerprint, PathsThreadsAndTheShardInfoFieldsLeaveItAlone) {
  const Scene base = fingerprint_scene();
  const std::string h0 = scene_fingerprint(base);
  EXPECT_EQ(scene_fingerprint(base), h0);  // the same on every call: no pointer or address in it
  Scene s = base;
  s.source = "/elsewhere/scene.json";
  s.textures[0].source = "/elsewhere/tex0.png";
  s.meshes[0].source = "/elsewhere/tri.obj";
  s.environment.source = "/elsewhere/sky.exr";
  s.materials[0].brdf = nullptr;
  s.settings.threads = 7;
  s.settings.spp = 99;
  s.settings.max_depth = 2;
  s.settings.seed = 123;
  EXPECT_EQ(scene_fingerprint(s), h0);
  // A copy made by another route (the image data in a fresh buffer) hashes the same.
  Scene copy = base;
  copy.environment.latlong = Image(8, 4);
  std::copy(base.environment.latlong.data.begin(), base.environment.latlong.data.end(), copy.environment.latlong.data.begin());
  EXPECT_EQ(scene_fingerprint(copy), h0);
  // Pinned: the same value on every machine and run (bit patterns, widened integers, no std::hash); a change to
  // the walk must change scene_fingerprint_version in shard_file.cpp, and this value with it.
  EXPECT_EQ(scene_fingerprint(shard_scene()), "57c3e0c7a582f456");
}

}  // namespace
}  // namespace shadelab
