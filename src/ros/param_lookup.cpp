#include "brick_pose/ros/param_lookup.h"

#include <sstream>

#include <XmlRpcValue.h>

namespace brick_pose
{
namespace
{
std::string toText(XmlRpc::XmlRpcValue& value)
{
  std::ostringstream text;
  switch (value.getType())
  {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return static_cast<bool>(value) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeInt:
      return std::to_string(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeDouble:
      text.precision(17);
      text << static_cast<double>(value);
      return text.str();
    case XmlRpc::XmlRpcValue::TypeString:
      return static_cast<std::string>(value);
    case XmlRpc::XmlRpcValue::TypeArray:
      for (int i = 0; i < value.size(); ++i)
        text << (i > 0 ? "," : "") << toText(value[i]);
      return text.str();
    default:
      return value.toXml();
  }
}
}  // namespace

std::optional<std::string> paramAsText(const ros::NodeHandle& node, const std::string& name)
{
  XmlRpc::XmlRpcValue value;
  if (!node.getParam(name, value)) return std::nullopt;
  return toText(value);
}

ParamLookup rosParamLookup(const ros::NodeHandle& private_node, const ros::NodeHandle& node)
{
  return [private_node, node](const std::string& name) {
    auto value = paramAsText(private_node, name);
    return value ? value : paramAsText(node, name);
  };
}
}  // namespace brick_pose
