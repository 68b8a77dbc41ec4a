// shadelab image files: read and write OpenEXR, Radiance RGBE and PNG as linear RGB float Images.
//
// Contract (details and reasons in docs/images.md):
// - The format is chosen by the file extension, case-insensitive: .exr (OpenEXR), .hdr / .pic (Radiance
//   RGBE), .png. Any other extension is an error. The file's content must match its extension.
// - read_image returns linear RGB with row 0 at the top. PNG (8 or 16 bit) is decoded with the exact sRGB
//   curve (srgb.h); gAMA / iCCP chunks are ignored. EXR and HDR values are taken as stored (no EXPOSURE or
//   PRIMARIES conversion). Grey becomes R = G = B; alpha is dropped, never multiplied in.
// - EXR: the R, G, B channels (one missing reads as 0), else Y (grey), else luminance/chroma (Y, RY, BY);
//   other channels and layers are ignored; half, float or uint; any compression; scan lines or tiles (the
//   full-resolution level); the first part of a multi-part file. The image covers the display window:
//   texels outside the data window are 0, data outside the display window is cropped.
// - NaN and +-Inf values are replaced by 0 and counted in ReadInfo::nonfinite_repaired; negative values are
//   kept as they are and counted in ReadInfo::negative_values; the first of each (in row-major order) is
//   recorded in ReadInfo::first_nonfinite / first_negative. read_radiance_image refuses both instead.
// - Every failure (missing, empty, truncated or corrupt file, unknown extension, zero or too large size,
//   over the memory budget) is an Error whose one-line message names the file. Nothing throws, nothing
//   prints.
// - Writing is atomic (write_file_atomically): a temporary file in the target's directory, renamed over the
//   target only when complete; on failure the temporary is removed and an existing target is untouched.
//   SIGINT, SIGTERM and SIGHUP are held while a write is in progress and raised again after it, so a signal
//   never leaves a half-written file or a temporary behind; temporaries of our naming left by a process
//   that no longer exists (kill -9) are removed at the next write beside them.
// - Memory: a read allocates at most image_read_budget_bytes (checked from the header, before allocating);
//   an EXR's buffers follow its data window, read in strips, not its display window.
// - PNG palette images whose pixels index past the palette are errors (they would read undefined entries).
// - Different files may be read and written from different threads at once.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/image/image.h"

