#include "brick_pose/ros/brick_markers.h"

#include <cstdio>
#include <string>

#include <Eigen/Geometry>

#include "brick_pose/geometry/cuboid.h"

namespace brick_pose
{
namespace
{
std_msgs::ColorRGBA colourOf(const std::string& type, const BrickCatalogue& catalogue)
{
  std_msgs::ColorRGBA colour;
  colour.a = 1.0f;
  colour.r = colour.g = colour.b = 1.0f;
  if (const BrickType* known = catalogue.find(type))
  {
    colour.r = known->plate_rgb[0] / 255.0f;
    colour.g = known->plate_rgb[1] / 255.0f;
    colour.b = known->plate_rgb[2] / 255.0f;
  }
  return colour;
}

geometry_msgs::Point toPoint(const Eigen::Vector3d& vector)
{
  geometry_msgs::Point point;
  point.x = vector.x();
  point.y = vector.y();
  point.z = vector.z();
  return point;
}

/// A marker of `type` at the detection's pose, in namespace `ns`.
visualization_msgs::Marker markerAt(const BrickDetection& detection, const std::string& ns, int id, int type)
{
  visualization_msgs::Marker marker;
  marker.header = detection.pose.header;
  marker.ns = ns;
  marker.id = id;
  marker.type = type;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose = detection.pose.pose;
  return marker;
}

visualization_msgs::Marker outline(const BrickDetection& detection, int id, const BrickCatalogue& catalogue)
{
  visualization_msgs::Marker marker = markerAt(detection, "brick_outlines", id, visualization_msgs::Marker::LINE_LIST);
  marker.scale.x = 0.004;
  marker.color = colourOf(detection.type, catalogue);
  BrickType shape;
  shape.length_m = detection.dimensions.x;
  shape.width_m = detection.dimensions.y;
  shape.height_m = detection.dimensions.z;
  const auto corners = cuboidCornersInBrick(shape);  // 0-3 top face, 4-7 the same corners below
  for (int k = 0; k < 4; ++k)
  {
    for (int layer : {0, 4})
    {
      marker.points.push_back(toPoint(corners[layer + k]));
      marker.points.push_back(toPoint(corners[layer + (k + 1) % 4]));
    }
    marker.points.push_back(toPoint(corners[k]));
    marker.points.push_back(toPoint(corners[k + 4]));
  }
  return marker;
}

visualization_msgs::Marker label(const BrickDetection& detection, int id)
{
  visualization_msgs::Marker marker =
      markerAt(detection, "brick_labels", id, visualization_msgs::Marker::TEXT_VIEW_FACING);
  // Above the plate: 5 cm along the brick's z axis.
  const Eigen::Quaterniond rotation(detection.pose.pose.orientation.w, detection.pose.pose.orientation.x,
                                    detection.pose.pose.orientation.y, detection.pose.pose.orientation.z);
  const Eigen::Vector3d lifted = rotation * Eigen::Vector3d(0.0, 0.0, 0.05);
  marker.pose.position.x += lifted.x();
  marker.pose.position.y += lifted.y();
  marker.pose.position.z += lifted.z();
  marker.scale.z = 0.04;
  marker.color.r = marker.color.g = marker.color.b = marker.color.a = 1.0f;
  char fitness[16];
  std::snprintf(fitness, sizeof(fitness), " %.2f", detection.fitness);
  marker.text = detection.frame + fitness + (detection.pickable ? " pick" : "");
  if (!detection.resting.empty() && detection.resting != "upright") marker.text += " " + detection.resting;
  // A type only a side would tell: the others it may be, beside the name.
  std::string others;
  for (const std::string& type : detection.other_possible_types) others += (others.empty() ? "" : ", ") + type;
  if (!others.empty()) marker.text += " (or " + others + ")";
  return marker;
}
}  // namespace

visualization_msgs::MarkerArray makeBrickMarkers(const BrickDetectionArray& detections, const BrickCatalogue& catalogue)
{
  visualization_msgs::MarkerArray markers;
  visualization_msgs::Marker clear;
  clear.header = detections.header;
  clear.action = visualization_msgs::Marker::DELETEALL;
  markers.markers.push_back(clear);
  for (std::size_t i = 0; i < detections.detections.size(); ++i)
  {
    markers.markers.push_back(outline(detections.detections[i], static_cast<int>(i), catalogue));
    markers.markers.push_back(label(detections.detections[i], static_cast<int>(i)));
  }
  return markers;
}
}  // namespace brick_pose
