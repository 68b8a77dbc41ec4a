#include "shadelab/scene/mesh_io.h"
#include "shadelab/scene/limits.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadelab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("shadelab_mesh_io_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

fs::path write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

void expect_vec(const Vec3& a, const Vec3& b, double tol = 1e-6) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// ---- OBJ ----

TEST(MeshIo, ObjQuadWithNormalsAndUvs) {
  const fs::path dir = temp_dir("obj_quad");
  const fs::path file = write_text(dir / "quad.obj",
                                   "# a unit quad in z = 0\n"
                                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 0.25\n"
                                   "vn 0 0 2\n"
                                   "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
  auto mesh = load_obj(file);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->source, file.string());
  ASSERT_EQ(mesh->indices.size(), 6u);  // the quad is triangulated as a fan: 2 triangles
  ASSERT_EQ(mesh->positions.size(), 4u);
  ASSERT_EQ(mesh->normals.size(), 4u);
  ASSERT_EQ(mesh->uvs.size(), 4u);
  for (const auto& n : mesh->normals) expect_vec(n, {0.0, 0.0, 1.0}, 1e-12);  // normalized
  // The two triangles cover the unit square, keep the face's counter-clockwise winding (+Z) and use
  // all four corners.
  double area = 0.0;
  for (std::size_t t = 0; t < 6; t += 3) {
    const Vec3 a = mesh->positions[mesh->indices[t]];
    const Vec3 c = cross(mesh->positions[mesh->indices[t + 1]] - a, mesh->positions[mesh->indices[t + 2]] - a);
    EXPECT_GT(c.z, 0.0);
    area += 0.5 * length(c);
  }
  EXPECT_NEAR(area, 1.0, 1e-12);
  std::vector<std::uint32_t> used(mesh->indices.begin(), mesh->indices.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  EXPECT_EQ(used.size(), 4u);
  // Find the corner at (0, 1, 0), whose vt is (0, 0.25).
  std::size_t corner = 4;
  for (std::size_t i = 0; i < 4; ++i) {
    if (mesh->positions[i].x == 0.0 && mesh->positions[i].y == 1.0) corner = i;
  }
  ASSERT_LT(corner, 4u);
  // OBJ's vt has v up; shadelab's (glTF's) has v down: vt (0, 0.25) -> uv (0, 0.75).
  EXPECT_NEAR(mesh->uvs[corner].x, 0.0, 1e-7);
  EXPECT_NEAR(mesh->uvs[corner].y, 0.75, 1e-7);
}

TEST(MeshIo, ObjVerticesAreDistinctIndexTriples) {
  const fs::path dir = temp_dir("obj_triples");
  // Two triangles sharing an edge; the shared corners have different normals in the two faces.
  const fs::path file = write_text(dir / "fold.obj",
                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                   "vn 0 0 1\nvn 1 0 0\n"
                                   "f 1//1 2//1 3//1\n"
                                   "f 2//2 4//2 3//2\n");
  auto mesh = load_obj(file);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->positions.size(), 6u);
  EXPECT_TRUE(mesh->uvs.empty());
  ASSERT_EQ(mesh->normals.size(), 6u);
  expect_vec(mesh->normals[mesh->indices[3]], {1, 0, 0});

  // The same corners with the same normal are shared.
  const fs::path shared = write_text(dir / "shared.obj",
                                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\n"
                                     "f 1//1 2//1 3//1\nf 2//1 4//1 3//1\n");
  auto m2 = load_obj(shared);
  ASSERT_TRUE(m2) << m2.error().message;
  EXPECT_EQ(m2->positions.size(), 4u);
  EXPECT_EQ(m2->indices.size(), 6u);
}

TEST(MeshIo, ObjNormalsOnlyWhenEveryCornerHasOne) {
  const fs::path dir = temp_dir("obj_mixed");
  const fs::path file = write_text(dir / "mixed.obj",
                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\n"
                                   "f 1//1 2//1 3//1\nf 2 4 3\n");
  auto mesh = load_obj(file);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_TRUE(mesh->normals.empty());
  EXPECT_EQ(mesh->positions.size(), 4u);
}

