#include "brick_pose/eval/scene_truth.h"

namespace brick_pose
{
namespace eval
{
const char* toString(FaceRole role)
{
  switch (role)
  {
    case FaceRole::kTop: return "top";
    case FaceRole::kSide: return "side";
    case FaceRole::kBottom: return "bottom";
    case FaceRole::kOther: return "other face";
    case FaceRole::kSupport: return "table / ground";
  }
  return "?";
}
}  // namespace eval
}  // namespace brick_pose
