// shadelab's bounds on scenes and the files they read, stated once (docs/scene-format.md, "Limits"; the
// image memory budget is in image/image_io.h). Each bound keeps a value inside what the code that uses it
// survives: Embree's float ray math, float images, the stack, the machine's memory.
//
// The scene parser (scene_json.cpp) checks every bound with the field's JSON pointer; the mesh loaders
// check theirs with the file's name; check_scene_limits is the backstop the renderers run on any Scene,
// including one built in code.
#pragma once

#include <cstddef>
#include <cstdint>

#include "shadelab/core/error.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

// Every coordinate of a position (camera, shapes, lights, mesh vertices after their transforms) and every
// length, in metres. Embree refuses ray origins beyond 1.8e18 (its ray.valid() assertion) and squares
// coordinates in float (3.4e38); 1e9 m (2.6 times the Moon's distance) leaves both far behind.
inline constexpr double max_scene_coordinate = 1e9;
// The smallest radius, quad edge or transform scale: below it areas underflow to 0 in the light pdfs.
inline constexpr double min_scene_length = 1e-9;
// Any radiometric light quantity per channel (radiance W m^-2 sr^-1, irradiance W m^-2, intensity W sr^-1)
// after unit conversion; environment texels times their scale. Float images (3.4e38) keep 8 decades of
// headroom for the sums of a render.
inline constexpr double max_light_value = 1e30;
// The sun disk's half-angle: its radiance is E / (pi sin^2(alpha)), which overflows as alpha -> 0.
inline constexpr double min_sun_angular_radius_deg = 1e-3;
// Texture tiling factors (uv_scale): beyond this a float texel index carries no fraction.
inline constexpr double max_uv_scale = 1e6;
// Gloss-map exponents (gloss_range): the BRDF models' own upper bound on n.
inline constexpr double max_gloss_exponent = 1e6;

// The camera: at most 16384 pixels on a side and max_render_pixels in all (2^25: 8192 x 4096, or 8K UHD's
// 7680 x 4320). The renderers allocate per pixel (render_bytes_per_pixel below); without this bound a
// 16384 x 16384 camera asked for some 10 GB before the first sample.
inline constexpr int max_camera_side = 16384;
inline constexpr long long max_render_pixels = 1LL << 25;
// The memory a render takes per pixel, beyond the scene, through writing its files (EXR, PNG): the
// reference renderer's exact accumulators (48 bytes of 128-bit fixed-point sums and a 4-byte non-finite
// count, render/fixed_sum.h: what makes shards merge bit for bit) and image, the tone-mapped copy and the
// encoders' buffers. With AOVs (albedo, normal, depth) the larger figure. At max_render_pixels: 3 GiB, or
// 7 GiB with AOVs. Checked by MemoryBound.RenderStaysWithinItsPerPixelBudget
// (tools/shadelab/cli_memory_test.cpp) under RLIMIT_AS.
inline constexpr std::uint64_t render_bytes_per_pixel = 96;
inline constexpr std::uint64_t render_aov_bytes_per_pixel = 224;
// The images one scene holds, together (file and procedural textures, the environment map; 12 bytes a
// pixel): a scene naming many large images is refused once they pass it, each read given only what is left
// (image_io.h, read_image's budget), so loading a scene's images never allocates more than this.
inline constexpr std::uint64_t max_scene_image_bytes = 2ULL << 30;

// Files.
inline constexpr std::size_t max_json_depth = 64;                       // nesting of scene and glTF JSON
inline constexpr std::uintmax_t max_scene_file_bytes = 64ULL << 20;     // a scene JSON file
inline constexpr std::uintmax_t max_mesh_file_bytes = 1ULL << 30;       // an OBJ, glTF, GLB or .bin file
inline constexpr std::uintmax_t max_material_file_bytes = 16ULL << 20;  // an OBJ's mtllib
// glTF: nodes visited through the scene's hierarchy (a DAG instances a node once per path to it).
inline constexpr std::uint64_t max_gltf_node_instances = 1'000'000;
// glTF: values in its JSON (each object, array and element; counted by brackets and commas before tinygltf
// parses). tinygltf builds a structure of some hundred bytes for each (an empty node 575 bytes, counted as
// two values with its comma): 499,000 empty nodes took 294 MB, where a 1 GiB file of them asked for some
// 200 GB. A real glTF's JSON holds thousands of values (its data is in buffers).
inline constexpr std::uint64_t max_gltf_json_values = 1'000'000;
// Triangles of all meshes of a scene together (each instance counted): about 1 GiB of vertex and index data.
inline constexpr std::uint64_t max_scene_triangles = 10'000'000;

// The renderers' backstop: every bound above that a Scene in memory can break (coordinates, lengths,
// directions, light values, triangle count, camera pixels), named by shape or light index.
Result<bool> check_scene_limits(const Scene& scene);

}  // namespace shadelab
