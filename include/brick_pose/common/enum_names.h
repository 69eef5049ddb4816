#pragma once
// One table of names per enum that parameters name: the parser, the printer
// and the error's list of valid values read the same table, so they cannot
// disagree.

#include <string>
#include <utility>
#include <vector>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
template <typename Enum>
using EnumNames = std::vector<std::pair<Enum, const char*>>;

/// The value named `text`; ConfigError naming `what` and the valid names otherwise.
template <typename Enum>
Enum parseEnumName(const std::string& what, const std::string& text, const EnumNames<Enum>& names)
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
template <typename Enum>
const char* enumName(Enum value, const EnumNames<Enum>& names)
{
  for (const auto& [known, name] : names)
    if (known == value) return name;
  return "unknown";
}
}  // namespace brick_pose
