#include "roi_filter_internal.h"

#include <algorithm>
#include <sstream>

namespace brick_pose
{
namespace roi_internal
{
std::string describe(const std::string& what, double value, const std::string& rule, double limit)
{
  std::ostringstream text;
  text.precision(3);
  text << what << " " << value << " " << rule << " " << limit;
  return text.str();
}

RoiRejection partRejection(const Segment& part, const std::string& reason)
{
  return {"part of a split segment: " + reason, part.bounding_box_px, part.area_px};
}

Eigen::Vector3d sideAxis(const BrickCandidate& candidate, const FrameContext& context)
{
  constexpr double kLevelDeg = 10.0;
  if (context.up.known() && candidate.tilt_from_up_deg <= kLevelDeg) return context.up.up;
  return candidate.normal;
}

bool anyTruncated(const BrickCandidate& candidate)
{
  return std::any_of(candidate.edge_truncated.begin(), candidate.edge_truncated.end(), [](bool cut) { return cut; });
}

std::string truncation(const BrickCandidate& candidate)
{
  for (int k = 0; k < 4; ++k)
    if (candidate.edge_truncated[k]) return "edge " + std::to_string(k) + ": " + toString(candidate.edge_kinds[k]);
  return "no edge";
}

std::vector<const BrickType*> typesFor(const BrickCatalogue& catalogue, const std::string& type_name)
{
  std::vector<const BrickType*> types;
  for (const BrickType& type : catalogue.types())
    if (type_name.empty() || type.name == type_name) types.push_back(&type);
  return types;
}

void addTypeDoubt(BrickCandidate& candidate, const std::string& doubt)
{
  candidate.type_doubt = candidate.type_doubt.empty() ? doubt : doubt + "; " + candidate.type_doubt;
}
}  // namespace roi_internal
}  // namespace brick_pose
