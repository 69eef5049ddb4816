#include "common/report_format.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace brick_pose
{
namespace bench
{
std::string formatted(const char* format, double value)
{
  if (std::isnan(value)) return "n/a";
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string jsonNumber(double value)
{
  if (!std::isfinite(value)) return "null";
  std::ostringstream text;
  text.precision(6);
  text << value;
  return text.str();
}

JsonLine& JsonLine::number(const std::string& key, double value)
{
  fields_.emplace_back(key, jsonNumber(value));
  return *this;
}

JsonLine& JsonLine::text(const std::string& key, const std::string& value)
{
  std::string quoted = "\"";
  for (const char c : value)
  {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  fields_.emplace_back(key, quoted + "\"");
  return *this;
}

std::string JsonLine::str() const
{
  std::string line = "{";
  for (std::size_t i = 0; i < fields_.size(); ++i)
    line += (i ? ", \"" : "\"") + fields_[i].first + "\": " + fields_[i].second;
  return line + "}";
}
}  // namespace bench
}  // namespace brick_pose
