// The request head parser of `shadelab explore --serve` (site.cpp's serve_site), in a file of its own so that
// the libFuzzer harness fuzz/fuzz_http.cpp and tests link it without the explorer's page and WebAssembly.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace shadelab::explore {

// The longest request line the server reads (longer: 414).
inline constexpr std::size_t max_request_line_bytes = 2048;

// status 0 is a request to answer: method GET or HEAD, path percent-decoded without its query or fragment.
// Otherwise the error status and its reason: 400 Bad Request, 405 Method Not Allowed, 414 URI Too Long.
struct HttpRequest {
  int status = 0;
  std::string reason;
  std::string method;
  std::string path;
};

// The request line and the headers of one head (up to the empty line), without anything that can throw on
// malformed input: "METHOD SP /TARGET SP HTTP/1.x", then "Name: value" lines; HTTP/1.1 needs one Host of
// 127.0.0.1 or localhost, with `port` if it has one (a page from another name, as by DNS rebinding, gets 400).
HttpRequest parse_request(std::string_view head, int port);

// The file of the (flat) site a decoded path asks for, or "" for 404: "/" is index.html; otherwise "/NAME"
// with NAME of [A-Za-z0-9._-], not starting with '.' (no dotfiles, no "..", no folders), at most 255 bytes.
std::string site_file_name(const std::string& path);

}  // namespace shadelab::explore
