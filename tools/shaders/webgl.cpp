#include "webgl.h"

#include <cstdlib>
#include <cstring>

#include <nlohmann/json.hpp>

#include "kernel_library.h"
#include "process.h"

namespace shadelab::shaders {

namespace {
constexpr int kWidth = 1024;  // render-target width; the height is ceil(cases / kWidth)
}  // namespace

std::string base64(const std::uint8_t* data, std::size_t n) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  for (std::size_t i = 0; i < n; i += 3) {
    const std::uint32_t b0 = data[i];
    const std::uint32_t b1 = i + 1 < n ? data[i + 1] : 0u;
    const std::uint32_t b2 = i + 2 < n ? data[i + 2] : 0u;
    const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += i + 1 < n ? digits[(v >> 6) & 63] : '=';
    out += i + 2 < n ? digits[v & 63] : '=';
  }
  return out;
}

namespace {

Result<std::vector<std::uint8_t>> unbase64(const std::string& s) {
  std::vector<std::uint8_t> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    int v = -1;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    else if (c >= '0' && c <= '9') v = c - '0' + 52;
    else if (c == '+') v = 62;
    else if (c == '/') v = 63;
    else if (c == '=' || c == '\n' || c == '\r' || c == ' ') continue;
    else return make_error("WebGL: malformed result from the browser");
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((acc >> bits) & 0xffu));
    }
  }
  return out;
}

std::string html_unescape(std::string s) {
  const std::pair<const char*, const char*> entities[] = {{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&#39;", "'"}, {"&amp;", "&"}};
  for (const auto& [from, to] : entities) {
    for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + std::strlen(to))) {
      s.replace(p, std::strlen(from), to);
    }
  }
  return s;
}

