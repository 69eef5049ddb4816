#pragma once
// The paper's oriented bounding box: principal axes of the segment's
// covariance, extents = max - min of the points along each axis.

#include <optional>
#include <string>

#include <Eigen/Core>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "brick_pose/catalogue/brick_catalogue.h"

namespace brick_pose
{
struct OrientedBoundingBox
{
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();
  /// Columns: major, middle and minor principal axis (right-handed, unit).
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  /// Full extents along the columns of `axes` (length, width, thickness).
  Eigen::Vector3d extents_m = Eigen::Vector3d::Zero();
  bool valid = false;
};

/// PCA box of the finite points; invalid with fewer than 3 points.
OrientedBoundingBox computeOrientedBoundingBox(const pcl::PointCloud<pcl::PointXYZ>& cloud);

/// How a measured top face may differ from a catalogue type.
struct DimensionTolerance
{
  double tolerance_m = 0.03;       ///< Allowed excess over length/width (noise, edge pixels).
  /// A top face is flat; more (beyond the spread of the depth noise) means a
  /// side face is included.
  double max_thickness_m = 0.03;
  /// A partly occluded plate is still a candidate when at least this fraction
  /// of its length and width is visible.
  double min_visible_fraction = 0.4;
};

/// Empty when a face of length x width x thickness fits `type`'s top face;
/// otherwise the reason, naming the dimension at fault.
std::optional<std::string> checkTopFaceDimensions(double length_m, double width_m, double thickness_m,
                                                  const BrickType& type, const DimensionTolerance& tolerance);
}  // namespace brick_pose
