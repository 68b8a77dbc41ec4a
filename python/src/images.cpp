// shadelab.read_image, write_image, compare, bake_sh, bake_irradiance: images as float32 (H, W, 3) arrays,
// the figures of `shadelab compare`, and the `bake sh` / `bake irradiance` products.
#include <fmt/core.h>

#include <cmath>
#include <cstring>
#include <optional>

#include "bindings.h"
#include "common.h"
#include "shadelab/envmap/base/environment.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/envmap/diffuse/environment_bakes.h"
#include "shadelab/envmap/diffuse/irradiance.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/metrics.h"

namespace shadelab::python {

namespace {

std::string quoted(const std::string& s) { return "'" + s + "'"; }

void warn_repaired(const std::string& path, const ReadInfo& info) {
  if (info.nonfinite_repaired > 0) {
    // The CLI's warning line, as a RuntimeWarning.
    const std::string text = quoted(path) + ": " + std::to_string(info.nonfinite_repaired) + " NaN/Inf values replaced by 0";
    if (PyErr_WarnEx(PyExc_RuntimeWarning, text.c_str(), 1) != 0) throw py::error_already_set();
  }
}

py::dict info_dict(const ReadInfo& info) {
  py::dict d;
  d["format"] = info.format;
  d["sample_type"] = info.sample_type;
  d["channels"] = info.channels;
  d["had_alpha"] = info.had_alpha;
  d["grey"] = info.grey;
  d["partial_data_window"] = info.partial_data_window;
  d["nonfinite_repaired"] = info.nonfinite_repaired;
  d["negative_values"] = info.negative_values;
  return d;
}

Image read(const std::string& path, ReadInfo* info) {
  Result<Image> r = make_error("");
  {
    py::gil_scoped_release release;
    r = read_image(path, info);
  }
  return unwrap(std::move(r));
}

py::object read_image_py(py::handle path, bool with_info) {
  const std::string p = path_text(path);
  ReadInfo info;
  Image img = read(p, &info);
  warn_repaired(p, info);
  py::array_t<float> a = image_array(std::move(img));
  if (with_info) return py::make_tuple(a, info_dict(info));
  return a;
}

void write_image_py(py::handle path, py::handle image, double exposure, const std::string& pixel_type,
                    const std::string& compression) {
  const std::string p = path_text(path);
  if (!std::isfinite(exposure)) fail("exposure: must be a finite number of stops");
  WriteOptions o;
  o.exposure = exposure;
  if (pixel_type == "float32") o.exr_pixel_type = ExrPixelType::float32;
  else if (pixel_type == "half") o.exr_pixel_type = ExrPixelType::half;
  else fail("pixel_type: '" + pixel_type + "' is not one of float32 | half");
  if (compression == "none") o.exr_compression = ExrCompression::none;
  else if (compression == "rle") o.exr_compression = ExrCompression::rle;
  else if (compression == "zips") o.exr_compression = ExrCompression::zips;
  else if (compression == "zip") o.exr_compression = ExrCompression::zip;
  else if (compression == "piz") o.exr_compression = ExrCompression::piz;
  else fail("compression: '" + compression + "' is not one of none | rle | zips | zip | piz");
  const Image img = to_image(image, "image", false);
  Result<bool> r = make_error("");
  {
    py::gil_scoped_release release;
    r = write_image(img, p, o);
  }
  unwrap(std::move(r));
}

// An image argument that may be a file: (the image, the name errors use).
std::pair<Image, std::string> image_or_file(py::handle obj, const std::string& name) {
  if (is_path(obj)) {
    const std::string p = path_text(obj);
    ReadInfo info;
    Image img = read(p, &info);
    warn_repaired(p, info);
    return {std::move(img), quoted(p)};
  }
  return {to_image(obj, name, false), name};
}

const char* channel_name(int c) { return c == 0 ? "R" : (c == 1 ? "G" : "B"); }

py::dict compare(py::handle a_obj, py::handle b_obj, double epsilon, double exposure, bool heatmap,
                 const std::string& metric_name, double scale) {
  // The CLI's checks and messages (compare --exposure, --scale, --epsilon, --heatmap-metric).
  if (!std::isfinite(exposure)) fail("exposure: must be a finite number of stops");
  if (!std::isfinite(scale) || scale < 0.0) fail(fmt::format("heatmap_scale: {} must be a finite error > 0 (0: automatic)", scale));
  if (!std::isfinite(epsilon) || !(epsilon > 0.0)) fail(fmt::format("epsilon: {} must be a finite number > 0", epsilon));
  ErrorMetric metric = ErrorMetric::relative;
  if (metric_name == "absolute") metric = ErrorMetric::absolute;
  else if (metric_name == "relative") metric = ErrorMetric::relative;
  else fail("heatmap_metric: '" + metric_name + "' is not one of absolute | relative");
  const auto [a, name_a] = image_or_file(a_obj, "a");
  const auto [b, name_b] = image_or_file(b_obj, "b");
  CompareOptions co;
  co.name_a = name_a;
  co.name_b = name_b;
  co.relative_mse_epsilon = epsilon;
  co.exposure_stops = exposure;
  co.heatmap_metric = metric;
  co.heatmap_scale = scale;
  Result<ImageDifference> diff = make_error("");
  Result<Heatmap> heat = make_error("");
  {
    py::gil_scoped_release release;
    diff = compare_images(a, b, co);
    if (diff && heatmap) heat = error_heatmap(a, b, co);
  }
  const ImageDifference d = unwrap(std::move(diff));
  py::dict j;  // the keys of `shadelab compare --json` (NaN stays NaN here; JSON writes it as null)
  j["width"] = d.width;
  j["height"] = d.height;
  j["mse"] = d.mse;
  j["rmse"] = d.rmse;
  j["relative_mse"] = d.relative_mse;
  j["relative_mse_epsilon"] = d.relative_mse_epsilon;
  j["max_error"] = d.max_abs_error;
  j["max_error_at"] = py::make_tuple(d.max_x, d.max_y);
  j["max_error_channel"] = channel_name(d.max_channel);
  j["mean_luminance_a"] = d.mean_luminance_a;
  j["mean_luminance_b"] = d.mean_luminance_b;
  j["mean_luminance_ratio"] = d.mean_luminance_ratio;
  j["ssim"] = d.ssim;
  j["ssim_windows"] = d.ssim_windows;
  j["exposure"] = exposure;
  if (heatmap) {
    Heatmap h = unwrap(std::move(heat));
    j["heatmap_metric"] = metric_name;
    j["heatmap_scale"] = h.scale;
    j["heatmap_scale_automatic"] = !(scale > 0.0);
    j["heatmap_max_error"] = h.max_error;
    j["heatmap"] = image_array(std::move(h.image));
  }
  return j;
}

RadianceUnits parse_units(const std::string& u) {
  if (u == "game") return RadianceUnits::game;
  if (u == "radiometric") return RadianceUnits::radiometric;
  fail("units: '" + u + "' is not one of game | radiometric");
}

ShWindow parse_window(const std::string& w) {
  if (w == "none") return ShWindow::none;
  if (w == "hanning") return ShWindow::hanning;
  if (w == "lanczos") return ShWindow::lanczos;
  fail("window: '" + w + "' is not one of none | hanning | lanczos");
}

// The environment as a cube: a file or an array, a 2:1 lat-long (resampled to input_size faces) or a cube
// cross, or six faces as a (6, S, S, 3) array. Non-finite values in an array are errors; a file's are
// replaced by 0 with a warning (read_image's rule, as the CLI).
// The environment as the bakes read it: a 2:1 lat-long without input_size stays a lat-long, which the bakes
// use over its own texels (environment_sh9, environment_irradiance: as the CLI); anything else a cube map.
struct Environment {
  std::optional<Image> latlong;
  CubeMap cube;
};

Environment environment(py::handle image, py::handle input_size) {
  int size = -1;
  if (!input_size.is_none()) {
    const long long s = to_integer(input_size, "input_size");
    if (s < 1 || s > max_environment_face_size) {
      fail(fmt::format("input_size: {} is out of range [1, {}]", s, max_environment_face_size));
    }
    size = static_cast<int>(s);
  }
  if (is_path(image)) {
    const std::string p = path_text(image);
    ReadInfo info;
    const Image img = read(p, &info);
    warn_repaired(p, info);
    if (size == -1 && img.is_valid() && img.width == 2 * img.height) return {img, {}};
    return {std::nullopt, unwrap(environment_cube(img, size), p + ": ")};
  }
  const FloatArray arr = FloatArray::ensure(real_array(image, "image", "expected an image array of shape (H, W, 3)"));
  if (!arr) throw py::error_already_set();
  if (arr.ndim() == 4) {
    const py::ssize_t s = arr.shape(1);
    if (arr.shape(0) != 6 || arr.shape(2) != s || arr.shape(3) != 3 || s < 1 || s > max_environment_face_size) {
      fail("image: cube faces need shape (6, S, S, 3) with S in [1, " + std::to_string(max_environment_face_size) +
           "], got " + shape_text(arr));
    }
    CubeMap cube(static_cast<int>(s));
    const std::size_t face_floats = static_cast<std::size_t>(s) * static_cast<std::size_t>(s) * 3;
    for (std::size_t f = 0; f < 6; ++f) {
      std::memcpy(cube.faces[f].data.data(), arr.data() + f * face_floats, face_floats * sizeof(float));
      for (std::size_t i = 0; i < face_floats; ++i) {
        if (!std::isfinite(cube.faces[f].data[i])) {
          fail(fmt::format("image: face {} texel {} channel {} is not a finite number", f, i / 3, "RGB"[i % 3]));
        }
      }
    }
    return {std::nullopt, cube};
  }
  const Image img = to_image(image, "image", true);
  if (size == -1 && img.is_valid() && img.width == 2 * img.height) return {img, {}};
  return {std::nullopt, unwrap(environment_cube(img, size), "image: ")};
}

py::array_t<double> sh_array(const Sh9& sh) {
  py::array_t<double> a({py::ssize_t{9}, py::ssize_t{3}});
  double* d = a.mutable_data();
  for (std::size_t i = 0; i < 9; ++i) {
    d[3 * i] = sh.c[i].r;
    d[3 * i + 1] = sh.c[i].g;
    d[3 * i + 2] = sh.c[i].b;
  }
  return a;
}

// The basis and convention texts of `shadelab bake sh --json` (tested equal to the CLI's).
constexpr const char* sh_basis_text =
    "real SH, Condon-Shortley phase, z polar axis, Sloan 2008 order: Y00, Y1-1, Y10, Y11, Y2-2, Y2-1, Y20, Y21, "
    "Y22; world axes (+Y up)";
constexpr const char* sh_game_convention =
    "irradiance_coefficients give E/pi = sum_i c_i Y_i(n): multiply by kd for the diffuse exit radiance (game "
    "units, no pi)";
constexpr const char* sh_radiometric_convention =
    "irradiance_coefficients give E = sum_i c_i Y_i(n) in W/m^2 per unit of radiance";

py::object bake_sh(py::handle image, const std::string& units_name, const std::string& window_name,
                   py::handle input_size, bool details) {
  const RadianceUnits units = parse_units(units_name);
  const ShWindow window = parse_window(window_name);
  const Environment env = environment(image, input_size);
  Sh9 sh;
  Sh9 irr;
  const BandFactors factors = sh9_irradiance_factors(units, window);
  {
    py::gil_scoped_release release;
    sh = env.latlong ? unwrap(environment_sh9(*env.latlong), "image: ") : project_sh9(env.cube);
    irr = sh9_scale_bands(sh, factors);
  }
  if (!details) return sh_array(irr);
  py::dict d;
  d["order"] = 3;
  d["basis"] = sh_basis_text;
  d["units"] = units_name;
  d["convention"] = units == RadianceUnits::game ? sh_game_convention : sh_radiometric_convention;
  d["band_factors"] = py::make_tuple(factors[0], factors[1], factors[2]);
  d["window"] = window_name;
  d["radiance_coefficients"] = sh_array(sh);
  d["irradiance_coefficients"] = sh_array(irr);
  return d;
}

py::array_t<float> bake_irradiance(py::handle image, int size, const std::string& units_name,
                                   const std::string& layout, py::handle input_size) {
  if (size < 1 || size > 1024) fail(fmt::format("size: {} is out of range [1, 1024]", size));  // as --size
  const RadianceUnits units = parse_units(units_name);
  if (layout != "faces" && layout != "hcross" && layout != "vcross" && layout != "latlong") {
    fail("layout: '" + layout + "' is not one of faces | hcross | vcross | latlong");
  }
  const Environment env = environment(image, input_size);
  CubeMap e;
  {
    py::gil_scoped_release release;
    e = env.latlong ? unwrap(environment_irradiance(*env.latlong, size, units), "image: ") : irradiance_cube(env.cube, size, units);
  }
  if (layout == "faces") return cube_array(e);
  if (layout == "hcross") return image_array(cube_to_cross(e, CrossLayout::horizontal));
  if (layout == "vcross") return image_array(cube_to_cross(e, CrossLayout::vertical));
  return image_array(cube_to_latlong(e, 4 * e.size));
}

}  // namespace

void bind_images(py::module_& m) {
  m.def("read_image", &read_image_py, py::arg("path"), py::kw_only(), py::arg("info") = false,
        R"(read_image(path, *, info=False) -> ndarray  (or (ndarray, dict) with info=True)

Reads an EXR, Radiance HDR or PNG file (by extension) as linear RGB float32 of shape (H, W, 3), row 0 at the
top. PNG is decoded with the exact sRGB curve; grey is copied to R, G, B; alpha is dropped. NaN/Inf values
are replaced by 0 with a RuntimeWarning. info=True also returns what was found: format, sample_type,
channels, had_alpha, grey, partial_data_window, nonfinite_repaired, negative_values. A missing, truncated or
corrupt file raises ValueError naming it.)");
  m.def("write_image", &write_image_py, py::arg("path"), py::arg("image"), py::kw_only(), py::arg("exposure") = 0.0,
        py::arg("pixel_type") = "float32", py::arg("compression") = "zip",
        R"(write_image(path, image, *, exposure=0.0, pixel_type='float32', compression='zip')

Writes a linear RGB image ((H, W, 3), (H, W, 1) or (H, W) numbers) by the path's extension: .exr (float32 or
half; none, rle, zips, zip or piz compression), .hdr, .png (8-bit sRGB after multiplying by 2^exposure and
clamping). The file is written to a temporary file and renamed, so it is never half-written.)");
  m.def("compare", &compare, py::arg("a"), py::arg("b"), py::kw_only(), py::arg("epsilon") = default_relative_mse_epsilon,
        py::arg("exposure") = 0.0, py::arg("heatmap") = false, py::arg("heatmap_metric") = "relative",
        py::arg("heatmap_scale") = 0.0,
        R"(compare(a, b, *, epsilon=0.01, exposure=0.0, heatmap=False, heatmap_metric='relative', heatmap_scale=0.0) -> dict

How far image a is from the reference b (arrays or file paths, same size): mse, rmse, relative_mse
((a - b)^2 / (b^2 + epsilon)), max_error with max_error_at (x, y) and max_error_channel, mean luminances and
their ratio, ssim (11 x 11 Gaussian windows on sRGB-encoded luminance at `exposure` stops) and ssim_windows:
the figures of `shadelab compare --json` (docs/compare.md). heatmap=True adds the error heat map as a float32
(H, W, 3) array and its scale.)");
  m.def("bake_sh", &bake_sh, py::arg("image"), py::kw_only(), py::arg("units") = "game", py::arg("window") = "none",
        py::arg("input_size") = py::none(), py::arg("details") = false,
        R"(bake_sh(image, *, units='game', window='none', input_size=None, details=False) -> ndarray (9, 3)

Nine RGB spherical-harmonic irradiance coefficients of an environment: a path, a 2:1 lat-long or a cube cross
as (H, W, 3), or six faces as (6, S, S, 3) in the order +X, -X, +Y, -Y, +Z, -Z. A lat-long is projected over its
own texels, or with input_size first resampled to a cube of input_size faces.

Convention: real SH with the Condon-Shortley phase, z polar axis, in Sloan's order Y00, Y1-1, Y10, Y11, Y2-2,
Y2-1, Y20, Y21, Y22, world axes (+Y up). units='game': sum_i c_i Y_i(n) is E/pi, the exit radiance of a
white Lambert surface with normal n (multiply by kd; no pi); units='radiometric': it is E in W/m^2 per unit of
radiance. window: none, hanning or lanczos (damps ringing). details=True returns the dict of
`shadelab bake sh --json` (radiance and irradiance coefficients, band factors, the texts).)");
  m.def("bake_irradiance", &bake_irradiance, py::arg("image"), py::kw_only(), py::arg("size") = 32,
        py::arg("units") = "game", py::arg("layout") = "faces", py::arg("input_size") = py::none(),
        R"(bake_irradiance(image, *, size=32, units='game', layout='faces', input_size=None) -> ndarray

The cosine-convolved irradiance cube map of an environment (the image argument as bake_sh), exact over its texels:
units='game' stores E/pi (a constant 0.5 environment bakes to 0.5), 'radiometric' stores E. layout='faces'
returns float32 (6, size, size, 3) in the order +X, -X, +Y, -Y, +Z, -Z (OpenGL orientation); 'hcross',
'vcross' or 'latlong' return the (H, W, 3) image `shadelab bake irradiance --layout` writes.)");
}

}  // namespace shadelab::python
