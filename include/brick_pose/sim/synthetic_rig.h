#pragma once
// The synthetic D415: renders a Scene into what realsense2_camera publishes
// with align_depth:=true (rgb8 colour and 16UC1 depth in millimetres, both in
// the colour camera's geometry) plus exact ground truth.
//
// Deterministic: the same scene, camera, sensor model and seed give
// bit-identical frames.

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/sim/scene.h"
#include "brick_pose/sim/sensor_model.h"

namespace brick_pose
{
namespace sim
{
struct SyntheticFrame
{
  PinholeCamera camera;
  cv::Mat rgb;              ///< CV_8UC3 in R, G, B order
  cv::Mat depth_mm;         ///< CV_16UC1, 0 where the sensor has no depth
  cv::Mat depth_clean_m;    ///< CV_32FC1 noise-free depth Z, NaN where nothing was hit
  cv::Mat instance_labels;  ///< CV_16UC1: 0 ground or nothing, i + 1 for Scene::bricks[i]
  cv::Mat face_labels;      ///< CV_8UC1: a CuboidFace value
  std::vector<BrickTruth> truth;  ///< one per brick, in Scene::bricks order
  /// The ground the scene stands on (world z = 0, +z up) in the camera
  /// frame: its xy-plane is what a user gives as support_frame.
  Eigen::Isometry3d camera_T_ground = Eigen::Isometry3d::Identity();
};

class SyntheticRig
{
public:
  /// Throws ConfigError when the camera or the sensor model is invalid.
  SyntheticRig(const PinholeCamera& camera, const SensorModel& sensor);

  SyntheticFrame render(const Scene& scene, std::uint64_t seed) const;

  const PinholeCamera& camera() const { return camera_; }
  const SensorModel& sensor() const { return sensor_; }

private:
  PinholeCamera camera_;
  SensorModel sensor_;
};
}  // namespace sim
}  // namespace brick_pose
