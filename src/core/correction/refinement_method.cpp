#include "brick_pose/correction/refinement_method.h"

#include "brick_pose/common/enum_names.h"

namespace brick_pose
{
constexpr EnumName<RefinementMethod> kRefinementMethodNames[] = {
    {RefinementMethod::kCorrection, "correction"}, {RefinementMethod::kIcp, "icp"}, {RefinementMethod::kNone, "none"}};

RefinementMethod parseRefinementMethod(const std::string& name)
{
  return parseEnumName("refinement method", name, kRefinementMethodNames);
}

const char* toString(RefinementMethod method) { return enumName(method, kRefinementMethodNames); }
}  // namespace brick_pose
