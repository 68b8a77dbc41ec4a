#include "shadelab/render/film.h"

#include <algorithm>
#include <array>
#include <vector>

#include "shadelab/color/ocio.h"
#include "shadelab/core/text.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/srgb.h"
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

namespace {
constexpr std::array<std::pair<ViewTransform, const char*>, 5> kViewNames{{{ViewTransform::standard, "standard"},
                                                                        {ViewTransform::filmic, "filmic"},
                                                                        {ViewTransform::pbr_neutral, "pbr-neutral"},
                                                                        {ViewTransform::agx, "agx"},
                                                                        {ViewTransform::aces, "aces"}}};
static_assert(static_cast<int>(ViewTransform::standard) == kernel::VIEW_STANDARD &&
              static_cast<int>(ViewTransform::filmic) == kernel::VIEW_FILMIC &&
              static_cast<int>(ViewTransform::pbr_neutral) == kernel::VIEW_PBR_NEUTRAL &&
              static_cast<int>(ViewTransform::agx) == kernel::VIEW_AGX &&
              static_cast<int>(ViewTransform::aces) == kernel::VIEW_ACES);
}  // namespace

const char* view_name(ViewTransform view) {
  for (const auto& [v, name] : kViewNames) {
    if (v == view) return name;
  }
  return "OCIO";
}

DisplayView view_of(ToneCurve curve) {
  DisplayView v;
  v.transform = curve == ToneCurve::filmic ? ViewTransform::filmic : ViewTransform::standard;
  return v;
}

Result<DisplayView> parse_view(std::string_view text) {
  DisplayView v;
  for (const auto& [view, name] : kViewNames) {
    if (text == name) {
      v.transform = view;
      return v;
    }
  }
  constexpr std::string_view prefix = "OCIO:";
  if (text.substr(0, prefix.size()) == prefix) {
    const std::string_view rest = text.substr(prefix.size());
    const auto last = rest.rfind(':');
    const auto middle = last == std::string_view::npos || last == 0 ? std::string_view::npos : rest.rfind(':', last - 1);
    if (middle != std::string_view::npos) {
      v.transform = ViewTransform::ocio;
      v.ocio_config = std::string(rest.substr(0, middle));
      v.ocio_display = std::string(rest.substr(middle + 1, last - middle - 1));
      v.ocio_view = std::string(rest.substr(last + 1));
      if (!v.ocio_display.empty() && !v.ocio_view.empty()) return v;
    }
    return make_error("'" + printable(text) + "': an OCIO view is OCIO:<config>:<display>:<view> (the config may be empty: $OCIO)");
  }
  return make_error("'" + printable(text) + "': not a view (standard, filmic, pbr-neutral, agx, aces, OCIO:<config>:<display>:<view>)");
}

Result<Image> apply_view(const Image& hdr, double exposure_stops, const DisplayView& view) {
  Image out(hdr.width, hdr.height);
  if (view.transform == ViewTransform::ocio) {
    const double scale = kernel::exposure_scale(exposure_stops);  // 2^stops (kernels/display.sl)
    for (std::size_t i = 0; i < hdr.data.size(); ++i) out.data[i] = static_cast<float>(static_cast<double>(hdr.data[i]) * scale);
    ocio::DisplayViewRequest r{view.ocio_config, view.ocio_display, view.ocio_view, view.looks, {}};
    if (auto ok = ocio::apply_display_view(r, out.data.data(), out.pixel_count()); !ok) return ok.error();
    // The config's code values, decoded so that the PNG writer's sRGB encoding gives them back.
    for (auto& x : out.data) x = static_cast<float>(srgb_to_linear(std::clamp(static_cast<double>(x), 0.0, 1.0)));
    return out;
  }
  const int v = static_cast<int>(view.transform);
  for (std::size_t i = 0; i + 2 < hdr.data.size(); i += 3) {
    const kernel::rgb c{static_cast<double>(hdr.data[i]), static_cast<double>(hdr.data[i + 1]),
                        static_cast<double>(hdr.data[i + 2])};
    const kernel::rgb d = kernel::view_transform(v, exposure_stops, c);  // kernels/display.sl
    out.data[i] = static_cast<float>(d.r);
    out.data[i + 1] = static_cast<float>(d.g);
    out.data[i + 2] = static_cast<float>(d.b);
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
    auto shown = apply_view(result.beauty, o.exposure_stops, o.view ? *o.view : view_of(o.curve));
    if (!shown) return shown.error();
    if (auto r = put(*shown, o.png); !r) return r.error();
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