std::string b64_text(const std::string& s) {
  return base64(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
}

// The page: decodes the inputs, then for each program compiles the fragment shader around its code, draws one
// fragment per case and records {"ok": true, "renderer": ..., "data": base64 floats} or {"ok": false,
// "compile": bool, "error": ...}; the JSON array goes into <pre id="out">.
std::string page(const std::string& programs_json, const std::string& wi_b64, const std::string& wo_b64, std::size_t cases) {
  return R"(<!doctype html><html><head><meta charset="utf-8"></head><body><pre id="out">[{"ok": false, "error": "the page did not run"}]</pre><script>
(function () {
  const out = document.getElementById('out');
  function bytes(s) { const b = atob(s); const a = new Uint8Array(b.length); for (let i = 0; i < b.length; ++i) a[i] = b.charCodeAt(i); return a; }
  function b64(u8) { let s = ''; for (let i = 0; i < u8.length; i += 0x8000) s += String.fromCharCode.apply(null, u8.subarray(i, i + 0x8000)); return btoa(s); }
  const programs = )" + programs_json + R"(;
  const results = [];
  try {
    const n = )" + std::to_string(cases) + R"(, W = )" + std::to_string(kWidth) + R"(, H = Math.max(1, Math.ceil(n / W));
    const wi = new Float32Array(W * H * 4); wi.set(new Float32Array(bytes(')" + wi_b64 + R"(').buffer));
    const wo = new Float32Array(W * H * 4); wo.set(new Float32Array(bytes(')" + wo_b64 + R"(').buffer));
    const canvas = document.createElement('canvas'); canvas.width = 1; canvas.height = 1;
    const gl = canvas.getContext('webgl2', {antialias: false});
    if (!gl) throw 'no WebGL 2 context';
    if (!gl.getExtension('EXT_color_buffer_float')) throw 'no EXT_color_buffer_float';
    const dbg = gl.getExtension('WEBGL_debug_renderer_info');
    const renderer = dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
    function texture(unit, data) {
      const t = gl.createTexture(); gl.activeTexture(gl.TEXTURE0 + unit); gl.bindTexture(gl.TEXTURE_2D, t);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST); gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE); gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, W, H, 0, gl.RGBA, gl.FLOAT, data);
      return t;
    }
    texture(0, wi); texture(1, wo);
    const target = gl.createTexture(); gl.activeTexture(gl.TEXTURE2); gl.bindTexture(gl.TEXTURE_2D, target);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, W, H);
    const fbo = gl.createFramebuffer(); gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw 'the RGBA32F render target is incomplete';
    function compile(type, text) {
      const s = gl.createShader(type); gl.shaderSource(s, text); gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw {compile: true, log: gl.getShaderInfoLog(s)};
      return s;
    }
    const vs = compile(gl.VERTEX_SHADER, '#version 300 es\nvoid main() {\n  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n  gl_Position = vec4(p, 0.0, 1.0);\n}\n');
    for (const p of programs) {
      try {
        const fs = compile(gl.FRAGMENT_SHADER, new TextDecoder().decode(bytes(p.frag)));
        const prog = gl.createProgram(); gl.attachShader(prog, vs); gl.attachShader(prog, fs); gl.linkProgram(prog);
        if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw 'the program does not link: ' + gl.getProgramInfoLog(prog);
        gl.useProgram(prog);
        gl.uniform1i(gl.getUniformLocation(prog, 'shadelab_wi_tex'), 0);
        gl.uniform1i(gl.getUniformLocation(prog, 'shadelab_wo_tex'), 1);
        const ubytes = bytes(p.uniform);
        if (ubytes.length > 0) {
          const index = gl.getUniformBlockIndex(prog, p.block);
          if (index === gl.INVALID_INDEX) throw 'the shader has no uniform block ' + p.block;
          const size = gl.getActiveUniformBlockParameter(prog, index, gl.UNIFORM_BLOCK_DATA_SIZE);
          const data = new Uint8Array(Math.max(size, ubytes.length)); data.set(ubytes);
          const ubo = gl.createBuffer(); gl.bindBuffer(gl.UNIFORM_BUFFER, ubo); gl.bufferData(gl.UNIFORM_BUFFER, data, gl.STATIC_DRAW);
          gl.uniformBlockBinding(prog, index, 0); gl.bindBufferBase(gl.UNIFORM_BUFFER, 0, ubo);
        }
        const tbytes = bytes(p.tables);
        let tindex = tbytes.length > 0 ? gl.getUniformBlockIndex(prog, ')" + std::string(kGgxEnergyBlock) + R"(') : gl.INVALID_INDEX;
        if (tbytes.length > 0 && tindex === gl.INVALID_INDEX) tindex = gl.getUniformBlockIndex(prog, ')" + std::string(kSheenEnergyBlock) + R"(');
        if (tindex !== gl.INVALID_INDEX) {  // a shader of the user's (--source) may not read the tables
          const index = tindex;
          const tbo = gl.createBuffer(); gl.bindBuffer(gl.UNIFORM_BUFFER, tbo); gl.bufferData(gl.UNIFORM_BUFFER, tbytes, gl.STATIC_DRAW);
          gl.uniformBlockBinding(prog, index, 1); gl.bindBufferBase(gl.UNIFORM_BUFFER, 1, tbo);
        }
        if (p.ibl) {  // the exported IBL fetches' textures (texelFetch only: NEAREST, no filtering involved)
          const chain = new Float32Array(bytes(p.ibl.chain).buffer);
          gl.activeTexture(gl.TEXTURE3);
          const ct = gl.createTexture(); gl.bindTexture(gl.TEXTURE_2D_ARRAY, ct);
          gl.texStorage3D(gl.TEXTURE_2D_ARRAY, p.ibl.levels, gl.RGBA32F, p.ibl.size, p.ibl.size, 6);
          let off = 0;
          for (let l = 0; l < p.ibl.levels; ++l) {
            const s = Math.max(1, p.ibl.size >> l);
            gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, l, 0, 0, 0, s, s, 6, gl.RGBA, gl.FLOAT, chain, off);
            off += s * s * 6 * 4;
          }
          gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.NEAREST_MIPMAP_NEAREST);
          gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
          gl.uniform1i(gl.getUniformLocation(prog, 'shadelab_ggx_chain'), 3);
          const table = function (unit, n, b64data, name) {
            gl.activeTexture(gl.TEXTURE0 + unit);
            const t = gl.createTexture(); gl.bindTexture(gl.TEXTURE_2D, t);
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST); gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
            gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, n, n, 0, gl.RGBA, gl.FLOAT, new Float32Array(bytes(b64data).buffer));
            gl.uniform1i(gl.getUniformLocation(prog, name), unit);
          };
          table(4, p.ibl.dfg_size, p.ibl.dfg, 'shadelab_dfg');
          table(5, p.ibl.lobe_size, p.ibl.lobes, 'shadelab_split_sum_lobes');
          gl.activeTexture(gl.TEXTURE0);
        }
        gl.viewport(0, 0, W, H); gl.disable(gl.BLEND); gl.disable(gl.DITHER);
        gl.drawArrays(gl.TRIANGLES, 0, 3);
        const result = new Float32Array(W * H * 4);
        gl.readPixels(0, 0, W, H, gl.RGBA, gl.FLOAT, result);
        const err = gl.getError();
        if (err !== gl.NO_ERROR) throw 'WebGL error ' + err;
        results.push({ok: true, renderer: renderer, data: b64(new Uint8Array(result.buffer, 0, n * 16))});
      } catch (e) {
        results.push(e && e.compile ? {ok: false, compile: true, error: e.log} : {ok: false, error: String(e)});
      }
    }
    out.textContent = JSON.stringify(results);
  } catch (e) {
    out.textContent = JSON.stringify([{ok: false, error: String(e && e.compile ? e.log : e)}]);
  }
})();
</script></body></html>
)";
}