TEST(MeshIo, ObjErrorsNameTheFile) {
  const fs::path dir = temp_dir("obj_errors");
  const fs::path bad = write_text(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  auto r = load_obj(bad);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, bad.string() + ": a face refers to vertex 9 of 3");

  const fs::path empty = write_text(dir / "empty.obj", "# nothing\nv 0 0 0\n");
  auto e = load_obj(empty);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().message, empty.string() + ": the mesh has no triangles");

  auto unknown = load_mesh(dir / "x.ply");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().message,
            (dir / "x.ply").string() + ": unknown mesh format '.ply' (expected .obj, .gltf or .glb)");

  auto missing = load_mesh(dir / "missing.obj");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message.rfind((dir / "missing.obj").string() + ": cannot read OBJ", 0), 0u)
      << missing.error().message;
}

// ---- glTF ----

// Builds a glTF document with one buffer from typed arrays.
class GltfWriter {
 public:
  template <typename T>
  int add(const std::vector<T>& values, int component_type, int count, const char* type, bool normalized = false) {
    while (m_bin.size() % 4 != 0) m_bin.push_back(0);
    const std::size_t offset = m_bin.size();
    const std::size_t bytes = values.size() * sizeof(T);
    m_bin.resize(offset + bytes);
    std::memcpy(m_bin.data() + offset, values.data(), bytes);
    m_views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    json accessor = {
        {"bufferView", m_views.size() - 1}, {"componentType", component_type}, {"count", count}, {"type", type}};
    if (normalized) accessor["normalized"] = true;
    m_accessors.push_back(accessor);
    return static_cast<int>(m_accessors.size() - 1);
  }

  json document(const json& nodes, const json& meshes, const json& scenes) const {
    json doc = {{"asset", {{"version", "2.0"}}},
                {"nodes", nodes},
                {"meshes", meshes},
                {"accessors", m_accessors},
                {"bufferViews", m_views}};
    if (!scenes.is_null()) {
      doc["scenes"] = scenes;
      doc["scene"] = 0;
    }
    return doc;
  }

  // .gltf with the buffer in a .bin file beside it.
  void write_gltf(const fs::path& path, json doc) const {
    const fs::path bin = fs::path(path).replace_extension(".bin");
    std::ofstream(bin, std::ios::binary)
        .write(reinterpret_cast<const char*>(m_bin.data()), static_cast<std::streamsize>(m_bin.size()));
    doc["buffers"] = json::array({{{"byteLength", m_bin.size()}, {"uri", bin.filename().string()}}});
    write_text(path, doc.dump(1));
  }

  // .glb: 12-byte header, a JSON chunk and a BIN chunk, each padded to 4 bytes (glTF 2.0, section 4.4).
  void write_glb(const fs::path& path, json doc) const {
    doc["buffers"] = json::array({{{"byteLength", m_bin.size()}}});
    std::string text = doc.dump();
    while (text.size() % 4 != 0) text += ' ';
    std::vector<unsigned char> bin = m_bin;
    while (bin.size() % 4 != 0) bin.push_back(0);
    std::vector<unsigned char> out;
    auto u32 = [&out](std::uint32_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
    };
    u32(0x46546C67);  // "glTF"
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    u32(static_cast<std::uint32_t>(text.size()));
    u32(0x4E4F534A);  // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    u32(static_cast<std::uint32_t>(bin.size()));
    u32(0x004E4942);  // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
  }

 private:
  std::vector<unsigned char> m_bin;
  json m_accessors = json::array();
  json m_views = json::array();
};

constexpr int k_float = 5126;
constexpr int k_ubyte = 5121;
constexpr int k_ushort = 5123;
constexpr int k_uint = 5125;

// One triangle in z = 0 with normals +Z and uvs; the index accessor's component type is a parameter.
GltfWriter triangle(int index_type, std::vector<int>* accessors) {
  GltfWriter w;
  const int pos = w.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}, k_float, 3, "VEC3");
  const int nor = w.add(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}, k_float, 3, "VEC3");
  const int uv = w.add(std::vector<float>{0, 0, 1, 0, 0.5f, 1}, k_float, 3, "VEC2");
  int idx = -1;
  if (index_type == k_ubyte) idx = w.add(std::vector<std::uint8_t>{0, 1, 2}, k_ubyte, 3, "SCALAR");
  if (index_type == k_ushort) idx = w.add(std::vector<std::uint16_t>{0, 1, 2}, k_ushort, 3, "SCALAR");
  if (index_type == k_uint) idx = w.add(std::vector<std::uint32_t>{0, 1, 2}, k_uint, 3, "SCALAR");
  *accessors = {pos, nor, uv, idx};
  return w;
}

