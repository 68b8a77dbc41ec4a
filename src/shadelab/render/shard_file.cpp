#include "shadelab/render/shard_file.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <concepts>
#include <cstring>
#include <exception>
#include <map>
#include <variant>

#include "shadelab/core/text.h"
#include "shadelab/image/image_io.h"
#include "shadelab/sampling/owen.h"

namespace shadelab {

namespace {

namespace fs = std::filesystem;

constexpr const char* shard_format = "shadelab-shard/1";
constexpr const char* shard_attribute = "shadelab.shard";
// Changes when the fingerprint's walk changes, so that no two walks can give the same hash by chance.
constexpr const char* scene_fingerprint_version = "shadelab-scene-fingerprint/2";
constexpr const char* channel_colour[3] = {"R", "G", "B"};

std::string sum_channel(int c, int word) { return std::string("sum.") + channel_colour[c] + ".w" + std::to_string(word); }

// A fingerprint, not a cryptographic hash: every 64-bit word goes through SplitMix64's finalizer, chained
// with its position, so reordered or shifted data hashes differently.
class Hasher {
 public:
  void u64(std::uint64_t v) { m_h = mix64(m_h ^ mix64(v + m_n++)); }
  std::uint64_t value() const { return m_h; }

 private:
  std::uint64_t m_h = 0x243f6a8885a308d3ULL;
  std::uint64_t m_n = 0;
};

// The scene fingerprint's walk over a Scene: robust by construction, not a list kept by hand.
//
// - Every struct is taken apart with a structured binding, which must name every data member: a member added
//   to Scene, Camera, Texture, Material, a shape, a light, Environment, SkyModel, RenderSettings, Image,
//   GlossEncoding, Vec2/Vec3 or Rgb stops this file compiling until it is hashed here, or left out below
//   with its reason. (That is the check the issue 40 finding lacked: Material's base_color_texture and
//   metallic_roughness_texture were added after the list was written, and two scenes differing only there
//   gave parts that merged.) The light variant is visited with one overload per alternative and no catch-all,
//   so a new light type does not compile without one either.
// - Values are hashed as the renderer sees them, after loading: texels after decoding, vertices after the
//   transform, the environment map's texels. So the content of every file the scene read is covered, and
//   its name is not (a scene moved to another folder or machine still matches).
// - Deterministic across runs and machines: doubles and floats by their bit patterns, integers widened to 64
//   bits, sizes before every sequence and string; no pointer, no padding byte, no std::hash.
// - Left out, each for its reason: Scene::source, Texture::source, MeshShape::source, Environment::source
//   (paths, for messages); Material::brdf (built from model and params, which are hashed); RenderSettings'
//   spp, max_depth and seed (fields of their own in ShardInfo, as the render resolved them: options may
//   override the scene's) and threads (the image is the same for any thread count).
class SceneHasher {
 public:
  explicit SceneHasher(Hasher& h) : m_h(h) {}

