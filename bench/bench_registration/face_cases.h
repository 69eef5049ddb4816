#pragma once
// Face cases: segmented brick top faces from the synthetic D415 (the
// registration the pipeline runs on every candidate).

#include <cstdint>

#include <Eigen/Geometry>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/registration/point_set.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace bench_registration
{
constexpr int kMinSegmentPoints = 1000;
constexpr int kMaxSegmentPoints = 2000;

/// One registration problem: a segmented top face and its ground truth.
struct FaceSample
{
  brick_pose::BrickType type;
  brick_pose::registration::PointSet segment;  ///< camera frame
  Eigen::Isometry3d camera_T_brick = Eigen::Isometry3d::Identity();
  double distance_m = 0.0;
};

/// Makes the face samples. Kept behind this one class so that another
/// source of segments (e.g. recorded data) can replace the rig.
class RigFaceSource
{
public:
  RigFaceSource(std::uint64_t seed, double min_visible_fraction);

  /// The next usable face; `skipped` counts the frames passed over.
  FaceSample next(int& skipped);

private:
  static brick_pose::sim::SceneParams sceneParams();
  /// Top-face pixels of one brick, back-projected from the noisy depth.
  brick_pose::registration::PointSet topFacePoints(const brick_pose::sim::SyntheticFrame& frame,
                                                   int instance_id) const;

  double min_visible_fraction_;
  brick_pose::BrickCatalogue catalogue_;
  brick_pose::PinholeCamera camera_;
  brick_pose::sim::SceneGenerator generator_;
  brick_pose::sim::SyntheticRig rig_;
  std::uint64_t next_seed_;
};
}  // namespace bench_registration

#include "bench_registration/outcomes.h"
#include "brick_pose/registration/registration_result.h"

namespace bench_registration
{
/// A face registration judged: the estimate is first canonicalised (brick z
/// towards the camera, which a face without normals cannot tell) and the
/// error taken modulo the half turn about the face normal. Success = right.
Outcome judgeFace(const brick_pose::registration::RegistrationResult& result, const Eigen::Isometry3d& truth);
}  // namespace bench_registration
