#include "site.h"
#include "http_request.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <string_view>
#include <thread>
#include <vector>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/envmap/specular/prefilter.h"
#include "shadelab/envmap/specular/split_sum_lobes.h"
#include "shadelab/image/image_io.h"
#include "shadelab/render/env_light.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/scene/limits.h"
#include "webgl.h"

namespace shadelab::explore {

namespace fs = std::filesystem;

namespace {

using nlohmann::json;

bool valid_env_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

std::vector<char> js_assignment(const std::string& lhs, const json& value) {
  const std::string text = lhs + " = " + value.dump(-1, ' ', true, json::error_handler_t::replace) + ";\n";
  return {text.begin(), text.end()};
}

// One lat-long map through the game renderer's bake (the environment of a scene {"environment": {"file":
// path}}, scale 1), packed as env-NAME.js describes (site.h).
Result<json> bake_environment(const std::string& name, const fs::path& file, int size) {
  auto image = read_radiance_image(file);  // NaN, Inf or negative: the map is skipped, named
  if (!image) return image.error();
  if (image->width != 2 * image->height) {
    return make_error("'" + file.string() + "' is " + std::to_string(image->width) + " x " + std::to_string(image->height) +
                      "; a lat-long map is twice as wide as it is high");
  }
  Scene scene;
  scene.environment.kind = Environment::Kind::image;
  scene.environment.latlong = std::move(image).value();
  scene.environment.source = file.string();
  if (auto limits = check_scene_limits(scene); !limits) return limits.error();
  GameOptions go;
  go.environment_size = size;
  go.specular_size = size;
  const EnvironmentLight light(scene);
  auto baked = bake_game_environment(light, go);
  if (!baked) return baked.error();
  std::vector<const CubeMap*> blocks = {&baked->radiance};
  for (const CubeMap& level : baked->specular.levels) blocks.push_back(&level);
  // The split sum's GGX chain (the ggx and filament spheres), after the Phong chain.
  const std::size_t ggx_first = blocks.size();
  for (const CubeMap& level : baked->specular_ggx.levels) blocks.push_back(&level);
  const int width = size;
  int height = 0;
  json block_list = json::array();
  for (const CubeMap* c : blocks) {
    block_list.push_back({{"size", c->size}, {"row", height}});
    height += 6 * c->size;
  }
  std::vector<float> texels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, 0.0f);
  int row = 0;
  for (const CubeMap* c : blocks) {
    for (int f = 0; f < 6; ++f) {
      for (int y = 0; y < c->size; ++y, ++row) {
        for (int x = 0; x < c->size; ++x) {
          const Image& face = c->faces[static_cast<std::size_t>(f)];
          const std::size_t from = face.index(x, y);
          const std::size_t to = (static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
          for (int k = 0; k < 3; ++k) texels[to + static_cast<std::size_t>(k)] = face.data[from + static_cast<std::size_t>(k)];
        }
      }
    }
  }
  static_assert(std::endian::native == std::endian::little, "the page reads little-endian float32");
  json sh = json::array();
  for (const Rgb& c : baked->sh.c) sh.push_back({c.r, c.g, c.b});
  const PrefilterOptions po;
  // The split sum's tables as the renderer reads them (game_dfg_table(64), split_sum_lobe_table()): RGBA float32
  // texels, row-major (row = roughness): the DFG table's A, B (A + B, 0) and the lobe table's angle_a,
  // roughness_a, angle_b, roughness_b.
  const GameOptions defaults;
  const DfgTable& dfg = game_dfg_table(defaults.dfg_size);
  std::vector<float> dfg_texels;
  for (int j = 0; j < dfg.size; ++j) {
    for (int i = 0; i < dfg.size; ++i) {
      for (int c = 0; c < 3; ++c) dfg_texels.push_back(static_cast<float>(dfg.at(i, j, c)));
      dfg_texels.push_back(0.0f);
    }
  }
  const SplitSumLobeTable& lobes = split_sum_lobe_table();
  std::vector<float> lobe_texels;
  for (const SplitSumLobes& l : lobes.all()) {
    for (double v : {l.a.angle, l.a.roughness, l.b.angle, l.b.roughness}) lobe_texels.push_back(static_cast<float>(v));
  }
  const auto b64 = [](const std::vector<float>& v) {
    return shaders::base64(reinterpret_cast<const std::uint8_t*>(v.data()), v.size() * sizeof(float));
  };
  const json split_sum = {{"ggx_first_block", ggx_first}, {"ggx_levels", baked->specular_ggx.levels.size()},
                          {"ggx_mapping", baked->specular_ggx.mapping.name()},
                          {"dfg_size", dfg.size}, {"dfg", b64(dfg_texels)},
                          {"lobe_size", lobes.size()}, {"lobes", b64(lobe_texels)}};
  return json{{"name", name}, {"file", file.string()}, {"size", size}, {"specular_size", size}, {"split_sum", split_sum},
              {"gloss_scale", po.gloss_scale}, {"gloss_bias", po.gloss_bias}, {"exponents", baked->specular.exponents},
              {"sh", sh}, {"width", width}, {"height", height}, {"blocks", block_list},
              {"texels", shaders::base64(reinterpret_cast<const std::uint8_t*>(texels.data()), texels.size() * sizeof(float))}};
}

}  // namespace

Result<SiteReport> write_site(const fs::path& dir, const SiteOptions& options) {
  if (options.env_size < 1 || options.env_size > 256 || (options.env_size & (options.env_size - 1)) != 0) {
    return make_error("--env-size: " + std::to_string(options.env_size) + " is not a power of two in [1, 256]");
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return make_error("--out: cannot create '" + dir.string() + "': " + ec.message());
  SiteReport report;
  for (const Asset& a : embedded_assets()) {
    const fs::path path = dir / std::string(a.name);
    auto r = write_file_atomically(path, std::vector<char>(a.bytes.begin(), a.bytes.end()));
    if (!r) return r.error();
    report.written.push_back(path);
  }
  // The sphere's environments: every NAME.exr of env_dir, baked as `render --mode game` bakes a scene's.
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, fs::path>> maps;
  if (!fs::is_directory(options.env_dir, ec)) {
    report.env_message = "no HDRI: '" + options.env_dir.string() +
                         "' is not a folder (Debian's blender-data installs the HDRIs there: apt-get install blender-data)";
  } else {
    for (const auto& entry : fs::directory_iterator(options.env_dir, ec)) {
      const fs::path& p = entry.path();
      if (p.extension() != ".exr" || !entry.is_regular_file(ec)) continue;
      if (valid_env_name(p.stem().string())) maps.emplace_back(p.stem().string(), p);
    }
    std::sort(maps.begin(), maps.end());
  }
  for (const auto& [name, file] : maps) {
    auto baked = bake_environment(name, file, options.env_size);
    if (!baked) {
      report.env_problems.push_back(name + ": " + baked.error().message);
      continue;
    }
    const fs::path path = dir / ("env-" + name + ".js");
    auto r = write_file_atomically(path, js_assignment("(window.shadelabEnvironmentData = window.shadelabEnvironmentData || {})[" +
                                                           json(name).dump() + "]", *baked));
    if (!r) return r.error();
    report.written.push_back(path);
    report.environments.push_back(name);
  }
  if (report.environments.empty() && report.env_message.empty()) {
    report.env_message = "no HDRI: no lat-long .exr map could be baked in '" + options.env_dir.string() + "'";
  }
  report.bake_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::string default_env;
  if (!report.environments.empty()) {
    const auto& e = report.environments;
    default_env = std::find(e.begin(), e.end(), options.default_env) != e.end() ? options.default_env : e.front();
  }
  const json index = {{"dir", options.env_dir.string()}, {"names", report.environments},
                      {"default", default_env.empty() ? json(nullptr) : json(default_env)},
                      {"size", options.env_size}, {"specular_size", options.env_size},
                      {"message", report.env_message.empty() ? json(nullptr) : json(report.env_message)},
                      {"problems", report.env_problems}};
  const fs::path path = dir / "environments.js";
  auto r = write_file_atomically(path, js_assignment("window.shadelabEnvironments", index));
  if (!r) return r.error();
  report.written.push_back(path);
  return report;
}

std::string_view content_type(std::string_view name) {
  auto ends = [&](std::string_view ext) { return name.size() >= ext.size() && name.substr(name.size() - ext.size()) == ext; };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".json")) return "application/json";
  if (ends(".png")) return "image/png";
  return "application/octet-stream";
}

