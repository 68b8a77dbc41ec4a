// The explorer's static site (docs/explorer.md): the embedded page files (web/, and the WebAssembly module
// shadelab_wasm.js built from the library) written to a folder, and a small HTTP server that serves that
// folder on 127.0.0.1.
//
// Contract:
// - embedded_assets(): every file of the site by name (index.html first is not implied; names are plain
//   file names without folders).
// - write_site(dir): creates dir (and parents) and writes every asset into it, each file atomically (a
//   temporary file renamed over the target, image/image_io.h); returns the paths written. An existing file
//   of the same name is replaced; other files in dir are left alone.
// - serve_site(dir, port, on_ready): listens on 127.0.0.1:port (0 picks a free port), calls on_ready(port)
//   once listening, then answers GET and HEAD requests for the files directly in dir ("/" is index.html)
//   until the process ends; other paths get 404, other methods 405. Returns an Error when the port cannot be
//   bound. One request at a time; no path outside dir is ever read (no '/' or ".." inside a name).
#pragma once

#include <filesystem>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "shadelab/core/error.h"

namespace shadelab::explore {

struct Asset {
  std::string_view name;
  std::string_view bytes;
};

std::span<const Asset> embedded_assets();

Result<std::vector<std::filesystem::path>> write_site(const std::filesystem::path& dir);

Result<bool> serve_site(const std::filesystem::path& dir, int port, const std::function<void(int)>& on_ready);

// The Content-Type the server sends for a file name.
std::string_view content_type(std::string_view name);

}  // namespace shadelab::explore