namespace shadelab {

// The largest image read_image accepts, in pixels (16384 x 8192), and along either side.
inline constexpr long long max_image_pixels = 16384LL * 8192LL;
inline constexpr long long max_image_side = 65536;
// The memory one read_image may allocate: the image (12 bytes a pixel) plus the decoder's buffers (PNG
// samples, EXR strips, the palette check). Checked from the header, before allocating; beyond it the read
// is an error naming the file. 1 GiB: an 8192 x 4096 HDRI takes 384 MiB; 16384 x 8192 (1.5 GiB) is refused.
inline constexpr std::uint64_t image_read_budget_bytes = 1ULL << 30;
// EXR tiles larger than this on a side are refused (OpenEXR allocates a tile buffer from the header).
inline constexpr long long max_exr_tile_side = 4096;

// What read_image found in the file, beyond the pixels.
struct ReadInfo {
  std::string format;           // "exr", "hdr" or "png"
  std::string sample_type;      // "half", "float" or "uint" (EXR), "rgbe" (HDR), "uint8" or "uint16" (PNG)
  int channels = 0;             // channels in the file (EXR: all channels; PNG: 1 to 4; HDR: 3)
  bool had_alpha = false;       // the file had an alpha channel, which was dropped
  bool grey = false;            // the file was grey / luminance only, copied to R, G and B
  bool partial_data_window = false;  // EXR: the data window differs from the display window
  int nonfinite_repaired = 0;   // float values that were NaN or +-Inf and are now 0
  int negative_values = 0;      // float values below 0, kept as they are
  // The first texel (row-major) with a NaN/Inf value and with a negative value, as stored before the repair;
  // x < 0 when there is none. channel: 0 R, 1 G, 2 B.
  struct Texel {
    int x = -1, y = -1, channel = -1;
    float value = 0.0f;
  };
  Texel first_nonfinite;
  Texel first_negative;
};

// How a PNG's samples become values: decoded from sRGB (pictures: the default), or as stored, code / 255 or code /
// 65535 (data such as the lookup tables engines ship linearly: `shadelab bake lut`, `audit-lut`).
// `alpha`: the PNG's alpha channel, code / 255 (or / 65535), in R, G and B; 1 where the file has no alpha (glTF's
// specularTexture and sheenRoughnessTexture keep their data there). Other formats have no alpha to read: an error.
enum class PngSamples { srgb, linear, alpha };

// Reads an image; `info`, when given, is filled on success.
Result<Image> read_image(const std::filesystem::path& path, ReadInfo* info = nullptr);
// The same with a smaller memory budget (at most image_read_budget_bytes): a scene gives each image what is
// left of its own budget (scene/limits.h, max_scene_image_bytes).
Result<Image> read_image(const std::filesystem::path& path, ReadInfo* info, std::uint64_t budget_bytes);
// The same with a PNG's samples read as `png` says (the other formats are unaffected).
Result<Image> read_image(const std::filesystem::path& path, ReadInfo* info, std::uint64_t budget_bytes, PngSamples png);

// Lossy EXR compression (DWAA/DWAB, the Blender worlds) leaves small negative values around dark texels:
// down to -0.025 of the map's mean value on blender-data's night.exr (-0.0057 and less on the seven others).
// A negative value no further below 0 than this share of the map's mean (over every value) is such noise and
// kept, as read_image keeps it; one further below is bad radiance.
inline constexpr double radiance_negative_tolerance = 0.05;

// An image of radiance (an environment map: `bake`, `ibl-error`, a scene's environment file, `sheet --hdri`,
// the explorer's HDRIs): read_image, and then a NaN or Inf value, or a negative one beyond the tolerance
// above (any negative one when the map's mean is not above 0), is an Error naming the file, the first such
// texel (x, y, as the image reads: row 0 at the top) and its channel. Radiance is never negative or
// infinite, and an environment's texels are light: repairing or clamping them would bake a different light
// than the file holds without saying so (docs/testing.md, "Classes of bad input").
Result<Image> read_radiance_image(const std::filesystem::path& path, ReadInfo* info = nullptr,
                                  std::uint64_t budget_bytes = image_read_budget_bytes);
// The check alone, for a read already made (image and info from read_image): an Error as above, or true.
Result<bool> check_radiance(const std::filesystem::path& path, const Image& image, const ReadInfo& info);

enum class ExrPixelType {
  float32,  // exact: 32-bit IEEE float per channel
  half,     // 16-bit half float; finite values beyond +-65504 are clamped to +-65504
};

enum class ExrCompression {
  none,
  rle,
  zips,  // zlib, one scan line per block
  zip,   // zlib, 16 scan lines per block
  piz,   // wavelet + Huffman; the usual choice for noisy half images
};

// Options for write_image. The defaults write an exact, lossless file.
struct WriteOptions {
  ExrPixelType exr_pixel_type = ExrPixelType::float32;
  ExrCompression exr_compression = ExrCompression::zip;
  // PNG only: pixels are multiplied by 2^exposure (stops) before clamping to [0, 1] and sRGB encoding.
  double exposure = 0.0;
  // PNG only: linear writes round(clamp(v 2^exposure, 0, 1) 255) with no sRGB encoding (8-bit data textures).
  PngSamples png_samples = PngSamples::srgb;
};

// An 8-bit RGBA image as its codes (row 0 at the top, 4 bytes a pixel): for textures whose codes matter as they
// are (the glTF material conversion, `convert gltf`).
struct Rgba8Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
};
// Decodes a PNG (with read_image's checks: chunks, CRC-independent truncation, palette indices, size) or a JPEG
// (stb_image) held in memory; grey and RGB gain A = 255, a 16-bit PNG is reduced to 8 bits by stb_image. The Error
// names `name` (a file, or where in a glTF the bytes are).
Result<Rgba8Image> decode_rgba8(const std::vector<unsigned char>& bytes, const std::string& name);
// The bytes of an 8-bit RGBA PNG of the codes (no colour conversion), for write_files_atomically.
Result<std::vector<char>> encode_png_rgba8(const Rgba8Image& image, const std::filesystem::path& path);

