#include "bench_registration/face_cases.h"

#include <random>

#include "brick_pose/registration/uniform_sampling.h"

namespace bench_registration
{
using namespace brick_pose;
using registration::PointSet;

RigFaceSource::RigFaceSource(std::uint64_t seed, double min_visible_fraction)
  : min_visible_fraction_(min_visible_fraction),
    catalogue_(BrickCatalogue::mbzirc2020()),
    camera_(PinholeCamera::d415Color1280x720()),
    generator_(catalogue_, sceneParams()),
    rig_(camera_, sim::SensorModel()),
    next_seed_(seed)
{
}

FaceSample RigFaceSource::next(int& skipped)
{
  for (;;)
  {
    const std::uint64_t seed = next_seed_++;
    const sim::Scene scene = generator_.generate(seed);
    const sim::SyntheticFrame frame = rig_.render(scene, seed);
    if (frame.truth.empty() || frame.truth[0].visible_fraction < min_visible_fraction_)
    {
      ++skipped;
      continue;
    }
    FaceSample sample;
    sample.type = scene.bricks[0].type;
    sample.camera_T_brick = frame.truth[0].camera_T_brick;
    sample.distance_m = sample.camera_T_brick.translation().norm();
    const PointSet all = topFacePoints(frame, frame.truth[0].instance_id);
    if (static_cast<int>(all.size()) < kMinSegmentPoints)
    {
      ++skipped;
      continue;
    }
    std::mt19937_64 rng(seed);
    sample.segment = all.subset(registration::uniformSubsample(all.points, kMaxSegmentPoints, rng));
    return sample;
  }
}

sim::SceneParams RigFaceSource::sceneParams()
{
  sim::SceneParams params;
  params.kind = sim::SceneKind::kSingle;
  params.min_distance_m = 0.5;
  params.max_distance_m = 2.0;
  return params;
}

PointSet RigFaceSource::topFacePoints(const sim::SyntheticFrame& frame, int instance_id) const
{
  PointSet points;
  for (int v = 0; v < frame.instance_labels.rows; ++v)
    for (int u = 0; u < frame.instance_labels.cols; ++u)
    {
      if (frame.instance_labels.at<std::uint16_t>(v, u) != instance_id ||
          frame.face_labels.at<std::uint8_t>(v, u) != static_cast<std::uint8_t>(sim::CuboidFace::kTop))
        continue;
      const std::uint16_t depth_mm = frame.depth_mm.at<std::uint16_t>(v, u);
      if (depth_mm == 0)
        continue;
      points.points.push_back(frame.camera.backProject(u, v, 1e-3 * depth_mm));
    }
  return points;
}
}  // namespace bench_registration

#include "brick_pose/registration/brick_symmetry.h"

namespace bench_registration
{
Outcome judgeFace(const brick_pose::registration::RegistrationResult& result, const Eigen::Isometry3d& truth)
{
  using namespace brick_pose::registration;
  const Eigen::Isometry3d estimate = canonicalisePose(result.source_to_target, ModelSymmetry::kRectangle);
  const PoseError error = poseErrorModuloSymmetry(estimate, truth, ModelSymmetry::kHalfTurnZ);
  Outcome outcome = outcomeOf(result, error.rotation_deg, error.translation_mm());
  outcome.success = outcome.correct;
  return outcome;
}
}  // namespace bench_registration
