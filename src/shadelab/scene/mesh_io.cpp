#include "shadelab/scene/mesh_io.h"

#include <tiny_gltf.h>
#include <tiny_obj_loader.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <new>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "shadelab/core/constants.h"
#include "shadelab/core/text.h"
#include "shadelab/scene/limits.h"

namespace shadelab {

namespace {

std::string one_line(std::string text) {
  // Library messages may hold several lines; the scene format promises one, printable and short (a glTF
  // syntax error quotes the JSON around it, base64 buffers included).
  std::string out;
  for (char c : text) {
    if (c == '\r') continue;
    out += c == '\n' ? std::string("; ") : std::string(1, c);
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  return printable(out, max_library_bytes);
}

// A mesh file or a file it names: it must be a regular file of at most `limit` bytes. Returns "" or why not.
std::string check_file(const std::filesystem::path& path, std::uintmax_t limit) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) return "no such file";
  if (!std::filesystem::is_regular_file(status)) return "not a regular file";
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return "cannot read its size: " + ec.message();
  if (size > limit) return "it has " + std::to_string(size) + " bytes, more than the limit of " + std::to_string(limit);
  return {};
}

// Is `path` inside the folder tree of `root` (both resolved through symbolic links and "..")?
bool inside_tree(const std::filesystem::path& root, const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path r = std::filesystem::weakly_canonical(root, ec);
  if (ec) return false;
  const std::filesystem::path p = std::filesystem::weakly_canonical(path, ec);
  if (ec) return false;
  auto ri = r.begin();
  auto pi = p.begin();
  for (; ri != r.end(); ++ri, ++pi) {
    if (ri->empty()) continue;  // a trailing separator
    if (pi == p.end() || *pi != *ri) return false;
  }
  return true;
}

// The whole file, after check_file; "" when it cannot be read (the caller says why).
bool read_whole(const std::filesystem::path& path, std::string& out) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const std::streamoff size = in.tellg();
  if (size < 0) return false;
  out.resize(static_cast<std::size_t>(size));
  in.seekg(0);
  return static_cast<bool>(in.read(out.data(), size));
}

Result<std::string> read_text(const std::filesystem::path& path, std::uintmax_t limit) {
  if (const std::string why = check_file(path, limit); !why.empty()) return make_error(why);
  std::string text;
  if (!read_whole(path, text)) return make_error("cannot read the file");
  return text;
}

// The nesting depth of JSON text ([ and { outside strings) and its values (each [ and { and each comma
// outside strings: at least the number of values tinygltf builds a structure for), the scan stopping as
// soon as the depth passes depth_limit or the values pass value_limit.
struct JsonShape {
  std::size_t depth = 0;
  std::uint64_t values = 0;
};
JsonShape json_shape(std::string_view text, std::size_t depth_limit, std::uint64_t value_limit) {
  std::size_t depth = 0;
  JsonShape shape;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      shape.depth = std::max(shape.depth, ++depth);
      if (shape.depth > depth_limit || ++shape.values > value_limit) return shape;
    } else if (c == ',') {
      if (++shape.values > value_limit) return shape;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return shape;
}

Error mesh_error(const std::filesystem::path& path, const std::string& message) {
  return make_error(path.string() + ": " + message);
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 r;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
    }
  }
  return r;
}

