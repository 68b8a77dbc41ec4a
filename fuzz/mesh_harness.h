// The mesh harnesses' shared body (fuzz_obj.cpp, fuzz_gltf.cpp, fuzz_glb.cpp): one input holds the mesh
// file and, after fuzz::file_separator, a second file beside it (the OBJ's mesh.mtl, the glTF's
// buffer.bin). Contract checked (mesh_io.h): an error is one printable line that starts with the file's
// path; a mesh has triangles, every index in range, finite positions, normals of unit length and uvs
// finite, each either absent or one per vertex, and at most max_scene_triangles triangles.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "harness.h"
#include "shadelab/scene/limits.h"
#include "shadelab/scene/mesh_io.h"

namespace shadelab::fuzz {

inline void check_mesh_contract(const MeshShape& mesh) {
  if (mesh.indices.empty() || mesh.indices.size() % 3 != 0) {
    finding("mesh without whole triangles", std::to_string(mesh.indices.size()) + " indices");
  }
  if (mesh.indices.size() / 3 > max_scene_triangles) finding("mesh beyond the triangle limit", "");
  for (std::uint32_t i : mesh.indices) {
    if (i >= mesh.positions.size()) finding("index out of range", std::to_string(i));
  }
  for (const Vec3& p : mesh.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) finding("non-finite position", "");
  }
  if (!mesh.normals.empty()) {
    if (mesh.normals.size() != mesh.positions.size()) finding("normals not one per vertex", "");
    for (const Vec3& n : mesh.normals) {
      const double len = length(n);
      if (!(std::abs(len - 1.0) < 1e-6)) finding("normal not of unit length", std::to_string(len));
    }
  }
  if (!mesh.uvs.empty()) {
    if (mesh.uvs.size() != mesh.positions.size()) finding("uvs not one per vertex", "");
    for (const Vec2& t : mesh.uvs) {
      if (!std::isfinite(t.x) || !std::isfinite(t.y)) finding("non-finite uv", "");
    }
  }
}

// Writes the input as <work>/<name>/mesh<extension> (plus <second_name> when the input has a second file)
// and loads it.
inline int fuzz_mesh(const char* name, const char* extension, const char* second_name, const std::uint8_t* data,
                     std::size_t size) {
  static const std::filesystem::path dir = [name] {
    const auto d = work_dir(name) / "mesh";
    std::filesystem::create_directories(d);
    return d;
  }();
  const auto [first, second] = split_files(as_text(data, size));
  const std::filesystem::path file = dir / (std::string("mesh") + extension);
  const std::filesystem::path other = dir / second_name;
  write_file(file, first);
  std::error_code ec;
  std::filesystem::remove(other, ec);
  if (!second.empty()) write_file(other, second);
  auto mesh = load_mesh(file);
  if (!mesh) {
    require_one_line(mesh.error().message, file.string());
    if (mesh.error().message.rfind(file.string(), 0) != 0) finding("message does not start with the file", mesh.error().message);
    return 0;
  }
  check_mesh_contract(*mesh);
  return 0;
}

}  // namespace shadelab::fuzz
