// shadelab.render(): the reference path tracer (or the game renderer) on a scene file, a scene dict in the
// JSON scene format, or the built-in default scene. The rules and messages of `shadelab render`.
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include <atomic>
#include <climits>
#include <cmath>
#include <filesystem>

#include "bindings.h"
#include "common.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/scene/default_scene.h"
#include "shadelab/scene/scene_json.h"

namespace shadelab::python {

namespace {

constexpr int max_nesting = 64;

// A Python object as JSON, for parse_scene. What JSON cannot hold (a non-finite number, a key that is not
// a string, another type, a cycle) is an error naming its JSON pointer, as the scene parser names fields.
nlohmann::json to_json(py::handle obj, const std::string& pointer, int depth) {
  const std::string where = "scene: " + (pointer.empty() ? std::string("/") : pointer) + ": ";
  if (depth > max_nesting) fail(where + "nested deeper than " + std::to_string(max_nesting) + " levels");
  if (obj.is_none()) return nullptr;
  if (py::isinstance<py::array>(obj) && py::reinterpret_borrow<py::array>(obj).ndim() == 0) {
    return to_json(obj.attr("item")(), pointer, depth + 1);  // a NumPy 0-d array: its Python scalar
  }
  if (py::isinstance<py::bool_>(obj)) return obj.cast<bool>();
  if (py::isinstance<py::str>(obj)) return obj.cast<std::string>();
  if (PyIndex_Check(obj.ptr())) {  // int and NumPy integers
    const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(obj.ptr()));
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
    if (overflow != 0) fail(where + "the integer " + py::str(obj).cast<std::string>() + " is too large");
    return v;
  }
  if (PyFloat_Check(obj.ptr()) || (py::hasattr(obj, "__float__") && !PySequence_Check(obj.ptr()))) {
    const double v = py::float_(py::reinterpret_borrow<py::object>(obj)).cast<double>();
    if (!std::isfinite(v)) fail(where + fmt::format("{} is not a finite number", v));
    return v;
  }
  if (py::isinstance<py::dict>(obj)) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(obj)) {
      if (!py::isinstance<py::str>(key)) fail(where + "the key " + py::repr(key).cast<std::string>() + " is not a string");
      const std::string k = key.cast<std::string>();
      std::string escaped;  // RFC 6901: ~ -> ~0, / -> ~1
      for (char c : k) escaped += c == '~' ? std::string("~0") : (c == '/' ? std::string("~1") : std::string(1, c));
      j[k] = to_json(value, pointer + "/" + escaped, depth + 1);
    }
    return j;
  }
  if (PySequence_Check(obj.ptr())) {
    nlohmann::json j = nlohmann::json::array();
    const py::sequence seq = py::reinterpret_borrow<py::sequence>(obj);
    for (std::size_t i = 0; i < seq.size(); ++i) j.push_back(to_json(seq[i], pointer + "/" + std::to_string(i), depth + 1));
    return j;
  }
  fail(where + "a " + py::str(py::type::of(obj).attr("__name__")).cast<std::string>() + " is not a JSON value");
}

Scene load(py::handle scene, py::handle base_dir) {
  if (scene.is_none()) return default_scene();
  if (is_path(scene)) {
    Result<Scene> r = make_error("");
    const std::string path = path_text(scene);
    {
      py::gil_scoped_release release;
      r = load_scene(path);
    }
    return unwrap(std::move(r));
  }
  if (!py::isinstance<py::dict>(scene)) {
    fail("scene: expected a path, a dict in the scene format or None, got " +
         py::str(py::type::of(scene).attr("__name__")).cast<std::string>());
  }
  const nlohmann::json doc = to_json(scene, "", 0);
  const std::filesystem::path base = base_dir.is_none() ? std::filesystem::current_path()
                                                        : std::filesystem::path(path_text(base_dir));
  Result<Scene> r = make_error("");
  {
    py::gil_scoped_release release;
    r = parse_scene(doc, base, "scene");
  }
  return unwrap(std::move(r));
}

int optional_int(py::handle v, const char* name, int min) {
  if (v.is_none()) return -1;
  const long long x = to_integer(v, name);
  if (x < min) fail(fmt::format("{}: {} must be >= {}", name, x, min));  // as --spp, --threads, --max-depth
  if (x > INT_MAX) fail(fmt::format("{}: {} is too large", name, x));
  return static_cast<int>(x);
}