json primitive(const std::vector<int>& a, int mode = 4) {
  json p = {{"attributes", {{"POSITION", a[0]}, {"NORMAL", a[1]}, {"TEXCOORD_0", a[2]}}}, {"mode", mode}};
  if (a[3] >= 0) p["indices"] = a[3];
  return p;
}

TEST(MeshIo, GltfEveryIndexComponentType) {
  const fs::path dir = temp_dir("gltf_index_types");
  for (int type : {k_ubyte, k_ushort, k_uint, 0}) {
    std::vector<int> a;
    const GltfWriter w = triangle(type, &a);
    const json doc = w.document(json::array({{{"mesh", 0}}}), json::array({{{"primitives", {primitive(a)}}}}),
                                json::array({{{"nodes", {0}}}}));
    const fs::path file = dir / ("tri" + std::to_string(type) + ".gltf");
    w.write_gltf(file, doc);
    auto mesh = load_gltf(file);
    ASSERT_TRUE(mesh) << mesh.error().message;
    ASSERT_EQ(mesh->indices, (std::vector<std::uint32_t>{0, 1, 2})) << "index type " << type;
    ASSERT_EQ(mesh->positions.size(), 3u);
    expect_vec(mesh->positions[1], {1, 0, 0});
    ASSERT_EQ(mesh->normals.size(), 3u);
    expect_vec(mesh->normals[2], {0, 0, 1});
    ASSERT_EQ(mesh->uvs.size(), 3u);
    EXPECT_NEAR(mesh->uvs[2].x, 0.5, 1e-7);  // glTF uvs are taken as they are (top-left origin)
    EXPECT_NEAR(mesh->uvs[2].y, 1.0, 1e-7);
  }
}

TEST(MeshIo, GlbAndNormalizedTexcoords) {
  const fs::path dir = temp_dir("glb");
  GltfWriter w;
  const int pos = w.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}, k_float, 3, "VEC3");
  const int uv = w.add(std::vector<std::uint8_t>{0, 0, 255, 51, 0, 255}, k_ubyte, 3, "VEC2", true);
  const json prim = {{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}};  // no mode: triangles
  const json doc = w.document(json::array({{{"mesh", 0}}}), json::array({{{"primitives", {prim}}}}), json());
  const fs::path file = dir / "tri.glb";
  w.write_glb(file, doc);
  auto mesh = load_mesh(file);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->indices, (std::vector<std::uint32_t>{0, 1, 2}));  // no indices: sequential
  EXPECT_TRUE(mesh->normals.empty());
  ASSERT_EQ(mesh->uvs.size(), 3u);
  EXPECT_NEAR(mesh->uvs[1].x, 1.0, 1e-12);  // 255 / 255
  EXPECT_NEAR(mesh->uvs[1].y, 0.2, 1e-12);  // 51 / 255
}

TEST(MeshIo, GltfNodeTransformsParentsFirst) {
  const fs::path dir = temp_dir("gltf_nodes");
  std::vector<int> a;
  const GltfWriter w = triangle(k_ushort, &a);
  const double s = std::sqrt(0.5);
  // Parent: scale 2 then translate (1, 2, 3); child: 90 degrees about +Z, carries the mesh.
  const json nodes = json::array({{{"children", {1}}, {"translation", {1, 2, 3}}, {"scale", {2, 2, 2}}},
                                  {{"mesh", 0}, {"rotation", {0, 0, s, s}}}});
  const json doc = w.document(nodes, json::array({{{"primitives", {primitive(a)}}}}), json::array({{{"nodes", {0}}}}));
  const fs::path file = dir / "nodes.gltf";
  w.write_gltf(file, doc);
  auto mesh = load_gltf(file);
  ASSERT_TRUE(mesh) << mesh.error().message;
  expect_vec(mesh->positions[0], {1, 2, 3});
  expect_vec(mesh->positions[1], {1, 4, 3});  // (1,0,0) -> rotate (0,1,0) -> scale (0,2,0) -> translate
  expect_vec(mesh->positions[2], {-1, 2, 3});
  expect_vec(mesh->normals[0], {0, 0, 1});

  // A column-major matrix that mirrors x: the winding is reversed so the triangle still faces +Z.
  const json mirror = json::array({{{"mesh", 0}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1}}}});
  const fs::path mfile = dir / "mirror.gltf";
  w.write_gltf(mfile,
               w.document(mirror, json::array({{{"primitives", {primitive(a)}}}}), json::array({{{"nodes", {0}}}})));
  auto m = load_gltf(mfile);
  ASSERT_TRUE(m) << m.error().message;
  expect_vec(m->positions[1], {4, 0, 0});
  EXPECT_EQ(m->indices, (std::vector<std::uint32_t>{0, 2, 1}));
  const Vec3 e1 = m->positions[m->indices[1]] - m->positions[m->indices[0]];
  const Vec3 e2 = m->positions[m->indices[2]] - m->positions[m->indices[0]];
  EXPECT_GT(cross(e1, e2).z, 0.0);
}

