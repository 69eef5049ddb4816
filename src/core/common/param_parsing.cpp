#include "brick_pose/common/param_parsing.h"

#include <cmath>
#include <sstream>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
ParamLookup mapParamLookup(std::map<std::string, std::string> values)
{
  return [values = std::move(values)](const std::string& name) -> std::optional<std::string> {
    const auto found = values.find(name);
    if (found == values.end()) return std::nullopt;
    return found->second;
  };
}

ParamLookup overlayParamLookup(ParamLookup first, ParamLookup second)
{
  return [first = std::move(first), second = std::move(second)](const std::string& name) {
    const std::optional<std::string> value = first(name);
    return value ? value : second(name);
  };
}

double parseDouble(const std::string& name, const std::string& text)
{
  std::size_t used = 0;
  double value = 0.0;
  try
  {
    value = std::stod(text, &used);
  }
  catch (const std::exception&)
  {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value))
    throw ConfigError("parameter '" + name + "': '" + text + "' is not a finite number");
  return value;
}

long long parseInteger(const std::string& name, const std::string& text)
{
  std::size_t used = 0;
  long long value = 0;
  try
  {
    value = std::stoll(text, &used);
  }
  catch (const std::exception&)
  {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw ConfigError("parameter '" + name + "': '" + text + "' is not an integer");
  return value;
}

bool parseBool(const std::string& name, const std::string& text)
{
  if (text == "true" || text == "1" || text == "True") return true;
  if (text == "false" || text == "0" || text == "False") return false;
  throw ConfigError("parameter '" + name + "': '" + text + "' is not true or false");
}

std::vector<std::string> splitList(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    const auto first = item.find_first_not_of(" []'\"");
    const auto last = item.find_last_not_of(" []'\"");
    if (first != std::string::npos) items.push_back(item.substr(first, last - first + 1));
  }
  return items;
}

void ParamReader::number(const std::string& name, double& target) const
{
  if (const auto value = lookup_(name)) target = parseDouble(name, *value);
}

void ParamReader::integer(const std::string& name, int& target) const
{
  if (const auto value = lookup_(name)) target = static_cast<int>(parseInteger(name, *value));
}

void ParamReader::flag(const std::string& name, bool& target) const
{
  if (const auto value = lookup_(name)) target = parseBool(name, *value);
}

void readBound(const ParamReader& read, const ParamBindings& bindings)
{
  for (const ParamBinding& binding : bindings)
  {
    if (auto* number = std::get_if<double*>(&binding.field)) read.number(binding.name, **number);
    else if (auto* integer = std::get_if<int*>(&binding.field)) read.integer(binding.name, **integer);
    else read.flag(binding.name, *std::get<bool*>(binding.field));
  }
}

std::map<std::string, std::string> boundValues(const ParamBindings& bindings)
{
  std::map<std::string, std::string> values;
  for (const ParamBinding& binding : bindings)
  {
    std::ostringstream text;
    text.precision(10);
    if (auto* flag = std::get_if<bool*>(&binding.field)) text << (**flag ? "true" : "false");
    else if (auto* integer = std::get_if<int*>(&binding.field)) text << **integer;
    else text << *std::get<double*>(binding.field);
    values[binding.name] = text.str();
  }
  return values;
}
}  // namespace brick_pose
