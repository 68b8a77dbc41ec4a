#include "shadelab/render/film.h"

#include <algorithm>

#include "shadelab/image/image_io.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

// Narkowicz 2015, ACES filmic fit (the kernel kernels/display.sl, shared with the explorer's WebGL sphere).
double filmic_curve(double x) { return kernel::tone_filmic(x); }

Image tonemap(const Image& hdr, double exposure_stops, ToneCurve curve) {
  Image out(hdr.width, hdr.height);
  const double scale = kernel::exposure_scale(exposure_stops);  // 2^stops (kernels/display.sl)
  for (std::size_t i = 0; i < hdr.data.size(); ++i) {
    const double v = static_cast<double>(hdr.data[i]) * scale;
    out.data[i] = static_cast<float>(curve == ToneCurve::filmic ? filmic_curve(v) : kernel::tone_clamp(v));
  }
  return out;
}

Result<std::vector<std::filesystem::path>> write_film(const RenderResult& result, const FilmOutputs& o) {
  // Every output is encoded first, then all are published as one output set (write_files_atomically): the
  // EXR, the PNG and the AOVs of one render are replaced together or not at all (issue 40, finding 7).
  std::vector<std::filesystem::path> written;
  std::vector<std::pair<std::filesystem::path, std::vector<char>>> files;
  auto put = [&](const Image& img, const std::filesystem::path& path) -> Result<bool> {
    auto bytes = encode_image(img, path);
    if (!bytes) return bytes.error();
    files.emplace_back(path, std::move(bytes).value());
    written.push_back(path);
    return true;
  };
  if (auto r = put(result.beauty, o.exr); !r) return r.error();
  if (!o.png.empty()) {
    if (auto r = put(tonemap(result.beauty, o.exposure_stops, o.curve), o.png); !r) return r.error();
  }
  if (o.aovs && !result.albedo.empty()) {
    const auto base = o.exr.parent_path() / o.exr.stem();
    for (const auto& [image, suffix] : {std::pair{&result.albedo, ".albedo.exr"}, std::pair{&result.normal, ".normal.exr"},
                                        std::pair{&result.depth, ".depth.exr"}}) {
      if (auto r = put(*image, base.string() + suffix); !r) return r.error();
    }
  }
  if (auto r = write_files_atomically(files); !r) return r.error();
  return written;
}

}  // namespace shadelab
