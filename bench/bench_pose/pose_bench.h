#pragma once
// The benchmark's frames (seeded scenes, the rig) and what is done with
// each: the front end, Super4PCS once per matched brick and every refinement
// method from that registration, plus the end-to-end latency of single-brick
// frames.

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "bench_pose/records.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/pose/brick_pose_estimator.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace pose_bench
{
/// The rig's scene generator of one kind at the benchmark's distances.
sim::SceneGenerator generatorFor(const BrickCatalogue& catalogue, sim::SceneKind kind, int max_pile_bricks);

class PoseBench
{
public:
  /// `camera`: the D415 mode rendered; `max_pile_bricks`: unorganised piles
  /// draw 2..this bricks (the rig's default 6; 12 for the piles of issue 14).
  PoseBench(const BrickCatalogue& catalogue, const PinholeCamera& camera, int max_pile_bricks)
    : catalogue_(catalogue), camera_(camera), front_end_(catalogue)
  {
    for (const Method method : kMethods) estimators_.emplace_back(catalogue, estimatorParamsFor(method));
    accuracy_registrar_.emplace(catalogue, accuracyRegistrationParams());
    for (const sim::SceneKind kind :
         {sim::SceneKind::kSingle, sim::SceneKind::kOrganisedPile, sim::SceneKind::kUnorganisedPile})
      generators_.emplace(kind, generatorFor(catalogue, kind, max_pile_bricks));
  }

  void runFrame(int index, std::uint64_t base_seed, BenchResults& results) const;

private:
  const BrickPoseEstimator& defaultEstimator() const
  {
    return estimators_[static_cast<std::size_t>(Method::kCorrectionFull)];
  }

  /// The registration every method starts from in the accuracy table. The
  /// pipeline's default stops Super4PCS early when the correction follows
  /// (correction_good_enough_ratio), which the correction does not feel but
  /// ICP would: here Super4PCS runs to its own stop score, as it does in the
  /// pipeline's icp mode, so that ICP gets a fair start.
  static BrickPoseEstimatorParams accuracyRegistrationParams()
  {
    BrickPoseEstimatorParams params = estimatorParamsFor(Method::kCorrectionFull);
    params.correction_good_enough_ratio = params.super4pcs.good_enough_ratio;
    return params;
  }

  /// The pipeline on one frame, from the raw buffers, as the node runs it:
  /// frame build, front end, registration and default refinement of every
  /// candidate; records its latency into `results`.
  void runTimedPipeline(const sim::SyntheticFrame& synthetic, FrontEndResult& front_end_result,
                        BenchResults& results) const;

  void evaluateCandidate(const BrickCandidate& candidate, const std::optional<BrickRegistration>& registration,
                         const sim::BrickTruth& truth, BrickRecord& record) const;

  BrickCatalogue catalogue_;
  PinholeCamera camera_;
  FrontEnd front_end_;
  std::vector<BrickPoseEstimator> estimators_;  // one per Method, in kMethods order
  std::optional<BrickPoseEstimator> accuracy_registrar_;
  std::map<sim::SceneKind, sim::SceneGenerator> generators_;
};

}  // namespace pose_bench
}  // namespace brick_pose
