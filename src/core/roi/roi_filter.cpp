#include "brick_pose/roi/roi_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/organized_cloud.h"
#include "brick_pose/roi/plate_splitter.h"

namespace brick_pose
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

std::string describe(const std::string& what, double value, const std::string& rule, double limit)
{
  std::ostringstream text;
  text.precision(3);
  text << what << " " << value << " " << rule << " " << limit;
  return text.str();
}

template <typename T>
std::array<T, 4> rotated(const std::array<T, 4>& values, int start)
{
  std::array<T, 4> out;
  for (int k = 0; k < 4; ++k) out[k] = values[(start + k) % 4];
  return out;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr planeInliers(const pcl::PointCloud<pcl::PointXYZ>& cloud, const PlaneFit& plane,
                                                 const PlaneFitParams& params)
{
  const double max_distance_m = std::max(params.min_inlier_distance_m, params.mad_factor * plane.rms_m);
  pcl::PointCloud<pcl::PointXYZ>::Ptr inliers(new pcl::PointCloud<pcl::PointXYZ>);
  inliers->reserve(cloud.size());
  for (const auto& point : cloud)
    if (std::abs(plane.signedDistance(Eigen::Vector3d(point.x, point.y, point.z))) <= max_distance_m)
      inliers->push_back(point);
  inliers->header = cloud.header;
  return inliers;
}

/// Mean distance between the long edges 0->1 and 3->2 (from the middle of
/// each to the line of the other). Equal to the short edges of a rectangle,
/// and still the plate's width when an occluder or the image border cuts the
/// face slantwise and the quad's short sides follow that cut.
double longEdgeSeparation(const std::array<Eigen::Vector3d, 4>& c)
{
  auto distanceToLine = [](const Eigen::Vector3d& point, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return (point - a).cross((b - a).normalized()).norm();
  };
  return 0.5 * (distanceToLine(0.5 * (c[0] + c[1]), c[3], c[2]) + distanceToLine(0.5 * (c[3] + c[2]), c[0], c[1]));
}

/// For each quad edge, whether the image border or a closer surface lies
/// just outside most of it (see BrickCandidate::edge_truncated).
std::array<bool, 4> truncatedEdges(const RgbdFrame& frame, const BrickCandidate& candidate, const RoiFilterParams& params)
{
  constexpr int kSamples = 16;
  std::array<bool, 4> truncated{{false, false, false, false}};
  for (int k = 0; k < 4; ++k)
  {
    const Eigen::Vector2d& a = candidate.corners_px[k];
    const Eigen::Vector2d& b = candidate.corners_px[(k + 1) % 4];
    Eigen::Vector2d outward(b.y() - a.y(), a.x() - b.x());
    outward.normalize();
    if (outward.dot(0.5 * (a + b) - candidate.centroid_px) < 0.0) outward = -outward;
    int cut = 0;
    for (int i = 0; i < kSamples; ++i)
    {
      const double t = 0.1 + 0.8 * i / (kSamples - 1);
      const Eigen::Vector2d probe = a + t * (b - a) + params.edge_probe_offset_px * outward;
      const int u = static_cast<int>(std::lround(probe.x())), v = static_cast<int>(std::lround(probe.y()));
      if (u < 0 || v < 0 || u >= frame.width_px() || v >= frame.height_px())
      {
        ++cut;
        continue;
      }
      const float z = frame.depthAt(u, v);
      Eigen::Vector3d on_plane;
      if (std::isnan(z) || !candidate.plane.intersectRay(frame.camera.ray(u, v), on_plane)) continue;
      if (z < on_plane.z() - params.occluder_margin_m) ++cut;
    }
    truncated[k] = cut * 10 >= kSamples * 3;
  }
  return truncated;
}

/// Every k-th index so that about `max_count` remain (all when max_count is 0).
std::vector<int> thinned(const std::vector<int>& indices, int max_count)
{
  if (max_count <= 0 || static_cast<int>(indices.size()) <= max_count) return indices;
  const std::size_t step = (indices.size() + max_count - 1) / static_cast<std::size_t>(max_count);
  std::vector<int> kept;
  kept.reserve(indices.size() / step + 1);
  for (std::size_t i = 0; i < indices.size(); i += step) kept.push_back(indices[i]);
  return kept;
}

bool anyTruncated(const BrickCandidate& candidate)
{
  return std::any_of(candidate.edge_truncated.begin(), candidate.edge_truncated.end(), [](bool cut) { return cut; });
}

/// Index (0 or 1) of the corner starting the first long edge of a
/// clockwise quad, then moved to the upper of the two long edges.
int longEdgeStart(const QuadCorners& corners_px, const std::array<Eigen::Vector3d, 4>& corners_m)
{
  auto edge = [&](int k) { return (corners_m[(k + 1) % 4] - corners_m[k]).norm(); };
  const int start = edge(0) + edge(2) >= edge(1) + edge(3) ? 0 : 1;
  const Eigen::Vector2d& a = corners_px[start];
  const Eigen::Vector2d& b = corners_px[start + 2];
  const bool a_first = a.y() < b.y() - 1e-9 || (std::abs(a.y() - b.y()) <= 1e-9 && a.x() <= b.x());
  return a_first ? start : start + 2;
}
}  // namespace

