// shadelab fitter: a registry model's free parameters fitted to data (fit/samples.h) under a metric
// (fit/metric.h), by NLopt's BOBYQA (Powell 2009, "The BOBYQA algorithm for bound constrained optimization
// without derivatives"), a derivative-free local method with bounds, from several deterministic starts; the best
// local minimum is kept. docs/fitting.md; docs/design.md says why NLopt.
//
// Free parameters: a model's default free set (fit/fit.cpp's table; models without an entry: every scalar and
// colour parameter), less the ones fixed by name, or exactly the ones named as free. Each free number is searched
// in a box (the table's, or the registry's range with colours capped at 1), through the unit interval: linearly,
// or logarithmically for a range that spans two decades or more with a positive lower end. A colour parameter is
// fitted as one grey value when the data are grey (fit_data_is_grey), else per channel; a lobes parameter
// (lafortune) as every number of its groups, the group count fixed by its value.
//
// Starts: the model's defaults (clamped into the box), then Halton points of the unit box (bases 2, 3, 5, ...,
// index 1, 2, ...). Each runs BOBYQA to a relative step of 1e-10 in the unit box or max_evaluations; the objective
// is E^2 (fit/metric.h), summed over fixed chunks of the data in parallel and added in chunk order, so that the
// result does not depend on the thread count.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/error.h"
#include "shadelab/fit/metric.h"
#include "shadelab/fit/samples.h"

namespace shadelab {

struct FitOptions {
  FitMetric metric = FitMetric::cosine_l2;
  ParamAssignments fixed;             // NAME=VALUE held fixed (and left out of the free set)
  std::vector<std::string> free;      // when not empty: exactly these are free
  int starts = 4;
  int max_evaluations = 4000;         // per start
};

struct FitParamValue {
  std::string name;
  std::vector<double> numbers;  // scalar: 1; colour: 3; lobes: the groups one after another
  int group_size = 0;           // lobes only
  bool fitted = false;
};

struct FitResult {
  std::string model;
  std::vector<FitParamValue> params;  // every parameter with numbers (scalar, colour, lobes), registry order
  ParamAssignments assignments;       // what make_brdf(model, ...) takes to rebuild the fit (fixed + fitted)
  std::vector<std::string> fitted;    // the names that were free
  FitMetric metric = FitMetric::cosine_l2;
  double residual = 0.0;              // E of the best start
  std::vector<double> start_residuals;
  std::int64_t evaluations = 0;       // objective evaluations, all starts
  std::size_t configurations = 0;
};

// A parameter's numbers as --param takes them ("0.3", "0.8,0.6,0.2", lobes "a,b,c,d;e,f,g,h"), each with
// `digits` significant digits (17: reads back to the same double).
std::string fit_param_text(const FitParamValue& p, int digits = 17);

// Fits `model` to the data. Errors (unknown model, a fixed or free name the model does not have, a bad value)
// name the parameter.
Result<FitResult> fit_model(const std::string& model, const FitData& data, const FitOptions& options = {});

// E (fit/metric.h) of a BRDF against the data.
double fit_residual(const Brdf& f, const FitData& data, FitMetric metric);

// "model:NAME[,PARAM=VALUE...]" as the fitter's DATA argument: the model and its assignments. A value may hold
// commas (a colour "0.8,0.6,0.2"): a piece without '=' continues the previous value.
Result<std::pair<std::string, ParamAssignments>> parse_model_spec(const std::string& spec);

}  // namespace shadelab
