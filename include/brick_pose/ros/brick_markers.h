#pragma once
// rviz markers of the detected bricks: cuboid outlines in the type's plate
// colour and a label above each.

#include <visualization_msgs/MarkerArray.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/catalogue/brick_catalogue.h"

namespace brick_pose
{
/// Clears the previous frame's markers, then one outline and one label per detection.
visualization_msgs::MarkerArray makeBrickMarkers(const BrickDetectionArray& detections, const BrickCatalogue& catalogue);
}  // namespace brick_pose
