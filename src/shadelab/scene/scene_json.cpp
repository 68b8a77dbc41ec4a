// The JSON scene format (docs/scene-format.md). Inside this file a parse error is thrown as a Failure (the
// JSON pointer and the message) and caught once, in parse_scene, which returns it as an Error: the checks
// read as straight-line code, and nothing crosses the library boundary but a Result.
#include "shadelab/scene/scene_json.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadelab/core/constants.h"
#include "shadelab/core/text.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/srgb.h"
#include "shadelab/light/units.h"
#include "shadelab/scene/limits.h"
#include "shadelab/scene/mesh_io.h"
#include "shadelab/scene/procedural.h"

namespace shadelab {

namespace {

using nlohmann::json;

constexpr std::array<std::string_view, 10> top_level_keys = {
    "$schema", "description", "units", "camera", "render", "textures", "materials", "shapes", "lights", "environment"};

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr int max_image_side = max_camera_side;  // camera width and height
constexpr int max_texture_side = 8192;  // procedural textures

struct Failure {
  std::string pointer;
  std::string message;
};

// RFC 6901: in a reference token "~" is written "~0" and "/" is written "~1". A key too long or not
// printable to quote whole is cut and escaped (core/text.h): the pointer is for a reader.
std::string pointer_token(std::string_view raw_key) {
  const std::string key = printable(raw_key);
  std::string out;
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::string format_number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// The shortest text that reads back as exactly v (for handing numbers to parse_params).
std::string exact_number(double v) {
  std::array<char, 64> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return ec == std::errc() ? std::string(buffer.data(), end) : format_number(v);
}

// A value as a message shows it: JSON text, shortened; non-finite numbers by name.
std::string describe(const json& v) {
  if (v.is_number_float()) {
    const double d = v.get<double>();
    if (std::isnan(d)) return "NaN";
    if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
  }
  // JSON escapes only bytes below 0x20: DEL and the like stay raw in a dumped string, so printable() writes
  // them as \xNN (the scene fuzzer's finding of 2026-12-06: a top-level string holding 0x7f).
  const std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
  return printable(s, s.size() > 60 ? 57 : 60);
}

std::string join(const std::vector<std::string>& words, std::string_view separator = ", ") {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : std::string(separator)) + w;
  return out;
}

// A value in the document and its JSON pointer.
class Node {
 public:
  Node(const json& value, std::string pointer) : m_value(&value), m_pointer(std::move(pointer)) {}

  const json& value() const { return *m_value; }
  const std::string& pointer() const { return m_pointer; }
  std::string child_pointer(std::string_view key) const { return m_pointer + "/" + pointer_token(key); }
  Node element(std::size_t i) const { return {(*m_value)[i], m_pointer + "/" + std::to_string(i)}; }

  [[noreturn]] void fail(const std::string& message) const { throw Failure{m_pointer, message}; }

 private:
  const json* m_value;
  std::string m_pointer;
};

// An object whose keys have been checked against the allowed ones.
class Object {
 public:
  Object(const Node& node, const std::vector<std::string_view>& allowed, std::string_view what) : m_node(node) {
    if (!node.value().is_object())
      node.fail("expected " + std::string(what) + " (a JSON object), got " + describe(node.value()));
    for (const auto& [key, value] : node.value().items()) {
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::vector<std::string> names(allowed.begin(), allowed.end());
        throw Failure{node.child_pointer(key),
                      "unknown key '" + printable(key) + "' (keys of " + std::string(what) + ": " + join(names) + ")"};
      }
    }
  }

  const Node& node() const { return m_node; }
  bool has(std::string_view key) const { return m_node.value().contains(key); }
  std::optional<Node> get(std::string_view key) const {
    const auto it = m_node.value().find(key);
    if (it == m_node.value().end()) return std::nullopt;
    return Node(*it, m_node.child_pointer(key));
  }
  Node require(std::string_view key) const {
    auto n = get(key);
    if (!n) throw Failure{m_node.child_pointer(key), "required key is missing"};
    return *n;
  }

 private:
  Node m_node;
};

// ---- scalar values ------------------------------------------------------------------------------------

double number(const Node& n) {
  if (!n.value().is_number()) n.fail("expected a number, got " + describe(n.value()));
  const double v = n.value().get<double>();
  if (!std::isfinite(v)) n.fail("expected a finite number, got " + describe(n.value()));
  return v;
}

// A number in a range; lo_open / hi_open exclude the bound; hi = inf means no upper bound.
double number_in(const Node& n, double lo, bool lo_open, double hi = inf, bool hi_open = false) {
  const double v = number(n);
  const bool ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  if (!ok) {
    const std::string condition = hi == inf ? std::string(lo_open ? "> " : ">= ") + format_number(lo)
                                            : std::string("in ") + (lo_open ? "(" : "[") + format_number(lo) + ", " +
                                                  format_number(hi) + (hi_open ? ")" : "]");
    n.fail("expected a number " + condition + ", got " + describe(n.value()));
  }
  return v;
}

double non_negative(const Node& n) { return number_in(n, 0.0, false); }

// An integer in [lo, hi]; 640.0 counts as an integer, 2.5 does not.
long long integer_in(const Node& n, long long lo, long long hi) {
  const std::string condition = hi == std::numeric_limits<long long>::max()
                                    ? ">= " + std::to_string(lo)
                                    : "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!n.value().is_number()) n.fail("expected an integer, got " + describe(n.value()));
  if (n.value().is_number_unsigned()) {
    const auto u = n.value().get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(hi) || (lo > 0 && u < static_cast<std::uint64_t>(lo)))
      n.fail("expected an integer " + condition + ", got " + describe(n.value()));
    return static_cast<long long>(u);
  }
  if (n.value().is_number_integer()) {
    const auto i = n.value().get<std::int64_t>();
    if (i < lo || i > hi) n.fail("expected an integer " + condition + ", got " + describe(n.value()));
    return i;
  }
  const double d = n.value().get<double>();
  if (!std::isfinite(d) || d != std::floor(d) || d < static_cast<double>(lo) || d > static_cast<double>(hi) ||
      std::abs(d) > 0x1.0p53) {
    n.fail("expected an integer " + condition + ", got " + describe(n.value()));
  }
  return static_cast<long long>(d);
}

int int_in(const Node& n, int lo, int hi) { return static_cast<int>(integer_in(n, lo, hi)); }

std::uint64_t seed_value(const Node& n) {
  if (n.value().is_number_unsigned()) return n.value().get<std::uint64_t>();
  return static_cast<std::uint64_t>(integer_in(n, 0, std::numeric_limits<long long>::max()));
}

std::string string_value(const Node& n) {
  if (!n.value().is_string()) n.fail("expected a string, got " + describe(n.value()));
  return n.value().get<std::string>();
}

std::string nonempty_string(const Node& n) {
  std::string s = string_value(n);
  if (s.empty()) n.fail("expected a non-empty string, got \"\"");
  return s;
}

bool boolean(const Node& n) {
  if (!n.value().is_boolean()) n.fail("expected true or false, got " + describe(n.value()));
  return n.value().get<bool>();
}

std::string word(const Node& n, const std::vector<std::string_view>& choices) {
  std::vector<std::string> quoted;
  for (auto c : choices) quoted.push_back("\"" + std::string(c) + "\"");
  const std::string expected = "expected one of " + join(quoted, ", ");
  if (!n.value().is_string()) n.fail(expected + ", got " + describe(n.value()));
  const std::string s = n.value().get<std::string>();
  if (std::find(choices.begin(), choices.end(), s) == choices.end()) n.fail(expected + ", got " + describe(n.value()));
  return s;
}