namespace {

// The server's bounds (site.h): a request head (request line and headers) of at most max_head_bytes, the
// request line at most max_request_line_bytes, the whole head within head_deadline (and no gap between its
// bytes longer than idle_timeout: an idle or trickling connection is answered 408 and closed), at most
// max_connections served at once (each on its own thread; one more is answered 503 at once), and each
// response sent within send_timeout per write.
constexpr std::size_t max_head_bytes = 8192;

constexpr int idle_timeout_ms = 5000;
constexpr int head_deadline_ms = 10000;
constexpr int send_timeout_s = 10;
constexpr int max_connections = 32;

void send_all(int fd, std::string_view data) {
  std::size_t sent = 0;
  while (sent < data.size()) {
    const ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // the client went away, or the send timed out
    sent += static_cast<std::size_t>(n);
  }
}

std::string head_of(int status, std::string_view reason, std::string_view type, std::uint64_t length,
                    std::string_view extra = {}) {
  std::string h = "HTTP/1.1 " + std::to_string(status) + " " + std::string(reason) + "\r\nContent-Type: " +
                  std::string(type) + "\r\nContent-Length: " + std::to_string(length) +
                  "\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nConnection: close\r\n";
  h += extra;
  h += "\r\n";
  return h;
}

void send_status(int fd, int status, std::string_view reason, std::string_view body, bool head,
                 std::string_view extra = {}) {
  std::string r = head_of(status, reason, "text/plain; charset=utf-8", body.size(), extra);
  if (!head) r += body;
  send_all(fd, r);
}

// Reads the request head (up to the blank line) within the bounds above. Returns 0 and the head, or the
// status to answer with (408, 413 for a head beyond the bound), or -1 when the client closed the connection.
int read_head(int fd, std::string& head) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(head_deadline_ms);
  char buf[2048];
  for (;;) {
    // The end of the head (a bare LF line end is taken too); the bound is on the head, not on a body after it.
    const std::size_t end = std::min(head.find("\r\n\r\n"), head.find("\n\n"));
    if (end != std::string::npos) return end > max_head_bytes ? 431 : 0;
    if (head.size() > max_head_bytes) return 431;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return 408;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), idle_timeout_ms)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return 408;  // idle for idle_timeout_ms (or the deadline passed)
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0) return -1;
    head.append(buf, static_cast<std::size_t>(n));
  }
}

}  // namespace