py::object render(py::handle scene_obj, py::handle spp_obj, py::handle threads_obj, py::handle seed_obj,
                  py::handle max_depth_obj, const std::string& mode, const std::string& sampling, bool aov,
                  py::handle base_dir) {
  const int spp = optional_int(spp_obj, "spp", 1);
  const int threads = optional_int(threads_obj, "threads", 0);
  const int max_depth = optional_int(max_depth_obj, "max_depth", 1);
  if (mode != "reference" && mode != "game") fail("mode: '" + mode + "' is not one of reference | game");
  RenderOptions ro;
  if (sampling == "mis") ro.mode = SamplingMode::mis;
  else if (sampling == "brdf") ro.mode = SamplingMode::brdf;
  else if (sampling == "light") ro.mode = SamplingMode::light;
  else fail("sampling: '" + sampling + "' is not one of mis | brdf | light");
  Scene scene = load(scene_obj, base_dir);
  if (!seed_obj.is_none()) {
    if (py::isinstance<py::bool_>(seed_obj) || !PyIndex_Check(seed_obj.ptr())) fail("seed: expected an integer");
    const py::int_ s = py::reinterpret_steal<py::int_>(PyNumber_Index(seed_obj.ptr()));
    if (PyObject_RichCompareBool(s.ptr(), py::int_(0).ptr(), Py_LT) == 1) fail("seed: " + py::str(py::handle(s)).cast<std::string>() + " must be >= 0");
    const unsigned long long v = PyLong_AsUnsignedLongLong(s.ptr());
    if (PyErr_Occurred() != nullptr) {
      PyErr_Clear();
      fail("seed: " + py::str(py::handle(s)).cast<std::string>() + " is larger than 2^64 - 1");
    }
    scene.settings.seed = v;
  }
  ro.spp = spp;
  ro.max_depth = max_depth;
  ro.threads = threads;
  ro.aovs = aov;
  GameOptions go;
  go.threads = threads;
  if (spp != -1) go.spp = spp;

  // Ctrl-C: checked after each pass; the render stops and KeyboardInterrupt is raised.
  std::atomic<bool> cancel{false};
  bool interrupted = false;
  ro.cancel = &cancel;
  ro.progress = [&](double, int) {
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) {
      interrupted = true;
      cancel.store(true);
    }
  };
  Result<RenderResult> result = make_error("");
  {
    py::gil_scoped_release release;
    result = mode == "game" ? render_game(scene, go) : render_scene(scene, ro);
  }
  if (interrupted) throw py::error_already_set();
  RenderResult r = unwrap(std::move(result), scene.source + ": ");
  if (!aov) return image_array(std::move(r.beauty));
  py::dict d;
  d["beauty"] = image_array(std::move(r.beauty));
  if (mode == "reference") {
    d["albedo"] = image_array(std::move(r.albedo));
    d["normal"] = image_array(std::move(r.normal));
    d["depth"] = image_array(std::move(r.depth));
  }
  d["spp"] = r.stats.spp_done;
  d["rays"] = r.stats.rays;
  d["seconds"] = r.stats.seconds;
  return d;
}

}  // namespace

void bind_render(py::module_& m) {
  m.def("render", &render, py::arg("scene") = py::none(), py::kw_only(), py::arg("spp") = py::none(),
        py::arg("threads") = py::none(), py::arg("seed") = py::none(), py::arg("max_depth") = py::none(),
        py::arg("mode") = "reference", py::arg("sampling") = "mis", py::arg("aov") = false,
        py::arg("base_dir") = py::none(),
        R"(render(scene=None, *, spp=None, threads=None, seed=None, max_depth=None, mode='reference', sampling='mis', aov=False, base_dir=None) -> ndarray

Renders a scene to linear radiance, float32 (H, W, 3). scene: a path to a JSON scene file, a dict in the same
format (docs/scene-format.md; relative file names resolve against base_dir, default the working directory),
or None for the built-in default scene. spp, threads (0: all cores), seed and max_depth override the scene's
settings. mode='reference' is the path tracer (sampling: mis, brdf or light); mode='game' shades as a game
engine does. The image is the same for any thread count. aov=True returns a dict with beauty, albedo,
normal and depth images (reference mode) and spp, rays, seconds. Ctrl-C stops after the current pass and
raises KeyboardInterrupt; the GIL is released while rendering.)");
}

}  // namespace shadelab::python
