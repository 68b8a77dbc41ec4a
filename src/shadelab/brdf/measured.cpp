#include "shadelab/brdf/measured.h"

#include "shadelab/brdf/rgl.h"
#include "shadelab/brdf/utia.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

#include "shadelab/color/rgb.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

namespace {

// Direction at elevation cos theta = z and azimuth phi.
Vec3 direction(double z, double phi) { return spherical_direction(std::sqrt(std::max(0.0, 1.0 - z * z)), z, phi); }

// The interpolation coordinate of one axis: the lower cell and the weight of the upper one.
struct Axis {
  int i0 = 0, i1 = 0;
  double t = 0.0;
};
Axis clamped_axis(double x, int n) {
  x = std::clamp(x, 0.0, static_cast<double>(n - 1));
  Axis a;
  a.i0 = std::min(static_cast<int>(x), n - 2);
  a.i1 = a.i0 + 1;
  a.t = x - a.i0;
  return a;
}
Axis periodic_axis(double x, int n) {
  const double f = std::floor(x);
  Axis a;
  a.t = x - f;
  const int i = static_cast<int>(f);
  a.i0 = ((i % n) + n) % n;
  a.i1 = (a.i0 + 1) % n;
  return a;
}

}  // namespace

MeasuredBrdf::MeasuredBrdf(std::shared_ptr<const MerlTable> table) : m_table(std::move(table)) {
  std::vector<Distribution2D> views;
  views.reserve(view_bins);
  std::vector<double> mass(static_cast<std::size_t>(phi_cells) * z_cells);
  for (int v = 0; v < view_bins; ++v) {
    const double theta_o = (v + 0.5) / view_bins * 0.5 * pi;
    const Vec3 wo = direction(std::cos(theta_o), 0.0);
    for (int j = 0; j < z_cells; ++j) {
      const double z = (j + 0.5) / z_cells;
      for (int i = 0; i < phi_cells; ++i) {
        const double phi = (i + 0.5) / phi_cells * two_pi;
        mass[static_cast<std::size_t>(j) * phi_cells + static_cast<std::size_t>(i)] =
            std::max(0.0, luminance(eval(direction(z, phi), wo))) * z;
      }
    }
    // Finite and non-negative by construction; an all-zero view (a black table) is uniform.
    views.push_back(std::move(*Distribution2D::create(mass, phi_cells, z_cells)));
  }
  m_views = std::make_shared<const std::vector<Distribution2D>>(std::move(views));
}

int MeasuredBrdf::view_bin(const Vec3& wo) const {
  const double theta_o = std::acos(std::clamp(wo.z, 0.0, 1.0));
  return std::min(static_cast<int>(theta_o / (0.5 * pi) * view_bins), view_bins - 1);
}

Rgb MeasuredBrdf::eval(const Vec3& wi, const Vec3& wo) const {
  if (!(wi.z > 0.0 && wo.z > 0.0)) return {};
  const HalfDiffAngles a = half_diff_angles(wi, wo);
  const double phi_d = a.phi_d < 0.0 ? a.phi_d + pi : a.phi_d;
  const Axis h = clamped_axis(std::sqrt(std::max(a.theta_h, 0.0) / (0.5 * pi)) * MerlTable::n_theta_h - 0.5, MerlTable::n_theta_h);
  const Axis d = clamped_axis(a.theta_d / (0.5 * pi) * MerlTable::n_theta_d - 0.5, MerlTable::n_theta_d);
  const Axis p = periodic_axis(phi_d / pi * MerlTable::n_phi_d - 0.5, MerlTable::n_phi_d);
  double sum[3] = {0.0, 0.0, 0.0};
  double weight[3] = {0.0, 0.0, 0.0};
  // The corners over (theta_h, phi_d) at theta_d bins id0 (weight 1 - td) and id1 (weight td).
  const auto gather = [&](int id0, int id1, double td) {
    for (int corner = 0; corner < 8; ++corner) {
      const int ih = (corner & 1) ? h.i1 : h.i0, id = (corner & 2) ? id1 : id0, ip = (corner & 4) ? p.i1 : p.i0;
      const double w = ((corner & 1) ? h.t : 1.0 - h.t) * ((corner & 2) ? td : 1.0 - td) * ((corner & 4) ? p.t : 1.0 - p.t);
      if (w == 0.0) continue;
      const std::size_t idx = MerlTable::index(ih, id, ip);
      for (int c = 0; c < 3; ++c) {
        const double v = m_table->value(c, idx);
        if (v < 0.0) continue;  // not measured: drops out
        sum[c] += w * v;
        weight[c] += w;
      }
    }
  };
  gather(d.i0, d.i1, d.t);
  // All eight missing (a grazing pair whose neighbouring centres are all below the horizon): the nearest theta_d
  // row below with a measured corner, constant in theta_d from there (a smaller theta_d brings both directions
  // toward h, above the horizon).
  for (int id = d.i0 - 1; id >= 0 && weight[0] == 0.0 && weight[1] == 0.0 && weight[2] == 0.0; --id) gather(id, id, 0.0);
  Rgb f;
  f.r = weight[0] > 0.0 ? sum[0] / weight[0] : 0.0;
  f.g = weight[1] > 0.0 ? sum[1] / weight[1] : 0.0;
  f.b = weight[2] > 0.0 ? sum[2] / weight[2] : 0.0;
  return f;
}

