#pragma once
// Pinhole intrinsics of the (aligned) colour camera and the paper's
// projection / inverse-projection equations (1)-(4).
//
// Pixel convention: integer pixel coordinates are pixel centres (OpenCV and
// sensor_msgs/CameraInfo), so pixel (u, v) back-projects along
// ((u - cx) / fx, (v - cy) / fy, 1). The frame is the REP-103 optical frame:
// x right, y down, z forward.

#include <Eigen/Core>

namespace brick_pose
{
struct PinholeCamera
{
  int width_px = 1280;
  int height_px = 720;
  double fx_px = 920.0;
  double fy_px = 920.0;
  double cx_px = 640.0;
  double cy_px = 360.0;

  /// Intrinsics of a D415 colour camera at 1280x720 (typical factory values).
  static PinholeCamera d415Color1280x720();

  /// Throws ConfigError naming the first bad field (zero/negative/NaN focal
  /// length, empty image, principal point far outside the image).
  void validate() const;

  // The three projections are defined here, inline: the ROI stage calls
  // them per pixel and per grid cell, where an out-of-line call cost more
  // than the arithmetic.

  /// Pixel of a point in the optical frame; z must be > 0.
  Eigen::Vector2d project(const Eigen::Vector3d& point_m) const
  {
    return {fx_px * point_m.x() / point_m.z() + cx_px, fy_px * point_m.y() / point_m.z() + cy_px};
  }

  /// Inverse projection of pixel (u, v) at depth Z (metres along the optical axis).
  Eigen::Vector3d backProject(double u_px, double v_px, double depth_m) const
  {
    return {(u_px - cx_px) * depth_m / fx_px, (v_px - cy_px) * depth_m / fy_px, depth_m};
  }

  /// Unit-less ray direction (z = 1) through pixel (u, v).
  Eigen::Vector3d ray(double u_px, double v_px) const { return {(u_px - cx_px) / fx_px, (v_px - cy_px) / fy_px, 1.0}; }

  /// Whether pixel (u, v) lies in the image, at least `margin_px` inside its
  /// outer edge (the edge of the first and last pixels, at -0.5 and
  /// width - 0.5).
  bool contains(double u_px, double v_px, double margin_px = 0.0) const;

  /// The same camera with the image scaled by `factor` (e.g. 0.5 for 640x360).
  PinholeCamera scaled(double factor) const;
};
}  // namespace brick_pose
