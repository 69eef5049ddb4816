#pragma once
// One table of names per enum that parameters name: the parser, the printer
// and the error's list of valid values read the same table, so they cannot
// disagree.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
/// A name table: `constexpr EnumName<E> kNames[] = {{E::kA, "a"}, ...};`
/// (constant-initialised, so that it can be read at any time).
template <typename Enum>
using EnumName = std::pair<Enum, const char*>;

/// The value named `text`; ConfigError naming `what` and the valid names otherwise.
template <typename Enum, std::size_t N>
Enum parseEnumName(const std::string& what, const std::string& text, const EnumName<Enum> (&names)[N])
{
  std::string valid;
  for (const auto& [value, name] : names)
  {
    if (text == name) return value;
    valid += (valid.empty() ? "" : ", ") + std::string(name);
  }
  throw ConfigError(what + ": unknown value '" + text + "'; expected one of: " + valid);
}

/// The name of `value`, or "unknown" for a value outside the table.
template <typename Enum, std::size_t N>
const char* enumName(Enum value, const EnumName<Enum> (&names)[N])
{
  for (const auto& [known, name] : names)
    if (known == value) return name;
  return "unknown";
}
}  // namespace brick_pose
