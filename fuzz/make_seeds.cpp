// Writes the binary seed corpora that need a library to make: OpenEXR files (fuzz/corpus/exr: every
// compression, half / float / uint, scan lines and tiles, mipmaps, luminance-chroma, Y only, alpha, data
// windows inside, outside and across the display window) and KTX cube maps (fuzz/corpus/ktx). Run once and
// commit the files:  cmake --build --preset ci --target shadelab_fuzz_seeds && build/ci/fuzz/shadelab_fuzz_seeds fuzz/corpus
// (the text-format seeds come from fuzz/make_seeds.py).
#include <ImfArray.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <ImfTiledRgbaFile.h>

#include <cstdio>
#include <fstream>
#include <filesystem>
#include <string>
#include <vector>

#include "shadelab/envmap/base/ktx.h"
#include "shadelab/envmap/base/ktx2.h"
#include "shadelab/envmap/base/texel_format.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/render/shard_file.h"
#include "shadelab/scene/default_scene.h"
#include "shadelab/image/image_io.h"

using namespace shadelab;
namespace fs = std::filesystem;

namespace {

Imf::Rgba texel(int x, int y) {
  return Imf::Rgba(static_cast<float>(0.1 + 0.1 * x), static_cast<float>(0.2 + 0.05 * y), 0.5f, 0.75f);
}

void rgba_file(const fs::path& path, const Imath::Box2i& display, const Imath::Box2i& data, Imf::RgbaChannels channels,
               Imf::Compression compression) {
  Imf::Header header(display, data);
  header.compression() = compression;
  Imf::RgbaOutputFile file(path.c_str(), header, channels);
  const int w = data.max.x - data.min.x + 1;
  const int h = data.max.y - data.min.y + 1;
  std::vector<Imf::Rgba> pixels(static_cast<std::size_t>(w * h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) pixels[static_cast<std::size_t>(y * w + x)] = texel(x, y);
  }
  file.setFrameBuffer(pixels.data() - data.min.x - static_cast<long>(data.min.y) * w, 1, static_cast<std::size_t>(w));
  file.writePixels(h);
}

void tiled_file(const fs::path& path, Imf::LevelMode mode) {
  const int w = 8, h = 4;
  Imf::TiledRgbaOutputFile file(path.c_str(), w, h, 4, 4, mode, Imf::ROUND_DOWN, Imf::WRITE_RGB);
  std::vector<Imf::Rgba> pixels(static_cast<std::size_t>(w * h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) pixels[static_cast<std::size_t>(y * w + x)] = texel(x, y);
  }
  file.setFrameBuffer(pixels.data(), 1, w);
  for (int level = 0; level < file.numLevels(); ++level) {
    file.writeTiles(0, file.numXTiles(level) - 1, 0, file.numYTiles(level) - 1, level);
  }
}

void uint_file(const fs::path& path) {
  const int w = 4, h = 2;
  Imf::Header header(w, h);
  header.channels().insert("R", Imf::Channel(Imf::UINT));
  header.channels().insert("G", Imf::Channel(Imf::UINT));
  header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
  std::vector<unsigned> r(w * h, 7), g(w * h, 1u << 20);
  std::vector<float> z(w * h, 3.0f);
  Imf::FrameBuffer fb;
  fb.insert("R", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(r.data()), sizeof(unsigned), sizeof(unsigned) * w));
  fb.insert("G", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(g.data()), sizeof(unsigned), sizeof(unsigned) * w));
  fb.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float), sizeof(float) * w));
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(h);
}

Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) img.set(x, y, {0.1 + 0.1 * x, 0.3 + 0.2 * y, x == 3 ? 70000.0 : -0.25});
  }
  return img;
}

CubeMap cube(int size, double base) {
  CubeMap c(size);
  for (int f = 0; f < 6; ++f) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) c.set(f, x, y, {base + 0.1 * f, base + 0.01 * x, base + 0.02 * y});
    }
  }
  return c;
}