TEST(MeshIo, GltfErrors) {
  const fs::path dir = temp_dir("gltf_errors");
  std::vector<int> a;
  const GltfWriter w = triangle(k_ushort, &a);
  const fs::path lines = dir / "lines.gltf";
  w.write_gltf(lines, w.document(json::array({{{"mesh", 0}}}), json::array({{{"primitives", {primitive(a, 1)}}}}),
                                 json::array({{{"nodes", {0}}}})));
  auto r = load_gltf(lines);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, lines.string() + ": mesh 0 primitive 0: mode 1 is not a triangle list (mode 4)");

  // Normals given as unsigned shorts are not allowed.
  GltfWriter w2;
  const int pos = w2.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}, k_float, 3, "VEC3");
  const int nor = w2.add(std::vector<std::uint16_t>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0}, k_ushort, 3, "VEC3");
  const json prim = {{"attributes", {{"POSITION", pos}, {"NORMAL", nor}}}};
  const fs::path bad = dir / "bad_normals.gltf";
  w2.write_gltf(bad, w2.document(json::array({{{"mesh", 0}}}), json::array({{{"primitives", {prim}}}}),
                                 json::array({{{"nodes", {0}}}})));
  auto b = load_gltf(bad);
  ASSERT_FALSE(b);
  EXPECT_EQ(
      b.error().message,
      bad.string() + ": mesh 0 primitive 0 NORMAL (accessor 1): component type unsigned short is not supported here");

  const fs::path broken = write_text(dir / "broken.gltf", "{ not json");
  auto c = load_gltf(broken);
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error().message.rfind(broken.string() + ": cannot read glTF", 0), 0u) << c.error().message;
  EXPECT_EQ(c.error().message.find('\n'), std::string::npos);
}

// ---- transforms ----

TEST(MeshIo, TransformScaleRotateTranslate) {
  MeshShape mesh;
  mesh.positions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.normals = {{1, 1, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.normals[0] = normalize(mesh.normals[0]);
  mesh.indices = {0, 1, 2};
  // Scale (2, 1, 1), then 90 degrees about +Y (x -> -z), then translate (0, 0, 10).
  transform_mesh(mesh, make_mesh_transform({0, 0, 10}, {0, 1, 0}, 90.0, {2, 1, 1}));
  expect_vec(mesh.positions[0], {0, 0, 8}, 1e-12);
  expect_vec(mesh.positions[1], {0, 1, 10}, 1e-12);
  expect_vec(mesh.positions[2], {1, 0, 10}, 1e-12);
  // Normals go through the inverse transpose: the plane x + y = c scaled by 2 in x has normal (1/2, 1, 0).
  expect_vec(mesh.normals[0], Vec3{0.0, 1.0, -0.5} / std::sqrt(1.25), 1e-12);
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));

  // A mirroring transform reverses the winding.
  transform_mesh(mesh, make_mesh_transform({}, {0, 1, 0}, 0.0, {-1, 1, 1}));
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 2, 1}));
}