double determinant(const Mat3& a) {
  const auto& m = a.m;
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// (M^-1)^T = cofactor(M) / det(M): the matrix that maps normals (Cramer's rule).
Mat3 inverse_transpose(const Mat3& a) {
  const auto& m = a.m;
  const double inv_det = 1.0 / determinant(a);
  Mat3 c;
  c.m = {{{(m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv_det, (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * inv_det,
           (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv_det},
          {(m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv_det, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv_det,
           (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv_det},
          {(m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv_det, (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv_det,
           (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv_det}}};
  return c;
}

MeshTransform compose(const MeshTransform& outer, const MeshTransform& inner) {
  return {multiply(outer.linear, inner.linear), outer.linear.apply(inner.translate) + outer.translate};
}

// Normalizes the normals; drops them all when one cannot be normalized (zero, NaN or infinite).
void finish_normals(MeshShape& mesh) {
  for (auto& n : mesh.normals) {
    const double len = length(n);
    if (!(len > 0.0) || !std::isfinite(len)) {
      mesh.normals.clear();
      return;
    }
    n = n / len;
  }
}

Result<bool> check_mesh(const std::filesystem::path& path, const MeshShape& mesh) {
  if (mesh.indices.empty()) return mesh_error(path, "the mesh has no triangles");
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!is_finite(mesh.positions[i])) return mesh_error(path, "vertex " + std::to_string(i) + " is not finite");
  }
  for (std::size_t i = 0; i < mesh.uvs.size(); ++i) {
    if (!std::isfinite(mesh.uvs[i].x) || !std::isfinite(mesh.uvs[i].y)) {
      return mesh_error(path, "texture coordinate " + std::to_string(i) + " is not finite");
    }
  }
  for (std::uint32_t index : mesh.indices) {
    if (index >= mesh.positions.size()) {
      return mesh_error(path, "index " + std::to_string(index) + " is out of range (" +
                                  std::to_string(mesh.positions.size()) + " vertices)");
    }
  }
  return true;
}

// ---- OBJ ----------------------------------------------------------------------------------------------

struct CornerHash {
  std::size_t operator()(const std::array<int, 3>& k) const {
    std::uint64_t h = static_cast<std::uint32_t>(k[0]);
    h = h * 0x9e3779b97f4a7c15ULL ^ static_cast<std::uint32_t>(k[1]);
    h = h * 0x9e3779b97f4a7c15ULL ^ static_cast<std::uint32_t>(k[2]);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

// The OBJ's mtllib files: materials are ignored (mesh_io.h), so none is parsed, but each named file that
// exists must be a regular file of at most max_material_file_bytes inside the OBJ's folder tree, or the OBJ
// is refused (tinyobjloader would open any path, /dev/zero included). A missing one is ignored.
class MaterialCheck final : public tinyobj::MaterialReader {
 public:
  explicit MaterialCheck(std::filesystem::path root) : m_root(std::move(root)) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>*, std::map<std::string, int>*,
                  std::string*, std::string*) override {
    const std::filesystem::path p = m_root / name;
    std::error_code ec;
    if (!std::filesystem::exists(p, ec)) return true;
    std::string why;
    if (!inside_tree(m_root, p)) {
      why = "it is outside the OBJ file's folder";
    } else {
      why = check_file(p, max_material_file_bytes);
    }
    if (!why.empty() && m_refused.empty()) m_refused = "mtllib '" + printable(name) + "': " + why;
    return why.empty();
  }
  const std::string& refused() const { return m_refused; }

 private:
  std::filesystem::path m_root;
  std::string m_refused;
};

Result<MeshShape> read_obj(const std::filesystem::path& path) {
  if (const std::string why = check_file(path, max_mesh_file_bytes); !why.empty()) {
    return mesh_error(path, "cannot read OBJ: " + why);
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) return mesh_error(path, "cannot read OBJ: cannot open the file");
  MaterialCheck materials(path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path());
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> unused_materials;
  std::string warn;
  std::string err;
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &unused_materials, &warn, &err, &file, &materials, true, false);
  if (!materials.refused().empty()) return mesh_error(path, "refused " + materials.refused());
  if (!ok) {
    const std::string why = one_line(err);
    return mesh_error(path, "cannot read OBJ" + (why.empty() ? std::string() : ": " + why));
  }
  const std::size_t num_positions = attrib.vertices.size() / 3;
  const std::size_t num_normals = attrib.normals.size() / 3;
  const std::size_t num_uvs = attrib.texcoords.size() / 2;

  // First pass: do all corners have normals / uvs?
  bool has_normals = true;
  bool has_uvs = true;
  std::size_t corners = 0;
  for (const auto& shape : shapes) {
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      if (shape.mesh.num_face_vertices[f] != 3) {
        return mesh_error(path, "face " + std::to_string(f) + " of '" + shape.name + "' has " +
                                    std::to_string(shape.mesh.num_face_vertices[f]) + " corners after triangulation");
      }
    }
    for (const auto& idx : shape.mesh.indices) {
      has_normals = has_normals && idx.normal_index >= 0;
      has_uvs = has_uvs && idx.texcoord_index >= 0;
      ++corners;
    }
  }

  if (corners / 3 > max_scene_triangles) {
    return mesh_error(path, std::to_string(corners / 3) + " triangles, more than the limit of " +
                                std::to_string(max_scene_triangles));
  }
  MeshShape mesh;
  mesh.source = path.string();
  std::unordered_map<std::array<int, 3>, std::uint32_t, CornerHash> vertex_of;
  mesh.indices.reserve(corners);
  for (const auto& shape : shapes) {
    for (const auto& idx : shape.mesh.indices) {
      const std::array<int, 3> key{idx.vertex_index, has_normals ? idx.normal_index : -1,
                                   has_uvs ? idx.texcoord_index : -1};
      if (key[0] < 0 || static_cast<std::size_t>(key[0]) >= num_positions) {
        return mesh_error(
            path, "a face refers to vertex " + std::to_string(key[0] + 1) + " of " + std::to_string(num_positions));
      }
      if (has_normals && static_cast<std::size_t>(key[1]) >= num_normals) {
        return mesh_error(
            path, "a face refers to normal " + std::to_string(key[1] + 1) + " of " + std::to_string(num_normals));
      }
      if (has_uvs && static_cast<std::size_t>(key[2]) >= num_uvs) {
        return mesh_error(path, "a face refers to texture coordinate " + std::to_string(key[2] + 1) + " of " +
                                    std::to_string(num_uvs));
      }
      const auto [it, inserted] = vertex_of.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
      if (inserted) {
        const auto p = static_cast<std::size_t>(key[0]) * 3;
        mesh.positions.push_back({static_cast<double>(attrib.vertices[p]), static_cast<double>(attrib.vertices[p + 1]),
                                  static_cast<double>(attrib.vertices[p + 2])});
        if (has_normals) {
          const auto n = static_cast<std::size_t>(key[1]) * 3;
          mesh.normals.push_back({static_cast<double>(attrib.normals[n]), static_cast<double>(attrib.normals[n + 1]),
                                  static_cast<double>(attrib.normals[n + 2])});
        }
        if (has_uvs) {
          const auto t = static_cast<std::size_t>(key[2]) * 2;
          // OBJ's vt origin is the image's bottom left; shadelab's (and glTF's) is the top left.
          mesh.uvs.push_back(
              {static_cast<double>(attrib.texcoords[t]), 1.0 - static_cast<double>(attrib.texcoords[t + 1])});
        }
      }
      mesh.indices.push_back(it->second);
    }
  }
  finish_normals(mesh);
  auto checked = check_mesh(path, mesh);
  if (!checked) return checked.error();
  return mesh;
}

// ---- glTF ---------------------------------------------------------------------------------------------


// A validated accessor: `count` elements of `components` values each, `stride` bytes apart.
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;

  double component(std::size_t element, int c) const {
    const unsigned char* p = data + element * stride;
    switch (component_type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f = 0.0f;
        std::memcpy(&f, p + 4 * c, sizeof f);
        return static_cast<double>(f);
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        const double v = p[c];
        return normalized ? v / 255.0 : v;  // glTF 2.0, 3.11: normalized ubyte c / 255
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t s = 0;
        std::memcpy(&s, p + 2 * c, sizeof s);
        return normalized ? s / 65535.0 : static_cast<double>(s);  // glTF 2.0, 3.11: c / 65535
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t u = 0;
        std::memcpy(&u, p + 4 * c, sizeof u);
        return static_cast<double>(u);
      }
      default:
        return 0.0;
    }
  }
};

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    default:
      return "a matrix type";
  }
}

std::string component_name(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_INT:
      return "int";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "float";
    default:
      return "component type " + std::to_string(type);
  }
}

// Checks accessor `index` against the expected type and the allowed component types, and its bounds.
Result<AccessorView> view_accessor(const tinygltf::Model& model, int index, const std::string& what, int type,
                                   std::initializer_list<int> component_types, bool require_normalized_ints) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    return make_error(what + ": accessor " + std::to_string(index) + " does not exist");
  }
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  const std::string where = what + " (accessor " + std::to_string(index) + ")";
  if (a.sparse.isSparse) return make_error(where + ": sparse accessors are not supported");
  if (a.type != type) return make_error(where + ": expected " + type_name(type) + ", got " + type_name(a.type));
  if (std::find(component_types.begin(), component_types.end(), a.componentType) == component_types.end()) {
    return make_error(where + ": component type " + component_name(a.componentType) + " is not supported here");
  }
  if (require_normalized_ints && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized) {
    return make_error(where + ": integer components must be normalized");
  }
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size()) {
    return make_error(where + ": has no valid bufferView");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
    return make_error(where + ": bufferView " + std::to_string(a.bufferView) + " has no valid buffer");
  }
  const tinygltf::Buffer& buffer = model.buffers[static_cast<std::size_t>(view.buffer)];
  const int component_size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  const auto element_size = static_cast<std::size_t>(component_size) * static_cast<std::size_t>(components);
  const std::size_t stride = view.byteStride != 0 ? view.byteStride : element_size;
  if (stride < element_size) return make_error(where + ": byteStride is smaller than an element");
  AccessorView out;
  out.stride = stride;
  out.count = a.count;
  out.component_type = a.componentType;
  out.components = components;
  out.normalized = a.normalized;
  if (a.count == 0) return out;
  // The view must lie in the buffer and the accessor's last element in the view. Checked by subtraction
  // and division only: count, offsets and lengths come from the file and may be near 2^64.
  const std::size_t buffer_size = buffer.data.size();
  if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
    return make_error("bufferView " + std::to_string(a.bufferView) + ": it runs past the end of its buffer (" +
                      std::to_string(buffer_size) + " bytes)");
  }
  if (a.byteOffset > view.byteLength || element_size > view.byteLength - a.byteOffset ||
      a.count - 1 > (view.byteLength - a.byteOffset - element_size) / stride) {
    return make_error(where + ": count " + std::to_string(a.count) + " runs past the end of its bufferView (" +
                      std::to_string(view.byteLength) + " bytes)");
  }
  out.data = buffer.data.data() + view.byteOffset + a.byteOffset;
  return out;
}

