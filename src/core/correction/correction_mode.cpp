#include "brick_pose/correction/correction_mode.h"

#include "brick_pose/common/enum_names.h"

namespace brick_pose
{
namespace
{
const EnumNames<CorrectionMode>& correctionModeNames()
{
  static const EnumNames<CorrectionMode> names{{CorrectionMode::kPaper, "paper"}, {CorrectionMode::kFull, "full"}};
  return names;
}
}  // namespace

CorrectionMode parseCorrectionMode(const std::string& name)
{
  return parseEnumName("correction mode", name, correctionModeNames());
}

const char* toString(CorrectionMode mode) { return enumName(mode, correctionModeNames()); }
}  // namespace brick_pose
