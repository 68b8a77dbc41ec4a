// shadelab errors: the one error type that library functions return instead of throwing on bad input.
//
// A message names the thing that is wrong (file, field or parameter) so the CLI can print it as one line
// and exit with code 2. Library code never prints.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace shadelab {

struct Error {
  std::string message;
};

// Either a value or an Error. Deliberately small: has_value / value / error, nothing else.
template <typename T>
class Result {
 public:
  Result(T value) : m_data(std::move(value)) {}          // NOLINT(google-explicit-constructor)
  Result(Error error) : m_data(std::move(error)) {}      // NOLINT(google-explicit-constructor)

  bool has_value() const { return m_data.index() == 0; }
  explicit operator bool() const { return has_value(); }
  const T& value() const& { return std::get<0>(m_data); }
  T& value() & { return std::get<0>(m_data); }
  T&& value() && { return std::get<0>(std::move(m_data)); }
  const T& operator*() const& { return value(); }
  // Non-const access, so that std::move(*result) moves: with only the const overload it copied, and a
  // scene holding a 1 GiB texture briefly held two (MemoryBound.SceneImagesStayWithinTheSceneBudget).
  T& operator*() & { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }
  const Error& error() const { return std::get<1>(m_data); }

 private:
  std::variant<T, Error> m_data;
};

inline Error make_error(std::string message) { return Error{std::move(message)}; }

}  // namespace shadelab
