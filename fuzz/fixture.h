// The small files a fuzzed scene or command line may name, written into a harness's work folder: the
// example meshes (scenes/meshes), a 32 x 16 lat-long environment as env.hdr, env.exr and env.png, an 8 x 8
// texture tex.png, a 4:3 cube cross cross.exr and a one-sphere scene small.json. The seed corpora of the
// scene and CLI harnesses name these files.
#pragma once

#include <filesystem>

namespace shadelab::fuzz {

void write_fixture(const std::filesystem::path& dir);

}  // namespace shadelab::fuzz