// glTF 2.0, 5.25: a node's matrix (column-major) or T * R * S, with the rotation a unit quaternion (x, y, z, w).
MeshTransform node_transform(const tinygltf::Node& node) {
  MeshTransform t;
  if (node.matrix.size() == 16) {
    for (std::size_t r = 0; r < 3; ++r) {
      for (std::size_t c = 0; c < 3; ++c) t.linear.m[r][c] = node.matrix[c * 4 + r];
    }
    t.translate = {node.matrix[12], node.matrix[13], node.matrix[14]};
    return t;
  }
  Mat3 rotation;
  if (node.rotation.size() == 4) {
    double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
    const double len = std::sqrt(x * x + y * y + z * z + w * w);
    if (len > 0.0) {
      x /= len, y /= len, z /= len, w /= len;
    }
    // Rotation matrix of a unit quaternion (Shoemake, "Animating rotation with quaternion curves", 1985).
    rotation.m = {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                   {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                   {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
  }
  std::array<double, 3> scale{1.0, 1.0, 1.0};
  if (node.scale.size() == 3) scale = {node.scale[0], node.scale[1], node.scale[2]};
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c) t.linear.m[r][c] = rotation.m[r][c] * scale[c];
  }
  if (node.translation.size() == 3) t.translate = {node.translation[0], node.translation[1], node.translation[2]};
  return t;
}

// Accumulates the primitives of the visited nodes into one mesh.
// With `split`, one mesh per glTF material index (-1: primitives without a material); otherwise one mesh.
struct GltfPart {
  MeshShape mesh;
  bool all_normals = true;
  bool all_uvs = true;
};

struct GltfBuilder {
  const tinygltf::Model& model;
  bool split = false;
  std::map<int, GltfPart> parts;
  std::size_t total_vertices = 0;
  std::size_t total_triangles = 0;

  Result<bool> add_primitive(const tinygltf::Primitive& prim, const std::string& where, const MeshTransform& xf) {
    if (split && prim.material >= 0 && static_cast<std::size_t>(prim.material) >= model.materials.size()) {
      return make_error(where + ": material " + std::to_string(prim.material) + " does not exist");
    }
    GltfPart& part = parts[split ? std::max(prim.material, -1) : 0];
    MeshShape& mesh = part.mesh;
    bool& all_normals = part.all_normals;
    bool& all_uvs = part.all_uvs;
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) {
      return make_error(where + ": mode " + std::to_string(prim.mode) + " is not a triangle list (mode 4)");
    }
    const auto pos_it = prim.attributes.find("POSITION");
    if (pos_it == prim.attributes.end()) return make_error(where + ": has no POSITION attribute");
    auto positions = view_accessor(model, pos_it->second, where + " POSITION", TINYGLTF_TYPE_VEC3,
                                   {TINYGLTF_COMPONENT_TYPE_FLOAT}, false);
    if (!positions) return positions.error();
    std::optional<AccessorView> normals;
    if (const auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
      auto v = view_accessor(model, it->second, where + " NORMAL", TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT},
                             false);
      if (!v) return v.error();
      if (v->count != positions->count) return make_error(where + ": NORMAL and POSITION counts differ");
      normals = *v;
    }
    std::optional<AccessorView> uvs;
    if (const auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
      auto v = view_accessor(model, it->second, where + " TEXCOORD_0", TINYGLTF_TYPE_VEC2,
                             {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                             true);
      if (!v) return v.error();
      if (v->count != positions->count) return make_error(where + ": TEXCOORD_0 and POSITION counts differ");
      uvs = *v;
    }
    all_normals = all_normals && normals.has_value();
    all_uvs = all_uvs && uvs.has_value();

    const std::size_t base = mesh.positions.size();
    const std::size_t count = positions->count;
    // Every instance copies its vertices: bound them (3 per triangle of the limit) before allocating.
    if (count > 3 * max_scene_triangles - total_vertices) {
      return make_error(where + ": the node hierarchy instances more than " + std::to_string(3 * max_scene_triangles) +
                        " vertices (the limit is " + std::to_string(max_scene_triangles) + " triangles)");
    }
    const Mat3 normal_matrix = inverse_transpose(xf.linear);
    for (std::size_t i = 0; i < count; ++i) {
      const Vec3 p{positions->component(i, 0), positions->component(i, 1), positions->component(i, 2)};
      mesh.positions.push_back(xf.linear.apply(p) + xf.translate);
      mesh.normals.push_back(
          normals ? normal_matrix.apply({normals->component(i, 0), normals->component(i, 1), normals->component(i, 2)})
                  : Vec3{});
      mesh.uvs.push_back(uvs ? Vec2{uvs->component(i, 0), uvs->component(i, 1)} : Vec2{});
    }

    std::vector<std::uint32_t> local;
    if (prim.indices >= 0) {
      auto idx = view_accessor(model, prim.indices, where + " indices", TINYGLTF_TYPE_SCALAR,
                               {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                               false);
      if (!idx) return idx.error();
      if (idx->count / 3 > max_scene_triangles) {
        return make_error(where + " indices: count " + std::to_string(idx->count) + " is more than " +
                          std::to_string(max_scene_triangles) + " triangles");
      }
      local.reserve(idx->count);
      for (std::size_t i = 0; i < idx->count; ++i) {
        const double v = idx->component(i, 0);
        if (v >= static_cast<double>(count)) {
          return make_error(where + ": index " + std::to_string(static_cast<std::uint64_t>(v)) + " is out of range (" +
                            std::to_string(count) + " vertices)");
        }
        local.push_back(static_cast<std::uint32_t>(v));
      }
    } else {
      for (std::size_t i = 0; i < count; ++i) local.push_back(static_cast<std::uint32_t>(i));
    }
    if (local.size() % 3 != 0) {
      return make_error(where + ": " + std::to_string(local.size()) + " indices is not a whole number of triangles");
    }
    if (local.size() / 3 > max_scene_triangles - total_triangles) {
      return make_error(where + ": the node hierarchy instances more than " + std::to_string(max_scene_triangles) +
                        " triangles");
    }
    const bool mirror = determinant(xf.linear) < 0.0;
    for (std::size_t t = 0; t < local.size(); t += 3) {
      const auto b = static_cast<std::uint32_t>(base);
      mesh.indices.push_back(b + local[t]);
      // A mirroring transform turns counter-clockwise triangles clockwise; swap two corners back.
      mesh.indices.push_back(b + local[mirror ? t + 2 : t + 1]);
      mesh.indices.push_back(b + local[mirror ? t + 1 : t + 2]);
    }
    total_vertices += count;
    total_triangles += local.size() / 3;
    return true;
  }

  // Visits the hierarchy under `root` depth first, parents before children, children in order, without
  // recursion (a chain of 10^5 nodes is a valid file). Every visit counts toward max_gltf_node_instances: a
  // DAG (a node listed as a child by several parents) is instanced once per path, which can grow as 8^20.
  Result<bool> visit(int root) {
    struct Pending {
      int node;
      MeshTransform parent;
      std::size_t depth;
    };
    std::vector<Pending> stack{{root, MeshTransform{}, 0}};
    while (!stack.empty()) {
      const Pending item = std::move(stack.back());
      stack.pop_back();
      const int node_index = item.node;
      if (node_index < 0 || static_cast<std::size_t>(node_index) >= model.nodes.size()) {
        return make_error("node " + std::to_string(node_index) + " does not exist");
      }
      if (item.depth > model.nodes.size()) return make_error("the node hierarchy has a cycle");
      if (++instances > max_gltf_node_instances) {
        return make_error("the node hierarchy instances more than " + std::to_string(max_gltf_node_instances) +
                          " nodes (nodes listed as children of several parents are instanced once per path)");
      }
      const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(node_index)];
      const MeshTransform xf = compose(item.parent, node_transform(node));
      if (node.mesh >= 0) {
        if (static_cast<std::size_t>(node.mesh) >= model.meshes.size()) {
          return make_error("node " + std::to_string(node_index) + " refers to mesh " + std::to_string(node.mesh) +
                            ", which does not exist");
        }
        if (std::abs(determinant(xf.linear)) == 0.0 || !std::isfinite(determinant(xf.linear))) {
          return make_error("node " + std::to_string(node_index) + " has a singular transform");
        }
        const tinygltf::Mesh& m = model.meshes[static_cast<std::size_t>(node.mesh)];
        for (std::size_t p = 0; p < m.primitives.size(); ++p) {
          const std::string where = "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p);
          auto r = add_primitive(m.primitives[p], where, xf);
          if (!r) return r;
        }
      }
      for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
        stack.push_back({*it, xf, item.depth + 1});
      }
    }
    return true;
  }

  std::uint64_t instances = 0;
};

