// The explorer's static site (docs/explorer.md): the embedded page files (web/, and the WebAssembly module
// shadelab_wasm.js built from the library) written to a folder, and a small HTTP server that serves that
// folder on 127.0.0.1.
//
// Contract:
// - embedded_assets(): every file of the site by name (index.html first is not implied; names are plain
//   file names without folders).
// - write_site(dir, options): creates dir (and parents) and writes every asset into it, each file atomically
//   (a temporary file renamed over the target, image/image_io.h), and the sphere's environments: every
//   lat-long map NAME.exr of options.env_dir (NAME of [a-z0-9_-], sorted) baked by the game renderer's own
//   bake (render/game_renderer.h bake_game_environment: the radiance cube point-sampled at options.env_size,
//   its SH9 and the prefiltered specular chain of options.env_size) into env-NAME.js, and environments.js,
//   the list (names, the default, the sizes, and a message when there are none: the folder missing, as
//   without Debian's blender-data, or no map in it; a map that fails to read or bake is skipped and named in
//   `problems`). Returns the paths written, the names baked, the message and the bake's seconds. An existing
//   file of the same name is replaced; other files in dir are left alone. A missing folder is not an error.
//   env-NAME.js sets window.shadelabEnvironmentData[NAME] to {name, file, size, specular_size, gloss_scale,
//   gloss_bias, exponents, sh (9 x [r, g, b], radiance units), width, height, blocks ([{size, row}]: block 0
//   the radiance cube, block 1 + i the Phong chain's level i, block ggx_first_block + i the GGX chain's level
//   i; face f of a block is the rows row + f size .. row + (f + 1) size - 1, its texels the first size
//   columns), texels (base64 of width x height RGB float32, little-endian, row-major, unused texels 0),
//   split_sum {ggx_first_block, ggx_levels, ggx_mapping, dfg_size, dfg, lobe_size, lobes} (the split sum's
//   tables as the renderer reads them: base64 RGBA float32, row-major)}; environments.js sets
//   window.shadelabEnvironments.
// - serve_site(dir, port, on_ready): listens on 127.0.0.1:port only (0 picks a free port), calls
//   on_ready(port) once listening, then answers GET and HEAD requests for the regular files directly in dir
//   ("/" is index.html) until the process ends. Returns an Error when the folder cannot be opened or the port
//   cannot be bound. Hardened for any local process as a client (issue 40): the request line is parsed
//   without anything that can throw (malformed: 400; the server goes on); HTTP/1.1 needs a Host of 127.0.0.1
//   or localhost (with this port, if any), else 400 (DNS rebinding); methods other than GET and HEAD get 405
//   with Allow; the path is percent-decoded and must then be "/" or "/NAME" with NAME of [A-Za-z0-9._-] not
//   starting with '.', opened in dir with O_NOFOLLOW and a regular file, else 404 (no traversal, no encoded
//   dots, no dotfiles, no symbolic links, no folders); a request head beyond 8 KiB gets 431, a request line
//   beyond 2 KiB 414; a connection idle for 5 s, or without a whole head within 10 s, gets 408 and is closed;
//   connections are served at once, each on its own thread, at most 32 at a time (one more gets 503); a
//   file is streamed in 64 KiB pieces; every response closes its connection.
#pragma once

#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "shadelab/core/error.h"

namespace shadelab::explore {

struct Asset {
  std::string_view name;
  std::string_view bytes;
};

std::span<const Asset> embedded_assets();

struct SiteOptions {
  std::filesystem::path env_dir = "/usr/share/blender/datafiles/studiolights/world";  // Debian's blender-data
  int env_size = 32;                  // face size of the baked cubes (a power of two)
  std::string default_env = "forest";  // the page's default map (the first name when absent)
};

struct SiteReport {
  std::vector<std::filesystem::path> written;
  std::vector<std::string> environments;  // the maps baked
  std::string env_message;                // why there are none (empty when there are)
  std::vector<std::string> env_problems;  // maps skipped, one line each
  double bake_seconds = 0.0;
};

Result<SiteReport> write_site(const std::filesystem::path& dir, const SiteOptions& options = {});

Result<bool> serve_site(const std::filesystem::path& dir, int port, const std::function<void(int)>& on_ready);

// The Content-Type the server sends for a file name.
std::string_view content_type(std::string_view name);

}  // namespace shadelab::explore
