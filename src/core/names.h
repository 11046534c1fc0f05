// One name table per enum: the names a value is printed as, parsed from and listed by in help and
// errors come from one array, so that the three cannot drift (a mode added to the enum and its
// printer but not to the parser was a usage error for a valid value).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace penumbra {

template <class E>
struct Named {
  E value;
  const char* name;
};

// The name of `value` ("?" for a value the table lacks: a programmer's omission).
template <class E, std::size_t N>
constexpr const char* nameOf(const Named<E> (&table)[N], E value) {
  for (const Named<E>& n : table)
    if (n.value == value) return n.name;
  return "?";
}

// The value named `name`, if any.
template <class E, std::size_t N>
std::optional<E> valueNamed(const Named<E> (&table)[N], std::string_view name) {
  for (const Named<E>& n : table)
    if (name == n.name) return n.value;
  return std::nullopt;
}

// Every name, joined by `separator`: "stratified | poisson | vogel".
template <class E, std::size_t N>
std::string namesOf(const Named<E> (&table)[N], std::string_view separator = " | ") {
  std::string out;
  for (const Named<E>& n : table) out += (out.empty() ? "" : std::string(separator)) + n.name;
  return out;
}

}  // namespace penumbra