constexpr std::string_view kExtensionsRead[] = {
    "KHR_materials_anisotropy", "KHR_materials_clearcoat",          "KHR_materials_emissive_strength",
    "KHR_materials_ior",        "KHR_materials_sheen",              "KHR_materials_specular",
    "KHR_texture_transform"};

std::string join_names(std::span<const std::string_view> names) {
  std::string out;
  for (std::string_view n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

// glTF images are not needed for geometry: skip decoding them.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// tinygltf's file access, restricted: the files a glTF names (buffers, images) must be regular files of at
// most max_mesh_file_bytes inside the folder tree of the glTF file; "~" is not expanded; nothing is written.
// A refused buffer fails the load with our reason; a refused image only loses the image (never decoded).
struct GltfFiles {
  std::filesystem::path root;
  std::string refused;  // the first file refused and why
};

bool gltf_file_exists(const std::string& name, void*) {
  std::error_code ec;
  return std::filesystem::exists(name, ec);
}

std::string gltf_expand_path(const std::string& name, void*) { return name; }

bool gltf_read_file(std::vector<unsigned char>* out, std::string* err, const std::string& name, void* user) {
  auto* files = static_cast<GltfFiles*>(user);
  std::string why;
  if (!inside_tree(files->root, name)) {
    why = "it is outside the glTF file's folder";
  } else {
    why = check_file(name, max_mesh_file_bytes);
  }
  if (why.empty()) {
    std::string bytes;
    if (read_whole(name, bytes)) {
      out->assign(bytes.begin(), bytes.end());
      return true;
    }
    why = "cannot read it";
  }
  if (files->refused.empty()) files->refused = "'" + printable(name, max_library_bytes) + "': " + why;
  if (err != nullptr) *err += "refused to read " + name + "\n";
  return false;
}

bool gltf_write_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err != nullptr) *err += "writing is not allowed\n";
  return false;
}

// The JSON text of a .gltf file, or the JSON chunk of a .glb (glTF 2.0, 4.4: a 12-byte header, then chunks
// of length, type and data, the first of type JSON).
std::string_view gltf_json(const std::string& bytes, bool binary) {
  if (!binary) return bytes;
  if (bytes.size() < 20) return {};
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return std::string_view(bytes).substr(20, std::min<std::size_t>(length, bytes.size() - 20));
}


// The meshes of a glTF file (one, or one per material with `split`) and its JSON text.
struct GltfRead {
  std::vector<std::pair<int, MeshShape>> parts;  // (glTF material index or -1, mesh); key 0 without split
  std::string json_text;
};

