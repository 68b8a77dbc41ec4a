// The served page's request head parser (http_request.h).
#include "http_request.h"

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>
#include <utility>

namespace shadelab::explore {

namespace {

bool is_token_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || std::string_view("!#$%&'*+-.^_`|~").find(c) != std::string_view::npos;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

using Request = HttpRequest;

Request bad(int status, std::string reason) {
  Request r;
  r.status = status;
  r.reason = std::move(reason);
  return r;
}

}  // namespace

// The request line and the headers, without anything that can throw on malformed input (string_view finds
// and compares only): "METHOD SP /TARGET SP HTTP/1.x", then "Name: value" lines; HTTP/1.1 needs a Host of
// 127.0.0.1 or localhost, with this server's port if it has one (a page from another name, as by DNS
// rebinding, gets 400).
HttpRequest parse_request(std::string_view head, int port) {
  const std::size_t eol = head.find('\n');
  std::string_view line = head.substr(0, eol);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (line.size() > max_request_line_bytes) return bad(414, "URI Too Long");
  const std::size_t sp1 = line.find(' ');
  if (sp1 == std::string_view::npos || sp1 == 0) return bad(400, "Bad Request");
  const std::size_t sp2 = line.find(' ', sp1 + 1);
  if (sp2 == std::string_view::npos || line.find(' ', sp2 + 1) != std::string_view::npos) return bad(400, "Bad Request");
  const std::string_view method = line.substr(0, sp1);
  const std::string_view target = line.substr(sp1 + 1, sp2 - sp1 - 1);
  const std::string_view version = line.substr(sp2 + 1);
  if (!std::all_of(method.begin(), method.end(), is_token_char)) return bad(400, "Bad Request");
  if (version != "HTTP/1.1" && version != "HTTP/1.0") return bad(400, "Bad Request");
  if (target.empty() || target.front() != '/') return bad(400, "Bad Request");
  for (const char c : target) {
    if (static_cast<unsigned char>(c) <= 0x20 || c == 0x7f) return bad(400, "Bad Request");
  }
  // Headers: each "name: value"; Host once.
  std::string_view rest = eol == std::string_view::npos ? std::string_view() : head.substr(eol + 1);
  int hosts = 0;
  std::string_view host;
  while (!rest.empty()) {
    const std::size_t e = rest.find('\n');
    std::string_view h = rest.substr(0, e);
    rest = e == std::string_view::npos ? std::string_view() : rest.substr(e + 1);
    if (!h.empty() && h.back() == '\r') h.remove_suffix(1);
    if (h.empty()) break;
    const std::size_t colon = h.find(':');
    if (colon == std::string_view::npos || colon == 0) return bad(400, "Bad Request");
    const std::string_view name = h.substr(0, colon);
    if (!std::all_of(name.begin(), name.end(), is_token_char)) return bad(400, "Bad Request");
    std::string_view value = h.substr(colon + 1);
    while (!value.empty() && (value.front() == ' ' || value.front() == '\t')) value.remove_prefix(1);
    while (!value.empty() && (value.back() == ' ' || value.back() == '\t')) value.remove_suffix(1);
    const bool is_host = name.size() == 4 && std::equal(name.begin(), name.end(), "host", [](char a, char b) {
                           return std::tolower(static_cast<unsigned char>(a)) == b;
                         });
    if (is_host) {
      ++hosts;
      host = value;
    }
  }
  if (hosts > 1 || (hosts == 0 && version == "HTTP/1.1")) return bad(400, "Bad Request");
  if (hosts == 1) {
    const std::string with_port = ":" + std::to_string(port);
    std::string_view name = host;
    if (name.size() > with_port.size() && name.substr(name.size() - with_port.size()) == with_port) {
      name.remove_suffix(with_port.size());
    }
    if (name != "127.0.0.1" && name != "localhost") return bad(400, "Bad Request");
  }
  if (method != "GET" && method != "HEAD") return bad(405, "Method Not Allowed");
  // The path: up to '?' (a fragment is never sent, but '#' ends it too), percent-decoded.
  const std::string_view raw = target.substr(0, target.find_first_of("?#"));
  std::string path;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '%') {
      path += raw[i];
      continue;
    }
    if (i + 2 >= raw.size() || hex_value(raw[i + 1]) < 0 || hex_value(raw[i + 2]) < 0) return bad(400, "Bad Request");
    path += static_cast<char>(hex_value(raw[i + 1]) * 16 + hex_value(raw[i + 2]));
    i += 2;
  }
  Request r;
  r.method = std::string(method);
  r.path = std::move(path);
  return r;
}

// The file name a decoded path asks for, or "" for 404: "/" is index.html; otherwise "/NAME" with NAME of
// [A-Za-z0-9._-], not starting with '.' (no dotfiles, no "..", no folders: the site is flat).
std::string site_file_name(const std::string& path) {
  if (path == "/") return "index.html";
  if (path.size() < 2 || path.size() > 256 || path.front() != '/') return {};
  const std::string name = path.substr(1);
  if (name.front() == '.') return {};
  for (const char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '.' && c != '_' && c != '-') return {};
  }
  return name;
}


}  // namespace shadelab::explore
