#include "brick_pose/roi/plate_splitter.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/union_find.h"
#include "brick_pose/roi/least_area_quad.h"

namespace brick_pose
{
namespace
{
/// Gaps between the rows of a pile are a few centimetres.
constexpr double kMaxGapM = 0.04;
constexpr double kMinDefectDepthPx = 4.0;

/// Position across the merged face of a 3D point on its plane: 0 on the
/// first long edge, 1 on the opposite one.
struct AcrossCoordinate
{
  Eigen::Vector3d origin;  // a point of the first edge along the bricks
  Eigen::Vector3d across;  // unit direction across the bricks, divided by the across extent

  double operator()(const Eigen::Vector3d& point) const { return (point - origin).dot(across); }
};

/// Mean distance between the lines a0-a1 and b0-b1 (from the middle of each
/// segment to the other line).
double lineSeparation(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                      const Eigen::Vector3d& b1)
{
  auto distanceToLine = [](const Eigen::Vector3d& point, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
    return (point - p0).cross((p1 - p0).normalized()).norm();
  };
  return 0.5 * (distanceToLine(0.5 * (a0 + a1), b0, b1) + distanceToLine(0.5 * (b0 + b1), a0, a1));
}

/// Convexity defects of the segment's outline (empty when there are none).
std::vector<cv::Vec4i> outlineDefects(const std::vector<cv::Point>& outline)
{
  std::vector<cv::Vec4i> defects;
  if (outline.size() < 4) return defects;
  std::vector<int> hull;
  cv::convexHull(outline, hull, false, false);
  try
  {
    if (hull.size() >= 3) cv::convexityDefects(outline, hull, defects);
  }
  catch (const cv::Exception&)
  {
    defects.clear();  // self-intersecting outline: no hint
  }
  return defects;
}

/// Image direction of the deepest notch (a gap between two plates seen
/// from its open end): from the middle of its mouth to its apex.
std::optional<Eigen::Vector2d> gapDirectionPx(const Segment& segment)
{
  constexpr double kMinGapDepthPx = 10.0;
  const std::vector<cv::Point> outline = largestOutline(segment.mask, segment.bounding_box_px.tl());
  double deepest_px = kMinGapDepthPx;
  std::optional<Eigen::Vector2d> direction;
  for (const cv::Vec4i& defect : outlineDefects(outline))
  {
    if (defect[3] / 256.0 < deepest_px) continue;
    deepest_px = defect[3] / 256.0;
    const cv::Point mouth = (outline[defect[0]] + outline[defect[1]]) * 0.5;
    const cv::Point apex = outline[defect[2]];
    direction = Eigen::Vector2d(apex.x - mouth.x, apex.y - mouth.y).normalized();
  }
  return direction;
}

/// Cut positions (fractions across), moved to the deepest nearby defect apex.
std::vector<double> cutFractions(const Segment& segment, const BrickCandidate& measured, const PinholeCamera& camera,
                                 const AcrossCoordinate& coordinate, int parts)
{
  std::vector<double> cuts;
  for (int k = 1; k < parts; ++k) cuts.push_back(static_cast<double>(k) / parts);
  std::vector<double> best_depth(cuts.size(), 0.0);

  const std::vector<cv::Point> outline = largestOutline(segment.mask, segment.bounding_box_px.tl());
  for (const cv::Vec4i& defect : outlineDefects(outline))
  {
    const double depth_px = defect[3] / 256.0;
    if (depth_px < kMinDefectDepthPx) continue;
    const cv::Point apex = outline[static_cast<std::size_t>(defect[2])];
    Eigen::Vector3d point;
    if (!measured.plane.intersectRay(camera.ray(apex.x, apex.y), point)) continue;
    const double fraction = coordinate(point);
    for (std::size_t k = 0; k < cuts.size(); ++k)
    {
      const double nominal = static_cast<double>(k + 1) / parts;
      if (std::abs(fraction - nominal) < 0.25 / parts && depth_px > best_depth[k])
      {
        best_depth[k] = depth_px;
        cuts[k] = fraction;
      }
    }
  }
  return cuts;
}
}  // namespace

int sideBySideCount(double across_m, double width_m)
{
  if (!(width_m > 0.0)) return 1;
  const int count = static_cast<int>(std::floor((across_m + 0.03) / (width_m + 0.01)));
  return std::max(1, count);
}

std::vector<Segment> splitSideBySide(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                                     const BrickType& type, double tolerance_m)
{
  const auto& c = measured.corners_m;
  // Which side holds the plates: the other one must be the brick's length.
  AcrossCoordinate coordinate;
  coordinate.origin = c[0];
  double across_m = 0.0;
  // The side along the bricks may be shorter than their length (image
  // border, occluders) but not longer, and must be longer than a width (or
  // the face would be one brick seen lengthwise).
  const double max_length_m = type.length_m + tolerance_m;
  const double min_length_m = type.width_m + tolerance_m;
  auto alongBricks = [&](double side_m) { return side_m > min_length_m && side_m <= max_length_m; };
  const bool along_long_edges = alongBricks(measured.length_m) && measured.width_m > type.width_m + tolerance_m;
  const bool along_short_edges = alongBricks(measured.width_m) && measured.length_m > type.width_m + tolerance_m;
  // When both sides could run along the bricks (rows clipped by the image
  // border), the visible end of a gap tells: it runs along the bricks.
  bool use_short_edges = along_short_edges && !along_long_edges;
  if (along_long_edges && along_short_edges)
    if (const std::optional<Eigen::Vector2d> gap = gapDirectionPx(segment))
    {
      const Eigen::Vector2d long_edge = (measured.corners_px[1] - measured.corners_px[0]).normalized();
      const Eigen::Vector2d short_edge = (measured.corners_px[2] - measured.corners_px[1]).normalized();
      use_short_edges = std::abs(gap->dot(short_edge)) > std::abs(gap->dot(long_edge));
    }
  // Cuts run along the bricks: the across coordinate is measured at right
  // angles to them on the plane, not along the quad's other edges, which
  // follow the image border when the rows are clipped.
  Eigen::Vector3d along, toward_far_edge;
  if (use_short_edges)
  {
    along = c[2] - c[1];
    toward_far_edge = c[1] - c[0];
    across_m = lineSeparation(c[1], c[2], c[3], c[0]);
  }
  else if (along_long_edges)
  {
    along = c[1] - c[0];
    toward_far_edge = c[3] - c[0];
    across_m = lineSeparation(c[0], c[1], c[3], c[2]);
  }
  else
    return {};
  Eigen::Vector3d across_direction = measured.plane.normal.cross(along).normalized();
  if (across_direction.dot(toward_far_edge) < 0.0) across_direction = -across_direction;
  const int parts = sideBySideCount(across_m, type.width_m);
  if (parts < 2 || across_m > parts * type.width_m + (parts - 1) * kMaxGapM + tolerance_m) return {};
  coordinate.across = across_direction / across_m;

  const std::vector<double> cuts = cutFractions(segment, measured, frame.camera, coordinate, parts);
  const cv::Rect& box = segment.bounding_box_px;
  std::vector<cv::Mat> part_masks(static_cast<std::size_t>(parts));
  for (cv::Mat& mask : part_masks) mask = cv::Mat::zeros(box.size(), CV_8UC1);
  for (int y = 0; y < box.height; ++y)
  {
    const std::uint8_t* mask_row = segment.mask.ptr<std::uint8_t>(y);
    for (int x = 0; x < box.width; ++x)
    {
      if (!mask_row[x]) continue;
      Eigen::Vector3d point;
      if (!measured.plane.intersectRay(frame.camera.ray(x + box.x, y + box.y), point)) continue;
      const double fraction = coordinate(point);
      const auto index = static_cast<std::size_t>(std::upper_bound(cuts.begin(), cuts.end(), fraction) - cuts.begin());
      part_masks[index].at<std::uint8_t>(y, x) = 255;
    }
  }
  std::vector<Segment> split;
  split.reserve(part_masks.size());  // a growing vector would copy the segments
  for (const cv::Mat& mask : part_masks)
    split.push_back(croppedSegmentFromMask(mask, box, frame.depth_m, segment.type_name));
  return split;
}
std::vector<Segment> splitAtDepthSteps(const RgbdFrame& frame, const Segment& segment, double max_step_m,
                                       int min_area_px)
{
  const cv::Rect& box = segment.bounding_box_px;
  const cv::Mat depth = frame.depth_m(box);
  const float max_step = static_cast<float>(max_step_m);
  // Mask pixels with depth, joined to their 4-neighbours within max_step.
  // Two raster passes with a union-find (the flood fill it replaces cost a
  // stack push and four bounds-checked look-ups per pixel): each pixel
  // joins its left and upper neighbours, then the components are numbered
  // in the order of their first pixel, as the fill numbered them.
  cv::Mat labels(box.size(), CV_32SC1, cv::Scalar(0));
  std::vector<int> parent(1, 0);  // provisional labels from 1
  auto joined = [max_step](float a, float b) { return !std::isnan(b) && std::abs(b - a) <= max_step; };
  for (int y = 0; y < box.height; ++y)
  {
    const std::uint8_t* mask_row = segment.mask.ptr<std::uint8_t>(y);
    const float* depth_row = depth.ptr<float>(y);
    const float* depth_up = y > 0 ? depth.ptr<float>(y - 1) : nullptr;
    int* label_row = labels.ptr<int>(y);
    const int* label_up = y > 0 ? labels.ptr<int>(y - 1) : nullptr;
    for (int x = 0; x < box.width; ++x)
    {
      const float z = depth_row[x];
      if (!mask_row[x] || std::isnan(z)) continue;
      const int left = x > 0 && label_row[x - 1] && joined(z, depth_row[x - 1]) ? label_row[x - 1] : 0;
      const int up = label_up && label_up[x] && joined(z, depth_up[x]) ? label_up[x] : 0;
      if (!left && !up)
      {
        label_row[x] = static_cast<int>(parent.size());
        parent.push_back(label_row[x]);
        continue;
      }
      label_row[x] = left ? left : up;
      if (left && up)
      {
        const int a = findRoot(parent, left), b = findRoot(parent, up);
        parent[std::max(a, b)] = std::min(a, b);
      }
    }
  }
  // Final labels in the order of each component's first pixel.
  std::vector<int> final_label(parent.size(), 0);
  std::vector<int> areas(1, 0);
  struct Extent
  {
    int x0, y0, x1, y1;  // inclusive, in the box
  };
  std::vector<Extent> extents(1);  // of each label
  for (int y = 0; y < box.height; ++y)
  {
    int* label_row = labels.ptr<int>(y);
    for (int x = 0; x < box.width; ++x)
    {
      if (!label_row[x]) continue;
      int& label = final_label[findRoot(parent, label_row[x])];
      if (!label)
      {
        label = static_cast<int>(areas.size());
        areas.push_back(0);
        extents.push_back({x, y, x, y});
      }
      label_row[x] = label;
      ++areas[label];
      Extent& extent = extents[label];
      extent.x0 = std::min(extent.x0, x);
      extent.x1 = std::max(extent.x1, x);
      extent.y1 = y;
    }
  }

  std::vector<int> kept;
  for (int label = 1; label < static_cast<int>(areas.size()); ++label)
    if (areas[label] >= min_area_px) kept.push_back(label);
  if (kept.size() < 2) return {};
  std::sort(kept.begin(), kept.end(), [&](int a, int b) { return areas[a] > areas[b]; });

  // Each part boxed tightly (scanning only its own box): the plates of a
  // pile are small parts of the segment that joined them. Labelled pixels
  // all have depth, so the part's area and indices are its label's.
  std::vector<Segment> parts;
  parts.reserve(kept.size());  // a growing vector would copy the segments
  for (const int label : kept)
  {
    const Extent& extent = extents[label];
    const cv::Rect own(extent.x0, extent.y0, extent.x1 - extent.x0 + 1, extent.y1 - extent.y0 + 1);
    parts.push_back(segmentFromMask(labels(own) == label, own + box.tl(), frame.depth_m, segment.type_name));
  }
  return parts;
}
}  // namespace brick_pose
