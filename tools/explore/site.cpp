#include "site.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

#include "shadelab/image/image_io.h"

namespace shadelab::explore {

namespace fs = std::filesystem;

Result<std::vector<fs::path>> write_site(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return make_error("--out: cannot create '" + dir.string() + "': " + ec.message());
  std::vector<fs::path> written;
  for (const Asset& a : embedded_assets()) {
    const fs::path path = dir / std::string(a.name);
    auto r = write_file_atomically(path, std::vector<char>(a.bytes.begin(), a.bytes.end()));
    if (!r) return r.error();
    written.push_back(path);
  }
  return written;
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
