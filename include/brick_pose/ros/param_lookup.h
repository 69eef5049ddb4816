#pragma once
// Reads rosparam values as text for the core's ParamLookup-based configs, so
// nodelets and command-line tools share one parser and one set of errors.

#include <optional>
#include <string>

#include <ros/node_handle.h>

namespace brick_pose
{
/// The parameter `name` under `node` as text: numbers and booleans printed,
/// lists joined with commas; nothing when the parameter is not set.
std::optional<std::string> paramAsText(const ros::NodeHandle& node, const std::string& name);
}  // namespace brick_pose
