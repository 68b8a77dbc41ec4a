// shadelab.render(): the reference path tracer (or the game renderer) on a scene file, a scene dict in the
// JSON scene format, or the built-in default scene. The rules and messages of `shadelab render`.
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
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
  const nlohmann::json doc = scene_dict_json(scene);
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

  // Ctrl-C (and any other signal whose Python handler raises): the render runs on a worker thread while this
  // thread, without the GIL, wakes every 20 ms to run Python's signal handlers (PyErr_CheckSignals; they run
  // only on the main thread, elsewhere it returns 0). A handler that raises sets `cancel`, which both
  // renderers check before each tile (RenderOptions::abort, GameOptions::cancel); the
  // exception is then raised here. The GIL is free for other Python threads all the while.
  std::atomic<bool> cancel{false};
  ro.abort = &cancel;
  go.cancel = &cancel;
  Result<RenderResult> result = make_error("");
  bool interrupted = false;
  std::exception_ptr failure;
  {
    py::gil_scoped_release release;
    std::mutex m;
    std::condition_variable cv;
    bool done = false;
    std::thread worker([&] {
      try {
        result = mode == "game" ? render_game(scene, go) : render_scene(scene, ro);
      } catch (...) {
        failure = std::current_exception();  // std::bad_alloc: MemoryError once the GIL is back
      }
      const std::lock_guard<std::mutex> lock(m);
      done = true;
      cv.notify_one();
    });
    std::unique_lock<std::mutex> lock(m);
    while (!cv.wait_for(lock, std::chrono::milliseconds(20), [&] { return done; })) {
      if (interrupted) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) {
          interrupted = true;  // the handler's exception stays set on this thread until it is raised below
          cancel.store(true);
        }
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (interrupted) throw py::error_already_set();
  if (failure) std::rethrow_exception(failure);
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
normal and depth images (reference mode) and spp, rays, seconds. Ctrl-C stops the render within a tile (16 x 16
pixels) and raises KeyboardInterrupt. The GIL is
released while rendering: other Python threads run, and renders in several threads run at once.)");
}

}  // namespace shadelab::python
