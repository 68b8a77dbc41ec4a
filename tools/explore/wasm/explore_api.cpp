// The explorer's WebAssembly entry point: the library itself (src/shadelab: the registry, the models, the
// albedo quadrature, the zoo, the lobe data of the plots, the game lobe) and the shader exporter
// (tools/shaders), compiled with Debian's emscripten, behind one function that takes a JSON request and
// returns a JSON answer. The page (tools/explore/web/explorer.js) never evaluates a formula itself.
//
// Requests ({"op": ...}); params is an object NAME -> VALUE, each value as `-p NAME=VALUE` takes it:
//   {"op": "models"}                                          the registry, as `brdf list --json` has it
//   {"op": "eval", model, params, "wi": [x,y,z], "wo": [x,y,z]}  {"f": [r,g,b]} as `brdf eval --json`
//   {"op": "albedo", model, params, "theta": [deg...]}        {"theta", "albedo"} as `brdf albedo --json`
//   {"op": "lobe", model, params, "theta_in", "times_cos", "fixed": "light"|"viewer", "samples"}
//                                                             the in-plane lobe of `plot lobe` (plot_data.h)
//   {"op": "lobe3d", model, params, "wi": [x,y,z], "n_theta", "n_phi"}  f_r luminance over the hemisphere
//   {"op": "zoo", "n"}                                        the zoo table rows, as `zoo --json` has them
//   {"op": "shader", model, params, "lang", "ibl"}            the text of `shader MODEL --param ... --lang [--ibl]`,
//                                                             the GGX tables' block name and bytes (or "", []),
//                                                             and with ibl the environment entry's name
//   {"op": "game_lobe", model, params}                        brdf/game_lobe.h's numbers for the sphere, and
//                                                             split_sum: whether the model shades with the split sum
//   {"op": "kernels", "names": [...], "lang"}                 the translated kernel files defining the names
// Every answer is {"error": "one line"} on bad input. Directions are normalized as the CLI does.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include <nlohmann/json.hpp>

#include "export.h"
#include "shadelab/analysis/albedo.h"
#include "shadelab/analysis/plot_data.h"
#include "shadelab/analysis/zoo.h"
#include "shadelab/brdf/game_lobe.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"

namespace shadelab::explore {
namespace {

using nlohmann::json;

struct BadRequest {
  std::string message;
};

json rgb_json(const Rgb& c) { return json::array({c.r, c.g, c.b}); }

std::string_view kind_name(ParamKind k) {
  switch (k) {
    case ParamKind::scalar: return "scalar";
    case ParamKind::color: return "color";
    case ParamKind::choice: return "choice";
    case ParamKind::lobes: return "lobes";
    case ParamKind::file: return "file";
  }
  return "?";
}

const ModelInfo& model_of(const json& req) {
  if (!req.contains("model") || !req["model"].is_string()) throw BadRequest{"model: missing"};
  const std::string name = req["model"].get<std::string>();
  const ModelInfo* m = find_brdf_model(name);
  if (m == nullptr) throw BadRequest{"model: unknown model '" + name + "'"};
  return *m;
}

// The assignments in the registry's order of the parameters (unknown names are errors).
ParamAssignments assignments_of(const ModelInfo& m, const json& req) {
  ParamAssignments out;
  if (!req.contains("params")) return out;
  const json& p = req["params"];
  if (!p.is_object()) throw BadRequest{"params: expected an object"};
  for (const auto& [name, value] : p.items()) {
    bool known = false;
    for (const auto& spec : m.params) known = known || spec.name == name;
    if (!known) throw BadRequest{"brdf " + m.name + ": unknown parameter '" + name + "'"};
    if (!value.is_string()) throw BadRequest{"parameter '" + name + "': expected a string value"};
  }
  for (const auto& spec : m.params) {
    if (p.contains(spec.name)) out.emplace_back(spec.name, p[spec.name].get<std::string>());
  }
  return out;
}

BrdfPtr brdf_of(const json& req) {
  const ModelInfo& m = model_of(req);
  auto f = make_brdf(m.name, assignments_of(m, req));
  if (!f) throw BadRequest{f.error().message};
  return std::move(f).value();
}

Vec3 direction_of(const json& req, const char* key) {
  if (!req.contains(key) || !req[key].is_array() || req[key].size() != 3) {
    throw BadRequest{std::string(key) + ": expected [x, y, z]"};
  }
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!req[key][i].is_number()) throw BadRequest{std::string(key) + ": expected numbers"};
  }
  v = {req[key][0].get<double>(), req[key][1].get<double>(), req[key][2].get<double>()};
  const double len = length(v);
  if (!(len > 0.0) || !std::isfinite(len)) throw BadRequest{std::string(key) + ": the vector has zero length"};
  return v / len;  // as the CLI's parse_direction
}