Result<GltfRead> read_gltf_parts(const std::filesystem::path& path, bool split) {
  const bool binary = lower_extension(path) == ".glb";
  auto bytes = read_text(path, max_mesh_file_bytes);
  if (!bytes) return mesh_error(path, "cannot read glTF: " + bytes.error().message);
  // tinygltf turns JSON "extras" into its own values by recursion: bound the nesting before it parses. It
  // also builds a structure of some hundred bytes for each value (575 bytes an empty node, 900 an
  // accessor): bound their number too, or a 1 GiB file of "{}," asks for 200 GB (issue 40).
  const JsonShape shape = json_shape(gltf_json(*bytes, binary), max_json_depth, max_gltf_json_values);
  if (shape.depth > max_json_depth) {
    return mesh_error(path, "JSON nested deeper than " + std::to_string(max_json_depth) + " levels");
  }
  if (shape.values > max_gltf_json_values) {
    return mesh_error(path, "the glTF JSON holds more than " + std::to_string(max_gltf_json_values) +
                                " values (objects, arrays and their elements), more than a mesh file may");
  }
  tinygltf::Model model;
  std::string err;
  std::string warn;
  bool ok = false;
  GltfFiles files;
  files.root = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  try {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&skip_image, nullptr);
    loader.SetFsCallbacks({&gltf_file_exists, &gltf_expand_path, &gltf_read_file, &gltf_write_file, &files});
    const std::string base_dir = files.root.string();
    const auto* data = reinterpret_cast<const unsigned char*>(bytes->data());
    const auto size = static_cast<unsigned int>(bytes->size());
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, size, base_dir)
                : loader.LoadASCIIFromString(&model, &err, &warn, bytes->data(), size, base_dir);
  } catch (const std::bad_alloc&) {
    return mesh_error(path, "out of memory while reading glTF");
  } catch (const std::exception& e) {
    return mesh_error(path, std::string("cannot read glTF: ") + one_line(e.what()));
  }
  if (!ok && !files.refused.empty()) return mesh_error(path, "refused to read " + files.refused);
  if (!ok) return mesh_error(path, "cannot read glTF: " + one_line(err.empty() ? warn : err));
  for (const std::string& required : model.extensionsRequired) {
    const auto known = gltf_extensions_read();
    if (std::find(known.begin(), known.end(), required) == known.end()) {
      return mesh_error(path, "extensionsRequired: extension '" + printable(required, max_library_bytes) +
                                  "' is not supported (shadelab reads " + join_names(known) + ")");
    }
  }

  GltfBuilder builder{model, split, {}, 0, 0, 0};
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<std::size_t>(scene) >= model.scenes.size()) {
      return mesh_error(path, "default scene " + std::to_string(scene) + " does not exist");
    }
    roots = model.scenes[static_cast<std::size_t>(scene)].nodes;
  } else {
    // No scenes: every node that is nobody's child is a root.
    std::vector<bool> is_child(model.nodes.size(), false);
    for (const auto& node : model.nodes) {
      for (int c : node.children) {
        if (c >= 0 && static_cast<std::size_t>(c) < is_child.size()) is_child[static_cast<std::size_t>(c)] = true;
      }
    }
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
    }
  }
  for (int root : roots) {
    auto r = builder.visit(root);
    if (!r) return mesh_error(path, r.error().message);
  }
  if (builder.parts.empty()) builder.parts[0] = GltfPart{};
  GltfRead out;
  out.json_text = std::string(gltf_json(*bytes, binary));
  for (auto& [key, part] : builder.parts) {
    MeshShape mesh = std::move(part.mesh);
    mesh.source = path.string();
    if (!part.all_normals) mesh.normals.clear();
    if (!part.all_uvs) mesh.uvs.clear();
    finish_normals(mesh);
    auto checked = check_mesh(path, mesh);
    if (!checked) return checked.error();
    out.parts.emplace_back(key, std::move(mesh));
  }
  // In material order, primitives without a material (key -1, first in the map) last.
  if (out.parts.size() > 1 && out.parts.front().first < 0) {
    std::rotate(out.parts.begin(), out.parts.begin() + 1, out.parts.end());
  }
  return out;
}

Result<MeshShape> read_gltf(const std::filesystem::path& path) {
  auto read = read_gltf_parts(path, false);
  if (!read) return read.error();
  return std::move(read->parts.front().second);
}


// ---- glTF materials (pbrMetallicRoughness, glTF 2.0 section 3.9.2) ------------------------------------------

// A field error: thrown inside read_gltf_materials, caught there and turned into one line naming the pointer.
struct GltfFieldError {
  std::string pointer;
  std::string message;
};

std::string describe_json(const nlohmann::json& v) { return printable(v.dump(), 40); }

const nlohmann::json* member(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// An element of a top-level array ("materials", "textures", "images"), or an error naming it.
const nlohmann::json& top_element(const nlohmann::json& doc, const char* array, long long index,
                                  const std::string& referrer) {
  const nlohmann::json* a = member(doc, array);
  if (index < 0 || a == nullptr || !a->is_array() || static_cast<std::size_t>(index) >= a->size()) {
    throw GltfFieldError{referrer, "refers to " + std::string(array) + " " + std::to_string(index) +
                                       ", which does not exist"};
  }
  const nlohmann::json& e = (*a)[static_cast<std::size_t>(index)];
  if (!e.is_object()) {
    throw GltfFieldError{"/" + std::string(array) + "/" + std::to_string(index), "expected an object, got " + describe_json(e)};
  }
  return e;
}

double unit_number(const nlohmann::json& v, const std::string& pointer) {
  // glTF 2.0 schema: metallicFactor, roughnessFactor and the baseColorFactor components lie in [0, 1].
  if (!v.is_number() || !(v.get<double>() >= 0.0 && v.get<double>() <= 1.0)) {
    throw GltfFieldError{pointer, "expected a number in [0, 1], got " + describe_json(v)};
  }
  return v.get<double>();
}

long long index_value(const nlohmann::json& v, const std::string& pointer) {
  if (!v.is_number_integer() && !v.is_number_unsigned()) {
    throw GltfFieldError{pointer, "expected an integer index, got " + describe_json(v)};
  }
  if (v.is_number_unsigned() && v.get<std::uint64_t>() > 0x7fffffffULL) return 0x7fffffffLL;
  return v.get<long long>();
}

// %XX escapes of a URI reference (RFC 3986 2.1); the rest as written.
std::string percent_decoded(const std::string& uri, const std::string& pointer) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] != '%') {
      out += uri[i];
      continue;
    }
    if (i + 2 >= uri.size() || !std::isxdigit(static_cast<unsigned char>(uri[i + 1])) ||
        !std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      throw GltfFieldError{pointer, "malformed percent escape in '" + printable(uri) + "'"};
    }
    out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
    i += 2;
  }
  return out;
}

