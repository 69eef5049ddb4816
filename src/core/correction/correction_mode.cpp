#include "brick_pose/correction/correction_mode.h"

#include "brick_pose/common/errors.h"

namespace brick_pose
{
CorrectionMode parseCorrectionMode(const std::string& name)
{
  if (name == "paper")
    return CorrectionMode::kPaper;
  if (name == "full")
    return CorrectionMode::kFull;
  throw ConfigError("correction mode: unknown value '" + name + "'; expected one of: paper, full");
}

const char* toString(CorrectionMode mode)
{
  switch (mode)
  {
    case CorrectionMode::kPaper:
      return "paper";
    case CorrectionMode::kFull:
      return "full";
  }
  return "unknown";
}
}  // namespace brick_pose
