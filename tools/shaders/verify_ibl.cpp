#include "verify_ibl.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "glslang.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/render/camera_model.h"
#include "shadelab/render/game_renderer.h"
#include "vulkan_compute.h"
#include "webgl.h"

namespace shadelab::shaders {

namespace {

constexpr std::uintmax_t kMaxJsonBytes = 64u << 20;

Result<nlohmann::json> read_json(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(path.string() + ": cannot read (" + ec.message() + ")");
  if (size > kMaxJsonBytes) return make_error(path.string() + ": larger than 64 MiB");
  std::ifstream in(path);
  if (!in) return make_error(path.string() + ": cannot open");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    return make_error(path.string() + ": not JSON (" + std::string(e.what()) + ")");
  }
}

// A finite number at j[key] (or j itself), else an error naming the file and field.
Result<double> number(const nlohmann::json& j, const std::string& file, const std::string& field) {
  if (!j.is_number()) return make_error(file + ": " + field + " is not a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) return make_error(file + ": " + field + " is not finite");
  return v;
}

}  // namespace

Result<IblBake> read_ibl_bake(const std::filesystem::path& dir) {
  IblBake b;
  const auto manifest_path = dir / "manifest.json";
  auto manifest = read_json(manifest_path);
  if (!manifest) return make_error(manifest.error().message + " (--ibl: a directory `shadelab bake ibl` wrote, or an environment image)");
  const std::string mname = manifest_path.string();
  const nlohmann::json& files = (*manifest)["files"];
  if (!files.is_object()) return make_error(mname + ": no files object");
  for (const char* key : {"specular", "dfg", "sh9", "split_sum_lobes"}) {
    if (!files.contains(key) || !files[key].is_object() || !files[key].contains("file") || !files[key]["file"].is_string()) {
      return make_error(mname + ": files." + key + ".file is missing");
    }
  }
  const nlohmann::json& spec = files["specular"];
  if (spec.value("container", "") != "ktx2") {
    return make_error(mname + ": files.specular.container is '" + spec.value("container", "") +
                      "'; --ibl reads KTX 2 bakes (bake ibl --container ktx2: DDS holds no mip mapping)");
  }
  // Plain names only: the manifest may not point outside its directory.
  const auto in_dir = [&](const nlohmann::json& entry, const char* key) -> Result<std::filesystem::path> {
    const std::string name = entry["file"].get<std::string>();
    if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..") {
      return make_error(mname + ": files." + key + ".file '" + name + "' is not a file name in the directory");
    }
    return dir / name;
  };
  auto chain_path = in_dir(spec, "specular");
  if (!chain_path) return chain_path.error();
  auto chain = read_ktx2(*chain_path);
  if (!chain) return chain.error();
  if (chain->faces != 6) return make_error(chain_path->string() + ": not a cube map (faceCount " + std::to_string(chain->faces) + ")");
  b.chain = std::move(*chain);
  const std::string mapping = spec.contains("mip_mapping") && spec["mip_mapping"].is_object() ? spec["mip_mapping"].value("mapping", "") : "";
  if (mapping == "linear") b.mapping = kernel::GGX_MIP_MAPPING_LINEAR;
  else if (mapping == "filament") b.mapping = kernel::GGX_MIP_MAPPING_FILAMENT;
  else return make_error(mname + ": files.specular.mip_mapping.mapping is '" + mapping + "' (linear or filament)");

  auto dfg_path = in_dir(files["dfg"], "dfg");
  if (!dfg_path) return dfg_path.error();
  auto dfg = read_ktx2(*dfg_path);
  if (!dfg) return dfg.error();
  if (dfg->faces != 1 || dfg->width != dfg->height || dfg->levels.size() != 1) {
    return make_error(dfg_path->string() + ": not a square one-level DFG table");
  }
  b.dfg = std::move(*dfg);

