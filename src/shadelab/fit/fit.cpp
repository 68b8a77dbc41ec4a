#include "shadelab/fit/fit.h"

#include <nlopt.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

namespace shadelab {

namespace {

struct Range {
  double lo = 0.0, hi = 1.0;
};

// The default free parameters of the models the fitter knows, with the box each is searched in. Left out on
// purpose: a scale that another free parameter already sets (ggx's and cook-torrance's ks beside f0, lafortune's
// ks beside its lobes' coefficients), alternative spellings (ggx's roughness and alpha_x/alpha_y, cook-torrance's
// n), and choices.
struct TableEntry {
  const char* model;
  std::vector<std::pair<const char*, Range>> free;
  std::vector<Range> lobe_positions;  // lafortune: Cx, Cy, Cz, n
};

const std::vector<TableEntry>& fit_table() {
  static const std::vector<TableEntry> table = {
      {"lambert", {{"kd", {0.0, 1.0}}}, {}},
      {"phong", {{"kd", {0.0, 1.0}}, {"ks", {0.0, 1.0}}, {"n", {1.0, 1e4}}}, {}},
      {"phong-modified", {{"kd", {0.0, 1.0}}, {"ks", {0.0, 1.0}}, {"n", {1.0, 1e4}}}, {}},
      {"blinn-phong", {{"kd", {0.0, 1.0}}, {"ks", {0.0, 1.0}}, {"n", {1.0, 1e4}}}, {}},
      {"blinn-phong-modified", {{"kd", {0.0, 1.0}}, {"ks", {0.0, 1.0}}, {"n", {1.0, 1e4}}}, {}},
      {"cook-torrance", {{"kd", {0.0, 1.0}}, {"m", {0.002, 1.0}}, {"f0", {0.0, 1.0}}}, {}},
      {"ward", {{"kd", {0.0, 1.0}}, {"ks", {0.0, 1.0}}, {"alpha", {0.005, 1.0}}}, {}},
      {"ward-anisotropic",
       {{"kd", {0.0, 1.0}}, {"ks", {0.0, 1.0}}, {"alpha_x", {0.005, 1.0}}, {"alpha_y", {0.005, 1.0}}}, {}},
      {"lafortune", {{"kd", {0.0, 1.0}}, {"lobes", {}}}, {{-3.0, 3.0}, {-3.0, 3.0}, {-3.0, 3.0}, {1.0, 1000.0}}},
      {"ggx", {{"kd", {0.0, 1.0}}, {"alpha", {0.002, 1.0}}, {"f0", {0.0, 1.0}}}, {}},
  };
  return table;
}

const TableEntry* table_entry(const std::string& model) {
  for (const auto& e : fit_table()) {
    if (model == e.model) return &e;
  }
  return nullptr;
}

bool has_numbers(ParamKind k) { return k == ParamKind::scalar || k == ParamKind::color || k == ParamKind::lobes; }

// One number the optimizer moves: component c of parameter p (-1: all three channels of a colour, grey), or
// position `pos` of lobes group `group`.
struct FreeNumber {
  std::size_t param = 0;
  int component = 0;
  Range range;
  bool log = false;
};

bool log_mapped(const Range& r) { return r.lo > 0.0 && r.hi / r.lo >= 100.0; }

double from_unit(const FreeNumber& f, double u) {
  u = std::clamp(u, 0.0, 1.0);
  if (f.log) return std::exp(std::log(f.range.lo) + u * (std::log(f.range.hi) - std::log(f.range.lo)));
  return f.range.lo + u * (f.range.hi - f.range.lo);
}

double to_unit(const FreeNumber& f, double v) {
  v = std::clamp(v, f.range.lo, f.range.hi);
  if (f.log) return (std::log(v) - std::log(f.range.lo)) / (std::log(f.range.hi) - std::log(f.range.lo));
  return f.range.hi > f.range.lo ? (v - f.range.lo) / (f.range.hi - f.range.lo) : 0.0;
}

// Halton point k (k >= 1) in dimension d: the radical inverse of k in the d-th prime base.
double halton(int k, std::size_t d) {
  static constexpr int primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71};
  const int b = primes[d % std::size(primes)];
  double f = 1.0, r = 0.0;
  for (int i = k; i > 0; i /= b) {
    f /= b;
    r += f * (i % b);
  }
  return r;
}

constexpr std::size_t chunk = 2048;

// sum_k w_k sum_c (T(f cos_i) - t_k,c)^2 over the data, in fixed chunks added in order (thread-count independent).
double weighted_sum(const Brdf& f, const FitData& data, const std::vector<Rgb>& target, FitMetric metric) {
  const std::size_t n = data.wi.size();
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::vector<double> partial(chunks, 0.0);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    const std::size_t begin = c * chunk, end = std::min(n, begin + chunk);
    std::vector<Rgb> model(end - begin);
    f.eval_batch(data.wi.data() + begin, data.wo.data() + begin, model.data(), end - begin);
    double s = 0.0;
    for (std::size_t k = begin; k < end; ++k) {
      const double cos_i = data.wi[k].z;
      double e = 0.0;
      for (int ch = 0; ch < 3; ++ch) {
        const double d = fit_metric_transform(metric, std::max(0.0, model[k - begin][ch]) * cos_i) - target[k][ch];
        e += d * d;
      }
      s += data.weight[k] * e;
    }
    partial[c] = s;
  });
  double s = 0.0;
  for (double p : partial) s += p;
  return s;
}

