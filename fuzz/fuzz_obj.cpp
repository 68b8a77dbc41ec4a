// Fuzz harness: load_mesh on an OBJ file and, after the separator, its mtllib mesh.mtl (mesh_harness.h).
#include "mesh_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shadelab::fuzz::fuzz_mesh("obj", ".obj", "mesh.mtl", data, size);
}