namespace {

// Ends a connection after the response: our side first (FIN), then what the client still sends (a body we did
// not read, at most 64 KiB within 200 ms) is read and dropped, so the close sends no RST that could cut the
// response short on the client's side.
void close_gracefully(int fd) {
  ::shutdown(fd, SHUT_WR);
  char buf[4096];
  std::size_t drained = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
  while (drained < 65536) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{fd, POLLIN, 0};
    if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    drained += static_cast<std::size_t>(n);
  }
  ::close(fd);
}

void answer(int fd, int dir_fd, int port) {
  std::string head;
  const int got = read_head(fd, head);
  if (got < 0) return;
  if (got == 408) {
    send_status(fd, 408, "Request Timeout", "request timeout\n", false);
    return;
  }
  if (got == 431) {
    send_status(fd, 431, "Request Header Fields Too Large", "request head too large\n", false);
    return;
  }
  const HttpRequest req = parse_request(head, port);
  if (req.status == 405) {
    send_status(fd, 405, req.reason, "only GET and HEAD\n", false, "Allow: GET, HEAD\r\n");
    return;
  }
  if (req.status != 0) {
    send_status(fd, req.status, req.reason, req.reason + "\n", false);
    return;
  }
  const bool head_only = req.method == "HEAD";
  const std::string name = site_file_name(req.path);
  // The file directly in the site folder, not a symbolic link (O_NOFOLLOW), a regular file (fstat).
  const int file = name.empty() ? -1 : ::openat(dir_fd, name.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  struct stat st {};
  if (file < 0 || ::fstat(file, &st) != 0 || !S_ISREG(st.st_mode)) {
    if (file >= 0) ::close(file);
    send_status(fd, 404, "Not Found", "not found\n", head_only);
    return;
  }
  send_all(fd, head_of(200, "OK", content_type(name), static_cast<std::uint64_t>(st.st_size)));
  if (!head_only) {
    // Streamed: memory per connection stays one buffer, whatever the file's size.
    std::vector<char> buf(65536);
    std::uint64_t left = static_cast<std::uint64_t>(st.st_size);
    while (left > 0) {
      const ssize_t n = ::read(file, buf.data(), std::min<std::uint64_t>(left, buf.size()));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;  // the file shrank: the client sees a short body and the close
      send_all(fd, std::string_view(buf.data(), static_cast<std::size_t>(n)));
      left -= static_cast<std::uint64_t>(n);
    }
  }
  ::close(file);
}

}  // namespace

Result<bool> serve_site(const fs::path& dir, int port, const std::function<void(int)>& on_ready) {
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd < 0) return make_error("--serve: cannot open the folder '" + dir.string() + "'");
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    ::close(dir_fd);
    return make_error("--serve: cannot open a socket");
  }
  const int yes = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // 127.0.0.1 only: nothing off this machine can connect
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || ::listen(fd, 64) != 0) {
    ::close(fd);
    ::close(dir_fd);
    return make_error("--port: cannot listen on 127.0.0.1:" + std::to_string(port) + " (in use?)");
  }
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  const int bound_port = ntohs(addr.sin_port);
  on_ready(bound_port);
  // Each connection on its own detached thread, at most max_connections at once; the count lives as long as
  // the process (serve_site never returns once listening).
  static std::atomic<int> active{0};
  for (;;) {
    const int client = ::accept4(fd, nullptr, nullptr, SOCK_CLOEXEC);
    if (client < 0) {
      if (errno != EINTR) std::this_thread::sleep_for(std::chrono::milliseconds(10));  // EMFILE and the like
      continue;
    }
    const timeval send_timeout{send_timeout_s, 0};
    ::setsockopt(client, SOL_SOCKET, SO_SNDTIMEO, &send_timeout, sizeof send_timeout);
    if (active.fetch_add(1) >= max_connections) {
      active.fetch_sub(1);
      send_status(client, 503, "Service Unavailable", "too many connections\n", false);
      close_gracefully(client);
      continue;
    }
    try {
      std::thread([client, dir_fd, bound_port] {
        try {
          answer(client, dir_fd, bound_port);
        } catch (...) {  // out of memory for a buffer: this connection ends, the server goes on
        }
        close_gracefully(client);
        active.fetch_sub(1);
      }).detach();
    } catch (...) {  // no thread to be had: refuse this one
      active.fetch_sub(1);
      send_status(client, 503, "Service Unavailable", "too many connections\n", false);
      ::close(client);
    }
  }
}

}  // namespace shadelab::explore