std::vector<Rgb> transformed_targets(const FitData& data, FitMetric metric) {
  std::vector<Rgb> t(data.value.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    for (int ch = 0; ch < 3; ++ch) {
      t[k][ch] = fit_metric_transform(metric, std::max(0.0, data.value[k][ch]) * data.wi[k].z);
    }
  }
  return t;
}

double total_weight(const FitData& data) {
  double w = 0.0;
  for (double x : data.weight) w += x;
  return w;
}

}  // namespace

std::string fit_param_text(const FitParamValue& p, int digits) {
  std::string s;
  for (std::size_t i = 0; i < p.numbers.size(); ++i) {
    if (i > 0) s += (p.group_size > 0 && i % static_cast<std::size_t>(p.group_size) == 0) ? ";" : ",";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", digits, p.numbers[i]);  // 17 digits round-trip a double
    s += buf;
  }
  return s;
}

double fit_residual(const Brdf& f, const FitData& data, FitMetric metric) {
  const double w = total_weight(data);
  if (!(w > 0.0)) return 0.0;
  return std::sqrt(weighted_sum(f, data, transformed_targets(data, metric), metric) / (3.0 * w));
}

Result<std::pair<std::string, ParamAssignments>> parse_model_spec(const std::string& spec) {
  const std::string prefix = "model:";
  if (spec.rfind(prefix, 0) != 0) return Error{"'" + spec + "' is not model:NAME[,PARAM=VALUE...]"};
  std::string rest = spec.substr(prefix.size());
  std::vector<std::string> pieces;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = rest.find(',', start);
    pieces.push_back(rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  std::pair<std::string, ParamAssignments> out;
  out.first = pieces.front();
  if (out.first.empty()) return Error{"'" + spec + "': no model name after model:"};
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    const std::size_t eq = pieces[i].find('=');
    if (eq == std::string::npos) {
      if (out.second.empty()) return Error{"'" + spec + "': '" + pieces[i] + "' is not PARAM=VALUE"};
      out.second.back().second += "," + pieces[i];  // a colour's further channels
      continue;
    }
    out.second.emplace_back(pieces[i].substr(0, eq), pieces[i].substr(eq + 1));
  }
  return out;
}