Eigen::Vector3d faceCentre(const std::array<Eigen::Vector3d, 4>& corners_m)
{
  return 0.25 * (corners_m[0] + corners_m[1] + corners_m[2] + corners_m[3]);
}

void RoiFilterParams::validate() const
{
  auto require = [](bool condition, const char* field, const char* rule) {
    if (!condition) throw ConfigError(std::string("roi filter: ") + field + " " + rule);
  };
  require(min_points >= 3, "min_points", "must be >= 3");
  require(max_points >= 0, "max_points", "must be >= 0 (0 keeps every pixel)");
  require(max_plane_rms_m > 0.0, "max_plane_rms_m", "must be > 0");
  require(max_depth_step_m > 0.0, "max_depth_step_m", "must be > 0");
  require(min_part_area_px >= 1, "min_part_area_px", "must be >= 1");
  require(dimensions.tolerance_m >= 0.0, "dimensions.tolerance_m", "must be >= 0");
  require(dimensions.max_thickness_m >= 0.0, "dimensions.max_thickness_m", "must be >= 0");
  require(dimensions.min_visible_fraction > 0.0 && dimensions.min_visible_fraction <= 1.0,
          "dimensions.min_visible_fraction", "must be in (0, 1]");
  require(classification_tolerance_m >= 0.0, "classification_tolerance_m", "must be >= 0");
  require(min_fill_ratio >= 0.0 && min_fill_ratio <= 1.0, "min_fill_ratio", "must be in [0, 1]");
  require(std::isfinite(up_direction.norm()), "up_direction", "must be finite");
  require(max_tilt_deg > 0.0 && max_tilt_deg <= 90.0, "max_tilt_deg", "must be in (0, 90]");
  require(edge_probe_offset_px > 0.0, "edge_probe_offset_px", "must be > 0");
  require(occluder_margin_m > 0.0, "occluder_margin_m", "must be > 0");
  require(quad.side_band_px > 0.0, "quad.side_band_px", "must be > 0");
  require(quad.side_search_px >= 0.0, "quad.side_search_px", "must be >= 0");
  require(quad.edge_quantile >= 0.0 && quad.edge_quantile <= 1.0, "quad.edge_quantile", "must be in [0, 1]");
  require(quad.min_side_points >= 2, "quad.min_side_points", "must be >= 2");
}

RoiFilter::RoiFilter(const BrickCatalogue& catalogue, const RoiFilterParams& params,
                     const CloudProcessorParams& cloud_params)
  : catalogue_(catalogue), params_(params), cloud_processor_(cloud_params)
{
  params_.validate();
}

RoiResult RoiFilter::filter(const RgbdFrame& frame, const Segment& segment, CloudProcessingTimings* cloud_timings) const
{
  BrickCandidate candidate;
  if (auto reason = measure(frame, segment, cloud_timings, candidate)) return *reason;
  if (auto reason = assignType(segment, candidate)) return *reason;
  return candidate;
}

