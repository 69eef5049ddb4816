#pragma once
// Which variant of the constant-time pose correction to run.

#include <string>

namespace brick_pose
{
/// `paper` follows the paper's equation for FinalPose (yaw about the pose's z
/// axis, then translation); `full` also removes roll and pitch by aligning the
/// pose's z axis with the measured face normal, so all six DOF are corrected.
enum class CorrectionMode
{
  kPaper,
  kFull,
};

/// "paper" or "full"; throws ConfigError naming the accepted values otherwise.
CorrectionMode parseCorrectionMode(const std::string& name);

/// The name parseCorrectionMode() accepts for `mode`.
const char* toString(CorrectionMode mode);
}  // namespace brick_pose
