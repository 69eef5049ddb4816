#pragma once
// How the pipeline refines the global registration pose before publishing it.

#include <string>

namespace brick_pose
{
/// `correction`: the constant-time geometric correction (correctPose());
/// `icp`: point-to-point ICP of the top-face model against the segment cloud
/// (refinePoseWithIcp()); `none`: publish the registration pose unchanged.
enum class RefinementMethod
{
  kCorrection,
  kIcp,
  kNone,
};

/// The default of the pipeline's `refinement` parameter.
constexpr RefinementMethod kDefaultRefinementMethod = RefinementMethod::kCorrection;

/// "correction", "icp" or "none"; throws ConfigError naming the accepted
/// values otherwise.
RefinementMethod parseRefinementMethod(const std::string& name);

/// The name parseRefinementMethod() accepts for `method`.
const char* toString(RefinementMethod method);
}  // namespace brick_pose