// "ERROR: 0:12: 'x' : undeclared identifier" -> "DISPLAY:12: 'x' : undeclared identifier".
std::string webgl_error_line(const std::string& log, const std::string& display_name) {
  std::size_t start = 0;
  while (start < log.size()) {
    std::size_t end = log.find('\n', start);
    if (end == std::string::npos) end = log.size();
    std::string line = log.substr(start, end - start);
    start = end + 1;
    const auto at = line.find("ERROR: ");
    if (at == std::string::npos) continue;
    line = line.substr(at + 7);
    const auto colon = line.find(':');
    if (colon != std::string::npos && colon > 0 && line.find_first_not_of("0123456789") == colon) {
      line = display_name + line.substr(colon);  // drop the source-string number
    }
    return line;
  }
  return display_name + ": " + log;
}

}  // namespace

std::string chromium_program() {
  const char* env = std::getenv("SHADELAB_CHROMIUM");
  if (env != nullptr && *env != '\0') return find_program(env);
  std::string p = find_program("chromium");
  return p.empty() ? find_program("chromium-browser") : p;
}

Result<std::vector<Result<WebglResult>>> run_webgl_batch(const std::vector<WebglProgram>& programs,
                                                         const std::vector<float>& input) {
  const std::string chromium = chromium_program();
  if (chromium.empty()) return make_error("chromium not found (install Debian's chromium: scripts/setup.sh; or verify with --device vulkan)");
  if (input.size() % 8 != 0) return make_error("WebGL: the input holds 8 floats per case");
  const std::size_t cases = input.size() / 8;
  std::vector<float> wi(cases * 4), wo(cases * 4);
  for (std::size_t i = 0; i < cases; ++i) {
    for (std::size_t c = 0; c < 4; ++c) {
      wi[4 * i + c] = input[8 * i + c];
      wo[4 * i + c] = input[8 * i + 4 + c];
    }
  }
  nlohmann::json list = nlohmann::json::array();
  for (const auto& p : programs) {
    std::string frag =
        "#version 300 es\nprecision highp float;\nprecision highp int;\nuniform highp sampler2D shadelab_wi_tex;\n"
        "uniform highp sampler2D shadelab_wo_tex;\nout vec4 shadelab_color;\n#line 1\n" + p.code;
    if (!p.code.empty() && p.code.back() != '\n') frag += "\n";
    frag += "void main() {\n  ivec2 shadelab_p = ivec2(gl_FragCoord.xy);\n"
            "  vec3 wi = texelFetch(shadelab_wi_tex, shadelab_p, 0).xyz;\n"
            "  vec3 wo = texelFetch(shadelab_wo_tex, shadelab_p, 0).xyz;\n"
            "  shadelab_color = vec4(" + p.expression + ", 0.0);\n}\n";
    nlohmann::json entry = {{"frag", b64_text(frag)}, {"uniform", base64(p.uniform.data(), p.uniform.size())}, {"block", p.block_name},
                            {"tables", base64(p.tables.data(), p.tables.size())}};
    if (p.ibl.chain_size > 0) {
      const auto b64f = [](const std::vector<float>& v) {
        return base64(reinterpret_cast<const std::uint8_t*>(v.data()), v.size() * sizeof(float));
      };
      entry["ibl"] = {{"size", p.ibl.chain_size}, {"levels", p.ibl.chain_levels}, {"chain", b64f(p.ibl.chain)},
                      {"dfg_size", p.ibl.dfg_size}, {"dfg", b64f(p.ibl.dfg)}, {"lobe_size", p.ibl.lobe_size},
                      {"lobes", b64f(p.ibl.lobes)}};
    }
    list.push_back(std::move(entry));
  }

  TempDir dir("shadelab-webgl");
  const auto html = dir / "verify.html";
  const std::string text = page(list.dump(), base64(reinterpret_cast<const std::uint8_t*>(wi.data()), wi.size() * sizeof(float)),
                                base64(reinterpret_cast<const std::uint8_t*>(wo.data()), wo.size() * sizeof(float)), cases);
  if (auto ok = write_file(html, text); !ok) return ok.error();
  // Flags: headless, software WebGL through SwiftShader, and no background network traffic (a closed network
  // would otherwise fail many connections at every start).
  const std::vector<std::string> args = {chromium,
                                         "--headless",
                                         "--no-sandbox",
                                         "--disable-gpu",
                                         "--use-angle=swiftshader",
                                         "--enable-unsafe-swiftshader",
                                         "--disable-quic",
                                         "--no-first-run",
                                         "--disable-background-networking",
                                         "--disable-component-update",
                                         "--disable-sync",
                                         "--disable-extensions",
                                         "--user-data-dir=" + (dir / "profile").string(),
                                         "--dump-dom",
                                         "file://" + html.string()};
  auto run = run_process(args, 300.0);
  if (!run) return run.error();
  if (run->timed_out) return make_error("WebGL: chromium did not finish in 300 s");
  const auto open = run->out.find("<pre id=\"out\">");
  const auto close = open == std::string::npos ? std::string::npos : run->out.find("</pre>", open);
  if (close == std::string::npos) {
    const std::string why = run->err.substr(0, run->err.find('\n'));
    return make_error("WebGL: chromium printed no result (exit code " + std::to_string(run->exit_code) + ")" +
                      (why.empty() ? "" : ": " + why));
  }
  nlohmann::json results;
  try {
    results = nlohmann::json::parse(html_unescape(run->out.substr(open + 14, close - open - 14)));
  } catch (const std::exception&) {
    return make_error("WebGL: the page's output is not JSON");
  }
  if (!results.is_array() || results.empty()) return make_error("WebGL: the page returned no results");
  if (results.size() != programs.size()) {
    const auto& r = results.front();
    return make_error("WebGL: " + (r.contains("error") ? r["error"].get<std::string>() : std::string("no results")));
  }
  std::vector<Result<WebglResult>> out;
  for (std::size_t i = 0; i < programs.size(); ++i) {
    const auto& r = results[i];
    if (!r.value("ok", false)) {
      const std::string why = r.value("error", std::string("unknown failure"));
      out.push_back(r.value("compile", false) ? make_error(webgl_error_line(why, programs[i].display_name))
                                              : make_error("WebGL: " + why));
      continue;
    }
    WebglResult w;
    w.renderer = r.value("renderer", std::string());
    auto data = unbase64(r.value("data", std::string()));
    if (!data) {
      out.push_back(data.error());
      continue;
    }
    if (data->size() != cases * 16) {
      out.push_back(make_error("WebGL: the browser returned " + std::to_string(data->size()) + " bytes, expected " +
                               std::to_string(cases * 16)));
      continue;
    }
    w.output.resize(cases * 4);
    std::memcpy(w.output.data(), data->data(), data->size());
    out.push_back(std::move(w));
  }
  return out;
}

Result<WebglResult> run_webgl(const std::string& code, const std::string& expression, const std::vector<float>& input,
                              const std::vector<std::uint8_t>& uniform, const std::string& block_name,
                              const std::string& display_name, const std::vector<std::uint8_t>& tables) {
  auto batch = run_webgl_batch({{code, expression, uniform, block_name, display_name, tables, {}}}, input);
  if (!batch) return batch.error();
  return std::move(batch->front());
}

}  // namespace shadelab::shaders
