#pragma once
// Named text parameters, the one configuration path of the core: nodelets
// read them from rosparam, command-line tools from their arguments, and both
// get the same parsing and the same errors (ConfigError naming the parameter).

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace brick_pose
{
/// Returns a parameter's value as text, or nothing when it is not set.
using ParamLookup = std::function<std::optional<std::string>(const std::string& name)>;

/// A lookup over fixed name/value pairs (a parsed file, a test's settings).
ParamLookup mapParamLookup(std::map<std::string, std::string> values);

/// `first`'s value where it has one, otherwise `second`'s.
ParamLookup overlayParamLookup(ParamLookup first, ParamLookup second);

double parseDouble(const std::string& name, const std::string& text);
long long parseInteger(const std::string& name, const std::string& text);
bool parseBool(const std::string& name, const std::string& text);
/// "a, b,c" or "[a, 'b']" -> {a, b, c}.
std::vector<std::string> splitList(const std::string& text);

/// Reads typed parameters through a ParamLookup, leaving unset ones alone.
class ParamReader
{
public:
  explicit ParamReader(ParamLookup lookup) : lookup_(std::move(lookup)) {}

  void number(const std::string& name, double& target) const;
  void integer(const std::string& name, int& target) const;
  void flag(const std::string& name, bool& target) const;
  std::optional<std::string> text(const std::string& name) const { return lookup_(name); }

private:
  ParamLookup lookup_;
};
}  // namespace brick_pose
