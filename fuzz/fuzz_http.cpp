// Fuzz harness: the request head parser of `shadelab explore --serve` (explore::parse_request) and the file
// name a path maps to (explore::site_file_name). Contract checked (site.h): nothing throws; a request to
// answer is GET or HEAD with a path that starts with '/'; an error is 400, 405 or 414 with its reason; the
// file asked for is "" (404), index.html, or a flat name of [A-Za-z0-9._-] that does not start with '.' and
// is at most 255 bytes: never a folder, "..", a dotfile or a byte outside that set (path traversal, encoded
// dots, NUL).
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <string>

#include "harness.h"
#include "http_request.h"

using namespace shadelab;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view head = fuzz::as_text(data, size);
  const explore::HttpRequest r = explore::parse_request(head, 8123);
  if (r.status != 0) {
    const bool known = (r.status == 400 && r.reason == "Bad Request") || (r.status == 405 && r.reason == "Method Not Allowed") ||
                       (r.status == 414 && r.reason == "URI Too Long");
    if (!known) fuzz::finding("an unexpected status", std::to_string(r.status) + " " + r.reason);
    return 0;
  }
  if (r.method != "GET" && r.method != "HEAD") fuzz::finding("a method answered", r.method);
  if (r.path.empty() || r.path.front() != '/') fuzz::finding("a path not starting with '/'", r.path);
  const std::string name = explore::site_file_name(r.path);
  if (name.empty() || name == "index.html") return 0;
  if (name.size() > 255 || name.front() == '.') fuzz::finding("a file name served", name);
  for (const char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '.' && c != '_' && c != '-') fuzz::finding("a file name served", name);
  }
  if (r.path != "/" + name) fuzz::finding("the name is not the path", r.path + " -> " + name);
  return 0;
}
