#pragma once
// Errors raised by the ROS-free core. Each message names the offending
// parameter or input so that a nodelet can log it verbatim.

#include <stdexcept>
#include <string>

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
}  // namespace brick_pose