// ---- vectors and colours ------------------------------------------------------------------------------

Vec3 vec3(const Node& n) {
  if (!n.value().is_array() || n.value().size() != 3) n.fail("expected [x, y, z], got " + describe(n.value()));
  return {number(n.element(0)), number(n.element(1)), number(n.element(2))};
}

// A direction: any non-zero vector, normalized after scaling by its largest component, so that neither
// [0, 1e-300, 0] (whose squared length underflows) nor [1e300, 0, 0] (overflows) loses its direction.
// Returns the zero vector when v is zero.
Vec3 scaled_normalize(const Vec3& v) {
  const double big = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return big > 0.0 ? normalize(v / big) : Vec3{};
}

Vec3 direction(const Node& n) {
  const Vec3 d = scaled_normalize(vec3(n));
  if (d.x == 0.0 && d.y == 0.0 && d.z == 0.0) n.fail("expected a non-zero vector, got " + describe(n.value()));
  return d;
}

// A position: each coordinate within +-max_scene_coordinate (scene/limits.h).
Vec3 position(const Node& n) {
  const Vec3 p = vec3(n);
  for (double c : {p.x, p.y, p.z}) {
    if (std::abs(c) > max_scene_coordinate) {
      n.fail("coordinate " + format_number(c) + " is beyond +-" + format_number(max_scene_coordinate) +
             " (the largest the renderer's float ray math survives with margin)");
    }
  }
  return p;
}

// A length (radius, scale): > 0, and within [min_scene_length, max_scene_coordinate] (scene/limits.h).
double length_value(const Node& n) {
  const double v = number_in(n, 0.0, true);
  if (v < min_scene_length || v > max_scene_coordinate) {
    n.fail("expected a length in [" + format_number(min_scene_length) + ", " + format_number(max_scene_coordinate) +
           "] (the scene's limits), got " + describe(n.value()));
  }
  return v;
}

// An edge vector (a quad's u and v): its length in [min_scene_length, max_scene_coordinate].
Vec3 edge(const Node& n) {
  const Vec3 v = vec3(n);
  if (v.x == 0.0 && v.y == 0.0 && v.z == 0.0) n.fail("expected a non-zero vector, got " + describe(n.value()));
  const double len = length(v);
  if (!(len >= min_scene_length && len <= max_scene_coordinate)) {
    n.fail("expected a vector of length in [" + format_number(min_scene_length) + ", " +
           format_number(max_scene_coordinate) + "], got " + describe(n.value()));
  }
  return v;
}

// A colour: a number >= 0 (grey) or [r, g, b], each >= 0.
Rgb colour(const Node& n) {
  if (n.value().is_number()) return Rgb::gray(non_negative(n));
  if (!n.value().is_array() || n.value().size() != 3) {
    n.fail("expected a colour (a number or [r, g, b]), got " + describe(n.value()));
  }
  return {non_negative(n.element(0)), non_negative(n.element(1)), non_negative(n.element(2))};
}

// ---- units --------------------------------------------------------------------------------------------

enum class Units { game, radiometric, photometric };

// The named unit (light/units.h) in which a scene of these units gives each quantity.
std::string_view unit_name(Units units, LightQuantity quantity) {
  switch (quantity) {
    case LightQuantity::irradiance:
      return units == Units::game ? "game" : units == Units::radiometric ? "W/m2" : "lux";
    case LightQuantity::intensity:
      return units == Units::game ? "game-point" : units == Units::radiometric ? "W/sr" : "cd";
    case LightQuantity::radiance:
      break;
  }
  return units == Units::game ? "game-radiance" : units == Units::radiometric ? "W/m2/sr" : "nit";
}

std::string_view radiometric_unit(LightQuantity quantity) {
  switch (quantity) {
    case LightQuantity::irradiance:
      return "W/m2";
    case LightQuantity::intensity:
      return "W/sr";
    case LightQuantity::radiance:
      break;
  }
  return "W/m2/sr";
}

Rgb convert(const Rgb& value, std::string_view from, std::string_view to, double cos_outer = -1.0) {
  auto r = convert_light(value, from, to, cos_outer);
  // The unit names are this file's constants and the cone is checked, so a failure is a programming error.
  if (!r) throw std::logic_error("scene_json: " + r.error().message);
  return *r;
}

// An RGB value per channel in the scene's unit of `quantity` -> radiometric (game: E = pi c, I = pi c;
// photometric: each channel / 683, i.e. the vector's luminance is the photometric value).
Rgb radiometric(const Rgb& value, Units units, LightQuantity quantity) {
  return convert(value, unit_name(units, quantity), radiometric_unit(quantity));
}

// A light value after conversion to radiometry must be at most max_light_value (scene/limits.h) per channel.
Rgb bounded_light(const Node& n, const Rgb& v) {
  if (!(v.max_component() <= max_light_value)) {
    n.fail("the light value " + format_number(v.max_component()) +
           " (radiometric, after unit conversion) is above the largest supported, " + format_number(max_light_value));
  }
  return v;
}

// A colour times a value: in game and radiometric units the product; in photometric units the colour is a
// chromaticity scaled so that its photometric value (683 x luminance) is `value` (light/units.h).
Rgb radiometric(const Rgb& colour_value, double value, Units units, LightQuantity quantity) {
  if (units == Units::photometric) return radiometric_from_photometric(colour_value, value);
  return radiometric(colour_value * value, units, quantity);
}

// ---- the parser ---------------------------------------------------------------------------------------

class Parser {
 public:
  Parser(const std::filesystem::path& base_dir, Scene& scene) : m_base_dir(base_dir), m_scene(scene) {}

  void parse(const json& document) {
    const Object top(Node(document, ""), {top_level_keys.begin(), top_level_keys.end()}, "a scene");
    if (auto n = top.get("$schema")) string_value(*n);
    if (auto n = top.get("description")) string_value(*n);
    if (auto n = top.get("units")) {
      const std::string u = word(*n, {"game", "radiometric", "photometric"});
      m_units = u == "game" ? Units::game : u == "radiometric" ? Units::radiometric : Units::photometric;
    }
    if (auto n = top.get("camera")) parse_camera(*n);
    if (auto n = top.get("render")) parse_render(*n);
    if (auto n = top.get("textures")) parse_textures(*n);
    if (auto n = top.get("materials")) parse_materials(*n);
    if (auto n = top.get("shapes")) parse_shapes(*n);
    if (auto n = top.get("lights")) parse_lights(*n);
    if (auto n = top.get("environment")) parse_environment(*n);
  }

 private:
  // A file named by node n, relative to the scene's folder unless absolute; it must exist.
  std::filesystem::path file(const Node& n) const {
    const std::filesystem::path given(nonempty_string(n));
    const std::filesystem::path p = (given.is_absolute() ? given : m_base_dir / given).lexically_normal();
    std::error_code ec;
    if (!std::filesystem::exists(p, ec)) n.fail("file not found: '" + p.string() + "'");
    if (!std::filesystem::is_regular_file(p, ec)) n.fail("not a regular file: '" + p.string() + "'");
    return p;
  }

