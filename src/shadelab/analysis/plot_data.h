// shadelab plot data: the numbers behind `shadelab plot lobe | albedo | fv | zoo` (docs/plots.md, "Gallery"),
// computed here so that tests can check them and the CLI only turns them into charts.
//
// Contract:
// - In-plane lobe (lobe_curve): the plane of incidence is the x-z plane of the local frame (normal +Z). A
//   direction there at signed angle a from the normal is in_plane_direction(a) = (sin a, 0, cos a); a < 0 is
//   to the left. The FIXED direction sits at -theta_in (left) and the SWEPT direction runs over
//   a in [-90, 90] degrees, so the mirror direction is at +theta_in. With LobeFixed::light (the default, as
//   BRDF Explorer draws it) the light wi is fixed and the viewer wo is swept: value f_r(wi, wo(a)). With
//   LobeFixed::viewer the viewer is fixed and the light is swept: f_r(wi(a), wo), whose f cos is, in this
//   plane, the integrand of directional_albedo(theta_in) (albedo.h; mirrored, the viewer is on the left).
//   times_cos multiplies by the cosine of the SWEPT direction,
//   cos(a): f_r cos is the density of reflected flux over directions. Values are RGB in 1/sr; `luminance`
//   is their Rec.709 luminance (color/rgb.h). At a = +-90 the swept direction is on the horizon: 0.
// - Albedo curves (albedo_curve): directional_albedo(f, theta) (albedo.h: the integral over wi of
//   f(wi, wo) cos(theta_i) with the viewer wo at theta) at each angle in degrees, in [0, 90), with the
//   quadrature options given (default albedo_curve_options(): relative tolerance 1e-8).
// - FV curves (fv_curve), the zoo article's figure "minimalist against Schlick with Kelemen/Szirmay-Kalos":
//   x is the angle theta_d between L and H in degrees, L.H = cos(theta_d). Both curves are the factor that
//   multiplies D in the specular term for a specular reflectance F0, i.e. ks F V with ks = F0 for the
//   minimalist model (its F V = 1/(4 (L.H)^3) and it is linear in ks) and ks = 1 for Schlick:
//     minimalist      = F0 / (4 (L.H)^3)                       (Schüler, ShaderX7 2.5; zoo article)
//     schlick_kelemen = F_schlick(L.H, F0) / (4 (L.H)^2)       (Schlick 1994 eq. 24; Kelemen & Szirmay-Kalos 2001)
//   so minimalist-cook-torrance with ks = F0 and cook-torrance with f = schlick, f0 = F0, g = kelemen, ks = 1
//   are D times these (brdf/minimalist_cook_torrance.h, brdf/cook_torrance.h). Both are F0/4 at L.H = 1;
//   they are dimensionless. Angles in [0, max_angle], max_angle in (0, 90).
// - Zoo curves (zoo_curves): for each row of the zoo (analysis/zoo.h, zoo_models()), the closed-form
//   normalization and, for blinn-phong and blinn-phong-modified, its lower and upper bounds, in 1/sr, from
//   zoo_row (so from the model code), at each exponent n (finite, >= 0); plus the row's texts. log_spaced
//   gives the exponents of a log axis.
// - Models with parameters (assign_model_params): parameter assignments given once for several models.
//   "NAME=VALUE" goes to every model that declares NAME (an error if none does; with one model it is
//   handed to it as is, so make_brdf names the unknown parameter); "MODEL:NAME=VALUE" goes to the models
//   of that name and "K:NAME=VALUE" to the K-th model (1-based), which tells apart a model given twice.
//   A later assignment of a parameter replaces an earlier one for the same model ("ks=1" then
//   "minimalist-cook-torrance:ks=0.05" leaves ks=0.05 for that model and ks=1 for the others).
//   Values are not checked here: make_brdf(model, params) does that. Labels are "model" or
//   "model (NAME=VALUE, ...)" with the parameters assigned to that model.
// - Errors (one line naming the field): bad angles, sample counts, F0 or exponents; unknown zoo rows.
//   Nothing prints, nothing is random.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "shadelab/analysis/albedo.h"
#include "shadelab/brdf/brdf.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/color/rgb.h"
#include "shadelab/core/error.h"
#include "shadelab/core/vec.h"

