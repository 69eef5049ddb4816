#pragma once
// Named text parameters, the one configuration path of the core: nodelets
// read them from rosparam, command-line tools from their arguments, and both
// get the same parsing and the same errors (ConfigError naming the parameter).

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <variant>
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

/// One named parameter bound to the struct field that holds its value. One
/// table of bindings both reads a struct's parameters and reports the values
/// in effect, so that the two cannot drift apart.
struct ParamBinding
{
  std::string name;
  std::variant<double*, int*, bool*> field;
};
using ParamBindings = std::vector<ParamBinding>;

/// Reads each bound parameter that is set into its field; unset ones keep
/// their value (the struct's default).
void readBound(const ParamReader& read, const ParamBindings& bindings);

/// The text of each bound field's value, by name: numbers to 10 significant
/// digits, flags as true/false.
std::map<std::string, std::string> boundValues(const ParamBindings& bindings);

/// Reads a params struct through its bindings table and validates it.
/// bind: returns the table of a struct's fields (e.g. stageBindings).
template <typename Params>
Params readValidated(const ParamLookup& lookup, ParamBindings (*bind)(Params&))
{
  Params params;
  readBound(ParamReader(lookup), bind(params));
  params.validate();
  return params;
}
}  // namespace brick_pose