  void add(std::uint64_t v) { m_h.u64(v); }
  void add(std::uint32_t v) { m_h.u64(v); }
  void add(int v) { m_h.u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(v))); }
  // bool and the variant only as themselves: a pointer member must not pass as a bool, nor a new light type
  // through the variant's converting constructor (which would recurse instead of failing to compile).
  template <class B>
    requires std::same_as<B, bool>
  void add(B v) {
    m_h.u64(v ? 1u : 0u);
  }
  void add(double v) { m_h.u64(std::bit_cast<std::uint64_t>(v)); }
  void add(const std::string& s) {
    add(static_cast<std::uint64_t>(s.size()));
    for (std::size_t k = 0; k < s.size(); k += 8) {
      std::uint64_t w = 0;
      std::memcpy(&w, s.data() + k, std::min<std::size_t>(8, s.size() - k));
      add(w);
    }
  }
  template <class A, class B>
  void add(const std::pair<A, B>& p) {
    add(p.first), add(p.second);
  }
  template <class T>
  void add(const std::vector<T>& v) {
    add(static_cast<std::uint64_t>(v.size()));
    for (const T& x : v) add(x);
  }
  void add(const Vec2& v) {
    const auto& [x, y] = v;
    add(x), add(y);
  }
  void add(const Vec3& v) {
    const auto& [x, y, z] = v;
    add(x), add(y), add(z);
  }
  void add(const Rgb& c) {
    const auto& [r, g, b] = c;
    add(r), add(g), add(b);
  }
  void add(const Image& im) {
    const auto& [width, height, data] = im;
    add(width), add(height), add(static_cast<std::uint64_t>(data.size()));
    // Two floats a word: the cost of a large environment map is one pass over its texels.
    std::size_t k = 0;
    for (; k + 1 < data.size(); k += 2) {
      add(std::bit_cast<std::uint32_t>(data[k]) | (static_cast<std::uint64_t>(std::bit_cast<std::uint32_t>(data[k + 1])) << 32u));
    }
    if (k < data.size()) add(std::bit_cast<std::uint32_t>(data[k]));
  }
  void add(const Camera& c) {
    const auto& [position, look_at, up, vfov_deg, width, height] = c;
    add(position), add(look_at), add(up), add(vfov_deg), add(width), add(height);
  }
  void add(const Texture& t) {
    const auto& [name, source, image, data] = t;
    (void)source;  // the path or generator, for messages; the texels are hashed
    add(name), add(image), add(data);
  }
  void add(const GlossEncoding& g) {
    const auto& [n_black, n_white] = g;
    add(n_black), add(n_white);
  }
  void add(const Material& m) {
    const auto& [name, model, params, brdf, kd_texture, ks_texture, gloss_texture, normal_texture, base_color_texture,
                 metallic_roughness_texture, param_textures, gloss_encoding, uv_scale, emission] = m;
    (void)brdf;  // built from model and params
    add(name), add(model), add(params);
    add(kd_texture), add(ks_texture), add(gloss_texture), add(normal_texture), add(base_color_texture),
        add(metallic_roughness_texture);
    // Only when there are any, so that the fingerprints of scenes without them (every scene before they existed)
    // stay what they were (SceneFingerprint.PathsThreadsAndTheShardInfoFieldsLeaveItAlone pins one).
    if (!param_textures.empty()) {
      add(static_cast<std::uint64_t>(param_textures.size()));
      for (const ParamTexture& p : param_textures) add(p);
    }
    add(gloss_encoding), add(uv_scale), add(emission);
  }
  void add(const ParamTexture& p) {
    const auto& [param, texture, channel, use, transform] = p;
    add(param), add(texture), add(channel), add(static_cast<int>(use));
    const auto& [m00, m01, m02, m10, m11, m12] = transform;
    add(m00), add(m01), add(m02), add(m10), add(m11), add(m12);
  }
  void add(const SphereShape& s) {
    const auto& [center, radius, material] = s;
    add(center), add(radius), add(material);
  }
  void add(const QuadShape& q) {
    const auto& [corner, u, v, material] = q;
    add(corner), add(u), add(v), add(material);
  }
  void add(const DiskShape& d) {
    const auto& [center, normal, radius, material] = d;
    add(center), add(normal), add(radius), add(material);
  }
  void add(const MeshShape& m) {
    const auto& [source, positions, normals, uvs, indices, material] = m;
    (void)source;  // the path, for messages; the vertices are hashed
    add(positions), add(normals), add(uvs), add(indices), add(material);
  }
  void add(const DirectionalLight& l) {
    const auto& [to_light, irradiance, game_sh] = l;
    add(to_light), add(irradiance), add(game_sh);
  }
  void add(const PointLight& l) {
    const auto& [position, intensity] = l;
    add(position), add(intensity);
  }
  void add(const SpotLight& l) {
    const auto& [position, axis, intensity, cos_inner, cos_outer] = l;
    add(position), add(axis), add(intensity), add(cos_inner), add(cos_outer);
  }
  void add(const SphereLight& l) {
    const auto& [center, radius, radiance] = l;
    add(center), add(radius), add(radiance);
  }
  void add(const HemisphereLight& l) {
    const auto& [up, sky, ground] = l;
    add(up), add(sky), add(ground);
  }
  template <class L>
    requires std::same_as<L, SceneLight>
  void add(const L& l) {
    add(static_cast<std::uint64_t>(l.index()));
    std::visit([this](const auto& x) { this->add(x); }, l);
  }
  void add(const SkyModel& s) {
    const auto& [sun_direction, sun_angular_radius_deg, sun_irradiance, zenith, horizon, ground] = s;
    add(sun_direction), add(sun_angular_radius_deg), add(sun_irradiance), add(zenith), add(horizon), add(ground);
  }
  void add(const Environment& e) {
    const auto& [kind, uniform, latlong, source, rotation_deg, scale, sky] = e;
    (void)source;  // the path, for messages; the texels are hashed
    add(static_cast<int>(kind)), add(uniform), add(latlong), add(rotation_deg), add(scale), add(sky);
  }
  void add(const RenderSettings& r) {
    const auto& [spp, max_depth, seed, threads, rr_depth] = r;
    (void)spp, (void)max_depth, (void)seed;  // ShardInfo's own fields, as resolved for the render
    (void)threads;                           // no effect on the image
    add(rr_depth);
  }
  void add(const Scene& s) {
    const auto& [source, camera, textures, materials, spheres, quads, disks, meshes, lights, environment, settings,
                 warnings] = s;
    (void)source;    // the path, for messages
    (void)warnings;  // messages about what was read past; they do not change the image
    add(camera), add(textures), add(materials), add(spheres), add(quads), add(disks), add(meshes), add(lights),
        add(environment), add(settings);
  }

