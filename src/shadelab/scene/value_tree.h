// A tree of values from outside JSON text (a Python dict, a fuzzer's tree) converted to the JSON document
// that parse_scene reads, within the bounds a scene file has (docs/scene-format.md, "Limits"): the same
// 64 levels of nesting and the same 64 MiB, counted as the compact JSON text the tree stands for. Every
// container's length is checked against what is left of the 64 MiB BEFORE any of it is converted, so a
// `range(10**8)` or a NumPy array of 10^8 numbers is one error line and no allocation. Non-finite numbers,
// integers beyond 64 bits, keys that are not strings and values of other types are errors too, each naming
// the JSON pointer of the value as the scene parser names fields ("scene: /shapes/0/radius: ...").
//
// The tree is read through a Source (a class with static-free member functions, below), so the Python
// module (python/src/scene_dict.cpp) and the C++ fuzz harness (fuzz/fuzz_scene_dict.cpp) run this one
// converter. A Source provides, for its Value type:
//   ValueKind kind(const Value&)                 what the value is (ValueKind::other for anything refused)
//   std::string type_name(const Value&)          its type, for "a value of type X is not a JSON value"
//   std::string repr(const Value&)               its text, for keys that are not strings and big integers
//   bool boolean(const Value&)
//   bool integer(const Value&, IntegerValue&)    false when it does not fit 64 bits (signed or unsigned)
//   double real(const Value&)
//   std::size_t length(const Value&)             strings: a lower bound of the UTF-8 bytes (e.g. code
//                                                points); sequences: items; mappings: members. O(1).
//   std::string string(const Value&)             the UTF-8 text
//   void items(const Value&, F f)                f(index, item) for each item, in order
//   void members(const Value&, F f)              f(key, value) for each member (key: any Value)
// A Source may throw its own exceptions (Python's pass through to the caller untouched).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "shadelab/core/text.h"
#include "shadelab/scene/limits.h"

namespace shadelab {

enum class ValueKind { null, boolean, integer, real, string, sequence, mapping, other };

struct IntegerValue {
  bool is_unsigned = false;  // beyond INT64_MAX: held in u
  std::int64_t i = 0;
  std::uint64_t u = 0;
};

// A refused value: the JSON pointer ("" for the root) and what is wrong with it.
struct ValueTreeError {
  std::string pointer;
  std::string message;
  // "scene: /shapes/0/radius: ..." (the root is "/").
  std::string line(const std::string& source) const {
    return source + ": " + (pointer.empty() ? std::string("/") : pointer) + ": " + message;
  }
};

template <typename Source>
class ValueTreeToJson {
 public:
  explicit ValueTreeToJson(Source& source, std::uint64_t byte_limit = max_scene_file_bytes,
                           std::size_t depth_limit = max_json_depth)
      : m_source(source), m_limit(byte_limit), m_depth_limit(depth_limit) {}

  // The document, or throws ValueTreeError (or the Source's own exceptions).
  template <typename Value>
  nlohmann::json convert(const Value& root) {
    m_used = 0;
    return value(root, "", 0);
  }

  // The compact JSON bytes counted so far (a lower bound of the text's length).
  std::uint64_t bytes_counted() const { return m_used; }

 private:
  [[noreturn]] static void fail(const std::string& pointer, const std::string& message) {
    throw ValueTreeError{pointer, message};
  }

  // RFC 6901: ~ -> ~0, / -> ~1; a key too long or not printable is cut and escaped (core/text.h).
  static std::string token(const std::string& key) {
    std::string out;
    for (char c : printable(key)) out += c == '~' ? std::string("~0") : (c == '/' ? std::string("~1") : std::string(1, c));
    return out;
  }

  std::string limit_text() const {
    return m_limit % (1ULL << 20) == 0 ? std::to_string(m_limit >> 20) + " MiB" : std::to_string(m_limit) + " bytes";
  }

