#include "site.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "shadelab/envmap/prefilter.h"
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
  return json{{"name", name}, {"file", file.string()}, {"size", size}, {"specular_size", size},
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

void send_all(int fd, const std::string& data) {
  std::size_t sent = 0;
  while (sent < data.size()) {
    const ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;  // the client went away
    sent += static_cast<std::size_t>(n);
  }
}

std::string response(int status, std::string_view reason, std::string_view type, const std::string& body, bool head) {
  std::ostringstream os;
  os << "HTTP/1.1 " << status << " " << reason << "\r\nContent-Type: " << type << "\r\nContent-Length: " << body.size()
     << "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n";
  if (!head) os << body;
  return os.str();
}

void answer(int fd, const fs::path& dir) {
  std::string request;
  char buf[4096];
  while (request.find("\r\n\r\n") == std::string::npos && request.size() < 65536) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) return;
    request.append(buf, static_cast<std::size_t>(n));
  }
  std::istringstream line(request.substr(0, request.find("\r\n")));
  std::string method, target;
  line >> method >> target;
  const bool head = method == "HEAD";
  if (method != "GET" && !head) {
    send_all(fd, response(405, "Method Not Allowed", "text/plain", "only GET and HEAD\n", false));
    return;
  }
  std::string name = target.substr(0, target.find_first_of("?#"));
  if (name == "/") name = "/index.html";
  name = name.substr(1);
  if (name.empty() || name.find('/') != std::string::npos || name.find("..") != std::string::npos) {
    send_all(fd, response(404, "Not Found", "text/plain", "not found\n", head));
    return;
  }
  std::ifstream in(dir / name, std::ios::binary);
  if (!in) {
    send_all(fd, response(404, "Not Found", "text/plain", "not found\n", head));
    return;
  }
  std::ostringstream body;
  body << in.rdbuf();
  send_all(fd, response(200, "OK", content_type(name), body.str(), head));
}

}  // namespace

Result<bool> serve_site(const fs::path& dir, int port, const std::function<void(int)>& on_ready) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return make_error("--serve: cannot open a socket");
  const int yes = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || ::listen(fd, 16) != 0) {
    ::close(fd);
    return make_error("--port: cannot listen on 127.0.0.1:" + std::to_string(port) + " (in use?)");
  }
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  on_ready(ntohs(addr.sin_port));
  for (;;) {
    const int client = ::accept(fd, nullptr, nullptr);
    if (client < 0) continue;
    answer(client, dir);
    ::close(client);
  }
}

}  // namespace shadelab::explore