TEST(MeshIo, ExampleMeshes) {
  auto ico = load_mesh(fs::path(SHADELAB_SCENES_DIR) / "meshes" / "icosahedron.obj");
  ASSERT_TRUE(ico) << ico.error().message;
  EXPECT_EQ(ico->positions.size(), 12u);
  EXPECT_EQ(ico->indices.size(), 60u);
  // Every face winds counter-clockwise seen from outside: its normal points away from the centre.
  for (std::size_t t = 0; t < ico->indices.size(); t += 3) {
    const Vec3 a = ico->positions[ico->indices[t]];
    const Vec3 b = ico->positions[ico->indices[t + 1]];
    const Vec3 c = ico->positions[ico->indices[t + 2]];
    EXPECT_GT(dot(cross(b - a, c - a), a + b + c), 0.0);
    EXPECT_NEAR(length(a), 1.0, 1e-6);  // OBJ coordinates are read as floats
  }
  auto box = load_mesh(fs::path(SHADELAB_SCENES_DIR) / "meshes" / "box.gltf");
  ASSERT_TRUE(box) << box.error().message;
  EXPECT_EQ(box->positions.size(), 24u);
  EXPECT_EQ(box->indices.size(), 36u);
  ASSERT_EQ(box->normals.size(), 24u);
  ASSERT_EQ(box->uvs.size(), 24u);
  for (std::size_t t = 0; t < box->indices.size(); t += 3) {
    const Vec3 a = box->positions[box->indices[t]];
    const Vec3 b = box->positions[box->indices[t + 1]];
    const Vec3 c = box->positions[box->indices[t + 2]];
    const Vec3 n = box->normals[box->indices[t]];
    EXPECT_NEAR(dot(normalize(cross(b - a, c - a)), n), 1.0, 1e-6);  // winding agrees with the normal
    EXPECT_NEAR(std::abs(dot(a, n)), 0.5, 1e-6);                     // on the face of the unit cube
  }
}

// ---- bad input that used to crash, hang or exhaust memory (issue 16) ----

// A chain of 100,000 nodes, each the only child of the one before, the last with the triangle: the
// recursive visit overflowed the stack (SIGSEGV). The chain is a valid file and loads.
TEST(MeshIoLimits, DeepNodeChainLoadsWithoutRecursion) {
  const fs::path dir = temp_dir("deep_chain");
  std::vector<int> a;
  const GltfWriter w = triangle(k_ushort, &a);
  const int n = 100000;
  json nodes = json::array();
  for (int i = 0; i < n; ++i) {
    json node = {{"translation", {0.0, 1e-5, 0.0}}};
    if (i + 1 < n) node["children"] = {i + 1};
    if (i + 1 == n) node["mesh"] = 0;
    nodes.push_back(node);
  }
  const fs::path file = dir / "chain.gltf";
  w.write_gltf(file, w.document(nodes, json::array({{{"primitives", {primitive(a)}}}}), json::array({{{"nodes", {0}}}})));
  auto mesh = load_gltf(file);
  ASSERT_TRUE(mesh) << mesh.error().message;
  ASSERT_EQ(mesh->positions.size(), 3u);
  // Every node's translation is applied: 100,000 x 1e-5 = 1 up.
  EXPECT_NEAR(mesh->positions[0].y, 1.0, 1e-6);
}

// 20 nodes, each listing the next 8 times: 8^19 instances from a 3 KB file ran for ever and grew to
// gigabytes. The visit count is bounded (limits.h): a clean error, at once.
TEST(MeshIoLimits, NodeDagInstancesAreBounded) {
  const fs::path dir = temp_dir("dag");
  std::vector<int> a;
  const GltfWriter w = triangle(k_ushort, &a);
  json nodes = json::array();
  for (int i = 0; i < 20; ++i) {
    json node = {{"mesh", 0}};
    if (i + 1 < 20) node["children"] = std::vector<int>(8, i + 1);
    nodes.push_back(node);
  }
  const fs::path file = dir / "dag.gltf";
  w.write_gltf(file, w.document(nodes, json::array({{{"primitives", {primitive(a)}}}}), json::array({{{"nodes", {0}}}})));
  ASSERT_LT(fs::file_size(file), 4000u);
  auto mesh = load_gltf(file);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message.rfind(file.string() + ": ", 0), 0u) << mesh.error().message;
  EXPECT_NE(mesh.error().message.find("instances more than"), std::string::npos) << mesh.error().message;
}

