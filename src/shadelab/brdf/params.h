// shadelab model parameters: the declared parameters of a model (name, kind, default, valid range) and
// the validated values a model is built from. The CLI and the scene format both go through parse_params,
// so a bad value is reported the same way everywhere: one line naming the model and the parameter.
#pragma once

#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "shadelab/color/rgb.h"
#include "shadelab/core/error.h"

namespace shadelab {

enum class ParamKind {
  scalar,  // one number
  color,   // a scalar or r,g,b
  choice,  // one of a fixed set of words
  lobes,   // groups of numbers separated by ';', each group of group_size numbers separated by ','
  file,    // a path to a data file (a measured table); an empty default means the parameter is required
};

// The kind's name as `brdf list --json` and shadelab.models() print it.
inline const char* param_kind_name(ParamKind k) {
  switch (k) {
    case ParamKind::scalar: return "scalar";
    case ParamKind::color: return "color";
    case ParamKind::choice: return "choice";
    case ParamKind::lobes: return "lobes";
    case ParamKind::file: return "file";
  }
  return "?";
}

struct ParamSpec;
// A file parameter with no default: make_brdf refuses the model without it ("brdf measured: parameter 'file' is
// required"), and the loops over every model give it a file or skip the model.
bool is_required(const ParamSpec& spec);

// The enumerator a choice parameter's word names; the table's first entry for a word not in it (parse_params
// has already refused words outside the declared choices, so that only happens for a model's own default).
template <typename E>
E pick_choice(const std::string& word, std::initializer_list<std::pair<const char*, E>> table) {
  for (const auto& [name, value] : table) {
    if (word == name) return value;
  }
  return table.begin()->second;
}

struct ParamSpec {
  std::string name;
  ParamKind kind = ParamKind::scalar;
  std::string default_value;          // as a user would type it
  double min = 0.0;                   // inclusive range of every number in the value
  double max = 0.0;
  std::vector<std::string> choices;   // choice only
  std::string description;
  int group_size = 0;                 // lobes only
  // Optional per-position ranges inside a lobe group (lobes only); empty means [min, max] for all.
  std::vector<std::pair<double, double>> group_ranges;
};

class ParamValues {
 public:
  double scalar(std::string_view name) const;
  Rgb color(std::string_view name) const;
  const std::string& choice(std::string_view name) const;
  const std::vector<std::vector<double>>& lobes(std::string_view name) const;
  // A file parameter's path as given (empty when a required one was not set).
  const std::string& file(std::string_view name) const;
  // True when the user set this parameter explicitly (not from its default).
  bool is_set(std::string_view name) const;
  // Overrides a scalar or colour parameter with already-validated numbers (textures at render time); the
  // caller keeps them in the parameter's range. Unknown names throw std::logic_error (a programming error).
  void set_numbers(std::string_view name, std::vector<double> numbers);

 private:
  friend Result<ParamValues> parse_params(std::string_view, const std::vector<ParamSpec>&,
                                          const std::vector<std::pair<std::string, std::string>>&);
  struct Value {
    std::vector<double> numbers;
    std::vector<std::vector<double>> groups;
    std::string word;
    bool explicit_set = false;
  };
  const Value& get(std::string_view name) const;
  std::map<std::string, Value, std::less<>> m_values;
};

// Validates name=value pairs against the specs (defaults fill the rest). Errors name the model and field:
// "brdf phong: parameter 'n' = -1 is out of range [0, 1e+06]".
Result<ParamValues> parse_params(std::string_view model, const std::vector<ParamSpec>& specs,
                                 const std::vector<std::pair<std::string, std::string>>& assignments);

// Splits "NAME=VALUE" as given on a command line.
Result<std::pair<std::string, std::string>> split_assignment(std::string_view text);

// Parses a comma-separated list of finite numbers ("0.5" or "0.8,0.6,0.2").
Result<std::vector<double>> parse_numbers(std::string_view text);

}  // namespace shadelab
