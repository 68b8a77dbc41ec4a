// Fuzz harness: load_mesh on a glTF JSON file and, after the separator, an external buffer buffer.bin (mesh_harness.h).
#include "mesh_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shadelab::fuzz::fuzz_mesh("gltf", ".gltf", "buffer.bin", data, size);
}