 private:
  Hasher& m_h;
};

// OpenEXR's messages quote the file's own bytes (a channel name holding \x01: the shard fuzzer's finding of
// issue 40): the reason is made one printable line (core/text.h) like every other message.
Error file_error(const fs::path& path, const std::string& why) {
  return make_error("'" + path.string() + "': " + printable(why, max_message_bytes));
}

class MemoryStream final : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    const auto count = static_cast<std::size_t>(n);
    if (m_bytes.size() < m_pos + count) m_bytes.resize(m_pos + count);
    std::memcpy(m_bytes.data() + m_pos, c, count);
    m_pos += count;
  }
  std::uint64_t tellp() override { return m_pos; }
  void seekp(std::uint64_t pos) override { m_pos = static_cast<std::size_t>(pos); }
  const std::vector<char>& bytes() const { return m_bytes; }

 private:
  std::vector<char> m_bytes;
  std::size_t m_pos = 0;
};

nlohmann::json to_json(const ShardInfo& s) {
  return {{"format", shard_format}, {"scene_hash", s.scene_hash}, {"scene", s.scene}, {"renderer", s.renderer},
          {"seed", s.seed}, {"spp", s.spp}, {"max_depth", s.max_depth}, {"sampling", s.sampling}, {"sampler", s.sampler},
          {"width", s.width}, {"height", s.height}, {"split", s.split}, {"index", s.index}, {"count", s.count},
          {"sample_begin", s.sample_begin}, {"sample_end", s.sample_end}, {"tile_size", s.tile_size},
          {"fixed_point_bits", s.fixed_point_bits}, {"nonfinite_samples", s.nonfinite_samples}};
}

}  // namespace

std::string scene_fingerprint(const Scene& scene) {
  Hasher h;
  SceneHasher walk(h);
  walk.add(std::string(scene_fingerprint_version));
  walk.add(scene);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.value()));
  return hex;
}

std::vector<std::pair<std::string, std::string>> ShardInfo::render_identity() const {
  return {{"renderer", renderer},
          {"scene_hash", scene_hash},
          {"seed", std::to_string(seed)},
          {"spp", std::to_string(spp)},
          {"max_depth", std::to_string(max_depth)},
          {"sampling", sampling},
          {"sampler", sampler},
          {"width", std::to_string(width)},
          {"height", std::to_string(height)},
          {"split", split},
          {"count", std::to_string(count)},
          {"tile_size", std::to_string(tile_size)},
          {"fixed_point_bits", std::to_string(fixed_point_bits)}};
}

std::string identity_difference(const ShardInfo& got, const ShardInfo& want) {
  const auto g = got.render_identity();
  const auto w = want.render_identity();
  for (std::size_t f = 0; f < w.size(); ++f) {
    if (w[f].second == g[f].second) continue;
    std::string why = g[f].first + " " + g[f].second + ", but " + w[f].second;
    // The hash alone says nothing to a person: say that the scenes differ, and which files they came from.
    if (g[f].first == "scene_hash") {
      why += " (another scene, or the scene's content differs: its camera, materials, textures, meshes, lights or "
             "environment; scene '" + got.scene + "' against '" + want.scene + "')";
    }
    return why;
  }
  return {};
}

ShardSpec ShardInfo::spec() const { return {index, count, split == "tiles" ? ShardSplit::tiles : ShardSplit::samples}; }