double number_of(const json& req, const char* key, double fallback) {
  if (!req.contains(key)) return fallback;
  if (!req[key].is_number()) throw BadRequest{std::string(key) + ": expected a number"};
  return req[key].get<double>();
}

json models() {
  json out = json::array();
  for (const auto& m : brdf_models()) {
    // The explorer draws every model with its exported shader; the layered ground truth (a Monte Carlo
    // estimate, Brdf::is_stochastic) has none, and reaches the explorer with the layered front-end work.
    // openpbr and measured have none either (ModelInfo::no_shader; measured also reads a file, which the page
    // cannot): tested before make_brdf, which measured refuses without its file.
    if (!m.no_shader.empty() || make_brdf(m.name).value()->is_stochastic()) continue;
    json params = json::array();
    for (const auto& p : m.params) {
      json jp = {{"name", p.name}, {"kind", kind_name(p.kind)}, {"default", p.default_value}, {"description", p.description}};
      if (p.kind == ParamKind::choice) {
        jp["choices"] = p.choices;
      } else if (p.kind == ParamKind::file) {
        jp["required"] = is_required(p);  // not reached today: measured, the one file model, is skipped above
      } else {
        jp["min"] = p.min;
        jp["max"] = p.max;
      }
      if (p.kind == ParamKind::lobes) jp["group_size"] = p.group_size;
      params.push_back(jp);
    }
    out.push_back({{"name", m.name}, {"formula", m.summary}, {"source", m.source}, {"params", params}});
  }
  return {{"models", out}};
}

json albedo(const json& req) {
  const BrdfPtr f = brdf_of(req);
  if (!req.contains("theta") || !req["theta"].is_array()) throw BadRequest{"theta: expected a list of degrees"};
  json thetas = json::array(), values = json::array();
  for (const auto& t : req["theta"]) {
    if (!t.is_number()) throw BadRequest{"theta: expected numbers"};
    const double deg = t.get<double>();
    if (!std::isfinite(deg) || deg < 0.0 || deg >= 90.0) {
      throw BadRequest{"theta: " + std::to_string(deg) + " is out of range [0, 90) degrees"};
    }
    thetas.push_back(deg);
    values.push_back(rgb_json(directional_albedo(*f, deg_to_rad(deg)).albedo));  // as `brdf albedo`
  }
  return {{"theta", thetas}, {"albedo", values}};
}

json lobe(const json& req) {
  const BrdfPtr f = brdf_of(req);
  LobeOptions o;
  o.theta_in_deg = number_of(req, "theta_in", o.theta_in_deg);
  o.times_cos = req.value("times_cos", false);
  o.fixed = req.value("fixed", std::string("light")) == "viewer" ? LobeFixed::viewer : LobeFixed::light;
  o.samples = static_cast<int>(number_of(req, "samples", 361));
  auto c = lobe_curve(*f, o);
  if (!c) throw BadRequest{c.error().message};
  json values = json::array();
  for (const auto& v : c->value) values.push_back(rgb_json(v));
  return {{"angle", c->angle_deg}, {"value", values}, {"luminance", c->luminance}, {"mirror", c->mirror_deg}};
}