// A glTF whose JSON arrays are huge (issue 40): tinygltf builds some 575 bytes for each empty node, so a
// 1 GiB file of "{}," asked for 200 GB (an abort through std::bad_alloc, or the OOM killer). The JSON's
// values are counted before tinygltf parses (limits.h max_gltf_json_values): one line naming the file, at
// once. A file just inside the bound loads.
TEST(MeshIoLimits, GltfJsonValuesAreBoundedBeforeParsing) {
  const fs::path dir = temp_dir("many_values");
  std::vector<int> a;
  const GltfWriter w = triangle(k_ushort, &a);
  const auto write = [&](std::size_t empty_nodes, const std::string& name) {
    json nodes = json::array({{{"mesh", 0}}});
    for (std::size_t i = 0; i < empty_nodes; ++i) nodes.push_back(json::object());
    const fs::path file = dir / name;
    w.write_gltf(file, w.document(nodes, json::array({{{"primitives", {primitive(a)}}}}), json::array({{{"nodes", {0}}}})));
    return file;
  };
  const fs::path big = write(max_gltf_json_values / 2 + 1, "big.gltf");  // each "{}," counts two
  const auto t0 = std::chrono::steady_clock::now();
  auto mesh = load_gltf(big);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message, big.string() + ": the glTF JSON holds more than 1000000 values (objects, arrays "
                                                 "and their elements), more than a mesh file may");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0.5);  // nothing parsed
  auto ok = load_gltf(write(1000, "fine.gltf"));
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_EQ(ok->positions.size(), 3u);
}

// An index accessor whose count is near 2^63 wrapped the bounds check (stride x count overflowed) and threw
// from reserve (exit 3). Every overflowing count is a clean error naming the accessor.
TEST(MeshIoLimits, AccessorCountsNearTwoToThe63AreErrors) {
  const fs::path dir = temp_dir("huge_count");
  for (const std::uint64_t count : {std::uint64_t{1} << 62, (std::uint64_t{1} << 63) + 1, ~std::uint64_t{0} / 2 + 7}) {
    for (const int which : {0, 3}) {  // POSITION, indices
      std::vector<int> a;
      const GltfWriter w = triangle(k_ushort, &a);
      json doc = w.document(json::array({{{"mesh", 0}}}), json::array({{{"primitives", {primitive(a)}}}}),
                            json::array({{{"nodes", {0}}}}));
      doc["accessors"][a[static_cast<std::size_t>(which)]]["count"] = count;
      const fs::path file = dir / ("count" + std::to_string(which) + ".gltf");
      w.write_gltf(file, doc);
      auto mesh = load_gltf(file);
      ASSERT_FALSE(mesh) << count;
      EXPECT_EQ(mesh.error().message.rfind(file.string() + ": ", 0), 0u) << mesh.error().message;
      EXPECT_NE(mesh.error().message.find("accessor " + std::to_string(a[static_cast<std::size_t>(which)])),
                std::string::npos)
          << mesh.error().message;
    }
  }
}

// tinygltf converts "extras" to its own values by recursion: 100,000 nested arrays are refused first.
TEST(MeshIoLimits, DeeplyNestedGltfJsonIsAnError) {
  const fs::path dir = temp_dir("deep_json");
  std::vector<int> a;
  const GltfWriter w = triangle(k_ushort, &a);
  const fs::path file = dir / "deep.gltf";
  w.write_gltf(file, w.document(json::array({{{"mesh", 0}}}), json::array({{{"primitives", {primitive(a)}}}}),
                                json::array({{{"nodes", {0}}}})));
  std::ostringstream read;
  read << std::ifstream(file, std::ios::binary).rdbuf();
  std::string text = read.str();
  const auto brace = text.rfind('}');
  ASSERT_NE(brace, std::string::npos);
  text.insert(brace, ",\"extras\":" + std::string(100000, '[') + std::string(100000, ']'));
  write_text(file, text);
  auto mesh = load_gltf(file);
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.error().message.find("nested deeper than 64"), std::string::npos) << mesh.error().message;
}