// A finite JSON number (nlohmann reads 1e999 as infinity), or an error naming the field.
double finite_number(const nlohmann::json& v, const std::string& pointer) {
  if (!v.is_number() || !std::isfinite(v.get<double>())) {
    throw GltfFieldError{pointer, "expected a number, got " + describe_json(v)};
  }
  return v.get<double>();
}

std::string short_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

double number_in(const nlohmann::json& v, const std::string& pointer, double lo, double hi, const char* why = "") {
  if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi)) {
    throw GltfFieldError{pointer, "expected a number in [" + short_number(lo) + ", " + short_number(hi) + "]" + why +
                                      ", got " + describe_json(v)};
  }
  return v.get<double>();
}

// An array of `n` numbers in [lo, hi] (a factor colour), into `out`.
template <std::size_t N>
void numbers_in(const nlohmann::json& v, const std::string& pointer, double lo, double hi, std::array<double, N>& out,
                const char* why = "") {
  if (!v.is_array() || v.size() != N) {
    throw GltfFieldError{pointer, "expected " + std::to_string(N) + " numbers, got " + describe_json(v)};
  }
  for (std::size_t c = 0; c < N; ++c) out[c] = number_in(v[c], pointer + "/" + std::to_string(c), lo, hi, why);
}

// KHR_texture_transform of a textureInfo, or the identity.
UvTransform texture_transform(const nlohmann::json& info, const std::string& pointer) {
  const nlohmann::json* extensions = member(info, "extensions");
  if (extensions == nullptr) return {};
  const nlohmann::json* t = member(*extensions, "KHR_texture_transform");
  if (t == nullptr) return {};
  const std::string tp = pointer + "/extensions/KHR_texture_transform";
  if (!t->is_object()) throw GltfFieldError{tp, "expected an object, got " + describe_json(*t)};
  Vec2 offset{0.0, 0.0};
  Vec2 scale{1.0, 1.0};
  double rotation = 0.0;
  auto pair = [&](const char* key, Vec2& out) {
    if (const nlohmann::json* v = member(*t, key)) {
      if (!v->is_array() || v->size() != 2) throw GltfFieldError{tp + "/" + key, "expected [u, v], got " + describe_json(*v)};
      out = {finite_number((*v)[0], tp + "/" + key + "/0"), finite_number((*v)[1], tp + "/" + key + "/1")};
    }
  };
  pair("offset", offset);
  pair("scale", scale);
  if (const nlohmann::json* v = member(*t, "rotation")) rotation = finite_number(*v, tp + "/rotation");
  if (const nlohmann::json* tc = member(*t, "texCoord")) {
    if (index_value(*tc, tp + "/texCoord") != 0) {
      throw GltfFieldError{tp + "/texCoord", "only TEXCOORD_0 is supported, got " + describe_json(*tc)};
    }
  }
  return make_gltf_uv_transform(offset, rotation, scale);
}

// A textureInfo (baseColorTexture, clearcoatTexture, ...): the image file its texture's source names.
std::filesystem::path texture_image(const nlohmann::json& doc, const nlohmann::json& info, const std::string& pointer,
                                    const std::filesystem::path& root) {
  if (!info.is_object()) throw GltfFieldError{pointer, "expected a textureInfo object, got " + describe_json(info)};
  const nlohmann::json* index = member(info, "index");
  if (index == nullptr) throw GltfFieldError{pointer + "/index", "required key is missing"};
  const long long t = index_value(*index, pointer + "/index");
  if (const nlohmann::json* tc = member(info, "texCoord")) {
    if (index_value(*tc, pointer + "/texCoord") != 0) {
      throw GltfFieldError{pointer + "/texCoord", "only TEXCOORD_0 is supported, got " + describe_json(*tc)};
    }
  }
  const nlohmann::json& texture = top_element(doc, "textures", t, pointer + "/index");
  const std::string tp = "/textures/" + std::to_string(t);
  const nlohmann::json* source = member(texture, "source");
  if (source == nullptr) {
    throw GltfFieldError{tp, "has no 'source' image (images of extensions such as KHR_texture_basisu are not supported)"};
  }
  const long long i = index_value(*source, tp + "/source");
  const nlohmann::json& image = top_element(doc, "images", i, tp + "/source");
  const std::string ip = "/images/" + std::to_string(i);
  const nlohmann::json* uri = member(image, "uri");
  if (uri == nullptr || member(image, "bufferView") != nullptr) {
    throw GltfFieldError{ip, "embedded images (bufferView) are not supported; give the image as a file 'uri'"};
  }
  if (!uri->is_string()) throw GltfFieldError{ip + "/uri", "expected a string, got " + describe_json(*uri)};
  const std::string text = uri->get<std::string>();
  if (text.rfind("data:", 0) == 0) {
    throw GltfFieldError{ip + "/uri", "embedded images (data: URIs) are not supported; give the image as a file"};
  }
  const std::filesystem::path file = root / std::filesystem::path(percent_decoded(text, ip + "/uri"));
  if (!inside_tree(root, file)) throw GltfFieldError{ip + "/uri", "'" + printable(text) + "' is outside the glTF file's folder"};
  if (const std::string why = check_file(file, max_mesh_file_bytes); !why.empty()) {
    throw GltfFieldError{ip + "/uri", "'" + printable(file.string()) + "': " + why};
  }
  return file;
}

// Reads the material's textureInfo `key` of `object` (at `pointer`), if present, as textures of `m`: one per
// (parameter, channel) it drives, sharing the image and transform.
struct TextureUse {
  const char* param;
  int channel;
  ParamTexture::Use use = ParamTexture::Use::multiply;
};
void read_texture(const nlohmann::json& doc, const nlohmann::json& object, const char* key, const std::string& pointer,
                  const std::filesystem::path& root, bool colour, bool alpha, std::initializer_list<TextureUse> uses,
                  GltfMaterial& m) {
  const nlohmann::json* info = member(object, key);
  if (info == nullptr) return;
  const std::string tp = pointer + "/" + key;
  const std::filesystem::path image = texture_image(doc, *info, tp, root);
  const UvTransform transform = texture_transform(*info, tp);
  for (const TextureUse& u : uses) {
    GltfTexture t;
    t.pointer = tp;
    t.image = image;
    t.colour = colour;
    t.alpha = alpha;
    t.param = u.param;
    t.channel = u.channel;
    t.use = u.use;
    t.transform = transform;
    m.textures.push_back(std::move(t));
  }
}

