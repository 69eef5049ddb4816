#include "bench_pose/pose_bench.h"

#include <array>
#include <chrono>
#include <string>

#include "bench_pose/measurement.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "common/run_environment.h"

namespace brick_pose
{
namespace pose_bench
{

namespace
{
struct FrameSpec
{
  sim::SceneKind kind = sim::SceneKind::kSingle;
  sim::Lighting lighting = sim::Lighting::kNormal;
  std::uint64_t seed = 0;
};

/// Two singles in four frames (single bricks are the common case and the
/// latency set), lighting cycling every four so each kind meets each mode.
FrameSpec frameSpec(int index, std::uint64_t base_seed)
{
  static const std::array<sim::SceneKind, 4> kinds{{sim::SceneKind::kSingle, sim::SceneKind::kSingle,
                                                    sim::SceneKind::kOrganisedPile,
                                                    sim::SceneKind::kUnorganisedPile}};
  static const std::array<sim::Lighting, 3> lightings{
      {sim::Lighting::kNormal, sim::Lighting::kSunlight, sim::Lighting::kLowLight}};
  FrameSpec spec;
  spec.kind = kinds[index % kinds.size()];
  spec.lighting = lightings[(index / kinds.size()) % lightings.size()];
  spec.seed = base_seed * 1000003ULL + static_cast<std::uint64_t>(index);
  return spec;
}

/// The registration, or nullopt when Super4PCS finds no pose.
std::optional<BrickRegistration> tryRegister(const BrickPoseEstimator& estimator, const BrickCandidate& candidate)
{
  try
  {
    return estimator.registerCandidate(candidate);
  }
  catch (const InputError&)
  {
    return std::nullopt;
  }
}

}  // namespace

sim::SceneGenerator generatorFor(const BrickCatalogue& catalogue, sim::SceneKind kind, int max_pile_bricks)
{
  sim::SceneParams params;
  params.kind = kind;
  params.max_pile_bricks = max_pile_bricks;
  params.min_distance_m = 0.6;
  params.max_distance_m = 1.5;
  return sim::SceneGenerator(catalogue, params);
}

void PoseBench::runTimedPipeline(const sim::SyntheticFrame& synthetic, FrontEndResult& front_end_result,
                                 BenchResults& results) const
{
  FrameHeader header;
  header.frame_id = "camera_color_optical_frame";
  const auto start = std::chrono::steady_clock::now();
  const RgbdFrame frame =
      makeRgbdFrame(imageViewOf(synthetic.rgb, "rgb8"), imageViewOf(synthetic.depth_mm, "16UC1"), camera_, header);
  front_end_result = front_end_.process(frame);
  const double front_end_ms = millisecondsSince(start);
  for (const BrickCandidate& candidate : front_end_result.candidates)
  {
    const std::optional<BrickRegistration> registration = tryRegister(defaultEstimator(), candidate);
    if (!registration) continue;
    try
    {
      defaultEstimator().refine(candidate, *registration);
    }
    catch (const InputError&)
    {
      // The node drops the brick; the time spent still counts.
    }
  }
  const double total_ms = millisecondsSince(start);
  results.latency_ms.push_back(total_ms);
  results.latency_frontend_ms.push_back(front_end_ms);
  results.latency_registration_ms.push_back(total_ms - front_end_ms);
}

void PoseBench::evaluateCandidate(const BrickCandidate& candidate,
                                  const std::optional<BrickRegistration>& registration, const sim::BrickTruth& truth,
                                  BrickRecord& record) const
{
  record.registered = registration.has_value();
  if (!registration)
  {
    for (MethodOutcome& outcome : record.outcomes) outcome.failure = "Super4PCS failed";
    return;
  }
  record.super4pcs_ms = registration->elapsed_ms;
  record.lcp_score = registration->result.lcp_score;
  for (std::size_t m = 0; m < kMethodCount; ++m)
  {
    MethodOutcome& outcome = record.outcomes[m];
    try
    {
      const BrickPoseEstimate estimate = estimators_[m].refine(candidate, *registration);
      const registration::PoseError error = registration::poseErrorModuloSymmetry(estimate.pose, truth.camera_T_brick);
      outcome.success = true;
      outcome.rotation_error_deg = error.rotation_deg;
      outcome.translation_error_mm = error.translation_mm();
      outcome.refinement_us = 1000.0 * estimate.refinement_ms;
    }
    catch (const InputError& error)
    {
      outcome.failure = error.what();
    }
  }
}

void PoseBench::runFrame(int index, std::uint64_t base_seed, BenchResults& results) const
{
  const FrameSpec spec = frameSpec(index, base_seed);
  const sim::Scene scene = generators_.at(spec.kind).generate(spec.seed);
  sim::SensorModel sensor;
  sensor.lighting = spec.lighting;
  const sim::SyntheticFrame synthetic = sim::SyntheticRig(camera_, sensor).render(scene, spec.seed);

  FrontEndResult front_end_result;
  if (spec.kind == sim::SceneKind::kSingle)
    runTimedPipeline(synthetic, front_end_result, results);
  else
  {
    // Bricks are registered for accuracy below, only those that count.
    FrameHeader header;
    front_end_result = front_end_.process(makeRgbdFrame(synthetic.rgb, synthetic.depth_mm, camera_, header));
  }

  ++results.frames;
  std::vector<bool> instance_taken(synthetic.truth.size() + 1, false);
  for (std::size_t c = 0; c < front_end_result.candidates.size(); ++c)
  {
    const BrickCandidate& candidate = front_end_result.candidates[c];
    ++results.candidates;
    std::string unmatched_reason;
    const sim::BrickTruth* truth = matchTruth(candidate, synthetic, unmatched_reason);
    if (!truth)
    {
      ++results.unmatched_candidates[unmatched_reason];
      continue;
    }
    BrickRecord record;
    record.frame = index;
    record.kind = spec.kind;
    record.lighting = spec.lighting;
    record.type = truth->type;
    record.instance = truth->instance_id;
    record.distance_m = truth->camera_T_brick.translation().norm();
    record.visible_fraction = truth->visible_fraction;
    record.complete = candidate.complete;
    record.exclusion = exclusionReason(candidate, *truth, instance_taken[truth->instance_id]);
    instance_taken[truth->instance_id] = true;
    record.measurement = measurementErrorOf(candidate, *truth, camera_);
    // Excluded bricks are not refined: ICP on them would double the run time
    // for numbers that are not reported.
    if (record.exclusion.empty())
    {
      const std::optional<BrickRegistration> registration = tryRegister(*accuracy_registrar_, candidate);
      evaluateCandidate(candidate, registration, *truth, record);
      if (!record.registered) record.exclusion = "Super4PCS failed";
    }
    record.counted = record.exclusion.empty();
    results.bricks.push_back(std::move(record));
  }
}
}  // namespace pose_bench
}  // namespace brick_pose
