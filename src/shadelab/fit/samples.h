// shadelab fitting data: the configurations (wi, wo) a fit compares a model with data at, their measure, and the
// data's values there.
//
// The configurations are the MERL 100 bin centres (brdf/merl.h: 90 theta_h bins dense near the specular peak,
// theta_d and phi_d uniform), every theta_h bin and every stride-th theta_d and phi_d bin, at n_phi_h azimuths of
// the half vector phi_h = 2 pi k / n_phi_h (1 for isotropic data: the MERL layout's phi_h = 0). phi_d covers
// [0, pi) as in MERL: phi_d and phi_d + pi are the same configuration with wi and wo swapped.
// A configuration's weight is its share of the measure of the configuration space,
//   dw_i dw_o = 4 cos(theta_d) sin(theta_h) sin(theta_d) dtheta_h dphi_h dtheta_d dphi_d
// (the half/difference change of variables, Rusinkiewicz 1998; fit_test checks that the weights of the upper
// hemisphere pairs sum to (2 pi)^2), with dtheta_h = (pi/2)(2i + 1)/90^2 for bin i (the square-root binning),
// dtheta_d = stride (pi/2)/90, dphi_d = 2 stride pi/180 (both halves of phi_d), dphi_h = 2 pi / n_phi_h.
// Kept: both directions above the horizon and within max_theta of the normal (80 degrees by default, as Ngan et
// al. 2005 leave out grazing data, where measurements are least reliable).
#pragma once

#include <cstddef>
#include <vector>

#include "shadelab/brdf/brdf.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/color/rgb.h"
#include "shadelab/core/vec.h"

namespace shadelab {

struct FitGridOptions {
  int theta_d_stride = 3;  // every 3rd of 90 theta_d bins
  int phi_d_stride = 6;    // every 6th of 180 phi_d bins
  int n_phi_h = 1;         // half-vector azimuths (1: isotropic)
  double max_theta_deg = 80.0;
};

struct FitData {
  std::vector<Vec3> wi, wo;
  std::vector<double> weight;  // dw_i dw_o of each configuration (above)
  std::vector<Rgb> value;      // the data's f_r there, 1/sr
};

// The configurations and their weights, without values.
FitData fit_grid(const FitGridOptions& options);
// The grid with a BRDF's values (data from a model, or a measured BRDF evaluated by its own interpolation).
FitData fit_data_from_brdf(const Brdf& data, const FitGridOptions& options);
// The grid's configurations that are bin centres measured in the table, with the table's values (no
// interpolation; n_phi_h is taken as 1: the MERL layout is isotropic). Bins where any channel is missing are
// left out.
FitData fit_data_from_merl(const MerlTable& table, const FitGridOptions& options);

// True when the three channels of every value are equal to 1e-12 relative (grey data: colour parameters are then
// fitted as one grey value).
bool fit_data_is_grey(const FitData& data);

// True when the BRDF looks isotropic: f(R wi, R wo) = f(wi, wo) to 1e-9 relative for rotations R about the
// normal, at 64 fixed pairs and 3 angles.
bool looks_isotropic(const Brdf& f);

}  // namespace shadelab