// The material's extension `name` as an object, or nullptr when absent.
const nlohmann::json* material_extension(const nlohmann::json& material, const char* name, const std::string& pointer) {
  const nlohmann::json* extensions = member(material, "extensions");
  if (extensions == nullptr) return nullptr;
  if (!extensions->is_object()) throw GltfFieldError{pointer + "/extensions", "expected an object, got " + describe_json(*extensions)};
  const nlohmann::json* e = member(*extensions, name);
  if (e != nullptr && !e->is_object()) {
    throw GltfFieldError{pointer + "/extensions/" + name, "expected an object, got " + describe_json(*e)};
  }
  return e;
}

// Material `index` of the document (-1: the glTF default material, section 3.9.1), as the `gltf` model's parameters
// and textures: glTF 2.0 section 3.9 and each extension's README (the channels and colour spaces:
// docs/scene-format.md, "glTF materials").
GltfMaterial read_gltf_material(const nlohmann::json& doc, int index, const std::filesystem::path& root) {
  GltfMaterial m;
  if (index < 0) {
    m.pointer = "(default material)";
    return m;
  }
  m.pointer = "/materials/" + std::to_string(index);
  const nlohmann::json& material = top_element(doc, "materials", index, m.pointer);
  if (const nlohmann::json* name = member(material, "name")) {
    if (!name->is_string()) throw GltfFieldError{m.pointer + "/name", "expected a string, got " + describe_json(*name)};
    m.name = printable(name->get<std::string>());
  }
  if (const nlohmann::json* f = member(material, "emissiveFactor")) numbers_in(*f, m.pointer + "/emissiveFactor", 0.0, 1.0, m.emissive);
  if (const nlohmann::json* pbr = member(material, "pbrMetallicRoughness")) {
    const std::string pp = m.pointer + "/pbrMetallicRoughness";
    if (!pbr->is_object()) throw GltfFieldError{pp, "expected an object, got " + describe_json(*pbr)};
    if (const nlohmann::json* f = member(*pbr, "baseColorFactor")) {
      if (!f->is_array() || f->size() != 4) {
        throw GltfFieldError{pp + "/baseColorFactor", "expected [r, g, b, a], got " + describe_json(*f)};
      }
      for (std::size_t c = 0; c < 4; ++c) {
        const double v = unit_number((*f)[c], pp + "/baseColorFactor/" + std::to_string(c));
        if (c < 3) m.base_color[c] = v;
      }
    }
    if (const nlohmann::json* f = member(*pbr, "metallicFactor")) m.metallic = unit_number(*f, pp + "/metallicFactor");
    if (const nlohmann::json* f = member(*pbr, "roughnessFactor")) m.roughness = unit_number(*f, pp + "/roughnessFactor");
    read_texture(doc, *pbr, "baseColorTexture", pp, root, true, false, {{"base_color", -1}}, m);
    read_texture(doc, *pbr, "metallicRoughnessTexture", pp, root, false, false, {{"roughness", 1}, {"metallic", 2}}, m);
  }
  const std::string ep = m.pointer + "/extensions/";
  if (const nlohmann::json* e = material_extension(material, "KHR_materials_emissive_strength", m.pointer)) {
    const std::string p = ep + "KHR_materials_emissive_strength";
    if (const nlohmann::json* f = member(*e, "emissiveStrength")) {
      m.emissive_strength = number_in(*f, p + "/emissiveStrength", 0.0, 1e6, " (the gltf model's range)");
    }
  }
  if (const nlohmann::json* e = material_extension(material, "KHR_materials_ior", m.pointer)) {
    const std::string p = ep + "KHR_materials_ior";
    if (const nlohmann::json* f = member(*e, "ior")) {
      const double v = f->is_number() ? f->get<double>() : -1.0;
      if (!f->is_number() || !(v == 0.0 || (v >= 1.0 && v <= 10.0))) {
        throw GltfFieldError{p + "/ior", "expected 0 or a number in [1, 10] (the gltf model's largest is 10), got " +
                                             describe_json(*f)};
      }
      m.ior = v;
    }
  }
  if (const nlohmann::json* e = material_extension(material, "KHR_materials_specular", m.pointer)) {
    const std::string p = ep + "KHR_materials_specular";
    if (const nlohmann::json* f = member(*e, "specularFactor")) m.specular = unit_number(*f, p + "/specularFactor");
    if (const nlohmann::json* f = member(*e, "specularColorFactor")) {
      numbers_in(*f, p + "/specularColorFactor", 0.0, 10.0, m.specular_color, " (the gltf model's range)");
    }
    read_texture(doc, *e, "specularTexture", p, root, false, true, {{"specular", 0}}, m);
    read_texture(doc, *e, "specularColorTexture", p, root, true, false, {{"specular_color", -1}}, m);
  }
  if (const nlohmann::json* e = material_extension(material, "KHR_materials_clearcoat", m.pointer)) {
    const std::string p = ep + "KHR_materials_clearcoat";
    if (const nlohmann::json* f = member(*e, "clearcoatFactor")) m.clearcoat = unit_number(*f, p + "/clearcoatFactor");
    if (const nlohmann::json* f = member(*e, "clearcoatRoughnessFactor")) {
      m.clearcoat_roughness = unit_number(*f, p + "/clearcoatRoughnessFactor");
    }
    read_texture(doc, *e, "clearcoatTexture", p, root, false, false, {{"clearcoat", 0}}, m);
    read_texture(doc, *e, "clearcoatRoughnessTexture", p, root, false, false, {{"clearcoat_roughness", 1}}, m);
  }
  if (const nlohmann::json* e = material_extension(material, "KHR_materials_sheen", m.pointer)) {
    const std::string p = ep + "KHR_materials_sheen";
    if (const nlohmann::json* f = member(*e, "sheenColorFactor")) numbers_in(*f, p + "/sheenColorFactor", 0.0, 1.0, m.sheen_color);
    if (const nlohmann::json* f = member(*e, "sheenRoughnessFactor")) m.sheen_roughness = unit_number(*f, p + "/sheenRoughnessFactor");
    read_texture(doc, *e, "sheenColorTexture", p, root, true, false, {{"sheen_color", -1}}, m);
    read_texture(doc, *e, "sheenRoughnessTexture", p, root, false, true, {{"sheen_roughness", 0}}, m);
  }
  if (const nlohmann::json* e = material_extension(material, "KHR_materials_anisotropy", m.pointer)) {
    const std::string p = ep + "KHR_materials_anisotropy";
    if (const nlohmann::json* f = member(*e, "anisotropyStrength")) m.anisotropy_strength = unit_number(*f, p + "/anisotropyStrength");
    if (const nlohmann::json* f = member(*e, "anisotropyRotation")) {
      // Any angle; reduced to [-pi, pi] (the model's range is [-100, 100], and a texture's direction adds up to pi).
      m.anisotropy_rotation = std::remainder(finite_number(*f, p + "/anisotropyRotation"), 2.0 * pi);
    }
    read_texture(doc, *e, "anisotropyTexture", p, root, false, false,
                 {{"anisotropy_strength", -1, ParamTexture::Use::anisotropy}}, m);
  }
  return m;
}