  auto sh_path = in_dir(files["sh9"], "sh9");
  if (!sh_path) return sh_path.error();
  auto sh = read_json(*sh_path);
  if (!sh) return sh.error();
  const nlohmann::json& rc = (*sh)["radiance_coefficients"];
  if (!rc.is_array() || rc.size() != 9) return make_error(sh_path->string() + ": radiance_coefficients is not 9 RGB triples");
  for (std::size_t i = 0; i < 9; ++i) {
    if (!rc[i].is_array() || rc[i].size() != 3) return make_error(sh_path->string() + ": radiance_coefficients[" + std::to_string(i) + "] is not RGB");
    double c[3];
    for (std::size_t k = 0; k < 3; ++k) {
      auto v = number(rc[i][k], sh_path->string(), "radiance_coefficients[" + std::to_string(i) + "]");
      if (!v) return v.error();
      c[k] = *v;
    }
    b.sh.c[i] = Rgb{c[0], c[1], c[2]};
  }

  auto lobes_path = in_dir(files["split_sum_lobes"], "split_sum_lobes");
  if (!lobes_path) return lobes_path.error();
  auto lobes = read_json(*lobes_path);
  if (!lobes) return lobes.error();
  const std::string lname = lobes_path->string();
  if (!(*lobes)["size"].is_number_integer()) return make_error(lname + ": size is not an integer");
  const int n = (*lobes)["size"].get<int>();
  if (n < 1 || n > 1024) return make_error(lname + ": size " + std::to_string(n) + " is out of range [1, 1024]");
  const nlohmann::json& texels = (*lobes)["texels"];
  if (!texels.is_array() || texels.size() != static_cast<std::size_t>(n) * static_cast<std::size_t>(n)) {
    return make_error(lname + ": texels does not hold size^2 entries");
  }
  b.lobe_size = n;
  b.lobes.reserve(texels.size());
  for (std::size_t i = 0; i < texels.size(); ++i) {
    const nlohmann::json& t = texels[i];
    if (!t.is_array() || t.size() != 4) return make_error(lname + ": texels[" + std::to_string(i) + "] is not 4 numbers");
    double v[4];
    for (std::size_t k = 0; k < 4; ++k) {
      auto x = number(t[k], lname, "texels[" + std::to_string(i) + "]");
      if (!x) return x.error();
      v[k] = *x;
    }
    b.lobes.push_back({{v[0], v[1]}, {v[2], v[3]}});
  }
  return b;
}

IblBuffer ibl_storage_buffer(const IblBake& bake, bool hlsl) {
  IblBuffer out;
  std::vector<std::size_t> offsets;
  for (const auto& level : bake.chain.levels) {
    offsets.push_back(out.texels.size() / 4);
    out.texels.insert(out.texels.end(), level.begin(), level.end());
  }
  const std::size_t dfg_offset = out.texels.size() / 4;
  out.texels.insert(out.texels.end(), bake.dfg.levels[0].begin(), bake.dfg.levels[0].end());
  const std::size_t lobe_offset = out.texels.size() / 4;
  for (const SplitSumLobes& l : bake.lobes) {
    for (double v : {l.a.angle, l.a.roughness, l.b.angle, l.b.roughness}) out.texels.push_back(static_cast<float>(v));
  }
  std::string offs;
  for (std::size_t i = 0; i < offsets.size(); ++i) offs += (i ? ", " : "") + std::to_string(offsets[i]);
  const std::string levels = std::to_string(offsets.size());
  const std::string size = std::to_string(bake.chain.width);
  const std::string dfg_n = std::to_string(bake.dfg.width);
  const std::string lobe_n = std::to_string(bake.lobe_size);
  std::string& s = out.prelude;
  s += "// shader verify --ibl: the IBL fetches over one storage buffer (the exported texture fetches are skipped).\n"
       "#define SHADELAB_IBL_FETCHES\n";
  const std::string v3 = hlsl ? "float3" : "vec3";
  if (hlsl) {
    s += "[[vk::binding(4)]] StructuredBuffer<float4> shadelab_ibl;\n"
         "static const int shadelab_chain_offsets[" + levels + "] = {" + offs + "};\n";
  } else {
    s += "layout(std430, binding = 4) readonly buffer ShadelabIbl { vec4 shadelab_ibl[]; };\n"
         "const int shadelab_chain_offsets[" + levels + "] = int[](" + offs + ");\n";
  }
  s += "int cube_size(int cube) { return max(1, " + size + " >> cube); }\n" +
       v3 + " cube_texel(int cube, int face, int x, int y) {\n  int n = cube_size(cube);\n"
       "  return shadelab_ibl[shadelab_chain_offsets[cube] + (face * n + y) * n + x].xyz;\n}\n"
       "float dfg_texel(int x, int y, int channel) { return shadelab_ibl[" + std::to_string(dfg_offset) + " + y * " + dfg_n +
       " + x][channel]; }\n"
       "int shadelab_dfg_size() { return " + dfg_n + "; }\n"
       "float split_sum_lobe_texel(int x, int y, int channel) { return shadelab_ibl[" + std::to_string(lobe_offset) + " + y * " +
       lobe_n + " + x][channel]; }\n"
       "int shadelab_split_sum_lobe_size() { return " + lobe_n + "; }\n";
  return out;
}