RoiOutcome RoiFilter::filterSplitting(const RgbdFrame& frame, const Segment& segment,
                                      CloudProcessingTimings* cloud_timings) const
{
  RoiOutcome outcome;
  BrickCandidate candidate;
  std::optional<std::string> reason = measure(frame, segment, cloud_timings, candidate);
  const bool measured = !reason;
  if (!reason) reason = assignType(segment, candidate);
  if (!reason)
  {
    outcome.candidates.push_back(std::move(candidate));
    return outcome;
  }
  // A coloured segment can only hold plates of its type; a colour-free one
  // is tried against each type in turn.
  std::vector<Segment> parts;
  if (measured)
    for (const BrickType& type : catalogue_.types())
    {
      if (!segment.type_name.empty() && type.name != segment.type_name) continue;
      parts = splitSideBySide(frame, segment, candidate, type, params_.dimensions.tolerance_m);
      if (!parts.empty()) break;
    }
  // Plates at two heights joined through an edge without a clean depth jump
  // give one bent "plane": split where the depth steps.
  if (parts.empty() && !measured && candidate.plane.valid && candidate.plane.rms_m > params_.max_plane_rms_m)
    parts = splitAtDepthSteps(frame, segment, params_.max_depth_step_m, params_.min_part_area_px);
  if (parts.empty())
  {
    outcome.rejections.push_back(*reason);
    return outcome;
  }
  for (const Segment& part : parts)
  {
    RoiResult result = filter(frame, part, cloud_timings);
    if (auto* part_candidate = std::get_if<BrickCandidate>(&result))
      outcome.candidates.push_back(std::move(*part_candidate));
    else
      outcome.rejections.push_back("part of a split segment: " + std::get<std::string>(result));
  }
  return outcome;
}

std::optional<std::string> RoiFilter::measure(const RgbdFrame& frame, const Segment& segment,
                                              CloudProcessingTimings* cloud_timings, BrickCandidate& candidate) const
{
  if (static_cast<int>(segment.pixel_indices.size()) < params_.min_points)
    return describe("only", static_cast<double>(segment.pixel_indices.size()), "depth pixels, need",
                    params_.min_points);

  candidate.pixel_indices = segment.pixel_indices;
  candidate.mask = segment.mask;
  candidate.bounding_box_px = segment.bounding_box_px;
  candidate.area_px = segment.area_px;
  const pcl::PointCloud<pcl::PointXYZ>::Ptr raw = backProjectPixels(frame, thinned(segment.pixel_indices, params_.max_points));
  ProcessedCloud processed = cloud_processor_.process(raw);
  if (cloud_timings)
  {
    cloud_timings->crop_ms += processed.timings.crop_ms;
    cloud_timings->voxel_ms += processed.timings.voxel_ms;
    cloud_timings->outlier_removal_ms += processed.timings.outlier_removal_ms;
    cloud_timings->mls_ms += processed.timings.mls_ms;
  }
  candidate.points = processed.points;
  candidate.smoothed_points = processed.with_normals;
  if (static_cast<int>(candidate.points->size()) < 3) return std::string("no points left after cloud processing");

  candidate.plane = fitPlane(*candidate.points, params_.plane);
  if (!candidate.plane.valid) return std::string("points are collinear: no plane");
  if (candidate.plane.rms_m > params_.max_plane_rms_m)
    return describe("plane rms", candidate.plane.rms_m, "m exceeds", params_.max_plane_rms_m);
  candidate.normal = candidate.plane.normal;
  if (params_.up_direction.norm() > 0.0)
  {
    const double cos_tilt = candidate.normal.dot(params_.up_direction.normalized());
    const double tilt_deg = std::acos(std::max(-1.0, std::min(1.0, cos_tilt))) * 180.0 / kPi;
    if (tilt_deg > params_.max_tilt_deg) return describe("face tilt", tilt_deg, "deg exceeds", params_.max_tilt_deg);
  }

  // The box of min/max extents is only as good as its worst point: measure it
  // on the plane's inliers (stray pixels of the background that happen to lie
  // near the extended plane, or flying pixels, are dropped here).
  candidate.points = planeInliers(*candidate.points, candidate.plane, params_.plane);
  candidate.obb = computeOrientedBoundingBox(*candidate.points);
  return fitOutline(frame, segment, candidate);
}

