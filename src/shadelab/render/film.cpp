#include "shadelab/render/film.h"

#include <algorithm>

#include "shadelab/image/image_io.h"

namespace shadelab {

double filmic_curve(double x) {
  x = std::max(0.0, x);
  // Narkowicz 2015, ACES filmic fit
  return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

Image tonemap(const Image& hdr, double exposure_stops, ToneCurve curve) {
  Image out(hdr.width, hdr.height);
  const double scale = std::exp2(exposure_stops);
  for (std::size_t i = 0; i < hdr.data.size(); ++i) {
    const double v = static_cast<double>(hdr.data[i]) * scale;
    out.data[i] = static_cast<float>(curve == ToneCurve::filmic ? filmic_curve(v) : std::clamp(v, 0.0, 1.0));
  }
  return out;
}

Result<std::vector<std::filesystem::path>> write_film(const RenderResult& result, const FilmOutputs& o) {
  std::vector<std::filesystem::path> written;
  auto put = [&](const Image& img, const std::filesystem::path& path) -> Result<bool> {
    auto r = write_image(img, path);
    if (r) written.push_back(path);
    return r;
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
  return written;
}

}  // namespace shadelab