ShardInfo make_shard_info(const Scene& scene, const RenderOptions& options, int spp, int max_depth) {
  ShardInfo s;
  s.scene_hash = scene_fingerprint(scene);
  s.scene = scene.source;
  s.seed = scene.settings.seed;
  s.spp = spp;
  s.max_depth = max_depth;
  s.sampling = options.mode == SamplingMode::mis ? "mis" : options.mode == SamplingMode::brdf ? "brdf" : "light";
  s.sampler = options.sampler == SamplerKind::owen_sobol ? "sobol" : "independent";
  s.width = scene.camera.width;
  s.height = scene.camera.height;
  s.split = options.shard.split == ShardSplit::tiles ? "tiles" : "samples";
  s.index = options.shard.index;
  s.count = options.shard.count;
  const auto [b, e] = shard_sample_range(spp, options.shard);
  s.sample_begin = b;
  s.sample_end = e;
  return s;
}

bool same_shard(const ShardInfo& a, const ShardInfo& b) {
  return a.render_identity() == b.render_identity() && a.index == b.index && a.sample_begin == b.sample_begin &&
         a.sample_end == b.sample_end;
}

Result<bool> write_shard(const fs::path& path, const ShardInfo& info, const RenderResult& result) {
  const auto pixels = static_cast<std::size_t>(info.width) * static_cast<std::size_t>(info.height);
  if (result.sums.size() != pixels || result.nonfinite.size() != pixels || result.beauty.pixel_count() != pixels) {
    return make_error("write_shard: " + file_error(path, "the render has not the image size of its description").message);
  }
  std::vector<std::uint32_t> words(pixels * 12);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < 3; ++c) {
      const auto w = to_words(result.sums[p].c[c]);
      for (int k = 0; k < 4; ++k) words[p * 12 + static_cast<std::size_t>(4 * c + k)] = w[static_cast<std::size_t>(k)];
    }
  }
  try {
    Imf::Header header(info.width, info.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    // The scene's path may be any bytes Linux allows; JSON holds UTF-8, so a byte outside it is written as
    // U+FFFD (the name is for people: parts match by render_identity(), which holds the scene's hash).
    header.insert(shard_attribute, Imf::StringAttribute(to_json(info).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)));
    Imf::FrameBuffer fb;
    auto* beauty = const_cast<float*>(result.beauty.data.data());  // OpenEXR's slices are non-const; only read
    auto* nonfinite = const_cast<std::uint32_t*>(result.nonfinite.data());
    header.channels().insert("nonfinite", Imf::Channel(Imf::UINT));
    fb.insert("nonfinite", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(nonfinite), sizeof(std::uint32_t),
                                      sizeof(std::uint32_t) * static_cast<std::size_t>(info.width)));
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(channel_colour[c], Imf::Channel(Imf::FLOAT));
      fb.insert(channel_colour[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(beauty + c), 3 * sizeof(float),
                                              3 * sizeof(float) * static_cast<std::size_t>(info.width)));
      for (int k = 0; k < 4; ++k) {
        header.channels().insert(sum_channel(c, k), Imf::Channel(Imf::UINT));
        fb.insert(sum_channel(c, k), Imf::Slice(Imf::UINT, reinterpret_cast<char*>(words.data() + 4 * c + k), 12 * sizeof(std::uint32_t),
                                                12 * sizeof(std::uint32_t) * static_cast<std::size_t>(info.width)));
      }
    }
    MemoryStream stream;
    {
      Imf::OutputFile out(stream, header);
      out.setFrameBuffer(fb);
      out.writePixels(info.height);
    }
    return write_file_atomically(path, stream.bytes());
  } catch (const std::exception& e) {
    return make_error("write_shard: " + file_error(path, e.what()).message);
  }
}