Result<FitResult> fit_model(const std::string& model, const FitData& data, const FitOptions& options) {
  const ModelInfo* info = find_brdf_model(model);
  if (info == nullptr) return Error{"fit: unknown model '" + model + "'"};
  auto base = parse_params(model, info->params, options.fixed);
  if (!base) return base.error();
  const auto find_spec = [&](const std::string& name) -> const ParamSpec* {
    for (const auto& s : info->params) {
      if (s.name == name) return &s;
    }
    return nullptr;
  };
  const TableEntry* entry = table_entry(model);
  const auto is_fixed = [&](const std::string& name) {
    return std::any_of(options.fixed.begin(), options.fixed.end(), [&](const auto& a) { return a.first == name; });
  };

  // The free names, in registry order.
  std::vector<std::string> free_names;
  for (const auto& name : options.free) {
    const ParamSpec* s = find_spec(name);
    if (s == nullptr) return Error{"fit " + model + ": --free: the model has no parameter '" + name + "'"};
    if (!has_numbers(s->kind)) return Error{"fit " + model + ": --free: parameter '" + name + "' is a " + param_kind_name(s->kind) + ", not a number"};
    if (is_fixed(name)) return Error{"fit " + model + ": parameter '" + name + "' is both --free and --fix"};
  }
  for (const auto& s : info->params) {
    bool free = false;
    if (!options.free.empty()) {
      free = std::find(options.free.begin(), options.free.end(), s.name) != options.free.end();
    } else if (entry != nullptr) {
      free = std::any_of(entry->free.begin(), entry->free.end(), [&](const auto& e) { return s.name == e.first; });
    } else {
      free = s.kind == ParamKind::scalar || s.kind == ParamKind::color;
    }
    if (free && !is_fixed(s.name)) free_names.push_back(s.name);
  }

  const bool grey = fit_data_is_grey(data);
  FitResult result;
  result.model = model;
  result.metric = options.metric;
  result.configurations = data.wi.size();
  std::vector<FreeNumber> numbers;
  for (std::size_t pi = 0; pi < info->params.size(); ++pi) {
    const ParamSpec& s = info->params[pi];
    if (!has_numbers(s.kind)) continue;
    FitParamValue v;
    v.name = s.name;
    if (s.kind == ParamKind::scalar) {
      v.numbers = {base->scalar(s.name)};
    } else if (s.kind == ParamKind::color) {
      const Rgb c = base->color(s.name);
      v.numbers = {c.r, c.g, c.b};
    } else {
      v.group_size = s.group_size;
      for (const auto& g : base->lobes(s.name)) v.numbers.insert(v.numbers.end(), g.begin(), g.end());
    }
    v.fitted = std::find(free_names.begin(), free_names.end(), s.name) != free_names.end();
    if (v.fitted) {
      Range r{s.min, s.kind == ParamKind::color ? std::min(s.max, std::max(1.0, s.min)) : s.max};
      std::vector<Range> positions;
      if (entry != nullptr) {
        for (const auto& [name, box] : entry->free) {
          if (s.name == name) r = box;
        }
        if (s.kind == ParamKind::lobes) positions = entry->lobe_positions;
      }
      if (s.kind == ParamKind::lobes && positions.empty()) {
        for (int k = 0; k < s.group_size; ++k) {
          const auto& gr = s.group_ranges;
          positions.push_back(static_cast<std::size_t>(k) < gr.size() ? Range{gr[static_cast<std::size_t>(k)].first, gr[static_cast<std::size_t>(k)].second}
                                                                       : Range{s.min, s.max});
        }
      }
      r.lo = std::max(r.lo, s.min);
      r.hi = std::min(r.hi, s.max);
      if (s.kind == ParamKind::scalar) {
        numbers.push_back({pi, 0, r, log_mapped(r)});
      } else if (s.kind == ParamKind::color) {
        if (grey) {
          numbers.push_back({pi, -1, r, log_mapped(r)});
        } else {
          for (int c = 0; c < 3; ++c) numbers.push_back({pi, c, r, log_mapped(r)});
        }
      } else {
        for (std::size_t k = 0; k < v.numbers.size(); ++k) {
          Range pr = positions[k % positions.size()];
          pr.lo = std::max(pr.lo, s.min);
          pr.hi = std::min(pr.hi, s.max);
          numbers.push_back({pi, static_cast<int>(k), pr, log_mapped(pr)});
        }
      }
      result.fitted.push_back(s.name);
    }
    result.params.push_back(std::move(v));
  }
  const auto param_index = [&](std::size_t registry_index) {
    const std::string& name = info->params[registry_index].name;
    for (std::size_t i = 0; i < result.params.size(); ++i) {
      if (result.params[i].name == name) return i;
    }
    return std::size_t{0};
  };

  // Writes unit-box coordinates into the parameter values; returns the assignments that rebuild the model.
  const auto apply = [&](const double* u, std::vector<FitParamValue>& values) {
    for (std::size_t i = 0; i < numbers.size(); ++i) {
      const FreeNumber& f = numbers[i];
      auto& v = values[param_index(f.param)];
      const double x = from_unit(f, u[i]);
      if (f.component < 0) {
        v.numbers = {x, x, x};
      } else {
        v.numbers[static_cast<std::size_t>(f.component)] = x;
      }
    }
    ParamAssignments a = options.fixed;
    for (const auto& v : values) {
      if (v.fitted) a.emplace_back(v.name, fit_param_text(v));
    }
    return a;
  };

  const std::vector<Rgb> target = transformed_targets(data, options.metric);
  const double w_total = total_weight(data);
  if (!(w_total > 0.0)) return Error{"fit " + model + ": the data have no configuration to fit to"};
  std::int64_t evaluations = 0;
  std::optional<Error> build_error;
  const auto objective = [&](const double* u) {
    ++evaluations;
    std::vector<FitParamValue> values = result.params;
    auto brdf = make_brdf(model, apply(u, values));
    if (!brdf) {
      if (!build_error) build_error = brdf.error();
      return std::numeric_limits<double>::max();
    }
    const double e2 = weighted_sum(**brdf, data, target, options.metric) / (3.0 * w_total);
    return std::isfinite(e2) ? e2 : std::numeric_limits<double>::max();
  };

  const std::size_t n = numbers.size();
  std::vector<double> best_u(n, 0.0);
  double best = std::numeric_limits<double>::infinity();
  const int starts = n == 0 ? 1 : std::max(1, options.starts);
  for (int st = 0; st < starts; ++st) {
    std::vector<double> u(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (st == 0) {
        const FreeNumber& f = numbers[i];
        const auto& v = result.params[param_index(f.param)];
        const double x = f.component < 0 ? (v.numbers[0] + v.numbers[1] + v.numbers[2]) / 3.0
                                         : v.numbers[static_cast<std::size_t>(f.component)];
        u[i] = to_unit(f, x);
      } else {
        u[i] = halton(st, i);
      }
    }
    double start_best = std::numeric_limits<double>::infinity();
    std::vector<double> start_u = u;
    if (n == 0) {
      start_best = objective(nullptr);
    } else {
      // NLopt's C interface (Debian's libnlopt-dev has no C++ header).
      const std::unique_ptr<nlopt_opt_s, decltype(&nlopt_destroy)> opt(nlopt_create(NLOPT_LN_BOBYQA, static_cast<unsigned>(n)),
                                                                       &nlopt_destroy);
      if (!opt) return Error{"fit " + model + ": NLopt could not create its optimizer"};
      nlopt_set_lower_bounds1(opt.get(), 0.0);
      nlopt_set_upper_bounds1(opt.get(), 1.0);
      nlopt_set_xtol_rel(opt.get(), 1e-10);
      nlopt_set_xtol_abs1(opt.get(), 1e-12);
      nlopt_set_maxeval(opt.get(), std::max(10, options.max_evaluations));
      nlopt_set_initial_step1(opt.get(), 0.05);
      struct Ctx {
        const decltype(objective)* f;
        double* best;
        std::vector<double>* best_u;
      };
      Ctx ctx{&objective, &start_best, &start_u};
      nlopt_set_min_objective(
          opt.get(),
          [](unsigned dim, const double* x, double*, void* context) {
            auto* c = static_cast<Ctx*>(context);
            const double v = (*c->f)(x);
            if (v < *c->best) {
              *c->best = v;
              c->best_u->assign(x, x + dim);
            }
            return v;
          },
          &ctx);
      double value = 0.0;
      // A failure code (NLOPT_ROUNDOFF_LIMITED and the like) keeps the best point seen (tracked above).
      (void)nlopt_optimize(opt.get(), u.data(), &value);
    }
    result.start_residuals.push_back(std::sqrt(start_best));
    if (start_best < best) {
      best = start_best;
      best_u = start_u;
    }
  }
  if (!std::isfinite(best) || best == std::numeric_limits<double>::max()) {
    return build_error ? *build_error : Error{"fit " + model + ": no start gave a finite residual"};
  }
  result.assignments = apply(best_u.data(), result.params);
  result.residual = std::sqrt(best);
  result.evaluations = evaluations;
  return result;
}

}  // namespace shadelab
