#include "glslang.h"

#include <cstdlib>
#include <cstring>
#include <sstream>

#include "process.h"

namespace shadelab::shaders {

std::string compute_harness(Lang lang, const std::string& code, const std::string& expression, const std::string& prelude) {
  std::string s;
  if (lang == Lang::hlsl) {
    s += "[[vk::binding(1)]] StructuredBuffer<float4> shadelab_in;\n"
         "[[vk::binding(2)]] RWStructuredBuffer<float4> shadelab_out;\n"
         "#define SHADELAB_TABLES_LAYOUT [[vk::binding(3)]]\n";
  } else {
    s += lang == Lang::glsl ? "#version 450\n" : "#version 310 es\nprecision highp float;\nprecision highp int;\n";
    s += "layout(local_size_x = 64) in;\n"
         "layout(std430, binding = 1) readonly buffer ShadelabIn { vec4 shadelab_in[]; };\n"
         "layout(std430, binding = 2) writeonly buffer ShadelabOut { vec4 shadelab_out[]; };\n"
         "#define SHADELAB_TABLES_LAYOUT layout(std140, binding = 3)\n";
  }
  s += prelude;
  s += "#line 1\n" + code;
  if (!code.empty() && code.back() != '\n') s += "\n";
  if (lang == Lang::hlsl) {
    s += "[numthreads(64, 1, 1)]\nvoid main(uint3 shadelab_id : SV_DispatchThreadID) {\n"
         "  float3 wi = shadelab_in[2 * shadelab_id.x].xyz;\n"
         "  float3 wo = shadelab_in[2 * shadelab_id.x + 1].xyz;\n"
         "  shadelab_out[shadelab_id.x] = float4(" + expression + ", 0.0);\n}\n";
  } else {
    s += "void main() {\n"
         "  uint shadelab_i = gl_GlobalInvocationID.x;\n"
         "  vec3 wi = shadelab_in[2u * shadelab_i].xyz;\n"
         "  vec3 wo = shadelab_in[2u * shadelab_i + 1u].xyz;\n"
         "  shadelab_out[shadelab_i] = vec4(" + expression + ", 0.0);\n}\n";
  }
  return s;
}

std::string glslang_program() {
  const char* env = std::getenv("SHADELAB_GLSLANG");
  if (env != nullptr && *env != '\0') return find_program(env);
  return find_program("glslangValidator");
}

std::string first_error_line(const std::string& log, const std::string& path, const std::string& display_name) {
  std::istringstream lines(log);
  std::string line;
  std::string first_nonempty;
  while (std::getline(lines, line)) {
    if (first_nonempty.empty() && !line.empty() && line != path) first_nonempty = line;
    const auto at = line.find("ERROR: ");
    if (at == std::string::npos) continue;
    std::string msg = line.substr(at + 7);
    for (std::size_t p = msg.find(path); !path.empty() && p != std::string::npos; p = msg.find(path)) {
      msg.replace(p, path.size(), display_name);
    }
    // Without -V glslang names the source string by its number: "0:12: ..." -> "DISPLAY:12: ...".
    const auto colon = msg.find(':');
    if (colon != std::string::npos && colon > 0 && msg.find_first_not_of("0123456789") == colon) {
      msg = display_name + msg.substr(colon);
    }
    return msg;
  }
  return first_nonempty.empty() ? "the compiler failed without a message" : first_nonempty;
}

namespace {

Result<ProcessResult> run_glslang(const std::vector<std::string>& args) {
  const std::string program = glslang_program();
  if (program.empty()) {
    return make_error("glslangValidator not found (install Debian's glslang-tools: scripts/setup.sh)");
  }
  std::vector<std::string> argv;
  argv.reserve(args.size() + 1);
  argv.push_back(program);
  for (const auto& a : args) argv.push_back(a);
  return run_process(argv, 120.0);
}

}  // namespace

Result<std::vector<std::uint32_t>> compile_compute(Lang lang, const std::string& source, const std::string& display_name) {
  TempDir dir;
  const std::string in = (dir / (lang == Lang::hlsl ? "shader.hlsl" : "shader.comp")).string();
  const std::string out = (dir / "shader.spv").string();
  if (auto ok = write_file(in, source); !ok) return ok.error();
  std::vector<std::string> args = {"-V", "--target-env", "vulkan1.1", "-S", "comp", "--auto-map-bindings"};
  if (lang == Lang::hlsl) {
    args.insert(args.end(), {"-D", "-e", "main"});
  }
  args.insert(args.end(), {"-o", out, in});
  auto run = run_glslang(args);
  if (!run) return run.error();
  if (run->timed_out) return make_error(display_name + ": glslangValidator did not finish in 120 s");
  if (run->exit_code != 0) return make_error(first_error_line(run->out + run->err, in, display_name));
  auto bytes = read_file(out);
  if (!bytes) return make_error("glslangValidator wrote no SPIR-V: " + bytes.error().message);
  if (bytes->size() % 4 != 0 || bytes->empty()) return make_error("glslangValidator wrote a malformed SPIR-V file");
  std::vector<std::uint32_t> words(bytes->size() / 4);
  std::memcpy(words.data(), bytes->data(), bytes->size());
  return words;
}

Result<bool> validate_essl300(const std::string& code, const std::string& expression, const std::string& display_name) {
  TempDir dir;
  const std::string in = (dir / "shader.frag").string();
  std::string s = "#version 300 es\nprecision highp float;\nprecision highp int;\nout vec4 shadelab_color;\n#line 1\n" + code;
  if (!code.empty() && code.back() != '\n') s += "\n";
  s += "void main() {\n  vec3 wi = vec3(0.0, 0.6, 0.8);\n  vec3 wo = vec3(0.0, -0.6, 0.8);\n  shadelab_color = vec4(" +
       expression + ", 1.0);\n}\n";
  if (auto ok = write_file(in, s); !ok) return ok.error();
  auto run = run_glslang({in});  // no -V: OpenGL ES semantics, validation only
  if (!run) return run.error();
  if (run->timed_out) return make_error(display_name + ": glslangValidator did not finish in 120 s");
  if (run->exit_code != 0) return make_error(first_error_line(run->out + run->err, in, display_name));
  return true;
}

}  // namespace shadelab::shaders
