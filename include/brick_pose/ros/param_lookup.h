#pragma once
// Reads rosparam values as text for the core's ParamLookup-based configs, so
// nodelets and command-line tools share one parser and one set of errors.

#include <optional>
#include <string>

#include <ros/node_handle.h>

#include "brick_pose/common/param_parsing.h"

namespace brick_pose
{
/// The parameter `name` under `node` as text: numbers and booleans printed,
/// lists joined with commas; nothing when the parameter is not set.
std::optional<std::string> paramAsText(const ros::NodeHandle& node, const std::string& name);

/// A ParamLookup over the nodelet's private parameters, falling back to its
/// namespace's (where launch files put what several stages share).
ParamLookup rosParamLookup(const ros::NodeHandle& private_node, const ros::NodeHandle& node);
}  // namespace brick_pose
