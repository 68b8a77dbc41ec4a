// shadelab scenes in memory: what the JSON scene format (docs/scene-format.md) describes, after parsing,
// validation and unit conversion. Everything here is radiometric (lights in W/m^2, W/sr, W/m^2/sr) and in
// world space (right-handed, +Y up, metres); the renderer never sees a game or photometric unit.
//
// Contract: a Scene returned by load_scene / parse_scene is valid: indices are in range, sizes positive,
// numbers finite, directions unit length, every material's base parameters validated by its model.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "shadelab/brdf/brdf.h"
#include "shadelab/brdf/gloss.h"
#include "shadelab/brdf/params.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/error.h"
#include "shadelab/image/image.h"
#include "shadelab/light/hemisphere_light.h"
#include "shadelab/light/punctual.h"
#include "shadelab/light/sphere_light.h"

namespace shadelab {

// Pinhole camera. fov is vertical, in degrees.
struct Camera {
  Vec3 position{0.0, 1.0, 5.0};
  Vec3 look_at{0.0, 1.0, 0.0};
  Vec3 up{0.0, 1.0, 0.0};
  double vfov_deg = 40.0;
  int width = 640;
  int height = 360;
};

// A texture: linear values in an Image. Colour textures (diffuse) were sRGB-decoded when read; data
// textures (gloss, specular F0, normal maps) hold the file's values as stored (PNG codes / 255).
struct Texture {
  std::string name;
  std::string source;  // the file read, or the procedural generator and its options, for messages
  Image image;
  bool data = false;
};

// Bilinear lookup with wrap-around in both directions; uv = (0, 0) is the top-left texel corner.
Rgb sample_texture(const Texture& texture, Vec2 uv);

// An affine map of texture coordinates, uv' = (m00 u + m01 v + m02, m10 u + m11 v + m12): glTF's
// KHR_texture_transform (make_gltf_uv_transform). The default is the identity.
struct UvTransform {
  double m00 = 1.0, m01 = 0.0, m02 = 0.0;
  double m10 = 0.0, m11 = 1.0, m12 = 0.0;
  Vec2 apply(Vec2 uv) const { return {m00 * uv.x + m01 * uv.y + m02, m10 * uv.x + m11 * uv.y + m12}; }
};

// KHR_texture_transform's matrix translation x rotation x scale (its README, "Overview"): uv' = offset +
// R(rotation) (scale_u u, scale_v v) with R = [cos r, sin r; -sin r, cos r], which turns the uvs counter-clockwise
// as glTF's image (v down) is seen: the README's example (offset [0, 1], rotation pi/2, scale [0.5, 0.5]) maps the
// unit square onto the image's lower-left quadrant.
UvTransform make_gltf_uv_transform(Vec2 offset, double rotation_rad, Vec2 scale);

// A texture that drives a model parameter (the scene's material "textures" by parameter name, and every glTF
// texture): the parameter's value becomes its factor (the material's own value) times the texel, clamped to the
// parameter's range, as glTF's factors and textures combine.
struct ParamTexture {
  enum class Use {
    multiply,    // channel -1: r, g, b x a colour parameter; channel 0, 1, 2: that channel x a scalar parameter
    anisotropy,  // KHR_materials_anisotropy's texture: anisotropy_strength x blue, anisotropy_rotation +
                 // atan2(2 green - 1, 2 red - 1) (the direction in the tangent frame); `param` is anisotropy_strength
  };
  std::string param;
  int texture = -1;  // index into Scene::textures
  int channel = -1;
  Use use = Use::multiply;
  UvTransform transform;  // applied to the material's (tiled) uv before the lookup
};

struct Material {
  std::string name;
  std::string model;                   // registry name, "" for a purely emissive material
  ParamAssignments params;             // as written in the scene (validated)
  std::shared_ptr<const Brdf> brdf;    // built from params; used when no texture varies the parameters
  // Optional textures (indices into Scene::textures, -1 = none):
  int kd_texture = -1;      // diffuse colour (sRGB) -> parameter kd
  int ks_texture = -1;      // specular reflectance F0 (data) -> parameter ks (or f0 for cook-torrance)
  int gloss_texture = -1;   // gloss map (data, red channel): exponent n by the zoo's logarithmic encoding
  int normal_texture = -1;  // tangent-space normal map (data, [0,1] -> [-1,1])
  // glTF's metallic-roughness textures (models with base_color / metallic / perceptual_roughness: filament):
  // they multiply the parameters, as glTF's factors and textures do.
  int base_color_texture = -1;          // colour (sRGB) x parameter base_color
  int metallic_roughness_texture = -1;  // data: green x perceptual_roughness, blue x metallic
  // Textures that multiply model parameters (gltf, principled-v1, layered, ... and glTF files' materials).
  std::vector<ParamTexture> param_textures;
  GlossEncoding gloss_encoding;
  Vec2 uv_scale{1.0, 1.0};  // texture lookups use (u * uv_scale.x, v * uv_scale.y): tiling
  Rgb emission;             // emitted radiance, W m^-2 sr^-1 (emissive shapes)
  bool textured() const {
    return kd_texture >= 0 || ks_texture >= 0 || gloss_texture >= 0 || base_color_texture >= 0 ||
           metallic_roughness_texture >= 0 || !param_textures.empty();
  }
};

struct SphereShape {
  Vec3 center;
  double radius = 1.0;
  int material = 0;
};

// A parallelogram corner + s u + t v, s, t in [0, 1]; its normal is normalize(u x v).
struct QuadShape {
  Vec3 corner;
  Vec3 u{1.0, 0.0, 0.0};
  Vec3 v{0.0, 0.0, -1.0};
  int material = 0;
};

struct DiskShape {
  Vec3 center;
  Vec3 normal{0.0, 1.0, 0.0};
  double radius = 1.0;
  int material = 0;
};

// Triangles in world space (the scene's transform applied). normals and uvs are per vertex, or empty.
struct MeshShape {
  std::string source;  // file it came from
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;
  std::vector<std::uint32_t> indices;  // 3 per triangle
  int material = 0;
};

using SceneLight = std::variant<DirectionalLight, PointLight, SpotLight, SphereLight, HemisphereLight>;

// The built-in sky: an analytic gradient (zenith, horizon, ground colours) and a sun disk, both radiance.
struct SkyModel {
  Vec3 sun_direction = normalize(Vec3{0.4, 0.6, -0.7});  // toward the sun
  double sun_angular_radius_deg = 0.27;                 // half-angle of the sun disk
  Rgb sun_irradiance{3.0, 2.9, 2.7};                   // E_perp of the sun disk, W/m^2
  Rgb zenith{0.12, 0.22, 0.45};                        // sky radiance at the zenith
  Rgb horizon{0.55, 0.62, 0.70};                       // sky radiance at the horizon
  Rgb ground{0.10, 0.09, 0.08};                        // radiance below the horizon
};

struct Environment {
  enum class Kind { none, uniform, image, sky } kind = Kind::none;
  Rgb uniform;               // kind uniform: radiance from every direction
  Image latlong;             // kind image: radiance, lat-long (envmap/base/latlong.h mapping)
  std::string source;        // the file, for messages
  double rotation_deg = 0.0; // about +Y, applied to the map
  double scale = 1.0;
  SkyModel sky;              // kind sky
};

struct RenderSettings {
  int spp = 64;
  int max_depth = 8;            // path vertices after the camera; 1 = direct light only
  std::uint64_t seed = 1;
  int threads = 0;              // 0: all cores
  int rr_depth = 3;             // Russian roulette from this depth on (0 = off)
};

struct Scene {
  std::string source;  // file name, or "(built-in default)"
  Camera camera;
  std::vector<Texture> textures;
  std::vector<Material> materials;
  std::vector<SphereShape> spheres;
  std::vector<QuadShape> quads;
  std::vector<DiskShape> disks;
  std::vector<MeshShape> meshes;
  std::vector<SceneLight> lights;
  Environment environment;
  RenderSettings settings;
  // What the loader read past and says so, one line each (a glTF extension in extensionsUsed that shadelab does not
  // read, ...): the CLI prints them on stderr as "warning: ...". They do not change the image.
  std::vector<std::string> warnings;
};

}  // namespace shadelab