  void parse_camera(const Node& node) {
    const Object o(node, {"position", "look_at", "up", "fov", "width", "height"}, "a camera");
    Camera& c = m_scene.camera;
    if (auto n = o.get("position")) c.position = position(*n);
    if (auto n = o.get("look_at")) c.look_at = position(*n);
    if (auto n = o.get("up")) c.up = direction(*n);
    if (auto n = o.get("fov")) c.vfov_deg = number_in(*n, 0.0, true, 180.0, true);
    if (auto n = o.get("width")) c.width = int_in(*n, 1, max_image_side);
    if (auto n = o.get("height")) c.height = int_in(*n, 1, max_image_side);
    if (static_cast<long long>(c.width) * c.height > max_render_pixels) {
      throw Failure{o.node().child_pointer(o.has("height") ? "height" : "width"),
                    std::to_string(c.width) + " x " + std::to_string(c.height) + " is " +
                        std::to_string(static_cast<long long>(c.width) * c.height) + " pixels, more than the limit of " +
                        std::to_string(max_render_pixels) + " (8192 x 4096)"};
    }
    const Vec3 view = c.look_at - c.position;
    if (length(view) == 0.0) {
      throw Failure{o.node().child_pointer(o.has("look_at") ? "look_at" : "position"),
                    "look_at equals position: the view direction is undefined"};
    }
    if (length(cross(normalize(view), c.up)) < 1e-9) {
      throw Failure{o.node().child_pointer("up"), "up is parallel to the view direction (look_at - position)"};
    }
  }

  void parse_render(const Node& node) {
    const Object o(node, {"spp", "max_depth", "seed", "threads", "rr_depth"}, "render settings");
    RenderSettings& s = m_scene.settings;
    if (auto n = o.get("spp")) s.spp = int_in(*n, 1, 1'000'000);
    if (auto n = o.get("max_depth")) s.max_depth = int_in(*n, 1, 1000);
    if (auto n = o.get("seed")) s.seed = seed_value(*n);
    if (auto n = o.get("threads")) s.threads = int_in(*n, 0, 4096);
    if (auto n = o.get("rr_depth")) s.rr_depth = int_in(*n, 0, 1000);
  }

  // ---- textures ----

  void parse_textures(const Node& node) {
    if (!node.value().is_object())
      node.fail("expected textures by name (a JSON object), got " + describe(node.value()));
    for (const auto& [name, value] : node.value().items()) {
      const Node n(value, node.child_pointer(name));
      m_texture_index[name] = static_cast<int>(m_scene.textures.size());
      m_scene.textures.push_back(parse_texture(n, name));
    }
  }

  Texture parse_texture(const Node& node, const std::string& name) {
    Texture t;
    t.name = name;
    if (!node.value().is_object()) node.fail("expected a texture (a JSON object), got " + describe(node.value()));
    const bool has_file = node.value().contains("file");
    const bool has_procedural = node.value().contains("procedural");
    if (has_file && has_procedural)
      throw Failure{node.child_pointer("procedural"), "give 'file' or 'procedural', not both"};
    if (!has_file && !has_procedural) node.fail("a texture needs 'file' or 'procedural'");
    if (has_file) {
      const Object o(node, {"file", "data", "alpha"}, "a file texture");
      const std::filesystem::path path = file(o.require("file"));
      const bool alpha = o.has("alpha") && boolean(*o.get("alpha"));
      if (alpha && o.has("data") && !boolean(*o.get("data"))) {
        throw Failure{o.node().child_pointer("data"), "an alpha texture is data (the alpha codes as stored)"};
      }
      read_file_texture(t, path, o.has("data") && boolean(*o.get("data")),
                        Node(o.node().value().at("file"), o.node().child_pointer("file")), alpha);
      return t;
    }
    return procedural_texture(node, t);
  }

  // A texture from an image file; errors name `where` (a scene field).
  // alpha: the PNG's alpha channel as data, in R, G and B (1 where the file has none).
  void read_file_texture(Texture& t, const std::filesystem::path& path, bool data, const Node& where, bool alpha = false) {
    {
      t.data = data || alpha;
      t.source = path.string() + (alpha ? " (alpha)" : "");
      ReadInfo info;
      auto image = read_budgeted(path, &info, alpha);
      if (image && alpha) {
        charge_image(where, image->pixel_count() * 12);
        t.image = std::move(image).value();
        return;  // the alpha codes / max, as stored
      }
      if (!image) where.fail(image.error().message);
      charge_image(where, image->pixel_count() * 12);
      t.image = std::move(image).value();
      if (t.data && info.format == "png") {
        // read_image decoded the PNG as sRGB colour; a data texture holds the stored code / max code.
        // linear_to_srgb inverts the decode; rounding to the nearest code makes the inversion exact.
        const double max_code = info.sample_type == "uint16" ? 65535.0 : 255.0;
        for (float& v : t.image.data) {
          v = static_cast<float>(std::round(linear_to_srgb(static_cast<double>(v)) * max_code) / max_code);
        }
      }
    }
  }

  Texture procedural_texture(const Node& node, Texture& t) {
    const std::string kind = word(Node(node.value().at("procedural"), node.child_pointer("procedural")),
                                  {"asphalt-diffuse", "asphalt-gloss", "checker"});
    const int default_size = kind == "checker" ? 256 : 512;
    std::vector<std::string_view> keys = {"procedural", "size"};
    if (kind == "asphalt-diffuse") keys.insert(keys.end(), {"seed", "albedo"});
    if (kind == "asphalt-gloss") keys.insert(keys.end(), {"seed", "wet_fraction"});
    if (kind == "checker") keys.insert(keys.end(), {"squares", "color_a", "color_b", "data"});
    const Object o(node, keys, "an " + kind + " texture");
    const int size = o.has("size") ? int_in(*o.get("size"), 1, max_texture_side) : default_size;
    const std::uint64_t seed = o.has("seed") ? seed_value(*o.get("seed")) : 1;
    charge_image(o.has("size") ? *o.get("size") : node, static_cast<std::uint64_t>(size) * static_cast<std::uint64_t>(size) * 12);
    if (kind == "asphalt-diffuse") {
      AsphaltDiffuseOptions opt{size, seed, 0.08};
      if (auto n = o.get("albedo")) opt.albedo = number_in(*n, 0.0, false, 1.0, false);
      t.image = asphalt_diffuse(opt);
      t.data = false;
      t.source = "procedural asphalt-diffuse (size " + std::to_string(size) + ", seed " + std::to_string(seed) + ")";
    } else if (kind == "asphalt-gloss") {
      AsphaltGlossOptions opt{size, seed, 0.3};
      if (auto n = o.get("wet_fraction")) opt.wet_fraction = number_in(*n, 0.0, false, 1.0, false);
      t.image = asphalt_gloss(opt);
      t.data = true;
      t.source = "procedural asphalt-gloss (size " + std::to_string(size) + ", seed " + std::to_string(seed) + ")";
    } else {
      CheckerOptions opt;
      opt.size = size;
      if (auto n = o.get("squares")) opt.squares = int_in(*n, 1, size);
      if (auto n = o.get("color_a")) opt.colour_a = colour(*n);
      if (auto n = o.get("color_b")) opt.colour_b = colour(*n);
      t.data = o.has("data") && boolean(*o.get("data"));
      t.image = checker(opt);
      t.source = "procedural checker (size " + std::to_string(size) + ")";
    }
    return t;
  }

