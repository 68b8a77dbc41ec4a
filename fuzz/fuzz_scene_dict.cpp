// Fuzz harness: the conversion of a scene dict (scene/value_tree.h, what the Python module's render() runs
// on a dict; python/src/scene_dict.cpp is its Python Source), then parse_scene on what it made. The input is
// JSON text read as the value tree, with special strings for what JSON cannot hold but a dict can:
//   "@huge:N"    a sequence of N items (not stored: like range(N), each item the integer 0)
//   "@other:T"   a value of another type T (complex, bytes, ...)
//   "@bigint"    an integer beyond 64 bits;  "@nan", "@inf": non-finite floats
// The converter runs with a bound of 1 MiB instead of a scene file's 64 MiB (its constructor's parameter;
// the same code), so that a "@huge" sequence just inside the bound converts in milliseconds, not seconds.
// Contract checked: the converter's error is one printable line "scene: /POINTER: ..." and no item of a
// sequence is read when its length alone passes the bound (at most 2^19 items, 2 bytes each, are ever read);
// the JSON it makes is at least as long as the bytes it counted (the count is a lower bound, so the bound
// holds for the JSON text); parse_scene's error is one printable line naming "scene"; an accepted scene passes
// check_scene_limits.
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "fixture.h"
#include "harness.h"
#include "shadelab/scene/limits.h"
#include "shadelab/scene/scene_json.h"
#include "shadelab/scene/value_tree.h"

using namespace shadelab;
using nlohmann::json;

namespace {

struct Value {
  const json* j = nullptr;  // null: an item of a "@huge" sequence (the integer 0)
};

constexpr std::uint64_t byte_limit = 1ULL << 20;

struct JsonSource {
  std::uint64_t items_read = 0;

  static std::string special(const Value& v) {
    if (v.j == nullptr || !v.j->is_string()) return {};
    const auto& s = v.j->get_ref<const std::string&>();
    return s.size() > 1 && s[0] == '@' ? s : std::string();
  }
  static std::size_t huge_length(const std::string& s) {
    std::size_t n = 0;
    for (std::size_t i = 6; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])) != 0; ++i) {
      n = n > std::numeric_limits<std::size_t>::max() / 10 ? std::numeric_limits<std::size_t>::max() : n * 10 + static_cast<std::size_t>(s[i] - '0');
    }
    return n;
  }

  ValueKind kind(const Value& v) const {
    if (v.j == nullptr) return ValueKind::integer;
    const std::string s = special(v);
    if (s.rfind("@huge:", 0) == 0) return ValueKind::sequence;
    if (s.rfind("@other:", 0) == 0) return ValueKind::other;
    if (s == "@bigint") return ValueKind::integer;
    if (s == "@nan" || s == "@inf") return ValueKind::real;
    switch (v.j->type()) {
      case json::value_t::null: return ValueKind::null;
      case json::value_t::boolean: return ValueKind::boolean;
      case json::value_t::number_integer:
      case json::value_t::number_unsigned: return ValueKind::integer;
      case json::value_t::number_float: return ValueKind::real;
      case json::value_t::string: return ValueKind::string;
      case json::value_t::array: return ValueKind::sequence;
      case json::value_t::object: return ValueKind::mapping;
      default: return ValueKind::other;
    }
  }
  std::string type_name(const Value& v) const { return special(v).substr(7); }
  std::string repr(const Value& v) const {
    return v.j == nullptr ? "0" : special(v) == "@bigint" ? "18446744073709551616" : v.j->dump(-1, ' ', false, json::error_handler_t::replace);
  }
  bool boolean(const Value& v) const { return v.j->get<bool>(); }
  bool integer(const Value& v, IntegerValue& out) const {
    if (v.j == nullptr) return out.i = 0, true;
    if (special(v) == "@bigint") return false;
    if (v.j->is_number_unsigned()) {
      out.is_unsigned = true;
      out.u = v.j->get<std::uint64_t>();
    } else {
      out.i = v.j->get<std::int64_t>();
    }
    return true;
  }
  double real(const Value& v) const {
    const std::string s = special(v);
    if (s == "@nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "@inf") return std::numeric_limits<double>::infinity();
    return v.j->get<double>();
  }
  std::size_t length(const Value& v) const {
    const std::string s = special(v);
    if (s.rfind("@huge:", 0) == 0) return huge_length(s);
    return v.j->is_string() ? v.j->get_ref<const std::string&>().size() : v.j->size();
  }
  std::string string(const Value& v) const { return v.j->get<std::string>(); }
  template <typename F>
  void items(const Value& v, F f) {
    const std::size_t n = length(v);
    const bool huge = !special(v).empty();
    for (std::size_t i = 0; i < n; ++i) {
      if (++items_read > byte_limit / 2) fuzz::finding("items read past the bound", std::to_string(items_read));
      f(i, huge ? Value{} : Value{&(*v.j)[i]});
    }
  }
  template <typename F>
  void members(const Value& v, F f) {
    for (const auto& [key, value] : v.j->items()) {
      const json k = key;
      f(Value{&k}, Value{&value});
    }
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    const auto d = fuzz::work_dir("scene_dict");
    fuzz::write_fixture(d);
    return d;
  }();
  const json tree = json::parse(fuzz::as_text(data, size), nullptr, false);
  if (tree.is_discarded()) return 0;  // the tree is the input's, not the converter's; the scene harness fuzzes the parser
  JsonSource source;
  ValueTreeToJson<JsonSource> convert(source, byte_limit);
  json doc;
  try {
    doc = convert.convert(Value{&tree});
  } catch (const ValueTreeError& e) {
    const std::string line = e.line("scene");
    fuzz::require_one_line(line, "scene: /");
    return 0;
  }
  if (convert.bytes_counted() > byte_limit) fuzz::finding("counted past the bound", std::to_string(convert.bytes_counted()));
  const std::string text = doc.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() < convert.bytes_counted()) {
    fuzz::finding("the count is not a lower bound", std::to_string(text.size()) + " < " + std::to_string(convert.bytes_counted()));
  }
  auto scene = parse_scene(doc, dir, "scene");
  if (!scene) {
    fuzz::require_one_line(scene.error().message, "scene");
    return 0;
  }
  if (auto limits = check_scene_limits(*scene); !limits) fuzz::finding("an accepted scene breaks the limits", limits.error().message);
  return 0;
}
