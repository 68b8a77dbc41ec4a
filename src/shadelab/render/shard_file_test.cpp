#include "shadelab/render/shard_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

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

}  // namespace
}  // namespace shadelab
