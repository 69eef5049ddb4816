#include "bench_pose/methods.h"

namespace brick_pose
{
namespace pose_bench
{
const char* methodName(Method method)
{
  switch (method)
  {
    case Method::kNone: return "super4pcs_only";
    case Method::kCorrectionPaper: return "correction_paper";
    case Method::kCorrectionFull: return "correction_full";
    case Method::kIcp: return "icp";
  }
  return "?";
}

const char* methodLabel(Method method)
{
  switch (method)
  {
    case Method::kNone: return "Super4PCS alone";
    case Method::kCorrectionPaper: return "Correction (paper)";
    case Method::kCorrectionFull: return "Correction (full, default)";
    case Method::kIcp: return "ICP";
  }
  return "?";
}

bool timedInMicroseconds(Method method)
{
  return method == Method::kCorrectionPaper || method == Method::kCorrectionFull;
}

BrickPoseEstimatorParams estimatorParamsFor(Method method)
{
  BrickPoseEstimatorParams params;
  switch (method)
  {
    case Method::kNone: params.refinement = RefinementMethod::kNone; break;
    case Method::kCorrectionPaper:
      params.refinement = RefinementMethod::kCorrection;
      params.correction.mode = CorrectionMode::kPaper;
      break;
    case Method::kCorrectionFull:
      params.refinement = RefinementMethod::kCorrection;
      params.correction.mode = CorrectionMode::kFull;
      break;
    case Method::kIcp: params.refinement = RefinementMethod::kIcp; break;
  }
  return params;
}
}  // namespace pose_bench
}  // namespace brick_pose