namespace shadelab {

// Which number of an RGB value a chart draws.
enum class PlotChannel { luminance, max, r, g, b };

double channel_value(const Rgb& c, PlotChannel channel);
std::string_view channel_name(PlotChannel channel);  // "luminance", "max", "r", "g", "b"
// "luminance" | "max" | "r" | "g" | "b"; an Error lists the choices otherwise.
Result<PlotChannel> parse_plot_channel(std::string_view text);

struct PlotModel {
  std::string model;        // registry name
  ParamAssignments params;  // in the order given
  std::string label;        // for legends
};

// Unknown model names and malformed or unmatched assignments are Errors naming the assignment.
Result<std::vector<PlotModel>> assign_model_params(const std::vector<std::string>& models,
                                                   const std::vector<std::string>& params);

// (sin a, 0, cos a), a in degrees from the normal, positive toward +X.
Vec3 in_plane_direction(double angle_deg);

// n equally spaced values from first to last (both included); n >= 2.
std::vector<double> linear_spaced(double first, double last, int n);
// n values from first to last (both > 0, included), equally spaced in log10; n >= 2.
std::vector<double> log_spaced(double first, double last, int n);

enum class LobeFixed { light, viewer };

struct LobeOptions {
  double theta_in_deg = 45.0;  // angle of the fixed direction from the normal, in [0, 90)
  LobeFixed fixed = LobeFixed::light;
  bool times_cos = false;  // multiply by cos of the swept direction
  int samples = 721;       // swept angles, equally spaced over [-90, 90] with both ends, in [3, 100001]
};

struct LobeCurve {
  LobeOptions options;
  Vec3 fixed_direction;           // in_plane_direction(-theta_in)
  double mirror_deg = 0.0;        // +theta_in
  std::vector<double> angle_deg;  // the swept direction's signed angle
  std::vector<Rgb> value;         // f_r or f_r cos(a), 1/sr
  std::vector<double> luminance;  // luminance(value[i])
};

Result<LobeCurve> lobe_curve(const Brdf& f, const LobeOptions& options = {});

// directional_albedo's options for curves: albedo_quadrature() with rel_tol 1e-8.
AlbedoOptions albedo_curve_options();
// 0, 1, ..., 89 degrees.
std::vector<double> default_albedo_angles();

struct AlbedoCurve {
  std::vector<double> theta_deg;
  std::vector<Rgb> albedo;
  std::vector<double> luminance;
  bool converged = true;  // every integral converged
};

Result<AlbedoCurve> albedo_curve(const Brdf& f, const std::vector<double>& theta_deg,
                                 const AlbedoOptions& options = albedo_curve_options());

// The two factors of the zoo article's figure, for L.H = lh in (0, 1] (see the contract above).
double fv_minimalist(double lh, double f0);
double fv_schlick_kelemen(double lh, double f0);

// The article's specular reflectances: 0.02, 0.05, 0.8.
std::vector<double> default_fv_f0();

struct FvCurve {
  double f0 = 0.0;
  std::vector<double> angle_deg;  // theta_d, the angle between L and H
  std::vector<double> minimalist;
  std::vector<double> schlick_kelemen;
};

// samples angles equally spaced over [0, max_angle_deg], both included; f0 in [0, 1].
Result<FvCurve> fv_curve(double f0, double max_angle_deg = 85.0, int samples = 171);

struct ZooCurve {
  std::string model;  // zoo row name ("blinn-phong-modified")
  std::string table;  // "RDF" or "NDF"
  std::string closed_form_text;
  std::string lower_text;  // empty without bounds
  std::string upper_text;
  std::vector<double> n;
  std::vector<double> closed_form;           // 1/sr
  std::optional<std::vector<double>> lower;  // bounds, where the zoo gives them
  std::optional<std::vector<double>> upper;
};

// One curve per model (zoo row names; empty: all six in table order) over the exponents n.
Result<std::vector<ZooCurve>> zoo_curves(const std::vector<double>& n, const std::vector<std::string>& models = {});

}  // namespace shadelab
