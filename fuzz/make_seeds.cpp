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
#include <filesystem>
#include <string>
#include <vector>

#include "shadelab/envmap/base/ktx.h"
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
  std::printf("wrote the EXR and KTX seeds under %s\n", argv[1]);
  return 0;
}
