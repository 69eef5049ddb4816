#include "brick_pose/pipeline/face_pieces.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "brick_pose/common/angles.h"

namespace brick_pose
{
bool mayBePiecesOfOneFace(const BrickCandidate& a, const BrickCandidate& b, double max_angle_deg, double max_offset_m)
{
  return a.typed_by_colour && b.typed_by_colour && a.type_name == b.type_name && !a.complete && !b.complete &&
         a.normal.dot(b.normal) >= std::cos(max_angle_deg * kDegToRad) &&
         std::abs(a.plane.signedDistance(b.centroid_m)) <= max_offset_m &&
         std::abs(b.plane.signedDistance(a.centroid_m)) <= max_offset_m;
}

Segment joinSegments(const BrickCandidate& a, const BrickCandidate& b)
{
  Segment joined;
  joined.type_name = a.type_name;
  joined.bounding_box_px = a.bounding_box_px | b.bounding_box_px;
  joined.mask = cv::Mat::zeros(joined.bounding_box_px.size(), CV_8UC1);
  for (const BrickCandidate* piece : {&a, &b})
  {
    cv::Mat target = joined.mask(piece->bounding_box_px - joined.bounding_box_px.tl());
    cv::bitwise_or(target, piece->mask, target);
  }
  joined.area_px = cv::countNonZero(joined.mask);
  // Segments list their pixels in raster order: a linear merge keeps that.
  std::vector<int> first = a.pixel_indices, second = b.pixel_indices;
  if (!std::is_sorted(first.begin(), first.end())) std::sort(first.begin(), first.end());
  if (!std::is_sorted(second.begin(), second.end())) std::sort(second.begin(), second.end());
  joined.pixel_indices.reserve(first.size() + second.size());
  std::set_union(first.begin(), first.end(), second.begin(), second.end(), std::back_inserter(joined.pixel_indices));
  return joined;
}
}  // namespace brick_pose