Result<VerifyReport> verify_ibl(const VerifyOptions& o, const ShaderExport& ex, const std::string& code_in,
                                const std::string& display) {
  if (o.ibl_size < 8 || o.ibl_size > 1024) return make_error("--ibl-size: " + std::to_string(o.ibl_size) + " is out of range [8, 1024]");
  auto bake = read_ibl_bake(o.ibl_dir);
  if (!bake) return bake.error();

  // The reference: the C++ game renderer with exactly these files (game_renderer.h GameEnvironment).
  GameEnvironment env;
  env.has_light = true;
  env.sh = bake->sh;
  const int chain_levels = static_cast<int>(bake->chain.levels.size());
  for (int l = 0; l < chain_levels; ++l) {
    const int n = bake->chain.level_width(l);
    CubeMap c(n);
    for (int f = 0; f < 6; ++f) {
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          const float* t = bake->chain.texel(l, f, x, y);
          c.set(f, x, y, Rgb{t[0], t[1], t[2]});
        }
      }
    }
    env.specular_ggx.levels.push_back(std::move(c));
  }
  env.specular_ggx.mapping.kind = bake->mapping == kernel::GGX_MIP_MAPPING_FILAMENT ? GgxRoughnessMapping::filament
                                                                                    : GgxRoughnessMapping::linear;
  env.specular_ggx.mapping.levels = chain_levels;
  auto dfg = std::make_shared<DfgTable>();
  dfg->size = bake->dfg.width;
  for (int j = 0; j < dfg->size; ++j) {
    for (int i = 0; i < dfg->size; ++i) {
      const float* t = bake->dfg.texel(0, 0, i, j);
      dfg->texels.insert(dfg->texels.end(), {static_cast<double>(t[0]), static_cast<double>(t[1]), static_cast<double>(t[0]) + static_cast<double>(t[1])});
    }
  }
  env.dfg = dfg;
  env.lobes = std::make_shared<SplitSumLobeTable>(bake->lobe_size, bake->lobes);

  Scene scene;
  scene.environment.kind = Environment::Kind::uniform;  // has light; the renderer reads only `env` on the sphere
  scene.environment.uniform = Rgb::gray(1.0);
  Material m;
  m.name = "verify";
  m.model = o.model;
  m.params = o.params;
  scene.materials.push_back(m);
  scene.spheres.push_back({{0.0, 0.0, 0.0}, 1.0, 0});
  scene.camera.position = {0.0, 0.0, 3.0};
  scene.camera.look_at = {0.0, 0.0, 0.0};
  scene.camera.up = {0.0, 1.0, 0.0};
  scene.camera.vfov_deg = 45.0;
  scene.camera.width = scene.camera.height = o.ibl_size;
  GameOptions go;
  go.spp = 1;
  go.punctual = false;
  go.shadows = false;
  go.ggx_specular = GameGgxSpecular::split_sum;
  go.split_sum_lookup = GameSplitSumLookup::lobes;
  go.dfg_size = dfg->size;
  auto image = render_game(scene, go, env);
  if (!image) return image.error();

  // The pixels on the sphere and their normal and view direction, as the shader's input (8 floats each).
  const CameraModel camera(scene.camera);
  std::vector<float> input;
  std::vector<Rgb> reference;
  for (int y = 0; y < o.ibl_size; ++y) {
    for (int x = 0; x < o.ibl_size; ++x) {
      const Ray ray = camera.ray(x + 0.5, y + 0.5);
      const double bq = dot(ray.origin, ray.direction);
      const double disc = bq * bq - (dot(ray.origin, ray.origin) - 1.0);
      if (disc <= 0.0) continue;
      const double t = -bq - std::sqrt(disc);
      const Vec3 n = normalize(ray.origin + ray.direction * t);
      const Vec3 v = -ray.direction;
      if (dot(n, v) < kIblMinCosine) continue;
      for (const Vec3& d : {n, v}) {
        input.insert(input.end(), {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z), 0.0f});
      }
      reference.push_back(image->beauty.at(x, y));
    }
  }

  // The SH coefficients as a function of the file, appended to the code (after it: the code's line numbers hold).
  const bool hlsl = o.lang == Lang::hlsl;
  const std::string v3 = hlsl ? "float3" : "vec3";
  std::string code = code_in;
  if (!code.empty() && code.back() != '\n') code += "\n";
  code += "Sh9Coefficients shadelab_verify_sh() {\n  Sh9Coefficients s;\n";
  for (std::size_t i = 0; i < 9; ++i) {
    const Rgb& c = bake->sh.c[i];
    code += "  s.c[" + std::to_string(i) + "] = " + v3 + "(" + float_literal(c.r) + ", " + float_literal(c.g) + ", " +
            float_literal(c.b) + ");\n";
  }
  code += "  return s;\n}\n";
  const std::string expression = ex.ibl_entry + "(wi, wo, shadelab_verify_sh(), " + std::to_string(chain_levels) + ", " +
                                 (bake->mapping == kernel::GGX_MIP_MAPPING_FILAMENT ? "GGX_MIP_MAPPING_FILAMENT" : "GGX_MIP_MAPPING_LINEAR") + ")";
  const std::vector<std::uint8_t> uniform = o.uniforms ? ex.uniform_data : std::vector<std::uint8_t>{};
  const auto reference_of = [&reference] {
    return [&reference, i = std::size_t{0}](const Vec3&, const Vec3&) mutable { return reference[i++]; };
  };

  VerifyReport report;
  report.lang = o.lang;
  report.tolerance = o.tolerance;
  report.pixels = reference.size();
  if (o.lang == Lang::essl) {
    if (auto ok = validate_essl300(code, expression, display); !ok) return ok.error();
  }
  if (o.device != VerifyDevice::webgl2) {
    const IblBuffer buffer = ibl_storage_buffer(*bake, hlsl);
    auto spirv = compile_compute(o.lang, compute_harness(o.lang, code, expression, buffer.prelude), display);
    if (!spirv) return spirv.error();
    auto dev = VulkanDevice::open();
    if (!dev) return dev.error();
    auto out = (*dev)->run(*spirv, input, uniform, ex.tables_data, buffer.texels);
    if (!out) return out.error();
    report.devices.push_back(compare_outputs((*dev)->name(), input, *out, reference_of()));
  }
  if (o.lang == Lang::essl && o.device != VerifyDevice::vulkan) {
    WebglProgram p{code, expression, uniform, ex.block_name, display, ex.tables_data, {}};
    p.ibl.chain_size = bake->chain.width;
    p.ibl.chain_levels = chain_levels;
    for (const auto& level : bake->chain.levels) p.ibl.chain.insert(p.ibl.chain.end(), level.begin(), level.end());
    p.ibl.dfg_size = bake->dfg.width;
    p.ibl.dfg = bake->dfg.levels[0];
    p.ibl.lobe_size = bake->lobe_size;
    for (const SplitSumLobes& l : bake->lobes) {
      for (double v : {l.a.angle, l.a.roughness, l.b.angle, l.b.roughness}) p.ibl.lobes.push_back(static_cast<float>(v));
    }
    auto batch = run_webgl_batch({p}, input);
    if (!batch) return batch.error();
    auto web = std::move(batch->front());
    if (!web) return web.error();
    report.devices.push_back(compare_outputs("Chromium WebGL 2: " + web->renderer, input, web->output, reference_of()));
  }
  report.combined = combine_reports(report.devices);
  report.passed = report.combined.nonfinite == 0 && report.combined.max_rel_error <= o.tolerance;
  return report;
}

}  // namespace shadelab::shaders
