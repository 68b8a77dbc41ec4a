// shadelab mesh files: Wavefront OBJ (tinyobjloader) and glTF 2.0, .gltf or .glb (tinygltf), read into a
// MeshShape (scene.h) of indexed triangles.
//
// Contract:
// - load_mesh picks the reader by extension, case-insensitive: .obj, .gltf, .glb; any other is an error.
// - OBJ: every object and group of the file in one mesh; polygons are triangulated as fans; materials
//   (.mtl) are ignored, but every mtllib that exists must be a regular file inside the OBJ's folder tree
//   (or the OBJ is refused: tinyobjloader would open /dev/zero). A vertex is a distinct (position, normal, uv) index triple of the file. Normals and
//   uvs are kept only when every face corner has one; uvs are flipped to the glTF convention (v -> 1 - v,
//   OBJ's vt has its origin at the bottom left of the image, shadelab's texture uv at the top left).
// - glTF: every primitive of every mesh instanced by the nodes of the default scene (the first scene when
//   none is marked default; every root node when the file has no scenes), with the node transforms
//   (matrix, or translation x rotation x scale, parents first) applied. Primitives must be triangle lists
//   (mode 4); attributes POSITION (float vec3, required), NORMAL (float vec3) and TEXCOORD_0 (float, or
//   normalized unsigned byte / short, vec2); indices unsigned byte, short or int, or none (sequential).
//   Sparse accessors and Draco compression are rejected. Images are not decoded. glTF uvs are already top-left.
//   Normals and uvs are kept only when every primitive has them. A node whose transform mirrors
//   (negative determinant) has its triangles' winding reversed, as the glTF specification requires.
// - Normals are normalized; if any is zero or not finite, all normals are dropped (the renderer then uses
//   the geometric normals). Positions must be finite and indices in range; a mesh without triangles is an
//   error. Every error is one line that starts with the file's path.
// - Files a glTF names (buffers, images) must be regular files inside its folder tree; "~" is not expanded.
// - Limits (scene/limits.h): files up to max_mesh_file_bytes, glTF JSON up to max_json_depth levels, at most
//   max_gltf_node_instances node visits (a DAG instances a node once per path) and max_scene_triangles
//   triangles; accessor bounds are checked without overflow; the node hierarchy is visited without
//   recursion. Running out of memory is an error, not an exception.
// - MeshShape::source is the path as given; material is 0.
// - load_gltf_scene: the same triangles, one MeshShape per glTF material its primitives use (MeshShape::material
//   indexes GltfScene::materials), with each material's pbrMetallicRoughness read and checked: factors in
//   [0, 1], baseColorFactor four numbers, textures through textures[].source to images[].uri files inside the
//   glTF's folder tree, texCoord 0 only. Embedded images (bufferView, data: URIs) are refused. Every material of
//   the file is checked, used or not; an error is one line: the file, the JSON pointer of the field, why.
//   Not read (docs/scene-format.md, "glTF materials"): normal, occlusion and emissive textures, emissiveFactor,
//   alphaMode, doubleSided, samplers (lookups are bilinear and repeat) and every extension.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/core/mat3.h"
#include "shadelab/core/vec.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

Result<MeshShape> load_mesh(const std::filesystem::path& path);
Result<MeshShape> load_obj(const std::filesystem::path& path);
Result<MeshShape> load_gltf(const std::filesystem::path& path);  // .gltf (JSON) or .glb (binary)

// A glTF material's pbrMetallicRoughness (glTF 2.0, section 3.9.2); the defaults are the spec's.
struct GltfMaterial {
  std::string name;     // the material's "name", or ""
  std::string pointer;  // "/materials/N", or "(default material)" for primitives without one (section 3.9.1)
  std::array<double, 3> base_color{1.0, 1.0, 1.0};  // baseColorFactor's r, g, b (its alpha is not used)
  double metallic = 1.0;                           // metallicFactor
  double roughness = 1.0;                          // roughnessFactor (perceptual roughness)
  std::filesystem::path base_color_image;          // baseColorTexture's image file (sRGB colour), or empty
  std::filesystem::path metallic_roughness_image;  // metallicRoughnessTexture's image file (data: G, B), or empty
};

struct GltfScene {
  // One per material used, in the file's material order, primitives without a material last;
  // MeshShape::material indexes `materials`.
  std::vector<MeshShape> parts;
  std::vector<GltfMaterial> materials;   // one per part, in the order of the parts
};

Result<GltfScene> load_gltf_scene(const std::filesystem::path& path);

// An affine map p -> linear p + translate. Normals go through the inverse transpose of `linear` and are
// renormalized; a mirroring map (det < 0) reverses the triangles' winding. `linear` must be invertible.
struct MeshTransform {
  Mat3 linear;
  Vec3 translate;
};

// The scene format's transform: scale, then rotate (angle in degrees about a unit axis), then translate.
MeshTransform make_mesh_transform(const Vec3& translate, const Vec3& rotation_axis, double rotation_deg,
                                  const Vec3& scale);

void transform_mesh(MeshShape& mesh, const MeshTransform& transform);

}  // namespace shadelab