// f_r(wi, wo) luminance with wo over a (theta, phi) grid of the hemisphere: theta_o = (90 i/(n_theta - 1))
// degrees, phi_o = 360 j / n_phi degrees.
json lobe3d(const json& req) {
  const BrdfPtr f = brdf_of(req);
  const Vec3 wi = direction_of(req, "wi");
  const int nt = static_cast<int>(number_of(req, "n_theta", 24));
  const int np = static_cast<int>(number_of(req, "n_phi", 48));
  if (nt < 2 || nt > 256 || np < 3 || np > 512) throw BadRequest{"lobe3d: n_theta in [2, 256], n_phi in [3, 512]"};
  json grid = json::array();
  for (int i = 0; i < nt; ++i) {
    json row = json::array();
    const double t = deg_to_rad(90.0 * i / (nt - 1));
    for (int j = 0; j < np; ++j) {
      const double p = 2.0 * pi * j / np;
      const Vec3 wo{std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
      row.push_back(luminance(f->eval(wi, wo)));
    }
    grid.push_back(row);
  }
  return {{"n_theta", nt}, {"n_phi", np}, {"luminance", grid}};
}

json zoo(const json& req) {
  const double n = number_of(req, "n", 100.0);
  if (!std::isfinite(n) || n < 0.0) throw BadRequest{"n: must be a finite number >= 0"};
  auto table = zoo_table(n);
  if (!table) throw BadRequest{table.error().message};
  json rows = json::array();
  for (const auto& r : *table) {
    rows.push_back({{"model", r.model}, {"table", r.table}, {"function", r.function_text}, {"n", r.n},
                    {"closed_form", r.closed_form_text}, {"closed_form_value", r.closed_form}, {"numeric", r.numeric},
                    {"relative_error", r.relative_error}, {"lower", r.lower ? json(*r.lower) : json(nullptr)},
                    {"upper", r.upper ? json(*r.upper) : json(nullptr)}, {"lower_text", r.lower_text},
                    {"upper_text", r.upper_text}, {"literature", r.literature}});
  }
  return {{"rows", rows}};
}

json shader(const json& req) {
  const ModelInfo& m = model_of(req);
  const ParamAssignments params = assignments_of(m, req);
  shaders::ExportOptions e;
  const std::string lang = req.value("lang", std::string("glsl"));
  auto l = shaders::parse_lang(lang);
  if (!l) throw BadRequest{l.error().message};
  e.lang = *l;
  // The header line `shadelab shader` writes for the same arguments (tools/shadelab/cmd_shader.cpp).
  e.command = "shadelab shader " + m.name;
  for (const auto& [name, value] : params) e.command += " --param " + name + "=" + value;
  e.command += " --lang " + lang;
  e.ibl = req.value("ibl", false);
  if (e.ibl) e.command += " --ibl";
  auto ex = shaders::export_model(m.name, params, e);
  if (!ex) throw BadRequest{ex.error().message};
  // A model that reads the GGX energy tables declares their uniform block: its name and std140 bytes (as
  // `shadelab shader --tables-out` writes them), which the page binds for the sphere.
  json tables = json::array();
  for (std::uint8_t b : ex->tables_data) tables.push_back(b);
  return {{"text", ex->text}, {"entry", ex->entry}, {"tables_block", ex->tables_block}, {"tables", tables},
          {"ibl_entry", ex->ibl_entry}};
}

json game_lobe_json(const json& req) {
  const ModelInfo& m = model_of(req);
  const ParamAssignments params = assignments_of(m, req);
  auto values = parse_params(m.name, m.params, params);
  if (!values) throw BadRequest{values.error().message};
  auto f = m.create(*values);
  if (!f) throw BadRequest{f.error().message};
  const GameLobe g = game_lobe(**f);
  json table = json::array();
  for (const auto& v : g.specular_albedo) table.push_back(rgb_json(v));
  return {{"exponent", g.exponent}, {"blinn_like", g.blinn_like}, {"wrap", g.wrap}, {"specular_albedo", table},
          {"diffuse_albedo", rgb_json((*f)->diffuse_albedo())}, {"split_sum", (*f)->split_sum_inputs().has_value()}};
}

json dispatch(const json& req) {
  const std::string op = req.value("op", std::string());
  if (op == "models") return models();
  if (op == "eval") {
    const BrdfPtr f = brdf_of(req);
    return {{"f", rgb_json(f->eval(direction_of(req, "wi"), direction_of(req, "wo")))}};
  }
  if (op == "albedo") return albedo(req);
  if (op == "lobe") return lobe(req);
  if (op == "lobe3d") return lobe3d(req);
  if (op == "zoo") return zoo(req);
  if (op == "shader") return shader(req);
  if (op == "game_lobe") return game_lobe_json(req);
  if (op == "kernels") {
    auto l = shaders::parse_lang(req.value("lang", std::string("essl")));
    if (!l) throw BadRequest{l.error().message};
    auto text = shaders::kernel_section(req.value("names", std::vector<std::string>{}), *l);
    if (!text) throw BadRequest{text.error().message};
    return {{"text", *text}};
  }
  throw BadRequest{"op: unknown operation '" + op + "'"};
}

std::string g_answer;

}  // namespace
}  // namespace shadelab::explore

// The answer stays valid until the next call.
extern "C" const char* shadelab_call(const char* request) {
  using shadelab::explore::g_answer;
  try {
    const auto req = nlohmann::json::parse(request);
    g_answer = shadelab::explore::dispatch(req).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  } catch (const shadelab::explore::BadRequest& e) {
    g_answer = nlohmann::json({{"error", e.message}}).dump();
  } catch (const std::exception& e) {
    g_answer = nlohmann::json({{"error", std::string("request: ") + e.what()}}).dump();
  }
  return g_answer.c_str();
}