  int texture_ref(const Node& n) const {
    const std::string name = nonempty_string(n);
    const auto it = m_texture_index.find(name);
    if (it == m_texture_index.end()) {
      std::vector<std::string> names;
      for (const auto& [k, v] : m_texture_index) names.push_back(printable(k));
      n.fail("unknown texture '" + printable(name) + "' (textures: " + (names.empty() ? std::string("none") : join(names)) + ")");
    }
    return it->second;
  }

  // ---- materials ----

  void parse_materials(const Node& node) {
    if (!node.value().is_object())
      node.fail("expected materials by name (a JSON object), got " + describe(node.value()));
    for (const auto& [name, value] : node.value().items()) {
      m_material_index[name] = static_cast<int>(m_scene.materials.size());
      m_scene.materials.push_back(parse_material(Node(value, node.child_pointer(name)), name));
    }
  }

  // A parameter's value as parse_params reads it: 0.5 -> "0.5", [r, g, b] -> "r,g,b", "word" -> word,
  // [[Cx, Cy, Cz, n], ...] -> "Cx,Cy,Cz,n;..." (lobes).
  static std::string param_text(const Node& n) {
    const json& v = n.value();
    if (v.is_number()) return exact_number(number(n));
    if (v.is_string()) return v.get<std::string>();
    if (v.is_array() && !v.empty()) {
      std::string out;
      const bool groups = v[0].is_array();
      for (std::size_t i = 0; i < v.size(); ++i) {
        const Node e = n.element(i);
        if (groups) {
          if (!e.value().is_array() || e.value().empty())
            e.fail("expected an array of numbers, like element 0, got " + describe(e.value()));
          std::string group;
          for (std::size_t j = 0; j < e.value().size(); ++j)
            group += (j ? "," : "") + exact_number(number(e.element(j)));
          out += (i ? ";" : "") + group;
        } else {
          out += (i ? "," : "") + exact_number(number(e));
        }
      }
      return out;
    }
    n.fail("expected a number, [r, g, b], a word or lobes, got " + describe(v));
  }

  Material parse_material(const Node& node, const std::string& name) {
    const Object o(node, {"model", "params", "textures", "gloss_range", "uv_scale", "emission"}, "a material");
    Material m;
    m.name = name;
    if (auto n = o.get("emission"))
      m.emission = bounded_light(*n, radiometric(colour(*n), m_units, LightQuantity::radiance));
    if (!o.has("model")) {
      if (!o.has("emission")) o.node().fail("a material needs a 'model' (a BRDF), an 'emission', or both");
      for (const char* key : {"params", "textures"}) {
        if (o.has(key)) throw Failure{o.node().child_pointer(key), std::string("'") + key + "' needs a 'model'"};
      }
      // Purely emissive: model "" and a black Lambert BRDF, so Material::brdf is never null.
      m.brdf = std::shared_ptr<const Brdf>(make_brdf("lambert", {{"kd", "0"}}).value());
    } else {
      const Node model_node = *o.get("model");
      m.model = nonempty_string(model_node);
      const ModelInfo* info = find_brdf_model(m.model);
      if (info == nullptr) model_node.fail(make_brdf(m.model).error().message);
      if (auto params = o.get("params")) {
        if (!params->value().is_object())
          params->fail("expected parameters by name (a JSON object), got " + describe(params->value()));
        for (const auto& [key, value] : params->value().items()) {
          const Node p(value, params->child_pointer(key));
          std::pair<std::string, std::string> assignment{key, param_text(p)};
          // A file parameter (measured's table) names a file relative to the scene's folder, as meshes and images.
          const std::string& param_name = key;  // a structured binding: clang 14 cannot capture one in a lambda
          const auto spec = std::find_if(info->params.begin(), info->params.end(),
                                         [&param_name](const ParamSpec& ps) { return ps.name == param_name; });
          if (spec != info->params.end() && spec->kind == ParamKind::file) assignment.second = file(p).string();
          // Validate each parameter alone first, so the error points at it.
          auto one = parse_params(info->name, info->params, {assignment});
          if (!one) p.fail(one.error().message);
          m.params.push_back(std::move(assignment));
        }
      }
      auto brdf = make_brdf(m.model, m.params);
      if (!brdf) {
        throw Failure{o.has("params") ? o.node().child_pointer("params") : o.node().pointer(), brdf.error().message};
      }
      m.brdf = std::shared_ptr<const Brdf>(std::move(brdf).value());
      if (auto n = o.get("textures")) parse_material_textures(*n, *info, m);
    }
    if (auto n = o.get("gloss_range")) {
      if (!n->value().is_array() || n->value().size() != 2)
        n->fail("expected [n_black, n_white], got " + describe(n->value()));
      const GlossEncoding encoding{number_in(n->element(0), 0.0, true, max_gloss_exponent),
                                   number_in(n->element(1), 0.0, true, max_gloss_exponent)};
      auto valid = encoding.validated();
      if (!valid) n->fail(valid.error().message);
      m.gloss_encoding = *valid;
    }
    if (auto n = o.get("uv_scale")) {
      if (n->value().is_number()) {
        const double s = number_in(*n, 0.0, true, max_uv_scale);
        m.uv_scale = {s, s};
      } else if (n->value().is_array() && n->value().size() == 2) {
        m.uv_scale = {number_in(n->element(0), 0.0, true, max_uv_scale),
                      number_in(n->element(1), 0.0, true, max_uv_scale)};
      } else {
        n->fail("expected a number or [su, sv], got " + describe(n->value()));
      }
    }
    return m;
  }

  static bool has_param(const ModelInfo& info, std::string_view name) {
    return std::any_of(info.params.begin(), info.params.end(), [&](const ParamSpec& p) { return p.name == name; });
  }

  void parse_material_textures(const Node& node, const ModelInfo& info, Material& m) const {
    // The named slots, then any colour or scalar parameter of the model by its name (ParamTexture: factor x texel).
    static const std::vector<std::string_view> slots = {"kd", "ks", "gloss", "normal", "base_color", "metallic_roughness"};
    std::vector<std::string_view> keys = slots;
    for (const ParamSpec& p : info.params) {
      if ((p.kind == ParamKind::color || p.kind == ParamKind::scalar) &&
          std::find(slots.begin(), slots.end(), p.name) == slots.end()) {
        keys.push_back(p.name);
      }
    }
    const Object o(node, keys, "material textures (brdf " + info.name + ")");
    for (const ParamSpec& p : info.params) {
      if (std::find(slots.begin(), slots.end(), p.name) != slots.end()) continue;
      if (auto n = o.get(p.name)) m.param_textures.push_back(param_texture(*n, p));
    }
    auto slot = [&](std::string_view key, bool data, const char* what) -> int {
      const Node n = *o.get(key);
      const int index = texture_ref(n);
      const Texture& t = m_scene.textures[static_cast<std::size_t>(index)];
      if (t.data != data) {
        n.fail("texture '" + t.name + "' is a " + (t.data ? "data" : "colour") + " texture; " + what + " needs a " +
               (data ? "data texture (\"data\": true)" : "colour texture (\"data\": false)"));
      }
      return index;
    };
    if (o.has("kd")) {
      if (!has_param(info, "kd"))
        throw Failure{o.node().child_pointer("kd"), "brdf " + info.name + " has no parameter 'kd'"};
      m.kd_texture = slot("kd", false, "a diffuse colour map");
    }
    if (o.has("ks")) {
      if (!has_param(info, "ks"))
        throw Failure{o.node().child_pointer("ks"), "brdf " + info.name + " has no parameter 'ks'"};
      m.ks_texture = slot("ks", true, "a specular map");
    }
    if (o.has("gloss")) {
      if (!has_param(info, "n")) {
        throw Failure{o.node().child_pointer("gloss"),
                      "brdf " + info.name + " has no exponent 'n' for a gloss map to drive"};
      }
      for (const auto& [key, value] : m.params) {
        if (key == "m") {
          throw Failure{o.node().child_pointer("gloss"),
                        "brdf " + info.name + ": a gloss map sets the exponent 'n'; remove parameter 'm'"};
        }
      }
      m.gloss_texture = slot("gloss", true, "a gloss map");
    }
    if (o.has("normal")) m.normal_texture = slot("normal", true, "a normal map");
    // glTF's metallic-roughness textures (they multiply the parameters: docs/scene-format.md).
    if (o.has("base_color")) {
      if (!has_param(info, "base_color"))
        throw Failure{o.node().child_pointer("base_color"), "brdf " + info.name + " has no parameter 'base_color'"};
      m.base_color_texture = slot("base_color", false, "a base colour map");
    }
    if (o.has("metallic_roughness")) {
      if (!has_param(info, "metallic") || !has_param(info, "perceptual_roughness")) {
        throw Failure{o.node().child_pointer("metallic_roughness"),
                      "brdf " + info.name + " has no parameters 'metallic' and 'perceptual_roughness'"};
      }
      m.metallic_roughness_texture = slot("metallic_roughness", true, "a metallic-roughness map");
    }
  }