// extensionsUsed entries no reader here knows: a warning (one line), or "".
std::string unread_extensions_warning(const nlohmann::json& doc) {
  const nlohmann::json* used = member(doc, "extensionsUsed");
  if (used == nullptr) return {};
  if (!used->is_array()) throw GltfFieldError{"/extensionsUsed", "expected an array of names, got " + describe_json(*used)};
  std::vector<std::string> unread;
  for (std::size_t i = 0; i < used->size(); ++i) {
    const nlohmann::json& name = (*used)[i];
    if (!name.is_string()) throw GltfFieldError{"/extensionsUsed/" + std::to_string(i), "expected a name, got " + describe_json(name)};
    const std::string text = name.get<std::string>();
    const auto known = gltf_extensions_read();
    if (std::find(known.begin(), known.end(), text) == known.end()) unread.push_back(printable(text, 80));
  }
  if (unread.empty()) return {};
  std::string list;
  for (const std::string& u : unread) list += (list.empty() ? "" : ", ") + u;
  return "extensionsUsed: " + std::string(unread.size() == 1 ? "extension " : "extensions ") + list +
         (unread.size() == 1 ? " is" : " are") + " not read; the file is rendered without " +
         (unread.size() == 1 ? "it" : "them");
}

Result<GltfScene> read_gltf_scene(const std::filesystem::path& path) {
  auto read = read_gltf_parts(path, true);
  if (!read) return read.error();
  const nlohmann::json doc = nlohmann::json::parse(read->json_text, nullptr, false);
  if (doc.is_discarded()) return mesh_error(path, "cannot read glTF: malformed JSON");
  const std::filesystem::path root = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  GltfScene scene;
  try {
    // Every material of the file is checked, used or not; the parts keep the ones they use, in file order.
    const nlohmann::json* materials = member(doc, "materials");
    if (materials != nullptr && !materials->is_array()) {
      throw GltfFieldError{"/materials", "expected an array, got " + describe_json(*materials)};
    }
    std::vector<GltfMaterial> all;
    for (std::size_t i = 0; materials != nullptr && i < materials->size(); ++i) {
      all.push_back(read_gltf_material(doc, static_cast<int>(i), root));
    }
    if (std::string w = unread_extensions_warning(doc); !w.empty()) scene.warnings.push_back(std::move(w));
    for (auto& [key, mesh] : read->parts) {
      GltfMaterial m = key >= 0 ? all[static_cast<std::size_t>(key)] : read_gltf_material(doc, -1, root);
      if (!m.textures.empty() && mesh.uvs.empty()) {
        throw GltfFieldError{m.pointer, "has textures, but the primitives that use it have no TEXCOORD_0"};
      }
      mesh.material = static_cast<int>(scene.materials.size());
      scene.materials.push_back(std::move(m));
      scene.parts.push_back(std::move(mesh));
    }
  } catch (const GltfFieldError& e) {
    return mesh_error(path, e.pointer + ": " + e.message);
  }
  return scene;
}

// Allocation failures (the file's sizes are checked, but memory may still run out) become errors.
Result<MeshShape> guarded(const std::filesystem::path& path, Result<MeshShape> (*read)(const std::filesystem::path&)) {
  try {
    return read(path);
  } catch (const std::bad_alloc&) {
    return mesh_error(path, "out of memory while reading the mesh");
  } catch (const std::length_error&) {
    return mesh_error(path, "out of memory while reading the mesh");
  }
}

}  // namespace

std::span<const std::string_view> gltf_extensions_read() { return kExtensionsRead; }

Result<MeshShape> load_obj(const std::filesystem::path& path) { return guarded(path, read_obj); }
Result<MeshShape> load_gltf(const std::filesystem::path& path) { return guarded(path, read_gltf); }

Result<GltfScene> load_gltf_scene(const std::filesystem::path& path) {
  try {
    return read_gltf_scene(path);
  } catch (const std::bad_alloc&) {
    return mesh_error(path, "out of memory while reading the mesh");
  } catch (const std::length_error&) {
    return mesh_error(path, "out of memory while reading the mesh");
  }
}

Result<MeshShape> load_mesh(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return load_obj(path);
  if (ext == ".gltf" || ext == ".glb") return load_gltf(path);
  return mesh_error(path, "unknown mesh format '" + path.extension().string() + "' (expected .obj, .gltf or .glb)");
}

MeshTransform make_mesh_transform(const Vec3& translate, const Vec3& rotation_axis, double rotation_deg,
                                  const Vec3& scale) {
  Mat3 s;
  s.m = {{{scale.x, 0.0, 0.0}, {0.0, scale.y, 0.0}, {0.0, 0.0, scale.z}}};
  const Mat3 r = Mat3::rotation(rotation_axis, deg_to_rad(rotation_deg));
  return {multiply(r, s), translate};
}

void transform_mesh(MeshShape& mesh, const MeshTransform& transform) {
  for (auto& p : mesh.positions) p = transform.linear.apply(p) + transform.translate;
  const Mat3 normal_matrix = inverse_transpose(transform.linear);
  for (auto& n : mesh.normals) n = normalize(normal_matrix.apply(n));
  if (determinant(transform.linear) < 0.0) {
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  }
}

}  // namespace shadelab
