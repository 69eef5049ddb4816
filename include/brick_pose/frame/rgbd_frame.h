#pragma once
// One aligned RGB-D frame in the form every later stage consumes: colour in
// RGB order, depth in metres with NaN for holes, and the intrinsics of the
// (colour) camera the depth is aligned to.

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Core>

#include <opencv2/core.hpp>

#include "brick_pose/camera/pinhole_camera.h"

namespace brick_pose
{
/// An aligned RGB-D frame. Build it with makeRgbdFrame(), which validates it.
struct RgbdFrame
{
  cv::Mat rgb;          ///< CV_8UC3, R,G,B channel order.
  cv::Mat depth_m;      ///< CV_32FC1, metres along the optical axis, NaN = no depth.
  PinholeCamera camera; ///< Intrinsics of the image both rasters live in.
  std::int64_t stamp_ns = 0;
  std::string frame_id; ///< Optical frame (x right, y down, z forward).
  /// "Up" (against gravity) in this camera's frame at the frame's stamp, when
  /// known (the ingestion stage looks up the configured up_frame in tf).
  /// Without it the front end infers up from the scene.
  std::optional<Eigen::Vector3d> up_in_camera;
  /// The plane the pile stands on (a pallet's deck, a table, the floor) in
  /// this camera's frame, when known (the ingestion stage looks up the
  /// configured support_frame in tf: its xy-plane): (n, d) with n . p + d = 0
  /// and n unit, pointing up.
  std::optional<Eigen::Vector4d> support_in_camera;

  int width_px() const { return rgb.cols; }
  int height_px() const { return rgb.rows; }
  double stampSeconds() const { return static_cast<double>(stamp_ns) * 1e-9; }

  /// Depth at pixel (u, v) in metres, NaN for a hole. No bounds check.
  float depthAt(int u_px, int v_px) const { return depth_m.ptr<float>(v_px)[u_px]; }
};
}  // namespace brick_pose