  // A texture for parameter `spec`: a texture's name, or {"texture": name, "channel": "r" | "g" | "b"} (a scalar
  // parameter reads one channel, red by default, of a data texture; a colour parameter r, g and b of any texture).
  ParamTexture param_texture(const Node& n, const ParamSpec& spec) const {
    ParamTexture p;
    p.param = spec.name;
    const bool colour = spec.kind == ParamKind::color;
    p.channel = colour ? -1 : 0;
    Node texture_node = n;
    if (n.value().is_object()) {
      const Object o(n, {"texture", "channel"}, "a parameter texture");
      texture_node = o.require("texture");
      if (auto c = o.get("channel")) {
        if (colour) c->fail("parameter '" + spec.name + "' is a colour: it takes the texture's r, g and b; remove 'channel'");
        const std::string w = word(*c, {"r", "g", "b"});
        p.channel = w == "r" ? 0 : w == "g" ? 1 : 2;
      }
    } else if (!n.value().is_string()) {
      n.fail("expected a texture name or {\"texture\": name, \"channel\": \"r\"}, got " + describe(n.value()));
    }
    p.texture = texture_ref(texture_node);
    const Texture& t = m_scene.textures[static_cast<std::size_t>(p.texture)];
    if (!colour && !t.data) {
      texture_node.fail("texture '" + t.name + "' is a colour texture; parameter '" + spec.name +
                        "' (a number) needs a data texture (\"data\": true)");
    }
    return p;
  }

  int material_ref(const Node& n) const {
    const std::string name = nonempty_string(n);
    const auto it = m_material_index.find(name);
    if (it == m_material_index.end()) {
      std::vector<std::string> names;
      for (const auto& [k, v] : m_material_index) names.push_back(printable(k));
      n.fail("unknown material '" + printable(name) + "' (materials: " + (names.empty() ? std::string("none") : join(names)) +
             ")");
    }
    return it->second;
  }

  // ---- shapes ----

  void parse_shapes(const Node& node) {
    if (!node.value().is_array()) node.fail("expected an array of shapes, got " + describe(node.value()));
    for (std::size_t i = 0; i < node.value().size(); ++i) parse_shape(node.element(i));
  }

  void parse_shape(const Node& node) {
    if (!node.value().is_object()) node.fail("expected a shape (a JSON object), got " + describe(node.value()));
    if (!node.value().contains("type")) throw Failure{node.child_pointer("type"), "required key is missing"};
    const std::string type =
        word(Node(node.value().at("type"), node.child_pointer("type")), {"sphere", "quad", "disk", "mesh"});
    if (type == "sphere") {
      const Object o(node, {"type", "center", "radius", "material"}, "a sphere");
      SphereShape s;
      s.center = position(o.require("center"));
      s.radius = length_value(o.require("radius"));
      s.material = material_ref(o.require("material"));
      m_scene.spheres.push_back(s);
    } else if (type == "quad") {
      const Object o(node, {"type", "corner", "u", "v", "material"}, "a quad");
      QuadShape q;
      q.corner = position(o.require("corner"));
      q.u = edge(o.require("u"));
      q.v = edge(o.require("v"));
      const Vec3 n = cross(normalize(q.u), normalize(q.v));
      if (length(n) < 1e-9) throw Failure{o.node().child_pointer("v"), "u and v are parallel: the quad has no area"};
      q.material = material_ref(o.require("material"));
      m_scene.quads.push_back(q);
    } else if (type == "disk") {
      const Object o(node, {"type", "center", "normal", "radius", "material"}, "a disk");
      DiskShape d;
      d.center = position(o.require("center"));
      if (auto n = o.get("normal")) d.normal = direction(*n);
      d.radius = length_value(o.require("radius"));
      d.material = material_ref(o.require("material"));
      m_scene.disks.push_back(d);
    } else {
      const Object o(node, {"type", "file", "transform", "material"}, "a mesh");
      const Node file_node = o.require("file");
      const std::filesystem::path path = file(file_node);
      MeshTransform xf;
      if (auto n = o.get("transform")) xf = parse_transform(*n);
      std::string ext = path.extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      const std::vector<MeshShape>* instances = nullptr;
      if (o.has("material") || (ext != ".gltf" && ext != ".glb")) {
        // The shape's material for every triangle.
        const int material = material_ref(o.require("material"));
        auto cached = m_meshes.find(path.string());
        if (cached == m_meshes.end()) {
          auto loaded = load_mesh(path);
          if (!loaded) file_node.fail(loaded.error().message);
          cached = m_meshes.emplace(path.string(), std::vector<MeshShape>{std::move(loaded).value()}).first;
        }
        cached->second.front().material = material;
        instances = &cached->second;
      } else {
        instances = &gltf_import(file_node, path);  // the file's own materials
      }
      for (const MeshShape& instance : *instances) add_mesh(o, file_node, path, xf, instance);
    }
  }

