#include "shadelab/color/ocio.h"

#include <OpenColorIO/OpenColorIO.h>

#include <cstdlib>
#include <exception>
#include <string_view>

#include "shadelab/core/text.h"

namespace OCIO = OCIO_NAMESPACE;

namespace shadelab::ocio {
namespace {

// One printable line of an OCIO message (they can span lines): line breaks become spaces, the rest printable().
std::string one_line(std::string_view s) {
  std::string out;
  for (char c : s) out += (c == '\n' || c == '\r' || c == '\t') ? ' ' : c;
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return printable(out, max_library_bytes);
}

std::string quoted(const std::string& s) { return "'" + printable(s) + "'"; }

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + printable(n);
  return s;
}

Result<OCIO::ConstConfigRcPtr> load(const std::string& path_in) {
  auto path = resolve_config(path_in);
  if (!path) return path.error();
  try {
    auto config = OCIO::Config::CreateFromFile(path->c_str());
    config->validate();
    return config;
  } catch (const OCIO::Exception& e) {
    return make_error("OCIO config " + quoted(*path) + ": " + one_line(e.what()));
  }
}

std::vector<std::string> display_names(const OCIO::ConstConfigRcPtr& config) {
  std::vector<std::string> out;
  for (int i = 0; i < config->getNumDisplays(); ++i) out.emplace_back(config->getDisplay(i));
  return out;
}

std::vector<std::string> view_names(const OCIO::ConstConfigRcPtr& config, const std::string& display) {
  std::vector<std::string> out;
  for (int i = 0; i < config->getNumViews(display.c_str()); ++i) out.emplace_back(config->getView(display.c_str(), i));
  return out;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  for (const auto& n : names) {
    if (n == name) return true;
  }
  return false;
}

Result<bool> run(const OCIO::ConstProcessorRcPtr& processor, float* rgb, std::size_t pixels) {
  if (pixels == 0) return true;
  auto cpu = processor->getDefaultCPUProcessor();  // float32 in and out
  // One row of `pixels` pixels, packed RGB.
  OCIO::PackedImageDesc desc(rgb, static_cast<long>(pixels), 1, 3);
  cpu->apply(desc);
  return true;
}

}  // namespace

Result<std::string> resolve_config(const std::string& path) {
  if (!path.empty()) return path;
  const char* env = std::getenv("OCIO");
  if (env != nullptr && *env != '\0') return std::string(env);
  return make_error("OCIO: no config (give --ocio-config FILE, OCIO:<config>:<display>:<view>, or set $OCIO)");
}

Result<bool> apply_display_view(const DisplayViewRequest& r, float* rgb, std::size_t pixels) {
  auto config = load(r.config);
  if (!config) return config.error();
  const auto path = resolve_config(r.config).value();
  const std::string what = "OCIO config " + quoted(path) + ", display " + quoted(r.display) + ", view " + quoted(r.view);
  try {
    const auto ds = display_names(*config);
    if (!contains(ds, r.display)) return make_error(what + ": no such display (the config's: " + join(ds) + ")");
    const auto vs = view_names(*config, r.display);
    if (!contains(vs, r.view)) return make_error(what + ": no such view (the display's: " + join(vs) + ")");
    std::string input = r.input_space;
    if (input.empty()) {
      auto role = (*config)->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
      if (!role) return make_error(what + ": the config has no scene_linear role (the input's colour space)");
      input = role->getName();
    } else if (!(*config)->getColorSpace(input.c_str())) {
      return make_error(what + ": no colour space " + quoted(input));
    }
    auto dvt = OCIO::DisplayViewTransform::Create();
    dvt->setSrc(input.c_str());
    dvt->setDisplay(r.display.c_str());
    dvt->setView(r.view.c_str());
    auto pipeline = OCIO::LegacyViewingPipeline::Create();
    pipeline->setDisplayViewTransform(dvt);
    if (!r.looks.empty()) {
      pipeline->setLooksOverrideEnabled(true);
      pipeline->setLooksOverride(r.looks.c_str());
    }
    auto processor = pipeline->getProcessor(*config, (*config)->getCurrentContext());
    return run(processor, rgb, pixels);
  } catch (const OCIO::Exception& e) {
    return make_error(what + (r.looks.empty() ? "" : ", looks " + quoted(r.looks)) + ": " + one_line(e.what()));
  }
}

Result<bool> convert(const std::string& config_path, const std::string& from, const std::string& to, float* rgb,
                     std::size_t pixels) {
  auto config = load(config_path);
  if (!config) return config.error();
  const auto path = resolve_config(config_path).value();
  const std::string what = "OCIO config " + quoted(path) + ", " + quoted(from) + " -> " + quoted(to);
  try {
    if (!(*config)->getColorSpace(from.c_str())) return make_error(what + ": no colour space " + quoted(from));
    if (!(*config)->getColorSpace(to.c_str())) return make_error(what + ": no colour space " + quoted(to));
    return run((*config)->getProcessor(from.c_str(), to.c_str()), rgb, pixels);
  } catch (const OCIO::Exception& e) {
    return make_error(what + ": " + one_line(e.what()));
  }
}

Result<std::vector<std::string>> displays(const std::string& config_path) {
  auto config = load(config_path);
  if (!config) return config.error();
  return display_names(*config);
}

Result<std::vector<std::string>> views(const std::string& config_path, const std::string& display) {
  auto config = load(config_path);
  if (!config) return config.error();
  return view_names(*config, display);
}

}  // namespace shadelab::ocio