Result<ShardInfo> read_shard_info(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return file_error(path, fs::exists(path, ec) ? "not a regular file" : "no such file");
  // Header sizes bounded by the file's before OpenEXR allocates from them (issue 40, finding 3).
  if (const std::string why = exr_header_problem(path); !why.empty()) return file_error(path, "not a readable EXR file: " + why);
  try {
    Imf::InputFile in(path.c_str());
    const Imf::Header& header = in.header();
    const auto* attr = header.findTypedAttribute<Imf::StringAttribute>(shard_attribute);
    if (attr == nullptr) return file_error(path, "not a shadelab shard (no '" + std::string(shard_attribute) + "' header attribute)");
    const auto j = nlohmann::json::parse(attr->value(), nullptr, false);
    if (j.is_discarded() || !j.is_object()) return file_error(path, "the shard description is not JSON");
    if (j.value("format", std::string()) != shard_format) {
      return file_error(path, "shard format '" + j.value("format", std::string("?")) + "', this shadelab reads '" + shard_format + "'");
    }
    ShardInfo s;
    try {
      s.scene_hash = j.at("scene_hash").get<std::string>();
      s.scene = j.at("scene").get<std::string>();
      s.renderer = j.at("renderer").get<std::string>();
      s.seed = j.at("seed").get<std::uint64_t>();
      s.spp = j.at("spp").get<int>();
      s.max_depth = j.at("max_depth").get<int>();
      s.sampling = j.at("sampling").get<std::string>();
      s.sampler = j.at("sampler").get<std::string>();
      s.width = j.at("width").get<int>();
      s.height = j.at("height").get<int>();
      s.split = j.at("split").get<std::string>();
      s.index = j.at("index").get<int>();
      s.count = j.at("count").get<int>();
      s.sample_begin = j.at("sample_begin").get<int>();
      s.sample_end = j.at("sample_end").get<int>();
      s.tile_size = j.at("tile_size").get<int>();
      s.fixed_point_bits = j.at("fixed_point_bits").get<int>();
      s.nonfinite_samples = j.at("nonfinite_samples").get<std::uint64_t>();
    } catch (const nlohmann::json::exception& e) {
      return file_error(path, std::string("the shard description lacks a field or has a wrong type: ") + e.what());
    }
    if (s.split != "samples" && s.split != "tiles") return file_error(path, "split '" + s.split + "' is not samples or tiles");
    if (s.count < 1 || s.index < 0 || s.index >= s.count) {
      return file_error(path, "shard " + std::to_string(s.index) + "/" + std::to_string(s.count) + " is out of range");
    }
    if (s.spp < 1 || s.spp > 1000000 || s.width < 1 || s.height < 1 || static_cast<long long>(s.width) * s.height > max_image_pixels) {
      return file_error(path, "spp, width or height out of range");
    }
    const auto [b, e] = shard_sample_range(s.spp, s.spec());
    if (s.sample_begin != b || s.sample_end != e) {
      return file_error(path, "samples [" + std::to_string(s.sample_begin) + ", " + std::to_string(s.sample_end) +
                                  ") are not those of shard " + std::to_string(s.index) + "/" + std::to_string(s.count) +
                                  " (an incomplete or altered part)");
    }
    if (s.tile_size != render_tile_size || s.fixed_point_bits != fixed_point_bits) {
      return file_error(path, "tile size or fixed-point precision of another shadelab version");
    }
    const Imath::Box2i dw = header.dataWindow();
    const Imath::Box2i disp = header.displayWindow();
    if (dw != disp || dw.min.x != 0 || dw.min.y != 0 || dw.max.x != s.width - 1 || dw.max.y != s.height - 1) {
      return file_error(path, "the data window is not the " + std::to_string(s.width) + " x " + std::to_string(s.height) + " image");
    }
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 4; ++k) {
        const Imf::Channel* ch = header.channels().findChannel(sum_channel(c, k));
        if (ch == nullptr || ch->type != Imf::UINT) return file_error(path, "channel " + sum_channel(c, k) + " missing or not uint");
      }
    }
    if (const Imf::Channel* ch = header.channels().findChannel("nonfinite"); ch == nullptr || ch->type != Imf::UINT) {
      return file_error(path, "channel nonfinite missing or not uint");
    }
    return s;
  } catch (const std::exception& e) {
    std::string why = e.what();
    std::replace(why.begin(), why.end(), '\n', ' ');
    return file_error(path, "not a readable EXR file: " + why);
  }
}

