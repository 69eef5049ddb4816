// Fuzz target: registration::Super4PCS::align on small fuzzed point sets
// (what the registration nodelet gets from a segment and a model), with a
// short time budget so one run stays in the tens of milliseconds.
//
// Coordinates are mostly on a millimetre grid within +-0.5 m (duplicates,
// collinear and coplanar sets come up often), sometimes NaN/Inf/huge.

#include <cmath>
#include <cstdint>

#include "brick_pose/common/errors.h"
#include "brick_pose/registration/super4pcs.h"
#include "fuzz_support.h"

namespace
{
using brick_pose::registration::PointSet;

double consumeCoordinate(FuzzedDataProvider& input)
{
  if (input.ConsumeIntegralInRange<int>(0, 31) != 0) return 0.001 * input.ConsumeIntegralInRange<int>(-500, 500);
  return brick_pose::fuzz::consumeDouble(input, -1e3, 1e3);
}

PointSet consumePointSet(FuzzedDataProvider& input, bool with_normals)
{
  PointSet set;
  const int count = input.ConsumeIntegralInRange<int>(0, 48);
  for (int i = 0; i < count && input.remaining_bytes() > 0; ++i)
  {
    set.points.emplace_back(consumeCoordinate(input), consumeCoordinate(input), consumeCoordinate(input));
    if (with_normals)
    {
      Eigen::Vector3d normal(consumeCoordinate(input), consumeCoordinate(input), consumeCoordinate(input));
      // Mostly unit as promised by PointSet; a raw (zero, NaN) one now and then.
      if (input.ConsumeIntegralInRange<int>(0, 15) != 0 && normal.norm() > 0.0) normal.normalize();
      set.normals.push_back(normal);
    }
  }
  return set;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace brick_pose;
  FuzzedDataProvider input(data, size);

  registration::Super4PCSParams params;
  params.max_time_s = 0.02;
  params.max_bases = input.ConsumeIntegralInRange<int>(1, 50);
  params.overlap = input.ConsumeFloatingPointInRange<double>(0.05, 1.0);
  params.delta_m = input.ConsumeFloatingPointInRange<double>(0.0005, 0.05);
  params.sample_size = input.ConsumeIntegralInRange<int>(4, 64);
  params.lcp_sample_size = input.ConsumeIntegralInRange<int>(4, 64);
  params.refine_iterations = input.ConsumeIntegralInRange<int>(0, 5);
  params.seed = input.ConsumeIntegral<std::uint8_t>();
  // Whole-view mode too: scan normals estimated, view checks, symmetries.
  if (input.ConsumeBool())
  {
    params.view.mode = registration::ViewMode::kOn;
    params.view.max_candidates = input.ConsumeIntegralInRange<int>(1, 200);
    params.view.viewpoint_m = Eigen::Vector3d(consumeCoordinate(input), consumeCoordinate(input), consumeCoordinate(input));
  }
  const bool with_normals = input.ConsumeBool();

  const PointSet source = consumePointSet(input, with_normals);
  const PointSet target = consumePointSet(input, with_normals);

  try
  {
    const registration::Super4PCS super4pcs(params);  // may throw ConfigError (a NaN viewpoint)
    const registration::RegistrationResult result = super4pcs.align(source, target);
    if (result.success)
    {
      fuzz::require(result.source_to_target.matrix().allFinite());
      fuzz::require(result.lcp_score >= 0.0 && result.lcp_score <= 1.0);
      fuzz::require(result.confidence >= 0.0 && result.confidence <= 1.0);
    }
  }
  catch (const InputError&)
  {
  }
  catch (const ConfigError&)
  {
  }
  return 0;
}