std::optional<std::string> RoiFilter::fitOutline(const RgbdFrame& frame, const Segment& segment,
                                                 BrickCandidate& candidate) const
{
  // One blob for a segment from a single component; several for the pieces
  // of a face merged across an occluder.
  const std::vector<std::vector<cv::Point>> outlines = allOutlines(segment.mask, segment.bounding_box_px.tl());
  const std::optional<QuadCorners> quad = fitLeastAreaQuad(outlines, params_.quad);
  if (!quad) return std::string("outline has no enclosing quadrilateral");

  const PinholeCamera& camera = frame.camera;
  std::array<Eigen::Vector3d, 4> corners_m;
  for (int k = 0; k < 4; ++k)
    if (!candidate.plane.intersectRay(camera.ray((*quad)[k].x(), (*quad)[k].y()), corners_m[k]))
      return std::string("a quad corner's ray misses the segment plane");

  double outline_area_px = 0.0;
  for (const auto& outline : outlines) outline_area_px += std::abs(cv::contourArea(outline));
  candidate.fill_ratio = outline_area_px / std::max(1e-9, std::abs(signedAreaPx(*quad)));
  const int start = longEdgeStart(*quad, corners_m);
  candidate.corners_px = rotated(*quad, start);
  candidate.corners_m = rotated(corners_m, start);
  const auto& c = candidate.corners_m;
  candidate.length_m = 0.5 * ((c[1] - c[0]).norm() + (c[2] - c[3]).norm());
  candidate.width_m = longEdgeSeparation(c);

  candidate.centroid_m = faceCentre(c);
  candidate.centroid_px = camera.project(candidate.centroid_m);
  const Eigen::Vector3d long_axis = ((c[1] - c[0]) + (c[2] - c[3])).normalized();
  candidate.t1_m = candidate.centroid_m + 0.25 * candidate.length_m * long_axis;
  candidate.t2_m = candidate.centroid_m - 0.25 * candidate.length_m * long_axis;
  candidate.t1_px = camera.project(candidate.t1_m);
  candidate.t2_px = camera.project(candidate.t2_m);
  candidate.edge_truncated = truncatedEdges(frame, candidate, params_);
  return std::nullopt;
}

std::optional<std::string> RoiFilter::assignType(const Segment& segment, BrickCandidate& candidate) const
{
  const DimensionTolerance& tolerance = params_.dimensions;
  // The box is measured on plane inliers, whose spread grows with depth
  // noise; only thickness beyond that spread says "not a flat face".
  const double noise_spread_m = 6.0 * candidate.plane.rms_m;
  const double thickness_m = candidate.obb.valid ? std::max(0.0, candidate.obb.extents_m.z() - noise_spread_m) : 0.0;
  auto complete = [&](const BrickType& type, double tolerance_m) {
    return std::abs(candidate.length_m - type.length_m) <= tolerance_m &&
           std::abs(candidate.width_m - type.width_m) <= tolerance_m;
  };

  if (!segment.type_name.empty())
  {
    const BrickType* type = catalogue_.find(segment.type_name);
    if (!type) return "unknown brick type '" + segment.type_name + "'";
    if (auto reason = checkTopFaceDimensions(candidate.length_m, candidate.width_m, thickness_m, *type, tolerance))
      return segment.type_name + ": " + *reason;
    candidate.type_name = type->name;
    candidate.complete = complete(*type, tolerance.tolerance_m) && !anyTruncated(candidate);
    if (!candidate.complete)
      candidate.partial_reason = anyTruncated(candidate) ? "an edge is cut by an occluder or the image border"
                                                         : "smaller than the catalogue's top face";
    return std::nullopt;
  }

  // Colour-free: only whole faces can be told apart by size (half a blue
  // brick looks like a green one).
  if (anyTruncated(candidate)) return std::string("face is cut by an occluder or the image border");
  if (candidate.fill_ratio < params_.min_fill_ratio)
    return describe("segment fills", candidate.fill_ratio, "of its quad, less than", params_.min_fill_ratio);
  if (thickness_m > tolerance.max_thickness_m)
    return describe("thickness", thickness_m, "m exceeds", tolerance.max_thickness_m);
  const BrickType* best = nullptr;
  double best_error_m = std::numeric_limits<double>::max();
  for (const BrickType& type : catalogue_.types())
  {
    const double error_m = std::abs(candidate.length_m - type.length_m) + std::abs(candidate.width_m - type.width_m);
    if (complete(type, params_.classification_tolerance_m) && error_m < best_error_m)
    {
      best = &type;
      best_error_m = error_m;
    }
  }
  if (!best)
  {
    std::ostringstream text;
    text.precision(3);
    text << "face " << candidate.length_m << " x " << candidate.width_m << " m matches no catalogue type";
    return text.str();
  }
  candidate.type_name = best->name;
  candidate.complete = true;
  return std::nullopt;
}
}  // namespace brick_pose
