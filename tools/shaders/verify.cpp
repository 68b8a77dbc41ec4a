#include "verify.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "export.h"
#include "glslang.h"
#include "process.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/sampling/rng.h"
#include "sl_lexer.h"
#include "vulkan_compute.h"
#include "verify_ibl.h"
#include "webgl.h"

namespace shadelab::shaders {

namespace {

constexpr std::uintmax_t kMaxSourceBytes = 16u << 20;

Vec3 uniform_hemisphere(double u1, double u2) {
  const double z = u1;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = two_pi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 at_height(double z, double u) {
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = two_pi * u;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// z log-uniform in [1e-5, 0.03].
double grazing_z(double u) { return std::exp(std::log(1e-5) + u * (std::log(0.03) - std::log(1e-5))); }

void push(std::vector<float>& out, const Vec3& wi, const Vec3& wo) {
  const Vec3 a = normalize(wi);
  const Vec3 b = normalize(wo);
  for (const Vec3& v : {a, b}) {
    out.push_back(static_cast<float>(v.x));
    out.push_back(static_cast<float>(v.y));
    out.push_back(static_cast<float>(v.z));
    out.push_back(0.0f);
  }
}

}  // namespace

std::vector<float> verification_pairs(std::size_t n, std::uint64_t seed) {
  std::vector<float> out;
  out.reserve(8 * n);
  const double s45 = std::sqrt(0.5);
  const std::vector<std::pair<Vec3, Vec3>> fixed = {
      {{0.0, 0.0, 1.0}, {0.0, 0.0, 1.0}},    // normal incidence, the mirror pair
      {{s45, 0.0, s45}, {-s45, 0.0, s45}},   // the mirror pair at 45 degrees
      {{0.6, 0.0, 0.8}, {0.0, 0.6, 0.8}},    // off-specular
      {{1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}},    // wi on the horizon
      {{0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}},    // wo on the horizon
      {{0.0, 0.0, -1.0}, {0.0, 0.0, 1.0}},   // wi below
      {{0.0, 0.0, 1.0}, {0.0, 0.0, -1.0}},   // wo below
      {{0.3, 0.4, 1e-4}, {-0.3, -0.4, 1e-4}},  // both grazing, mirror
  };
  Pcg32 rng(seed, 0x5ade1abULL);
  for (std::size_t i = 0; i < n; ++i) {
    if (i < fixed.size()) {
      push(out, fixed[i].first, fixed[i].second);
      continue;
    }
    const std::size_t kind = i % 20;
    const double u1 = rng.next_double(), u2 = rng.next_double(), u3 = rng.next_double(), u4 = rng.next_double();
    Vec3 wi, wo;
    if (kind < 12) {  // both uniform over the upper hemisphere
      wi = uniform_hemisphere(u1, u2);
      wo = uniform_hemisphere(u3, u4);
    } else if (kind < 15) {  // wi near the mirror direction of wo
      wo = uniform_hemisphere(u1, u2);
      const Vec3 m{-wo.x, -wo.y, wo.z};
      const double angle = std::exp(std::log(1e-4) + u3 * (std::log(0.5) - std::log(1e-4)));
      const Frame f = Frame::from_normal(m);
      const double phi = two_pi * u4;
      wi = f.to_world({std::sin(angle) * std::cos(phi), std::sin(angle) * std::sin(phi), std::cos(angle)});
    } else if (kind < 17) {  // one direction grazing
      const Vec3 g = at_height(grazing_z(u1), u2);
      const Vec3 other = uniform_hemisphere(u3, u4);
      wi = kind == 15 ? g : other;
      wo = kind == 15 ? other : g;
    } else if (kind < 18) {  // both grazing
      wi = at_height(grazing_z(u1), u2);
      wo = at_height(grazing_z(u3), u4);
    } else {  // on or below the horizon
      const std::size_t sub = (i / 20) % 5;
      const Vec3 below = at_height(-u1, u2);
      const Vec3 above = uniform_hemisphere(u3, u4);
      const Vec3 horizon = at_height(0.0, u1);
      if (sub == 0) { wi = below; wo = above; }
      else if (sub == 1) { wi = above; wo = below; }
      else if (sub == 2) { wi = below; wo = at_height(-u3, u4); }
      else if (sub == 3) { wi = horizon; wo = above; }
      else { wi = above; wo = horizon; }
    }
    push(out, wi, wo);
  }
  return out;
}

DeviceReport compare_outputs(const std::string& device, const std::vector<float>& input, const std::vector<float>& output,
                             const std::function<Rgb(const Vec3& wi, const Vec3& wo)>& reference) {
  DeviceReport r;
  r.device = device;
  r.cases = input.size() / 8;
  double sum = 0.0;
  std::size_t finite = 0;
  std::optional<CaseResult> worst_finite;
  for (std::size_t i = 0; i < r.cases; ++i) {
    CaseResult c;
    for (std::size_t k = 0; k < 3; ++k) {
      c.wi[k] = input[8 * i + k];
      c.wo[k] = input[8 * i + 4 + k];
      c.shader[k] = output[4 * i + k];
    }
    const Vec3 wi{c.wi[0], c.wi[1], c.wi[2]};
    const Vec3 wo{c.wo[0], c.wo[1], c.wo[2]};
    const Rgb ref = reference(wi, wo);
    c.reference = {ref.r, ref.g, ref.b};
    bool ok = true;
    double e = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double s = c.shader[k];
      const double f = c.reference[k];
      if (!std::isfinite(s) || !std::isfinite(f)) {
        ok = false;
        break;
      }
      e = std::max(e, std::abs(s - f) / std::max(std::abs(f), kRelativeErrorFloor));
    }
    if (!ok) {
      if (r.nonfinite == 0) r.worst = c;
      ++r.nonfinite;
      continue;
    }
    c.rel_error = e;
    sum += e;
    ++finite;
    if (!worst_finite || e > worst_finite->rel_error) worst_finite = c;
  }
  r.max_rel_error = worst_finite ? worst_finite->rel_error : 0.0;
  r.mean_rel_error = finite > 0 ? sum / static_cast<double>(finite) : 0.0;
  if (r.nonfinite == 0) r.worst = worst_finite;
  return r;
}

std::string strip_version_directive(const std::string& code) {
  std::vector<Token> t = lex(code);
  for (auto& tok : t) {
    if (is_trivia(tok)) continue;
    if (tok.kind == TokenKind::preprocessor && tok.text.find("version") != std::string::npos &&
        tok.text.substr(tok.text.find_first_not_of("# \t")).rfind("version", 0) == 0) {
      tok.text = "// (the harness's own #version replaces) " + tok.text.substr(1);
    }
    break;
  }
  return join(t);
}

namespace {

bool defines_function(const std::string& code, const std::string& name) {
  const std::vector<Token> t = lex(code);
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k].kind != TokenKind::identifier || t[k].text != name) continue;
    std::size_t j = k + 1;
    while (j < t.size() && is_trivia(t[j])) ++j;
    if (j < t.size() && t[j].text == "(") return true;
  }
  return false;
}

}  // namespace