  // A glTF file's meshes with its materials as `gltf` materials (docs/scene-format.md, "glTF materials"); read
  // once per file, its materials and textures added to the scene once.
  const std::vector<MeshShape>& gltf_import(const Node& file_node, const std::filesystem::path& path) {
    if (auto it = m_gltf.find(path.string()); it != m_gltf.end()) return it->second;
    auto loaded = load_gltf_scene(path);
    if (!loaded) file_node.fail(loaded.error().message);
    for (const std::string& w : loaded->warnings) {
      m_scene.warnings.push_back(m_scene.source + ": " + file_node.pointer() + ": " + printable(path.string()) + ": " + w);
    }
    std::vector<MeshShape> parts = std::move(loaded->parts);
    for (MeshShape& part : parts) {
      const GltfMaterial& g = loaded->materials[static_cast<std::size_t>(part.material)];
      Material m;
      m.name = path.string() + "#" + g.pointer + (g.name.empty() ? "" : " (" + g.name + ")");
      m.model = "gltf";
      auto rgb = [](const std::array<double, 3>& c) {
        return exact_number(c[0]) + "," + exact_number(c[1]) + "," + exact_number(c[2]);
      };
      m.params = {{"base_color", rgb(g.base_color)},
                  {"metallic", exact_number(g.metallic)},
                  {"roughness", exact_number(g.roughness)},
                  {"ior", exact_number(g.ior)},
                  {"specular", exact_number(g.specular)},
                  {"specular_color", rgb(g.specular_color)},
                  {"anisotropy_strength", exact_number(g.anisotropy_strength)},
                  {"anisotropy_rotation", exact_number(g.anisotropy_rotation)},
                  {"sheen_color", rgb(g.sheen_color)},
                  {"sheen_roughness", exact_number(g.sheen_roughness)},
                  {"clearcoat", exact_number(g.clearcoat)},
                  {"clearcoat_roughness", exact_number(g.clearcoat_roughness)},
                  {"emissive", rgb(g.emissive)},
                  {"emissive_strength", exact_number(g.emissive_strength)}};
      auto brdf = make_brdf(m.model, m.params);
      if (!brdf) file_node.fail(path.string() + ": " + g.pointer + ": " + brdf.error().message);
      m.brdf = std::shared_ptr<const Brdf>(std::move(brdf).value());
      // emissiveFactor x emissiveStrength: radiance in the scene's radiance unit, as a material's "emission".
      const Rgb emissive{g.emissive[0] * g.emissive_strength, g.emissive[1] * g.emissive_strength,
                         g.emissive[2] * g.emissive_strength};
      m.emission = bounded_light(file_node, radiometric(emissive, m_units, LightQuantity::radiance));
      for (const GltfTexture& gt : g.textures) {
        const char* kind = gt.alpha ? " (alpha)" : gt.colour ? " (colour)" : " (data)";
        const std::string name = gt.image.string() + kind;
        int index = -1;
        if (auto it = m_gltf_textures.find(name); it != m_gltf_textures.end()) {
          index = it->second;
        } else {
          Texture t;
          t.name = name;
          read_file_texture(t, gt.image, !gt.colour, file_node, gt.alpha);
          index = static_cast<int>(m_scene.textures.size());
          m_scene.textures.push_back(std::move(t));
          m_gltf_textures.emplace(name, index);
        }
        m.param_textures.push_back({gt.param, index, gt.channel, gt.use, gt.transform});
      }
      part.material = static_cast<int>(m_scene.materials.size());
      m_scene.materials.push_back(std::move(m));
    }
    return m_gltf.emplace(path.string(), std::move(parts)).first->second;
  }

