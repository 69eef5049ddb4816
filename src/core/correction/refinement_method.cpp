#include "brick_pose/correction/refinement_method.h"

#include "brick_pose/common/enum_names.h"

namespace brick_pose
{
namespace
{
const EnumNames<RefinementMethod>& refinementMethodNames()
{
  static const EnumNames<RefinementMethod> names{
      {RefinementMethod::kCorrection, "correction"}, {RefinementMethod::kIcp, "icp"}, {RefinementMethod::kNone, "none"}};
  return names;
}
}  // namespace

RefinementMethod parseRefinementMethod(const std::string& name)
{
  return parseEnumName("refinement method", name, refinementMethodNames());
}

const char* toString(RefinementMethod method) { return enumName(method, refinementMethodNames()); }
}  // namespace brick_pose