// A buffer URI may name any file: it must be a regular file inside the glTF's folder tree.
TEST(MeshIoLimits, GltfBuffersOutsideTheFolderOrNotRegularAreRefused) {
  const fs::path dir = temp_dir("gltf_uri");
  fs::create_directories(dir / "model");
  std::vector<int> a;
  const GltfWriter w = triangle(k_ushort, &a);
  const json doc = w.document(json::array({{{"mesh", 0}}}), json::array({{{"primitives", {primitive(a)}}}}),
                              json::array({{{"nodes", {0}}}}));
  w.write_gltf(dir / "outside.gltf", doc);  // outside.bin beside it, one folder up from model/
  fs::create_symlink("/dev/zero", dir / "model" / "zero.bin");  // inside by name, /dev/zero in fact
  for (const std::string uri : {"../outside.bin", "zero.bin", "/dev/zero"}) {
    json d = doc;
    d["buffers"] = json::array({{{"byteLength", fs::file_size(dir / "outside.bin")}, {"uri", uri}}});
    const fs::path file = write_text(dir / "model" / "m.gltf", d.dump());
    auto mesh = load_gltf(file);
    ASSERT_FALSE(mesh) << uri;
    EXPECT_EQ(mesh.error().message.rfind(file.string() + ": ", 0), 0u) << mesh.error().message;
    // tinygltf looks "/dev/zero" up under the glTF's folder and does not find it; the others reach our check.
    if (uri != "/dev/zero") {
      EXPECT_NE(mesh.error().message.find("refused to read"), std::string::npos) << mesh.error().message;
    }
  }
  // Inside the folder tree it loads.
  fs::copy_file(dir / "outside.bin", dir / "model" / "inside.bin");
  json d = doc;
  d["buffers"] = json::array({{{"byteLength", fs::file_size(dir / "outside.bin")}, {"uri", "inside.bin"}}});
  auto mesh = load_gltf(write_text(dir / "model" / "m.gltf", d.dump()));
  EXPECT_TRUE(mesh) << mesh.error().message;
}

// tinyobjloader opened any mtllib, /dev/zero included (unbounded memory). Material files must be regular
// files inside the OBJ's folder tree, or the OBJ is refused; a missing one is ignored (materials are).
TEST(MeshIoLimits, ObjMtllibMustBeARegularFileInsideTheFolder) {
  const fs::path dir = temp_dir("mtllib");
  fs::create_directories(dir / "model");
  write_text(dir / "outside.mtl", "newmtl a\nKd 1 0 0\n");
  write_text(dir / "model" / "inside.mtl", "newmtl a\nKd 1 0 0\n");
  const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
  for (const std::string lib : {"/dev/zero", "../outside.mtl", "/etc/passwd"}) {
    const fs::path file = write_text(dir / "model" / "m.obj", "mtllib " + lib + "\n" + body);
    auto mesh = load_obj(file);
    ASSERT_FALSE(mesh) << lib;
    EXPECT_EQ(mesh.error().message.rfind(file.string() + ": refused mtllib", 0), 0u) << mesh.error().message;
  }
  for (const std::string lib : {"inside.mtl", "missing.mtl"}) {
    auto mesh = load_obj(write_text(dir / "model" / "m.obj", "mtllib " + lib + "\n" + body));
    ASSERT_TRUE(mesh) << lib << ": " << mesh.error().message;
    EXPECT_EQ(mesh->indices.size(), 3u);
  }
  // The mesh file itself must be a regular file.
  fs::create_directories(dir / "folder.obj");
  auto folder = load_obj(dir / "folder.obj");
  ASSERT_FALSE(folder);
  EXPECT_NE(folder.error().message.find("not a regular file"), std::string::npos) << folder.error().message;
}

// A glTF syntax error quoted the JSON around it, a whole base64 buffer included (1,163 bytes): messages are
// one printable line, cut (core/text.h).
TEST(MeshIoLimits, LibraryMessagesAreCutAndPrintable) {
  const fs::path dir = temp_dir("long_message");
  const std::string base64(5000, 'A');
  const fs::path file = write_text(dir / "bad.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"uri\": "
                                                    "\"data:application/octet-stream;base64," + base64 + "\"}\x01\x1b]");
  auto mesh = load_gltf(file);
  ASSERT_FALSE(mesh);
  const std::string& m = mesh.error().message;
  EXPECT_LT(m.size(), file.string().size() + 400) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos);
  EXPECT_TRUE(std::none_of(m.begin(), m.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; })) << m;
}

}  // namespace
}  // namespace shadelab
