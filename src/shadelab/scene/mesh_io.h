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
//   indexes GltfScene::materials), with each material's pbrMetallicRoughness, emissive factor and the extensions
//   KHR_materials_ior, _specular, _clearcoat, _sheen, _anisotropy and _emissive_strength read and checked, their
//   textures with KHR_texture_transform (docs/scene-format.md, "glTF materials"): factors in their ranges, textures
//   through textures[].source to images[].uri files inside the glTF's folder tree, texCoord 0 only. Embedded images
//   (bufferView, data: URIs) are refused. Every material of the file is checked, used or not; an error is one line:
//   the file, the JSON pointer of the field, why.
//   Extensions: every glTF reader here accepts a file whose extensionsRequired lists only the ones above and
//   KHR_texture_transform (gltf_extensions_read), and refuses any other, naming it; an extension in extensionsUsed
//   only that is not read is a warning in GltfScene::warnings (one line each).
//   Not read: normal, occlusion and emissive textures, alphaMode, doubleSided, samplers (lookups are bilinear and
//   repeat), clearcoatNormalTexture.
#pragma once

#include <array>
#include <filesystem>
#include <span>
#include <string_view>
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

// The extensions the glTF readers know: a file may require them (extensionsRequired); any other required one is an
// error naming it.
std::span<const std::string_view> gltf_extensions_read();

// A texture of a glTF material: the image file, how it is decoded, the `gltf` model parameter it multiplies and
// with which channel (docs/scene-format.md, "glTF materials").
struct GltfTexture {
  std::string pointer;               // the textureInfo's JSON pointer, e.g. /materials/0/extensions/KHR_materials_sheen/sheenColorTexture
  std::filesystem::path image;       // the image file (images[].uri, percent escapes decoded)
  bool colour = false;               // sRGB colour (decoded to linear), or data (code / max)
  bool alpha = false;                // data from the image's alpha channel (specularTexture, sheenRoughnessTexture)
  std::string param;                 // the gltf parameter it multiplies (anisotropy: anisotropy_strength)
  int channel = -1;                  // -1: r, g, b onto a colour; 0, 1, 2: that channel (alpha images: any)
  ParamTexture::Use use = ParamTexture::Use::multiply;
  UvTransform transform;             // KHR_texture_transform, or the identity
};

// A glTF material as the `gltf` model's parameters (docs/models/gltf.md); the defaults are the specifications'.
struct GltfMaterial {
  std::string name;     // the material's "name", or ""
  std::string pointer;  // "/materials/N", or "(default material)" for primitives without one (section 3.9.1)
  std::array<double, 3> base_color{1.0, 1.0, 1.0};  // baseColorFactor's r, g, b (its alpha is not used)
  double metallic = 1.0;                           // metallicFactor
  double roughness = 1.0;                          // roughnessFactor (perceptual roughness)
  std::array<double, 3> emissive{0.0, 0.0, 0.0};   // emissiveFactor
  double emissive_strength = 1.0;                  // KHR_materials_emissive_strength
  double ior = 1.5;                                // KHR_materials_ior
  double specular = 1.0;                           // KHR_materials_specular
  std::array<double, 3> specular_color{1.0, 1.0, 1.0};
  double clearcoat = 0.0;                          // KHR_materials_clearcoat
  double clearcoat_roughness = 0.0;
  std::array<double, 3> sheen_color{0.0, 0.0, 0.0};  // KHR_materials_sheen
  double sheen_roughness = 0.0;
  double anisotropy_strength = 0.0;                // KHR_materials_anisotropy
  double anisotropy_rotation = 0.0;                // radians
  std::vector<GltfTexture> textures;               // in the order the material names them
};

struct GltfScene {
  // One per material used, in the file's material order, primitives without a material last;
  // MeshShape::material indexes `materials`.
  std::vector<MeshShape> parts;
  std::vector<GltfMaterial> materials;   // one per part, in the order of the parts
  std::vector<std::string> warnings;     // one line each, without the file's name
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