DeviceReport combine_reports(const std::vector<DeviceReport>& reports) {
  if (reports.size() == 1) return reports.front();
  DeviceReport c;
  c.cases = reports.front().cases;
  const DeviceReport* worst = &reports.front();
  for (const auto& r : reports) {
    c.device += (c.device.empty() ? "" : "; ") + r.device;
    c.max_rel_error = std::max(c.max_rel_error, r.max_rel_error);
    c.mean_rel_error = std::max(c.mean_rel_error, r.mean_rel_error);
    c.nonfinite = std::max(c.nonfinite, r.nonfinite);
    const bool worse = (r.nonfinite > 0) != (worst->nonfinite > 0) ? r.nonfinite > 0 : r.max_rel_error > worst->max_rel_error;
    if (worse) worst = &r;
  }
  c.worst = worst->worst;
  return c;
}


Result<VerifyReport> verify_shader(const VerifyOptions& o) {
  if (o.cases < 1 || o.cases > 1000000) return make_error("--cases: " + std::to_string(o.cases) + " is out of range [1, 1000000]");
  if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance)) return make_error("--tolerance must be a positive number");
  if (o.device == VerifyDevice::webgl2 && o.lang != Lang::essl) return make_error("--device webgl2 needs --lang essl");
  ExportOptions eo;
  eo.lang = o.lang;
  eo.entry = o.entry;
  eo.uniforms = o.uniforms;
  eo.ibl = !o.ibl_dir.empty();
  auto ex = export_model(o.model, o.params, eo);
  if (!ex) return ex.error();
  auto brdf = make_brdf(o.model, o.params);
  if (!brdf) return brdf.error();
  const Brdf& reference = **brdf;

  std::string code = ex->text;
  std::string display = "exported shader";
  if (!o.source.empty()) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(o.source, ec);
    if (!ec && size > kMaxSourceBytes) {
      return make_error("--source: " + o.source + " is larger than 16 MiB, not a shader function file");
    }
    auto text = read_file(o.source);
    if (!text) return make_error("--source: " + text.error().message);
    code = strip_version_directive(*text);
    display = o.source;
    const std::string& needed = eo.ibl ? ex->ibl_entry : ex->entry;
    if (!defines_function(code, needed)) {
      return make_error(o.source + ": defines no function '" + needed + "' (name the entry with --entry NAME)");
    }
  }
  if (eo.ibl) return verify_ibl(o, *ex, code, display);
  const std::string expression = ex->entry + "(wi, wo)";
  const std::vector<float> pairs = verification_pairs(o.cases, o.seed);
  const std::vector<std::uint8_t> uniform = o.uniforms ? ex->uniform_data : std::vector<std::uint8_t>{};
  const auto ref = [&](const Vec3& wi, const Vec3& wo) { return reference.eval(wi, wo); };

  VerifyReport report;
  report.lang = o.lang;
  report.tolerance = o.tolerance;
  if (o.lang == Lang::essl) {
    if (auto ok = validate_essl300(code, expression, display); !ok) return ok.error();
  }
  if (o.device != VerifyDevice::webgl2) {
    auto spirv = compile_compute(o.lang, compute_harness(o.lang, code, expression), display);
    if (!spirv) return spirv.error();
    auto dev = VulkanDevice::open();
    if (!dev) return dev.error();
    auto out = (*dev)->run(*spirv, pairs, uniform, ex->tables_data);
    if (!out) return out.error();
    report.devices.push_back(compare_outputs((*dev)->name(), pairs, *out, ref));
  }
  if (o.lang == Lang::essl && o.device != VerifyDevice::vulkan) {
    auto web = run_webgl(code, expression, pairs, uniform, ex->block_name, display, ex->tables_data);
    if (!web) return web.error();
    report.devices.push_back(compare_outputs("Chromium WebGL 2: " + web->renderer, pairs, web->output, ref));
  }
  report.combined = combine_reports(report.devices);
  report.passed = report.combined.nonfinite == 0 && report.combined.max_rel_error <= o.tolerance;
  return report;
}

}  // namespace shadelab::shaders