  void add_mesh(const Object& o, const Node& file_node, const std::filesystem::path& path, const MeshTransform& xf,
                const MeshShape& instance) {
    {
      // Bound the scene's triangles before copying another instance (scene/limits.h).
      const std::uint64_t triangles = instance.indices.size() / 3;
      if (m_triangles + triangles > max_scene_triangles) {
        file_node.fail("this mesh's " + std::to_string(triangles) + " triangles bring the scene to " +
                       std::to_string(m_triangles + triangles) + ", above the limit of " +
                       std::to_string(max_scene_triangles));
      }
      m_triangles += triangles;
      MeshShape mesh = instance;
      transform_mesh(mesh, xf);
      for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3& p = mesh.positions[i];
        if (!(std::abs(p.x) <= max_scene_coordinate && std::abs(p.y) <= max_scene_coordinate &&
              std::abs(p.z) <= max_scene_coordinate)) {
          throw Failure{o.has("transform") ? o.node().child_pointer("transform") : file_node.pointer(),
                        "vertex " + std::to_string(i) + " of '" + printable(path.string()) +
                            "' is beyond +-" + format_number(max_scene_coordinate) + " after the transform"};
        }
      }
      m_scene.meshes.push_back(std::move(mesh));
    }
  }

  static MeshTransform parse_transform(const Node& node) {
    const Object o(node, {"translate", "rotate", "rotate_y", "scale"}, "a transform");
    Vec3 translate;
    Vec3 axis{0.0, 1.0, 0.0};
    double degrees = 0.0;
    Vec3 scale{1.0, 1.0, 1.0};
    if (auto n = o.get("translate")) translate = position(*n);
    if (o.has("rotate") && o.has("rotate_y"))
      throw Failure{o.node().child_pointer("rotate_y"), "give 'rotate' or 'rotate_y', not both"};
    if (auto n = o.get("rotate")) {
      if (!n->value().is_array() || n->value().size() != 4)
        n->fail("expected [axis x, axis y, axis z, degrees], got " + describe(n->value()));
      const Vec3 a{number(n->element(0)), number(n->element(1)), number(n->element(2))};
      if (a.x == 0.0 && a.y == 0.0 && a.z == 0.0) n->fail("the rotation axis is the zero vector");
      axis = scaled_normalize(a);
      degrees = number(n->element(3));
    }
    if (auto n = o.get("rotate_y")) degrees = number(*n);
    if (auto n = o.get("scale")) {
      if (n->value().is_number()) {
        const double s = length_value(*n);
        scale = {s, s, s};
      } else if (n->value().is_array() && n->value().size() == 3) {
        scale = {length_value(n->element(0)), length_value(n->element(1)), length_value(n->element(2))};
      } else {
        n->fail("expected a number or [sx, sy, sz], got " + describe(n->value()));
      }
    }
    return make_mesh_transform(translate, axis, degrees, scale);
  }

  // ---- lights ----

  void parse_lights(const Node& node) {
    if (!node.value().is_array()) node.fail("expected an array of lights, got " + describe(node.value()));
    for (std::size_t i = 0; i < node.value().size(); ++i) parse_light(node.element(i));
  }

  // color x intensity (or the alternatives of point and spot lights) -> radiometric.
  Rgb light_colour(const Object& o) const { return o.has("color") ? colour(*o.get("color")) : Rgb::gray(1.0); }

  // The field a light's converted value is blamed on: its intensity (or power), else its colour, else itself.
  static Node value_node(const Object& o) {
    for (const char* key : {"intensity", "power", "blender_watts", "color"}) {
      if (auto n = o.get(key)) return *n;
    }
    return o.node();
  }

  Rgb punctual_intensity(const Object& o, double cos_outer) const {
    const Rgb c = light_colour(o);
    std::vector<std::string_view> given;
    for (std::string_view key : {"intensity", "power", "blender_watts"}) {
      if (o.has(key)) given.push_back(key);
    }
    if (given.size() > 1) {
      throw Failure{o.node().child_pointer(given[1]),
                    "give one of 'intensity', 'power' or 'blender_watts', not several"};
    }
    if (o.has("power")) {
      const Node n = *o.get("power");
      const double power = non_negative(n);
      if (m_units == Units::game) {
        n.fail(
            "'power' needs \"units\": \"radiometric\" (watts) or \"photometric\" (lumens); game units have no power");
      }
      const Rgb watts = m_units == Units::photometric ? radiometric_from_photometric(c, power) : c * power;
      return convert(watts, "W", "W/sr", cos_outer);  // I = Phi / (solid angle of the sphere or the cone)
    }
    if (o.has("blender_watts")) {
      return convert(c * non_negative(*o.get("blender_watts")), "blender-W", "W/sr");  // I = P / (4 pi)
    }
    const double value = o.has("intensity") ? non_negative(*o.get("intensity")) : 1.0;
    return radiometric(c, value, m_units, LightQuantity::intensity);
  }

  void parse_light(const Node& node) {
    if (!node.value().is_object()) node.fail("expected a light (a JSON object), got " + describe(node.value()));
    if (!node.value().contains("type")) throw Failure{node.child_pointer("type"), "required key is missing"};
    const std::string type = word(Node(node.value().at("type"), node.child_pointer("type")),
                                  {"directional", "point", "spot", "sphere", "hemisphere"});
    if (type == "directional") {
      const Object o(node, {"type", "direction", "color", "intensity", "game"}, "a directional light");
      DirectionalLight l;
      l.to_light = direction(o.require("direction"));
      // Game mode: shaded per pixel ("punctual", the default) or added to the SH9 ambient ("sh", D3DX-style).
      if (auto n = o.get("game")) l.game_sh = word(*n, {"punctual", "sh"}) == "sh";
      const double value = o.has("intensity") ? non_negative(*o.get("intensity")) : 1.0;
      l.irradiance = bounded_light(value_node(o), radiometric(light_colour(o), value, m_units, LightQuantity::irradiance));
      m_scene.lights.emplace_back(l);
    } else if (type == "point") {
      const Object o(node, {"type", "position", "color", "intensity", "power", "blender_watts"}, "a point light");
      PointLight l;
      l.position = position(o.require("position"));
      l.intensity = bounded_light(value_node(o), punctual_intensity(o, -1.0));
      m_scene.lights.emplace_back(l);
    } else if (type == "spot") {
      const Object o(node,
                     {"type", "position", "direction", "inner_angle", "outer_angle", "color", "intensity", "power",
                      "blender_watts"},
                     "a spot light");
      SpotLight l;
      l.position = position(o.require("position"));
      l.axis = direction(o.require("direction"));
      const double outer = o.has("outer_angle") ? number_in(*o.get("outer_angle"), 0.0, true, 90.0, false) : 45.0;
      const double inner = o.has("inner_angle") ? number_in(*o.get("inner_angle"), 0.0, false, outer, true) : 0.0;
      l.cos_outer = std::cos(deg_to_rad(outer));
      l.cos_inner = std::cos(deg_to_rad(inner));
      l.intensity = bounded_light(value_node(o), punctual_intensity(o, l.cos_outer));
      m_scene.lights.emplace_back(l);
    } else if (type == "sphere") {
      const Object o(node, {"type", "center", "radius", "radiance", "color", "intensity"}, "a sphere light");
      SphereLight l;
      l.center = position(o.require("center"));
      l.radius = length_value(o.require("radius"));
      if (o.has("radiance")) {
        for (const char* key : {"color", "intensity"}) {
          if (o.has(key))
            throw Failure{o.node().child_pointer(key), "give 'radiance' or 'color' x 'intensity', not both"};
        }
        l.radiance = bounded_light(*o.get("radiance"), radiometric(colour(*o.get("radiance")), m_units, LightQuantity::radiance));
      } else {
        const double value = o.has("intensity") ? non_negative(*o.get("intensity")) : 1.0;
        l.radiance = bounded_light(value_node(o), radiometric(light_colour(o), value, m_units, LightQuantity::radiance));
      }
      m_scene.lights.emplace_back(l);
    } else {
      const Object o(node, {"type", "sky", "ground", "up"}, "a hemisphere light");
      HemisphereLight l;
      l.sky = bounded_light(o.require("sky"), radiometric(colour(o.require("sky")), m_units, LightQuantity::radiance));
      if (auto n = o.get("ground"))
        l.ground = bounded_light(*n, radiometric(colour(*n), m_units, LightQuantity::radiance));
      if (auto n = o.get("up")) l.up = direction(*n);
      m_scene.lights.emplace_back(l);
    }
  }

  // ---- environment ----

  void parse_environment(const Node& node) {
    if (!node.value().is_object()) node.fail("expected an environment (a JSON object), got " + describe(node.value()));
    std::vector<std::string> kinds;
    for (const char* k : {"file", "uniform", "sky"}) {
      if (node.value().contains(k)) kinds.emplace_back(k);
    }
    if (kinds.empty()) node.fail("an environment needs one of 'file', 'uniform' or 'sky'");
    if (kinds.size() > 1)
      throw Failure{node.child_pointer(kinds[1]), "give one of 'file', 'uniform' or 'sky', not several"};
    Environment& env = m_scene.environment;
    if (kinds[0] == "file") {
      const Object o(node, {"file", "rotation", "scale"}, "an image environment");
      const Node file_node = *o.get("file");
      const std::filesystem::path path = file(file_node);
      ReadInfo info;
      auto image = read_budgeted(path, &info);
      if (!image) file_node.fail(image.error().message);
      // Radiance: a NaN, Inf or (beyond lossy-compression noise) negative texel is refused, naming it (image_io.h read_radiance_image).
      if (auto ok = check_radiance(path, *image, info); !ok) file_node.fail(ok.error().message);
      charge_image(file_node, image->pixel_count() * 12);
      if (image->width != 2 * image->height) {
        file_node.fail("'" + path.string() + "' is " + std::to_string(image->width) + " x " +
                       std::to_string(image->height) + "; a lat-long map is twice as wide as it is high");
      }
      env.kind = Environment::Kind::image;
      env.latlong = std::move(image).value();
      env.source = path.string();
      if (auto n = o.get("rotation")) env.rotation_deg = number(*n);
      const double scale = o.has("scale") ? number_in(*o.get("scale"), 0.0, false, max_light_value) : 1.0;
      // The map's texels are radiance in the scene's units; fold the unit conversion into the scale.
      env.scale = scale * radiometric(Rgb::gray(1.0), m_units, LightQuantity::radiance).r;
      float peak = 0.0f;
      for (float v : env.latlong.data) peak = std::max(peak, std::abs(v));
      if (!(static_cast<double>(peak) * env.scale <= max_light_value)) {
        throw Failure{o.has("scale") ? o.node().child_pointer("scale") : file_node.pointer(),
                      "the brightest texel of '" + printable(path.string()) + "' (" + format_number(static_cast<double>(peak)) +
                          ") times the scale is " + format_number(static_cast<double>(peak) * env.scale) +
                          ", above the largest supported light value " + format_number(max_light_value)};
      }
    } else if (kinds[0] == "uniform") {
      const Object o(node, {"uniform"}, "a uniform environment");
      env.kind = Environment::Kind::uniform;
      env.uniform = bounded_light(*o.get("uniform"), radiometric(colour(*o.get("uniform")), m_units, LightQuantity::radiance));
      env.source = "uniform";
    } else {
      const Object outer(node, {"sky"}, "a sky environment");
      const Object o(*outer.get("sky"),
                     {"sun_direction", "sun_angular_radius", "sun_irradiance", "zenith", "horizon", "ground"}, "a sky");
      SkyModel& sky = env.sky;
      if (auto n = o.get("sun_direction")) sky.sun_direction = direction(*n);
      if (auto n = o.get("sun_angular_radius"))
        sky.sun_angular_radius_deg = number_in(*n, min_sun_angular_radius_deg, false, 45.0, false);
      if (auto n = o.get("sun_irradiance"))
        sky.sun_irradiance = bounded_light(*n, radiometric(colour(*n), m_units, LightQuantity::irradiance));
      auto sky_radiance = [&](const Node& n) { return bounded_light(n, radiometric(colour(n), m_units, LightQuantity::radiance)); };
      if (auto n = o.get("zenith")) sky.zenith = sky_radiance(*n);
      if (auto n = o.get("horizon")) sky.horizon = sky_radiance(*n);
      if (auto n = o.get("ground")) sky.ground = sky_radiance(*n);
      env.kind = Environment::Kind::sky;
      env.source = "sky";
    }
  }

  std::filesystem::path m_base_dir;
  Scene& m_scene;
  Units m_units = Units::game;
  std::map<std::string, int, std::less<>> m_texture_index;
  std::map<std::string, int, std::less<>> m_material_index;
  std::map<std::string, std::vector<MeshShape>> m_meshes;  // each mesh file read once, by resolved path
  std::map<std::string, std::vector<MeshShape>> m_gltf;    // glTF files with their own materials, by path
  std::map<std::string, int> m_gltf_textures;              // their textures, by image file and kind
  std::uint64_t m_triangles = 0;              // of all mesh instances so far
  std::uint64_t m_image_bytes = 0;            // of all textures and the environment map so far

  // The scene's image budget (max_scene_image_bytes): what is left, and charging an image to it.
  std::uint64_t image_budget_left() const { return max_scene_image_bytes - m_image_bytes; }
  std::string image_budget_note() const {
    return "the images of a scene may take " + std::to_string(max_scene_image_bytes >> 20) + " MiB in all, " +
           std::to_string(image_budget_left() >> 20) + " MiB are left";
  }
  void charge_image(const Node& n, std::uint64_t bytes) {
    if (bytes > image_budget_left()) {
      n.fail("the image takes " + std::to_string((bytes + (1ULL << 20) - 1) >> 20) + " MiB; " + image_budget_note());
    }
    m_image_bytes += bytes;
  }
  // read_image within what is left of the budget; a read refused for memory says so.
  Result<Image> read_budgeted(const std::filesystem::path& path, ReadInfo* info, bool alpha = false) {
    auto image = read_image(path, info, image_budget_left(), alpha ? PngSamples::alpha : PngSamples::srgb);
    if (!image && image_budget_left() < image_read_budget_bytes &&
        image.error().message.find("memory budget") != std::string::npos) {
      return make_error(image.error().message + " (" + image_budget_note() + ")");
    }
    return image;
  }
};