double MeasuredBrdf::pdf(const Vec3& wi, const Vec3& wo) const {
  if (!(wo.z > 0.0) || !(wi.z > 0.0)) return 0.0;
  double rel = std::atan2(wi.y, wi.x) - std::atan2(wo.y, wo.x);
  rel -= two_pi * std::floor(rel / two_pi);
  const double x = std::min(rel / two_pi, std::nextafter(1.0, 0.0));
  const double y = std::min(wi.z, std::nextafter(1.0, 0.0));
  // dw = d(cos theta) d(phi) = 2 pi dx dy.
  const double table = (*m_views)[static_cast<std::size_t>(view_bin(wo))].pdf({x, y}) / two_pi;
  return cosine_share * wi.z * inv_pi + (1.0 - cosine_share) * table;
}

BrdfSample MeasuredBrdf::sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  BrdfSample s;
  if (!(wo.z > 0.0)) return s;
  if (u_lobe < cosine_share) {
    s.wi = sample_cosine_hemisphere(u);
  } else {
    const auto t = (*m_views)[static_cast<std::size_t>(view_bin(wo))].sample(u);
    s.wi = direction(t.p.y, std::atan2(wo.y, wo.x) + two_pi * t.p.x);
  }
  s.pdf = pdf(s.wi, wo);
  if (s.pdf > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
  return s;
}

namespace {

struct CacheKey {
  std::string path;  // canonical
  std::filesystem::file_time_type::rep mtime = 0;
  std::uintmax_t size = 0;
  bool operator<(const CacheKey& o) const { return std::tie(path, mtime, size) < std::tie(o.path, o.mtime, o.size); }
};

struct Cache {
  std::mutex mutex;
  std::map<CacheKey, std::weak_ptr<const MeasuredBrdf>> entries;
  std::deque<std::shared_ptr<const MeasuredBrdf>> recent;  // the last four loaded stay alive
  std::atomic<std::size_t> reads{0};
};

Cache& cache() {
  static Cache c;
  return c;
}

}  // namespace

std::size_t measured_file_reads() { return cache().reads.load(); }

Result<BrdfPtr> load_measured_brdf(const std::filesystem::path& path) {
  // The one place a format is chosen, by the file's extension: RGL tensor files (.bsdf) and UTIA files (.bin) are
  // read by their readers (a few MB: read for each material that names them, not cached); anything else is read
  // as MERL 100 (.binary, 35 MB: cached below).
  const std::string ext = path.extension().string();
  if (ext == ".bsdf") return read_rgl_brdf(path);
  if (ext == ".bin") return read_utia_brdf(path);
  std::error_code ec;
  const std::filesystem::path canonical = std::filesystem::canonical(path, ec);
  if (ec) return make_error(path.string() + ": cannot read (" + ec.message() + ")");
  if (!std::filesystem::is_regular_file(canonical, ec)) return make_error(path.string() + ": not a regular file");
  CacheKey key;
  key.path = canonical.string();
  key.mtime = std::filesystem::last_write_time(canonical, ec).time_since_epoch().count();
  if (!ec) key.size = std::filesystem::file_size(canonical, ec);
  if (ec) return make_error(path.string() + ": cannot read (" + ec.message() + ")");
  Cache& c = cache();
  const std::lock_guard<std::mutex> lock(c.mutex);
  if (const auto it = c.entries.find(key); it != c.entries.end()) {
    if (const auto hit = it->second.lock()) return BrdfPtr(std::make_unique<MeasuredBrdf>(*hit));
  }
  auto table = read_merl(path);
  if (!table) return table.error();
  ++c.reads;
  auto made = std::make_shared<const MeasuredBrdf>(std::make_shared<const MerlTable>(std::move(*table)));
  for (auto it = c.entries.begin(); it != c.entries.end();) it = it->second.expired() ? c.entries.erase(it) : std::next(it);
  c.entries[key] = made;
  c.recent.push_back(made);
  if (c.recent.size() > 4) c.recent.pop_front();
  return BrdfPtr(std::make_unique<MeasuredBrdf>(*made));
}

ModelInfo measured_model() {
  ModelInfo info;
  info.name = "measured";
  info.summary = "the table's f_r: MERL trilinear between bin centres in (theta_h, theta_d, phi_d); RGL and UTIA by their readers (brdf/measured.h)";
  info.source = "MERL 100 (Matusik et al. 2003; binning: Rusinkiewicz 1998), RGL (Dupuy & Jakob 2018), UTIA (Filip & Vavra 2014) files";
  info.no_shader = "it reads a measured table (35 MB) from a file at run time; no shader binds one";
  info.params = {
      {"file", ParamKind::file, "", 0.0, 0.0, {},
       "a MERL 100 .binary (34,992,012 bytes), RGL .bsdf (RGB) or UTIA .bin file; in a scene, relative to the scene file's folder", 0, {}},
  };
  info.create = [](const ParamValues& v) -> Result<BrdfPtr> {
    if (v.file("file").empty()) return make_error("brdf measured: parameter 'file' is required");
    auto f = load_measured_brdf(v.file("file"));
    if (!f) return make_error("brdf measured: parameter 'file': " + f.error().message);
    return f;
  };
  return info;
}

}  // namespace shadelab