// Writes `bytes` to `path` atomically: to a new temporary file in the same directory (created exclusively,
// flushed with fsync), renamed over `path` only when complete. On failure the temporary is removed, an
// existing `path` is untouched, and the Error names `path`. write_image uses it; so can any other writer.
Result<bool> write_file_atomically(const std::filesystem::path& path, const std::vector<char>& bytes);

// Options of write_files_atomically.
struct PublishOptions {
  // Called under the folder locks with every other regular file in the targets' folders (not a target, not a
  // temporary): true removes it in the same step as the renames. For the files of an older output of the same
  // name that the new one does not have (`bake specular`'s deeper levels of a longer chain).
  std::function<bool(const std::filesystem::path&)> remove_also;
  // Tests only: called at each step ("locked", "written", "prepared" (multi-folder sets), "committed",
  // "renamed-first", "renamed", "done"), so that a test can end the process there as a kill -9 would.
  std::function<void(const char* step)> after_step;
};

// Writes several files as one output set, the one mechanism behind every file shadelab writes (docs/design.md,
// "Output sets"): the targets' folders are locked (flock on each folder, in the order of their real paths;
// concurrent writers are serialised), what a dead run left there is settled (a committed set completed, stale
// temporaries removed), every file is written to its temporary beside its target (".NAME.set-ID.tmp", fsync'd),
// a journal ".shadelab-set-ID.journal" is written (the commit point; only for more than one change), then the
// renames and removals, then the journal goes. A failure before the commit leaves every target untouched; a
// failed rename puts the targets renamed before it back; a kill -9 after the commit is completed by the next
// writer into that folder. No temporary is left. The Error names the file that failed.
Result<bool> write_files_atomically(
    const std::vector<std::pair<std::filesystem::path, std::vector<char>>>& files, const PublishOptions& options = {});

// The bytes write_image would write to `path` (format by extension), for a caller that writes several files
// as one set (write_files_atomically).
Result<std::vector<char>> encode_image(const Image& image, const std::filesystem::path& path,
                                       const WriteOptions& options = {});

// Walks an OpenEXR file's header(s) before OpenEXR reads them: the magic number, the version field, and
// every attribute (name, type, a 4-byte size, the value), checking that each name is terminated within the
// limit, that no size is negative, and that no attribute claims more bytes than the file has left after it.
// OpenEXR 3.1 allocates an attribute's value from its claimed size before reading it and has no setting that
// bounds it (issue 40, finding 3: a 1,124-byte file whose string attribute claimed 0x7fffffff bytes took
// 2.1 GB), so every EXR reader here calls this first. Reads the header in small pieces; allocates nothing in
// proportion to a claimed size. The Error (`who: 'FILE': ...`) names the file and the attribute.
Result<bool> check_exr_header(const std::filesystem::path& path, const char* who = "read_image");
// The same walk: what is wrong with the header (one line, without the file's name), or "" when nothing is.
std::string exr_header_problem(const std::filesystem::path& path);

// Writes `image` by extension: .exr (OpenEXR, R G B channels, options above), .hdr / .pic (Radiance RGBE;
// negative and non-finite values are written as 0, as RGBE cannot hold them), .png (8-bit sRGB, or linear codes
// with png_samples = linear; exposure applied, clamped to [0, 1], rounded to the nearest code, NaN -> 0). Returns true or an Error.
Result<bool> write_image(const Image& image, const std::filesystem::path& path, const WriteOptions& options = {});

}  // namespace shadelab
