// Fuzz target: correctPose, the constant-time correction, on fuzzed poses
// (rigid or not, NaN/Inf) and fuzzed measured faces.

#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/correction/pose_correction.h"
#include "fuzz_support.h"

namespace
{
Eigen::Vector3d consumeVector(FuzzedDataProvider& input, double low, double high)
{
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = brick_pose::fuzz::consumeDouble(input, low, high);
  return v;
}

/// Mostly a rigid pose from a quaternion and a translation in front of the
/// camera; sometimes a raw 3x4 matrix (scaled, sheared, NaN).
Eigen::Isometry3d consumePose(FuzzedDataProvider& input)
{
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (input.ConsumeIntegralInRange<int>(0, 3) != 0)
  {
    Eigen::Quaterniond q(brick_pose::fuzz::consumeDouble(input, -1, 1), brick_pose::fuzz::consumeDouble(input, -1, 1),
                         brick_pose::fuzz::consumeDouble(input, -1, 1), brick_pose::fuzz::consumeDouble(input, -1, 1));
    if (q.norm() > 0.0) q.normalize();
    pose.linear() = q.toRotationMatrix();
  }
  else
  {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) pose.linear()(r, c) = brick_pose::fuzz::consumeDouble(input, -2, 2);
  }
  pose.translation() = consumeVector(input, -3.0, 3.0);
  return pose;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace brick_pose;
  static const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  FuzzedDataProvider input(data, size);

  PoseCorrectionParams parameters;
  parameters.mode = input.ConsumeBool() ? CorrectionMode::kFull : CorrectionMode::kPaper;
  // A brick of the catalogue, or one with any dimensions (no validate():
  // correctPose documents its own check of the length).
  BrickType brick = catalogue.types()[input.ConsumeIntegralInRange<std::size_t>(0, catalogue.types().size() - 1)];
  if (input.ConsumeIntegralInRange<int>(0, 7) == 0)
  {
    brick.length_m = fuzz::consumeDouble(input, -1.0, 3.0);
    brick.width_m = fuzz::consumeDouble(input, -1.0, 3.0);
    brick.height_m = fuzz::consumeDouble(input, -1.0, 3.0);
  }
  const Eigen::Isometry3d pose = consumePose(input);
  MeasuredFace face;
  face.t1_m = consumeVector(input, -3.0, 3.0);
  face.t2_m = input.ConsumeIntegralInRange<int>(0, 3) != 0 ? face.t1_m + consumeVector(input, -2.0, 2.0)
                                                            : consumeVector(input, -3.0, 3.0);
  face.centroid_m = input.ConsumeBool() ? face.midpoint_m() : consumeVector(input, -3.0, 3.0);
  face.normal = consumeVector(input, -1.0, 1.0);

  try
  {
    const PoseCorrection correction = correctPose(pose, brick, face, parameters);
    // An accepted correction is a finite rigid transform.
    const Eigen::Matrix3d rotation = correction.corrected_pose.linear();
    fuzz::require(correction.corrected_pose.matrix().allFinite());
    fuzz::require((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm() < 1e-6);
    fuzz::require(std::abs(rotation.determinant() - 1.0) < 1e-6);
    fuzz::require(std::isfinite(correction.yaw_rad) && std::isfinite(correction.tilt_rad));
  }
  catch (const InputError&)
  {
  }
  catch (const ConfigError&)
  {
  }
  return 0;
}