Result<ShardSums> read_shard_sums(const fs::path& path, const ShardInfo& info) {
  const auto pixels = static_cast<std::size_t>(info.width) * static_cast<std::size_t>(info.height);
  try {
    std::vector<std::uint32_t> words(pixels * 12);
    Imf::InputFile in(path.c_str());
    Imf::FrameBuffer fb;
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 4; ++k) {
        fb.insert(sum_channel(c, k), Imf::Slice(Imf::UINT, reinterpret_cast<char*>(words.data() + 4 * c + k), 12 * sizeof(std::uint32_t),
                                                12 * sizeof(std::uint32_t) * static_cast<std::size_t>(info.width)));
      }
    }
    ShardSums out;
    out.nonfinite.assign(pixels, 0);
    fb.insert("nonfinite", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(out.nonfinite.data()), sizeof(std::uint32_t),
                                      sizeof(std::uint32_t) * static_cast<std::size_t>(info.width)));
    in.setFrameBuffer(fb);
    in.readPixels(0, info.height - 1);
    out.sums.resize(pixels);
    std::uint64_t nonfinite = 0;
    // No sample adds more than 2^(52 + 40) in magnitude (fixed_sum.h): a larger sum is not a render's, and the
    // bound keeps the merge's 128-bit additions far from overflow (spp <= 10^6 < 2^20 samples in all).
    const UInt128 bound = static_cast<UInt128>(info.sample_end - info.sample_begin) << 92u;
    for (std::size_t p = 0; p < pixels; ++p) {
      nonfinite += out.nonfinite[p];
      for (std::size_t c = 0; c < 3; ++c) {
        const Int128 v = from_words({words[p * 12 + 4 * c], words[p * 12 + 4 * c + 1], words[p * 12 + 4 * c + 2], words[p * 12 + 4 * c + 3]});
        const UInt128 magnitude = v < 0 ? static_cast<UInt128>(0) - static_cast<UInt128>(v) : static_cast<UInt128>(v);
        if (magnitude > bound) {
          return file_error(path, "pixel (" + std::to_string(p % static_cast<std::size_t>(info.width)) + ", " +
                                      std::to_string(p / static_cast<std::size_t>(info.width)) + ") has a sum larger than its samples can give (an altered part)");
        }
        out.sums[p].c[c] = v;
      }
    }
    if (nonfinite != info.nonfinite_samples) {
      return file_error(path, "the nonfinite channel adds up to " + std::to_string(nonfinite) + ", the header says " +
                                  std::to_string(info.nonfinite_samples) + " (an altered part)");
    }
    return out;
  } catch (const std::exception& e) {
    std::string why = e.what();
    std::replace(why.begin(), why.end(), '\n', ' ');
    return file_error(path, "cannot read the shard's sums: " + why);
  }
}

Result<MergeStatus> check_shards(const std::vector<fs::path>& parts) {
  if (parts.empty()) return make_error("no parts given");
  MergeStatus status;
  std::map<int, fs::path> seen;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    auto info = read_shard_info(parts[k]);
    if (!info) return info.error();
    if (k == 0) {
      status.first = *info;
    } else if (const std::string why = identity_difference(*info, status.first); !why.empty()) {
      return file_error(parts[k], "from another render: " + why + " in '" + parts[0].string() + "'");
    }
    if (const auto it = seen.find(info->index); it != seen.end()) {
      return file_error(parts[k], "shard " + std::to_string(info->index) + "/" + std::to_string(info->count) +
                                      " again (also '" + it->second.string() + "')");
    }
    seen.emplace(info->index, parts[k]);
    status.nonfinite_samples += info->nonfinite_samples;
  }
  for (int i = 0; i < status.first.count; ++i) (seen.count(i) != 0 ? status.present : status.missing).push_back(i);
  return status;
}

Result<MergedRender> merge_shards(const std::vector<fs::path>& parts, const std::function<void(double)>& progress) {
  auto status = check_shards(parts);
  if (!status) return status.error();
  const ShardInfo& first = status->first;
  if (!status->missing.empty()) {
    std::string list;
    for (std::size_t k = 0; k < status->missing.size() && k < 8; ++k) list += (k ? ", " : "") + std::to_string(status->missing[k]);
    if (status->missing.size() > 8) list += ", ...";
    return make_error(std::to_string(status->missing.size()) + " of " + std::to_string(first.count) + " shards missing (index " + list +
                      "): no part of " + std::to_string(parts.size()) + " given, starting with '" + parts[0].string() + "', is one");
  }
  MergedRender merged;
  merged.status = *status;
  RenderResult& r = merged.result;
  r.sums.assign(static_cast<std::size_t>(first.width) * static_cast<std::size_t>(first.height), FixedRgb{});
  r.nonfinite.assign(r.sums.size(), 0);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    auto info = read_shard_info(parts[k]);  // the file may have changed since check_shards
    if (!info) return info.error();
    if (info->render_identity() != first.render_identity()) return file_error(parts[k], "changed while merging");
    auto sums = read_shard_sums(parts[k], *info);
    if (!sums) return sums.error();
    for (std::size_t p = 0; p < r.sums.size(); ++p) {
      r.sums[p] += sums->sums[p];
      r.nonfinite[p] += sums->nonfinite[p];
    }
    if (progress) progress(static_cast<double>(k + 1) / static_cast<double>(parts.size()));
  }
  r.sample_begin = 0;
  r.sample_end = first.spp;
  r.beauty = image_from_sums(r.sums, r.nonfinite, first.width, first.height, static_cast<std::uint64_t>(first.spp));
  r.stats.spp_done = first.spp;
  r.stats.nonfinite_samples = status->nonfinite_samples;
  return merged;
}

}  // namespace shadelab
