#include "shadelab/brdf/params.h"

#include "shadelab/core/text.h"

#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace shadelab {

namespace {

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

std::string format_number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::vector<std::string> split(std::string_view s, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto pos = s.find(sep, start);
    parts.push_back(trim(s.substr(start, pos == std::string_view::npos ? std::string_view::npos : pos - start)));
    if (pos == std::string_view::npos) break;
    start = pos + 1;
  }
  return parts;
}

}  // namespace

Result<std::vector<double>> parse_numbers(std::string_view text) {
  std::vector<double> out;
  for (const auto& part : split(text, ',')) {
    if (part.empty()) return make_error("'" + printable(text) + "' has an empty number");
    double v = 0.0;
    const auto* first = part.data();
    const auto* last = part.data() + part.size();
#if defined(__cpp_lib_to_chars)
    const auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || ptr != last) return make_error("'" + printable(part) + "' is not a number");
#else
    // libc++ before 17 (the explorer's WebAssembly build, Debian's emscripten) has no floating-point
    // from_chars: strtod on the whole part, refusing what from_chars refuses and strtod would take (leading
    // space or '+', hexadecimal).
    const bool refused = std::isspace(static_cast<unsigned char>(part.front())) != 0 || part.front() == '+' ||
                         part.find_first_of("xX") != std::string::npos;
    char* end = nullptr;
    v = refused ? 0.0 : std::strtod(first, &end);  // overflow gives +-HUGE_VAL, refused as not finite below
    if (refused || end != last) return make_error("'" + printable(part) + "' is not a number");
#endif
    if (!std::isfinite(v)) return make_error("'" + printable(part) + "' is not finite");
    out.push_back(v);
  }
  return out;
}

Result<std::pair<std::string, std::string>> split_assignment(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0) {
    return make_error("parameter '" + printable(text) + "' is not of the form NAME=VALUE");
  }
  return std::pair{trim(text.substr(0, eq)), trim(text.substr(eq + 1))};
}

const ParamValues::Value& ParamValues::get(std::string_view name) const {
  const auto it = m_values.find(name);
  if (it == m_values.end()) throw std::logic_error("ParamValues: undeclared parameter " + std::string(name));
  return it->second;
}

double ParamValues::scalar(std::string_view name) const { return get(name).numbers.at(0); }

Rgb ParamValues::color(std::string_view name) const {
  const auto& n = get(name).numbers;
  return n.size() == 3 ? Rgb{n[0], n[1], n[2]} : Rgb::gray(n.at(0));
}

const std::string& ParamValues::choice(std::string_view name) const { return get(name).word; }

const std::string& ParamValues::file(std::string_view name) const { return get(name).word; }

bool is_required(const ParamSpec& spec) { return spec.kind == ParamKind::file && spec.default_value.empty(); }

const std::vector<std::vector<double>>& ParamValues::lobes(std::string_view name) const { return get(name).groups; }

bool ParamValues::is_set(std::string_view name) const { return get(name).explicit_set; }

void ParamValues::set_numbers(std::string_view name, std::vector<double> numbers) {
  const auto it = m_values.find(name);
  if (it == m_values.end()) throw std::logic_error("ParamValues: undeclared parameter " + std::string(name));
  it->second.numbers = std::move(numbers);
  it->second.explicit_set = true;
}

namespace {

Result<bool> check_range(const std::string& where, double v, double lo, double hi) {
  if (v < lo || v > hi) {
    return make_error(where + " = " + format_number(v) + " is out of range [" + format_number(lo) + ", " +
                      format_number(hi) + "]");
  }
  return true;
}

}  // namespace

Result<ParamValues> parse_params(std::string_view model, const std::vector<ParamSpec>& specs,
                                 const std::vector<std::pair<std::string, std::string>>& assignments) {
  const std::string prefix = "brdf " + printable(model) + ": parameter '";
  ParamValues out;
  auto assign = [&](const ParamSpec& spec, const std::string& text, bool is_explicit) -> Result<bool> {
    const std::string where = prefix + spec.name + "'";
    ParamValues::Value value;
    value.explicit_set = is_explicit;
    switch (spec.kind) {
      case ParamKind::choice: {
        bool ok = false;
        for (const auto& c : spec.choices) ok = ok || c == text;
        if (!ok) {
          std::string list;
          for (const auto& c : spec.choices) list += (list.empty() ? "" : " | ") + c;
          return make_error(where + " = '" + printable(text) + "' is not one of " + list);
        }
        value.word = text;
        break;
      }
      case ParamKind::scalar:
      case ParamKind::color: {
        auto nums = parse_numbers(text);
        if (!nums) return make_error(where + ": " + nums.error().message);
        const std::size_t count = nums->size();
        if (spec.kind == ParamKind::scalar && count != 1) {
          return make_error(where + " takes one number, got '" + printable(text) + "'");
        }
        if (spec.kind == ParamKind::color && count != 1 && count != 3) {
          return make_error(where + " takes a number or r,g,b, got '" + printable(text) + "'");
        }
        for (double v : *nums) {
          auto r = check_range(where, v, spec.min, spec.max);
          if (!r) return r.error();
        }
        value.numbers = *nums;
        break;
      }
      case ParamKind::file: {
        // Any path; whether it names a readable file is the model's loader's to say. An explicit empty one is refused
        // here (a default may be empty: the parameter is then required, checked by make_brdf).
        if (is_explicit && text.empty()) return make_error(where + " is an empty path");
        value.word = text;
        break;
      }
      case ParamKind::lobes: {
        for (const auto& group : split(text, ';')) {
          auto nums = parse_numbers(group);
          if (!nums) return make_error(where + ": " + nums.error().message);
          if (nums->size() != static_cast<std::size_t>(spec.group_size)) {
            return make_error(where + ": each lobe takes " + std::to_string(spec.group_size) +
                              " numbers separated by ',' (lobes separated by ';'), got '" + printable(group) + "'");
          }
          for (std::size_t i = 0; i < nums->size(); ++i) {
            const auto [lo, hi] = i < spec.group_ranges.size() ? spec.group_ranges[i] : std::pair{spec.min, spec.max};
            auto r = check_range(where, (*nums)[i], lo, hi);
            if (!r) return r.error();
          }
          value.groups.push_back(*nums);
        }
        break;
      }
    }
    out.m_values[spec.name] = std::move(value);
    return true;
  };

  for (const auto& spec : specs) {
    auto r = assign(spec, spec.default_value, false);
    if (!r) return make_error("internal default of " + r.error().message);
  }
  for (const auto& [name, text] : assignments) {
    const ParamSpec* spec = nullptr;
    for (const auto& s : specs) {
      if (s.name == name) spec = &s;
    }
    if (spec == nullptr) {
      std::string list;
      for (const auto& s : specs) list += (list.empty() ? "" : ", ") + s.name;
      return make_error("brdf " + printable(model) + ": unknown parameter '" + printable(name) + "' (parameters: " + list + ")");
    }
    auto r = assign(*spec, text, true);
    if (!r) return r.error();
  }
  return out;
}

}  // namespace shadelab
