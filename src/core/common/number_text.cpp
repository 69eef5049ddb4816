#include "brick_pose/common/number_text.h"

#include <sstream>

namespace brick_pose
{
std::string numberText(double value, int significant_digits)
{
  std::ostringstream text;
  text.precision(significant_digits);
  text << value;
  return text.str();
}
}  // namespace brick_pose
