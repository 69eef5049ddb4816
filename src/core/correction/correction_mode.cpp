#include "brick_pose/correction/correction_mode.h"

#include "brick_pose/common/enum_names.h"

namespace brick_pose
{
constexpr EnumName<CorrectionMode> kCorrectionModeNames[] = {
    {CorrectionMode::kPaper, "paper"}, {CorrectionMode::kFull, "full"}};

CorrectionMode parseCorrectionMode(const std::string& name)
{
  return parseEnumName("correction mode", name, kCorrectionModeNames);
}

const char* toString(CorrectionMode mode) { return enumName(mode, kCorrectionModeNames); }
}  // namespace brick_pose
