#include "brick_pose/correction/refinement_method.h"

#include "brick_pose/common/errors.h"

namespace brick_pose
{
RefinementMethod parseRefinementMethod(const std::string& name)
{
  if (name == "correction")
    return RefinementMethod::kCorrection;
  if (name == "icp")
    return RefinementMethod::kIcp;
  if (name == "none")
    return RefinementMethod::kNone;
  throw ConfigError("refinement: unknown method '" + name + "'; expected one of: correction, icp, none");
}

const char* toString(RefinementMethod method)
{
  switch (method)
  {
    case RefinementMethod::kCorrection:
      return "correction";
    case RefinementMethod::kIcp:
      return "icp";
    case RefinementMethod::kNone:
      return "none";
  }
  return "unknown";
}
}  // namespace brick_pose