void check(const Result<bool>& r) {
  if (!r) {
    std::fprintf(stderr, "%s\n", r.error().message.c_str());
    std::exit(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: shadelab_fuzz_seeds CORPUS_DIR (fuzz/corpus)\n");
    return 2;
  }
  const fs::path exr = fs::path(argv[1]) / "exr";
  const fs::path ktx = fs::path(argv[1]) / "ktx";
  fs::create_directories(exr);
  fs::create_directories(ktx);
  const Image img = gradient(8, 4);
  const std::pair<ExrCompression, const char*> compressions[] = {
      {ExrCompression::none, "none"}, {ExrCompression::rle, "rle"}, {ExrCompression::zips, "zips"},
      {ExrCompression::zip, "zip"}, {ExrCompression::piz, "piz"}};
  for (const auto& [c, name] : compressions) {
    for (ExrPixelType t : {ExrPixelType::float32, ExrPixelType::half}) {
      WriteOptions o;
      o.exr_compression = c;
      o.exr_pixel_type = t;
      check(write_image(img, exr / (std::string(name) + (t == ExrPixelType::half ? "_half" : "_float") + ".exr"), o));
    }
  }
  const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(7, 3));
  rgba_file(exr / "rgba_b44.exr", display, display, Imf::WRITE_RGBA, Imf::B44_COMPRESSION);
  rgba_file(exr / "rgb_dwaa.exr", display, display, Imf::WRITE_RGB, Imf::DWAA_COMPRESSION);
  rgba_file(exr / "rgb_pxr24.exr", display, display, Imf::WRITE_RGB, Imf::PXR24_COMPRESSION);
  rgba_file(exr / "yc.exr", display, display, Imf::WRITE_YC, Imf::PIZ_COMPRESSION);
  rgba_file(exr / "y.exr", display, display, Imf::WRITE_Y, Imf::ZIP_COMPRESSION);
  rgba_file(exr / "ya.exr", display, display, Imf::WRITE_YA, Imf::NO_COMPRESSION);
  rgba_file(exr / "data_inside.exr", display, Imath::Box2i(Imath::V2i(2, 1), Imath::V2i(5, 2)), Imf::WRITE_RGB,
            Imf::ZIP_COMPRESSION);
  rgba_file(exr / "data_across.exr", display, Imath::Box2i(Imath::V2i(-2, -1), Imath::V2i(4, 5)), Imf::WRITE_RGB,
            Imf::ZIPS_COMPRESSION);
  rgba_file(exr / "data_outside.exr", display, Imath::Box2i(Imath::V2i(10, 10), Imath::V2i(12, 11)), Imf::WRITE_RGB,
            Imf::NO_COMPRESSION);
  tiled_file(exr / "tiled.exr", Imf::ONE_LEVEL);
  tiled_file(exr / "tiled_mipmap.exr", Imf::MIPMAP_LEVELS);
  uint_file(exr / "uint_rg_z.exr");

  const std::vector<CubeMap> chain{cube(4, 0.5), cube(2, 0.25), cube(1, 0.125)};
  for (KtxPixelType t : {KtxPixelType::half, KtxPixelType::float32}) {
    const std::string suffix = t == KtxPixelType::half ? "_rgba16f.ktx" : "_rgba32f.ktx";
    check(write_ktx_cubemap(chain, ktx / ("chain" + suffix), t));
    check(write_ktx_cubemap({cube(1, 2.0)}, ktx / ("single" + suffix), t));
  }
  check(write_ktx_cubemap({cube(2, 1e5)}, ktx / "clamped_rgba16f.ktx", KtxPixelType::half));
  // KTX 2 (fuzz/corpus/ktx2): a chain in each cube format the reader reads, one level, and the DFG table's
  // 2D formats with key/value data.
  const fs::path ktx2 = fs::path(argv[1]) / "ktx2";
  fs::create_directories(ktx2);
  for (TexelFormat f : all_texel_formats) {
    const std::string name = texel_format_name(f);
    check(write_ktx2_cubemap(chain, ktx2 / ("chain_" + name + ".ktx2"), f, {{"shadelab.mip_mapping", "linear"}}));
  }
  check(write_ktx2_cubemap({cube(1, 2.0)}, ktx2 / "single_rgba16f.ktx2", TexelFormat::rgba16f));
  check(write_ktx2_image(gradient(4, 4), ktx2 / "table_rg16f.ktx2", Ktx2ImageFormat::rg16f, {{"shadelab.table", "dfg"}}));
  check(write_ktx2_image(gradient(3, 2), ktx2 / "table_rgba16f.ktx2", Ktx2ImageFormat::rgba16f));

  // Shard parts (fuzz/corpus/shard): the two sample shards of the default scene at 8 x 4 pixels and 4 spp,
  // each alone, and both in one input (the second after the separator line: a merge of the two).
  const fs::path shard = fs::path(argv[1]) / "shard";
  fs::create_directories(shard);
  Scene scene = default_scene();
  scene.camera.width = 8;
  scene.camera.height = 4;
  std::string both;
  for (int index = 0; index < 2; ++index) {
    RenderOptions ro;
    ro.spp = 4;
    ro.max_depth = 3;
    ro.threads = 1;
    ro.shard = ShardSpec{index, 2, ShardSplit::samples};
    auto result = render_scene(scene, ro);
    if (!result) {
      std::fprintf(stderr, "%s\n", result.error().message.c_str());
      return 1;
    }
    const fs::path part = shard / ("part-" + std::to_string(index) + "-of-2.exr");
    check(write_shard(part, make_shard_info(scene, ro, 4, 3), *result));
    std::string bytes(static_cast<std::size_t>(fs::file_size(part)), '\0');
    std::ifstream(part, std::ios::binary).read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    both += index == 0 ? bytes + "\n#--shadelab-fuzz-next-file--\n" : bytes;
  }
  std::ofstream(shard / "merge-0-and-1", std::ios::binary) << both;
  std::printf("wrote the EXR, KTX, KTX 2 and shard seeds under %s\n", argv[1]);
  return 0;
}