// Tracks the JSON pointer of the value being parsed (for duplicate keys and number overflow, which
// nlohmann reports without a position) through the parser's callback events, and bounds the nesting depth
// (max_json_depth, scene/limits.h) by throwing a Failure at the first container beyond it. Each frame keeps
// only its own key or index, so tracking costs O(1) per event; the pointer is joined only for a message.
class PointerTracker {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (m_stack.size() >= max_json_depth) {
          throw Failure{current(), "JSON nested deeper than " + std::to_string(max_json_depth) + " levels"};
        }
        m_stack.push_back({event == json::parse_event_t::array_start, 0, {}, {}});
        break;
      case json::parse_event_t::key: {
        Frame& f = m_stack.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second && !m_duplicate)
          m_duplicate = Failure{current(), "duplicate key '" + printable(f.key) + "'"};
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        m_stack.pop_back();
        element_done();
        break;
      case json::parse_event_t::value:
        element_done();
        break;
    }
    return true;
  }

  // The pointer of the value being parsed now.
  std::string current() const {
    std::string out;
    for (const Frame& f : m_stack) out += "/" + (f.array ? std::to_string(f.index) : pointer_token(f.key));
    return out;
  }
  const std::optional<Failure>& duplicate() const { return m_duplicate; }

 private:
  struct Frame {
    bool array = false;
    std::size_t index = 0;
    std::string key;
    std::set<std::string> keys;
  };
  void element_done() {
    if (!m_stack.empty() && m_stack.back().array) ++m_stack.back().index;
  }
  std::vector<Frame> m_stack;
  std::optional<Failure> m_duplicate;
};

// "[json.exception.parse_error.101] parse error at line 3, column 7: syntax error ..." ->
// "line 3, column 7: malformed JSON: syntax error ...".
std::string syntax_message(const std::string& what) {
  const auto at = what.find("line ");
  const auto colon = at == std::string::npos ? std::string::npos : what.find(": ", at);
  if (colon == std::string::npos) {
    const auto bracket = what.find("] ");
    return "malformed JSON: " + printable(bracket == std::string::npos ? what : what.substr(bracket + 2), max_library_bytes);
  }
  return what.substr(at, colon - at) + ": malformed JSON: " + printable(what.substr(colon + 2), max_library_bytes);
}

}  // namespace

std::span<const std::string_view> scene_top_level_keys() { return top_level_keys; }

Result<Scene> parse_scene(const nlohmann::json& document, const std::filesystem::path& base_dir,
                          const std::string& source) {
  Scene scene;
  scene.source = source;
  try {
    // A document parsed elsewhere has not been through the tracker: bound its depth here, without recursion
    // (messages quote values through json::dump, which recurses).
    std::vector<std::pair<const json*, std::size_t>> stack{{&document, 1}};
    while (!stack.empty()) {
      const auto [v, depth] = stack.back();
      stack.pop_back();
      if (!v->is_structured()) continue;
      if (depth > max_json_depth) {
        return make_error(source + ": JSON nested deeper than " + std::to_string(max_json_depth) + " levels");
      }
      for (const auto& child : *v) stack.emplace_back(&child, depth + 1);
    }
    Parser(base_dir, scene).parse(document);
  } catch (const Failure& f) {
    return make_error(source + ": " + (f.pointer.empty() ? std::string() : f.pointer + ": ") + f.message);
  } catch (const std::bad_alloc&) {
    return make_error(source + ": out of memory while reading the scene and the files it names");
  }
  return scene;
}

Result<Scene> load_scene(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return make_error(source + ": file not found");
  if (!std::filesystem::is_regular_file(path, ec)) return make_error(source + ": not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(source + ": cannot read the file size: " + ec.message());
  if (size > max_scene_file_bytes) {
    return make_error(source + ": the file has " + std::to_string(size) + " bytes; a scene file may have at most " +
                      std::to_string(max_scene_file_bytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) return make_error(source + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) return make_error(source + ": cannot read the file");

  PointerTracker tracker;
  json document;
  try {
    document = json::parse(text.str(), std::ref(tracker));
  } catch (const Failure& f) {  // nesting too deep (the tracker)
    return make_error(source + ": " + (f.pointer.empty() ? std::string() : f.pointer + ": ") + f.message);
  } catch (const std::bad_alloc&) {
    return make_error(source + ": out of memory while parsing the JSON");
  } catch (const json::parse_error& e) {
    return make_error(source + ": " + syntax_message(e.what()));
  } catch (const json::exception& e) {
    // Number overflow (1e999) is reported without a position; the tracker knows which value it was.
    const std::string what = e.what();
    const auto bracket = what.find("] ");
    return make_error(source + ": " + tracker.current() +
                      ": malformed JSON: " + printable(bracket == std::string::npos ? what : what.substr(bracket + 2), max_library_bytes));
  }
  if (tracker.duplicate())
    return make_error(source + ": " + tracker.duplicate()->pointer + ": " + tracker.duplicate()->message);
  return parse_scene(document, path.parent_path(), source);
}

}  // namespace shadelab
