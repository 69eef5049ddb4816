#pragma once
// Errors raised by the ROS-free core. Each message names the offending
// parameter or input so that a nodelet can log it verbatim.

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace brick_pose
{
/// A configuration value is out of range or inconsistent (e.g. fx <= 0).
class ConfigError : public std::invalid_argument
{
public:
  explicit ConfigError(const std::string& what) : std::invalid_argument(what) {}
};

/// One input (frame, cloud, segment) cannot be processed; the caller drops it
/// and carries on with the next one.
class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

/// Checks the fields of one parameter struct in its validate(): a failed
/// check throws a ConfigError that names the struct and the field, so every
/// stage reports a bad parameter the same way.
class ParamCheck
{
public:
  /// owner: how the message names the struct, e.g. "roi filter".
  explicit ParamCheck(std::string owner) : owner_(std::move(owner)) {}

  /// Throws "<owner>: <field> <rule>" unless condition holds; the rule says
  /// what the field must be ("must be > 0").
  void require(bool condition, const char* field, const char* rule = "is out of range") const
  {
    if (!condition) throw ConfigError(owner_ + ": " + field + " " + rule);
  }

  /// As above, with the value that broke the rule: "..., got <got>".
  void require(bool condition, const char* field, const char* rule, double got) const
  {
    if (condition) return;
    std::ostringstream message;
    message << owner_ << ": " << field << " " << rule << ", got " << got;
    throw ConfigError(message.str());
  }

  /// Throws "<owner>: <field> must be in [min, max], got value" unless
  /// min <= value <= max (a NaN value fails).
  void inRange(double value, double min, double max, const char* field) const
  {
    if (value >= min && value <= max) return;
    std::ostringstream message;
    message << owner_ << ": " << field << " must be in [" << min << ", " << max << "], got " << value;
    throw ConfigError(message.str());
  }

private:
  std::string owner_;
};
}  // namespace brick_pose