  // Counts `bytes` more of the JSON text; beyond the limit is an error naming `what`.
  void spend(std::uint64_t bytes, const std::string& pointer, const std::string& what) {
    if (bytes > m_limit - m_used) {
      fail(pointer, what + ": the scene is more than the " + limit_text() + " of JSON a scene file may hold");
    }
    m_used += bytes;
  }

  static std::string count_text(std::size_t n) {
    return n == std::numeric_limits<std::size_t>::max() ? "more than 2^64 - 2" : std::to_string(n);
  }

  template <typename Value>
  nlohmann::json value(const Value& v, const std::string& pointer, std::size_t depth) {
    if (depth > m_depth_limit) fail(pointer, "nested deeper than " + std::to_string(m_depth_limit) + " levels");
    switch (m_source.kind(v)) {
      case ValueKind::null: spend(4, pointer, "null"); return nullptr;
      case ValueKind::boolean: spend(4, pointer, "a boolean"); return m_source.boolean(v);
      case ValueKind::integer: {
        IntegerValue x;
        if (!m_source.integer(v, x)) fail(pointer, "the integer " + printable(m_source.repr(v)) + " is too large");
        spend(1, pointer, "a number");
        if (x.is_unsigned) return x.u;
        return x.i;
      }
      case ValueKind::real: {
        const double d = m_source.real(v);
        if (!std::isfinite(d)) fail(pointer, (std::isnan(d) ? std::string("nan") : d > 0 ? "inf" : "-inf") + " is not a finite number");
        spend(1, pointer, "a number");
        return d;
      }
      case ValueKind::string: {
        const std::size_t n = m_source.length(v);
        spend(2 + static_cast<std::uint64_t>(n), pointer, "a string of " + std::to_string(n) + " characters");
        std::string s = m_source.string(v);
        if (s.size() > n) spend(s.size() - n, pointer, "a string of " + std::to_string(s.size()) + " bytes");
        return s;
      }
      case ValueKind::sequence: {
        const std::size_t n = m_source.length(v);
        // "[]", and each item at least one byte and a comma: checked before any item is read.
        spend(n == 0 ? 2 : 1 + 2 * static_cast<std::uint64_t>(n), pointer,
              "a sequence of " + count_text(n) + " items");
        nlohmann::json j = nlohmann::json::array();
        m_source.items(v, [&](std::size_t i, const auto& item) {
          m_used -= 1;  // the byte counted for this item ahead; its value counts itself
          j.push_back(value(item, pointer + "/" + std::to_string(i), depth + 1));
        });
        return j;
      }
      case ValueKind::mapping: {
        const std::size_t n = m_source.length(v);
        // "{}", and each member at least `"":0,` (the key's and value's own bytes count when read).
        spend(n == 0 ? 2 : 1 + 5 * static_cast<std::uint64_t>(n), pointer,
              "a mapping of " + count_text(n) + " members");
        nlohmann::json j = nlohmann::json::object();
        m_source.members(v, [&](const auto& key, const auto& item) {
          if (m_source.kind(key) != ValueKind::string) {
            fail(pointer, "the key " + printable(m_source.repr(key), 80) + " is not a string");
          }
          const std::size_t kn = m_source.length(key);
          spend(kn, pointer, "a key of " + std::to_string(kn) + " characters");
          std::string k = m_source.string(key);
          if (k.size() > kn) spend(k.size() - kn, pointer, "a key of " + std::to_string(k.size()) + " bytes");
          const std::string child = pointer + "/" + token(k);
          m_used -= 1;  // the value's byte counted ahead
          j[std::move(k)] = value(item, child, depth + 1);
        });
        return j;
      }
      case ValueKind::other: break;
    }
    fail(pointer, "a value of type " + printable(m_source.type_name(v), 80) +
                      " is not a JSON value (numbers are int, float or a NumPy real scalar; arrays are list, tuple, "
                      "range or a NumPy array; objects are dict)");
  }

  Source& m_source;
  std::uint64_t m_limit;
  std::size_t m_depth_limit;
  std::uint64_t m_used = 0;
};

}  // namespace shadelab
