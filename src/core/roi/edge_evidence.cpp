#include "brick_pose/roi/edge_evidence.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "brick_pose/common/errors.h"
#include "brick_pose/common/rounding.h"
#include "brick_pose/common/statistics.h"
#include "brick_pose/roi/face_grey.h"

namespace brick_pose
{
namespace
{
constexpr float kMissing = std::numeric_limits<float>::quiet_NaN();
/// Where the profile has no depth beyond the edge, the first depth out to
/// this many probe widths stands in.
constexpr int kFarReachFactor = 6;

/// Depth (as signed distance from the face's plane) and grey level sampled
/// on a grid of rows (positions along the edge) x columns (offsets across
/// it, from -probe to +reach pixels; positive = outward).
struct Profile
{
  int rows = 0;
  int min_offset = 0;
  int max_offset = 0;
  /// Columns beyond this have only `in_image`: their depth is read where a
  /// judgement needs it (the far band stands in for a near band without
  /// depth, which is rare), and their grey level never is.
  int sampled_max_offset = 0;
  std::vector<float> offset_m;  ///< NaN where there is no depth
  std::vector<float> grey;      ///< NaN outside the image
  std::vector<unsigned char> in_image;

  int columns() const { return max_offset - min_offset + 1; }
  int at(int row, int offset) const { return row * columns() + (offset - min_offset); }
};

/// The line a profile is sampled across: `rows` positions evenly from
/// `from_px` to `to_px` (one in the middle when rows is 1), and whole-pixel
/// offsets along the unit vector `outward` from each.
struct ProfileLine
{
  const RgbdFrame& frame;
  const PlaneFit& plane;
  Eigen::Vector2d from_px, to_px, outward;
  int rows;

  Eigen::Vector2d onEdge(int row) const
  {
    const double t = rows == 1 ? 0.5 : static_cast<double>(row) / (rows - 1);
    return from_px + t * (to_px - from_px);
  }

  /// The pixel `offset` out from `on_edge`; false outside the image.
  bool pixel(const Eigen::Vector2d& on_edge, int offset, int& u, int& v) const
  {
    const Eigen::Vector2d p = on_edge + offset * outward;
    u = roundToInt(p.x());
    v = roundToInt(p.y());
    return u >= 0 && v >= 0 && u < frame.width_px() && v < frame.height_px();
  }

  /// Signed distance (m) of the pixel's depth from the plane; NaN without depth.
  double planeOffsetM(int u, int v) const
  {
    const float z = frame.depthAt(u, v);
    return std::isnan(z) ? std::numeric_limits<double>::quiet_NaN()
                         : plane.signedDistance(frame.camera.backProject(u, v, z));
  }
};

int profileRows(const Eigen::Vector2d& from_px, const Eigen::Vector2d& to_px, double spacing_px)
{
  return std::max(1, static_cast<int>(std::floor((to_px - from_px).norm() / spacing_px)) + 1);
}

/// Robust standard deviation; 0 for fewer than three values.
double robustSigma(std::vector<double> values)
{
  return values.size() < 3 ? 0.0 : robustSpread(std::move(values)).sigma;
}

/// The profile across `line` at offsets [min_offset, max_offset], depth and
/// grey read up to sampled_max_offset.
Profile sampleProfile(const ProfileLine& line, int min_offset, int max_offset, int sampled_max_offset)
{
  Profile profile;
  profile.rows = line.rows;
  profile.min_offset = min_offset;
  profile.max_offset = max_offset;
  profile.sampled_max_offset = sampled_max_offset;
  const std::size_t cells = static_cast<std::size_t>(profile.rows) * static_cast<std::size_t>(profile.columns());
  profile.offset_m.assign(cells, kMissing);
  profile.grey.assign(cells, kMissing);
  profile.in_image.assign(cells, 0);
  // The colours first: the grey levels are read in the colour of the
  // pixels on the face's plane (FaceGrey).
  std::vector<cv::Vec3b> colours(cells);
  FaceColourSum on_face;
  for (int row = 0; row < profile.rows; ++row)
  {
    const Eigen::Vector2d on_edge = line.onEdge(row);
    for (int offset = min_offset; offset <= max_offset; ++offset)
    {
      int u = 0, v = 0;
      if (!line.pixel(on_edge, offset, u, v)) continue;
      const int cell = profile.at(row, offset);
      profile.in_image[cell] = 1;
      if (offset > sampled_max_offset) continue;
      colours[cell] = line.frame.rgb.ptr<cv::Vec3b>(v)[u];
      profile.offset_m[cell] = static_cast<float>(line.planeOffsetM(u, v));
      if (std::abs(profile.offset_m[cell]) < kFaceColourOnPlaneM) on_face.add(colours[cell]);
    }
  }
  const FaceGrey grey = on_face.grey();
  for (int row = 0; row < profile.rows; ++row)
    for (int offset = min_offset; offset <= sampled_max_offset && offset <= max_offset; ++offset)
    {
      const int cell = profile.at(row, offset);
      if (profile.in_image[cell]) profile.grey[cell] = static_cast<float>(grey(colours[cell]));
    }
  return profile;
}

/// Median over rows of each column at offsets [first, last] (NaN at the
/// others), of depth offsets or grey levels.
std::vector<double> columnMedians(const Profile& profile, const std::vector<float>& values, int first, int last)
{
  std::vector<double> medians(static_cast<std::size_t>(profile.columns()), std::numeric_limits<double>::quiet_NaN());
  std::vector<double> column;
  for (int offset = std::max(first, profile.min_offset); offset <= std::min(last, profile.max_offset); ++offset)
  {
    column.clear();
    for (int row = 0; row < profile.rows; ++row)
    {
      const float value = values[profile.at(row, offset)];
      if (!std::isnan(value)) column.push_back(value);
    }
    if (column.size() * 2 >= static_cast<std::size_t>(profile.rows)) medians[offset - profile.min_offset] = upperMedianInPlace(column);
  }
  return medians;
}

/// Largest dip of a column-median profile at offsets [-search, search]:
/// the lower of the two sides `arm` away minus the middle (positive when the
/// middle is lower than both). NaN when the profile has gaps there.
double largestDip(const std::vector<double>& medians, int min_offset, int search, int arm)
{
  double best = std::numeric_limits<double>::quiet_NaN();
  for (int centre = -search; centre <= search; ++centre)
  {
    const int left = centre - arm - min_offset, middle = centre - min_offset, right = centre + arm - min_offset;
    if (left < 0 || right >= static_cast<int>(medians.size())) continue;
    // Both sides above the middle: a line or a groove, not a step.
    const double dip = std::min(medians[left], medians[right]) - medians[middle];
    if (std::isnan(dip)) continue;
    if (std::isnan(best) || dip > best) best = dip;
  }
  return best;
}

/// Row-wise scatter of a quantity across rows: robust sigma of the values
/// of one column inside the face (the noise a median over rows averages).
double insideScatter(const Profile& profile, const std::vector<float>& values, int inner_gap)
{
  std::vector<double> collected;
  for (int offset = profile.min_offset; offset <= -inner_gap; ++offset)
  {
    std::vector<double> column;
    for (int row = 0; row < profile.rows; ++row)
    {
      const float value = values[profile.at(row, offset)];
      if (!std::isnan(value)) column.push_back(value);
    }
    if (column.size() < 3) continue;
    const double centre = upperMedianInPlace(column);
    for (int row = 0; row < profile.rows; ++row)
    {
      const float value = values[profile.at(row, offset)];
      if (!std::isnan(value)) collected.push_back(value - centre);
    }
  }
  return robustSigma(collected);
}

struct SeamMeasure
{
  double groove_m = 0.0;
  double line_contrast = 0.0;
  double groove_se = 0.0;  // standard errors of the two over the rows
  double line_se = 0.0;
};

constexpr int kSeamArm = 3;

SeamMeasure measureSeam(const Profile& profile, const EdgeEvidenceParams& params)
{
  SeamMeasure seam;
  // Only the columns a dip may span are read.
  const int reach = params.seam_search_px + kSeamArm;
  const std::vector<double> depth = columnMedians(profile, profile.offset_m, -reach, reach);
  const std::vector<double> grey = columnMedians(profile, profile.grey, -reach, reach);
  const double groove = largestDip(depth, profile.min_offset, params.seam_search_px, kSeamArm);
  // A line darker or brighter than both sides (a shadowed gap, or a gap
  // showing a paler side face).
  std::vector<double> inverted(grey.size());
  for (std::size_t k = 0; k < grey.size(); ++k) inverted[k] = -grey[k];
  const double dark = largestDip(grey, profile.min_offset, params.seam_search_px, kSeamArm);
  const double bright = largestDip(inverted, profile.min_offset, params.seam_search_px, kSeamArm);
  const double line = std::isnan(dark) ? bright : (std::isnan(bright) ? dark : std::max(dark, bright));
  seam.groove_m = std::isnan(groove) ? 0.0 : groove;
  seam.line_contrast = std::isnan(line) ? 0.0 : line;
  // The dip mixes three column medians; the median of n samples has about
  // 1.25 sigma / sqrt(n) standard error; the dip's is ~1.2x one column's.
  const double root_rows = std::sqrt(static_cast<double>(std::max(1, profile.rows)));
  seam.groove_se = 1.5 * insideScatter(profile, profile.offset_m, 1) / root_rows;
  seam.line_se = 1.5 * insideScatter(profile, profile.grey, 1) / root_rows;
  return seam;
}

bool grooveSeen(const SeamMeasure& seam, const EdgeEvidenceParams& params)
{
  return seam.groove_m >= params.min_groove_m && seam.groove_m >= params.seam_noise_factor * seam.groove_se;
}

bool lineSeen(const SeamMeasure& seam, const EdgeEvidenceParams& params)
{
  return seam.line_contrast >= params.min_line_contrast && seam.line_contrast >= params.seam_noise_factor * seam.line_se;
}

/// Where the surface beyond the edge meets the edge line: the line fitted
/// to the column medians of the outside band, evaluated at offset 0.
double outsideInterceptM(const Profile& profile, int first_offset, int last_offset)
{
  const std::vector<double> medians = columnMedians(profile, profile.offset_m, first_offset, last_offset);
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (int offset = first_offset; offset <= last_offset; ++offset)
  {
    const double y = medians[offset - profile.min_offset];
    if (std::isnan(y)) continue;
    n += 1.0;
    sx += offset;
    sy += y;
    sxx += static_cast<double>(offset) * offset;
    sxy += offset * y;
  }
  if (n < 2.0) return std::numeric_limits<double>::infinity();
  const double slope = (n * sxy - sx * sy) / std::max(1e-12, n * sxx - sx * sx);
  return (sy - slope * sx) / n;
}

/// Beyond the profile: the plane offset (m) of the first pixel with depth
/// along a row, up to `reach_px` out (a stereo shadow beyond a step can be
/// wider than the profile at close range); NaN when there is none.
double firstDepthBeyond(const ProfileLine& line, int row, int first_offset, int reach_px)
{
  const Eigen::Vector2d on_edge = line.onEdge(row);
  for (int offset = first_offset; offset <= reach_px; ++offset)
  {
    int u = 0, v = 0;
    if (!line.pixel(on_edge, offset, u, v)) break;
    const double offset_m = line.planeOffsetM(u, v);
    if (!std::isnan(offset_m)) return offset_m;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// The profile's depth offset at a cell, read from the image for the columns
/// it did not sample (stored as the profile stores it, in float).
float profileOffsetM(const Profile& profile, const ProfileLine& line, int row, int offset)
{
  if (offset <= profile.sampled_max_offset) return profile.offset_m[profile.at(row, offset)];
  int u = 0, v = 0;
  if (!line.pixel(line.onEdge(row), offset, u, v)) return kMissing;
  return static_cast<float>(line.planeOffsetM(u, v));
}

/// Whether the surface beyond a stretch lies below the face's plane as a
/// whole although most rows alone do not clear the step: a side face seen at
/// a grazing angle on a far, noisy face (D4xx at VGA and 2 m: plane rms
/// ~6 mm, so one row needs ~2.4 cm) whose first pixels beyond the edge the
/// stereo window holds at the top's depth. The median over the stretch's
/// rows (at least kMinRowsToFallAway) has a small fraction of one row's
/// noise: half the one-row step below the face is far outside it, while a
/// plane that goes on (a seam, print, a mask's edge) stays at zero. The
/// outside must lie that far below both the plane and the inside band: a
/// band raised above the plane (a cover merged into the face) says nothing
/// about where the face ends.
constexpr int kMinRowsToFallAway = 8;
bool fallsAway(double outside_m, double inside_m, int rows_with_depth, double step_m,
               const EdgeEvidenceParams& params)
{
  return rows_with_depth >= kMinRowsToFallAway &&
         std::max(outside_m, outside_m - inside_m) < -std::max(params.min_step_m, 0.5 * step_m);
}

/// How much of the face a wall `height_m` tall standing upright on the edge
/// (perpendicular to the face) hides from the camera, measured across the
/// edge on the face's plane (m): zero or less when the camera is on the
/// face's side and sees the wall; infinite when the geometry is degenerate.
/// The camera sits at the origin; the line of sight to the edge rises by
/// (-M).n per (-M).e across it.
double hiddenByWallM(const ProfileLine& line, double height_m)
{
  constexpr double kInfinite = std::numeric_limits<double>::infinity();
  const Eigen::Vector2d middle_px = line.onEdge(line.rows / 2);
  const Eigen::Vector2d beyond_px = middle_px + line.outward.normalized();
  Eigen::Vector3d middle_m, beyond_m;
  if (!line.plane.intersectRay(line.frame.camera.ray(middle_px.x(), middle_px.y()), middle_m) ||
      !line.plane.intersectRay(line.frame.camera.ray(beyond_px.x(), beyond_px.y()), beyond_m))
    return kInfinite;
  Eigen::Vector3d outward_m = beyond_m - middle_m;
  outward_m -= outward_m.dot(line.plane.normal) * line.plane.normal;
  const double rise = -middle_m.dot(line.plane.normal);
  if (!(outward_m.norm() > 0.0) || !(std::abs(rise) > 1e-9)) return kInfinite;
  return height_m * -middle_m.dot(outward_m.normalized()) / std::abs(rise);
}

/// A stretch beside a neighbour's end may hold this share of rows neither
/// dropping nor rising: the neighbour's rounded corner, smoothed by the
/// stereo window.
constexpr double kMaxUnsortedRowFraction = 0.2;

/// A wall stands beside the face only where the band just inside the edge
/// is on the face's plane: something reaching over the face shows there
/// too (the least-area quad runs past the notch it cuts).
constexpr double kMaxInsideAboveFraction = 0.05;

/// A stretch whose rows either drop away or rise to a wall (a neighbour's
/// end falls inside it) is kDropBesideWall when the camera sees that wall
/// and nothing rises inside the edge; otherwise, or with more level or
/// unread rows than a rounded corner leaves, it is `occluded`, an
/// occlusion; one with no row dropping away, whose wall the camera sees and
/// with the face clear inside, is marked wall_beside_level (its other rows
/// level or without depth; read at an edge's ends, see occlusionAtEdgeEnds).
EdgeEvidence dropBesideWall(const ProfileLine& line, const std::vector<double>& outside_values, int below,
                            int rows, double step_m, const EdgeEvidenceParams& params, EdgeEvidence occluded)
{
  occluded.kind = EdgeKind::kOcclusion;
  std::vector<double> wall;
  for (const double value : outside_values)
    if (value > step_m) wall.push_back(value);
  const int other = rows - below - static_cast<int>(wall.size());
  if (below == 0 && !wall.empty() && occluded.inside_above_fraction <= kMaxInsideAboveFraction)
    occluded.wall_beside_level = hiddenByWallM(line, upperMedianInPlace(wall)) <= params.max_hidden_by_wall_m;
  if (below == 0 || wall.empty() || other > kMaxUnsortedRowFraction * rows ||
      occluded.inside_above_fraction > kMaxInsideAboveFraction)
    return occluded;
  const double wall_m = upperMedianInPlace(wall);
  if (!(hiddenByWallM(line, wall_m) <= params.max_hidden_by_wall_m)) return occluded;
  occluded.kind = EdgeKind::kDropBesideWall;
  occluded.lowest_wall_m = occluded.highest_wall_m = wall_m;
  return occluded;
}

/// Whether `wall_rows` of a stretch's `rows` (those with depth or none
/// beyond the edge) make a wall all along it: three quarters of them.
bool wallAllAlong(int wall_rows, int rows) { return wall_rows > 0 && wall_rows * 4 >= 3 * rows; }

/// The height of the wall a stretch stands beside, when it is a wall all
/// along only once its `rising` rows (level by the near band's median,
/// above the step by its outer half) count as wall rows, and the wall would
/// hide none of the face: the median of `wall_values` (each row's outside,
/// rising rows' read by the outer half).
std::optional<double> risingWallM(const ProfileLine& line, int above, int rising, int rows,
                                  std::vector<double> wall_values, const EdgeEvidenceParams& params)
{
  if (rising == 0 || wallAllAlong(above, rows) || !wallAllAlong(above + rising, rows)) return std::nullopt;
  const double wall_m = upperMedianInPlace(wall_values);
  if (!(hiddenByWallM(line, wall_m) <= params.max_hidden_by_wall_m)) return std::nullopt;
  return wall_m;
}

/// Judges one stretch of an edge from its profile.
EdgeEvidence judgeStretch(const Profile& profile, const ProfileLine& line, double step_m,
                          const EdgeEvidenceParams& params)
{
  EdgeEvidence evidence;
  const int first_outside = params.inner_gap_px + 1;
  int border = 0, above = 0, below = 0, coplanar = 0, missing = 0;
  // Level rows whose outer half of the near band stands above the step
  // (see risingWallM), and each row's outside read so.
  int rising = 0;
  std::vector<double> outside_values, sample_values, outer_values, wall_values;
  for (int row = 0; row < profile.rows; ++row)
  {
    int in_image = 0;
    sample_values.clear();
    outer_values.clear();
    // The near band decides; the far one only stands in where the near one
    // has no depth (a stereo shadow beyond a step).
    for (int offset = first_outside; offset <= profile.max_offset; ++offset)
    {
      const int cell = profile.at(row, offset);
      if (!profile.in_image[cell]) continue;
      ++in_image;
      const bool near_band = offset <= params.probe_px;
      if (!near_band && sample_values.size() >= 2) continue;
      const float offset_m = profileOffsetM(profile, line, row, offset);
      if (std::isnan(offset_m)) continue;
      sample_values.push_back(offset_m);
      if (near_band && 2 * offset > params.probe_px) outer_values.push_back(offset_m);
    }
    // The edge itself on (or next to) the border counts as cut too.
    if (in_image < 3 || !profile.in_image[profile.at(row, 0)])
    {
      ++border;
      continue;
    }
    if (sample_values.size() < 2)
    {
      const double beyond = firstDepthBeyond(line, row, profile.max_offset + 1, kFarReachFactor * params.probe_px);
      if (std::isnan(beyond))
      {
        ++missing;
        continue;
      }
      sample_values.assign(2, beyond);
    }
    const double outside = upperMedianInPlace(sample_values);
    outside_values.push_back(outside);
    // (The outer half's median only for level rows: the others read as
    // the band's median in every judgement.)
    double wall_reading_m = outside;
    if (std::abs(outside) <= step_m && outer_values.size() >= 2)
      if (const double outer = upperMedianInPlace(outer_values); outer > step_m)
      {
        wall_reading_m = outer;
        ++rising;
      }
    wall_values.push_back(wall_reading_m);
    if (outside > step_m) ++above;
    else if (outside < -step_m) ++below;
    else ++coplanar;
  }
  // Inside the edge the face must be on its plane.
  std::vector<double> inside_values;
  for (int row = 0; row < profile.rows; ++row)
    for (int offset = profile.min_offset; offset < -params.inner_gap_px; ++offset)
    {
      const float value = profile.offset_m[profile.at(row, offset)];
      if (!std::isnan(value)) inside_values.push_back(value);
    }
  const auto inside_above = std::count_if(inside_values.begin(), inside_values.end(),
                                          [step_m](double value) { return value > step_m; });
  evidence.inside_above_fraction =
      inside_values.empty() ? 0.0 : static_cast<double>(inside_above) / static_cast<double>(inside_values.size());
  const double inside = inside_values.empty() ? 0.0 : upperMedianInPlace(inside_values);
  const double rows = std::max(1, profile.rows);
  evidence.outside_offset_m = outside_values.empty() ? 0.0 : upperMedianInPlace(outside_values);
  const int with_depth = above + below + coplanar;
  if (border >= params.max_border_fraction * rows) evidence.kind = EdgeKind::kImageBorder;
  // Inside the edge but below the face's plane: the mask ran over the
  // face's edge onto a side face. (Above it is a cover lying across the
  // face; the outside band tells about that.)
  else if (inside < -step_m && inside > -params.max_overrun_m) evidence.kind = EdgeKind::kOverrun;
  // A wall the camera sees whose foot the stereo matching window smooths:
  // its depth rises across the near band from the edge, and the band's
  // median reads under the step in rows where its outer half stands above
  // it (pallet frame 145 at 640x480: three box_small tops beside a
  // box_large). Read so, only a wall all along the stretch that would hide
  // none of the face is taken (a step up); every other reading stays the
  // band's median's.
  else if (const std::optional<double> wall_m =
               risingWallM(line, above, rising, with_depth + missing, wall_values, params))
  {
    evidence.kind = EdgeKind::kStepUp;
    evidence.outside_offset_m = *wall_m;
    evidence.lowest_wall_m = evidence.highest_wall_m = *wall_m;
  }
  // A quarter of nearer samples is an occluder over part of the stretch;
  // nearer samples all along it, which as a wall standing upright on the
  // edge would hide almost none of the face, may be that wall: a taller
  // neighbour or something resting on the face (only its height tells).
  else if (above * 4 >= with_depth + missing && above > 0)
  {
    if (wallAllAlong(above, with_depth + missing))
    {
      evidence.kind = hiddenByWallM(line, evidence.outside_offset_m) <= params.max_hidden_by_wall_m
                          ? EdgeKind::kStepUp
                          : EdgeKind::kOcclusion;
      if (evidence.kind == EdgeKind::kStepUp)
        evidence.lowest_wall_m = evidence.highest_wall_m = evidence.outside_offset_m;
    }
    else
      evidence = dropBesideWall(line, outside_values, below, with_depth + missing, step_m, params, evidence);
  }
  else if (with_depth < params.min_depth_fraction * (rows - border)) evidence.kind = EdgeKind::kNoDepth;
  else if (below >= coplanar || fallsAway(evidence.outside_offset_m, inside, with_depth, step_m, params))
  {
    // A surface that falls away linearly from the edge itself bends (the
    // brick's own side seen obliquely); one that starts lower jumps.
    evidence.kind = std::abs(outsideInterceptM(profile, first_outside, params.probe_px)) <= step_m ? EdgeKind::kCrease
                                                                                                   : EdgeKind::kStepDown;
  }
  else
  {
    const SeamMeasure seam = measureSeam(profile, params);
    evidence.groove_m = seam.groove_m;
    evidence.line_contrast = seam.line_contrast;
    evidence.kind = grooveSeen(seam, params) ? EdgeKind::kSeam
                    : lineSeen(seam, params) ? EdgeKind::kColourLine
                                             : EdgeKind::kMaskEdge;
  }
  return evidence;
}

/// Rank of a kind when stretches disagree: the edge is as good as its worst stretch.
int badness(EdgeKind kind)
{
  switch (kind)
  {
    case EdgeKind::kImageBorder: return 8;
    case EdgeKind::kOcclusion: return 7;
    case EdgeKind::kNoDepth: return 6;
    case EdgeKind::kOverrun: return 6;
    case EdgeKind::kMaskEdge: return 5;
    case EdgeKind::kUnknown: return 4;
    case EdgeKind::kStepUp: return 4;
    case EdgeKind::kDropBesideWall: return 4;
    case EdgeKind::kColourLine: return 3;
    case EdgeKind::kSizePlacedLine: return 3;
    case EdgeKind::kSeam: return 2;
    case EdgeKind::kCrease: return 1;
    case EdgeKind::kStepDown:
    default: return 0;
  }
}
}  // namespace

bool isRealEdge(EdgeKind kind, bool uniform_colour)
{
  return kind == EdgeKind::kStepDown || kind == EdgeKind::kCrease || kind == EdgeKind::kSeam ||
         kind == EdgeKind::kStepUp || kind == EdgeKind::kDropBesideWall || kind == EdgeKind::kSizePlacedLine ||
         (uniform_colour && kind == EdgeKind::kColourLine);
}

std::string toString(EdgeKind kind)
{
  switch (kind)
  {
    case EdgeKind::kStepDown: return "step down";
    case EdgeKind::kCrease: return "crease";
    case EdgeKind::kSeam: return "seam";
    case EdgeKind::kColourLine: return "colour line";
    case EdgeKind::kSizePlacedLine: return "line placed by the catalogue's sizes";
    case EdgeKind::kOcclusion: return "occlusion boundary";
    case EdgeKind::kStepUp: return "step up to a wall standing on the edge";
    case EdgeKind::kDropBesideWall: return "drop beside a neighbour's wall";
    case EdgeKind::kImageBorder: return "image border";
    case EdgeKind::kMaskEdge: return "continuing plane (no edge seen)";
    case EdgeKind::kNoDepth: return "edge without depth beyond it";
    case EdgeKind::kOverrun: return "mask running over the face's edge";
    case EdgeKind::kUnknown:
    default: return "unexamined edge";
  }
}

void EdgeEvidenceParams::validate() const
{
  const ParamCheck check("edge evidence");
  check.require(probe_px >= 4, "probe_px", "must be >= 4");
  check.require(inner_gap_px >= 0 && inner_gap_px + 2 <= probe_px, "inner_gap_px", "must be in [0, probe_px - 2]");
  check.require(stretches >= 1, "stretches", "must be >= 1");
  check.require(sample_spacing_px > 0.0, "sample_spacing_px", "must be > 0");
  check.require(end_margin_fraction >= 0.0 && end_margin_fraction < 0.5, "end_margin_fraction", "must be in [0, 0.5)");
  check.require(min_step_m > 0.0, "min_step_m", "must be > 0");
  check.require(step_noise_factor >= 0.0, "step_noise_factor", "must be >= 0");
  check.require(max_border_fraction > 0.0 && max_border_fraction <= 1.0, "max_border_fraction", "must be in (0, 1]");
  check.require(min_depth_fraction >= 0.0 && min_depth_fraction <= 1.0, "min_depth_fraction", "must be in [0, 1]");
  check.require(min_groove_m > 0.0, "min_groove_m", "must be > 0");
  check.require(min_line_contrast > 0.0, "min_line_contrast", "must be > 0");
  check.require(seam_noise_factor >= 0.0, "seam_noise_factor", "must be >= 0");
  check.require(max_overrun_m > min_step_m, "max_overrun_m", "must be > min_step_m");
  check.require(max_hidden_by_wall_m >= 0.0, "max_hidden_by_wall_m", "must be >= 0");
  check.require(max_wall_foot_shift_px >= 0, "max_wall_foot_shift_px", "must be >= 0");
  check.require(max_step_inset_px >= 0, "max_step_inset_px", "must be >= 0");
  check.require(seam_search_px >= 0 && seam_search_px + kSeamArm <= probe_px, "seam_search_px",
          "must be in [0, probe_px - 3]");
}

namespace
{
/// Fraction of an edge left out at each end: corners are rounded and mixed,
/// and the neighbouring edges' outsides lie there.
double endMargin(double length_px, const EdgeEvidenceParams& params)
{
  return std::min(0.25, std::max(params.end_margin_fraction, params.probe_px / length_px));
}

/// The stretches an edge from `a_px` to `b_px` is judged in, each on its
/// own: its ends left out (endMargin), and short edges in fewer stretches,
/// each ~20 px at least. Stretch k runs from start(k) to start(k + 1).
class EdgeStretches
{
public:
  EdgeStretches(const Eigen::Vector2d& a_px, const Eigen::Vector2d& b_px, const EdgeEvidenceParams& params)
  {
    const double length_px = (b_px - a_px).norm();
    const double margin = endMargin(length_px, params);
    start_ = a_px + margin * (b_px - a_px);
    end_ = b_px - margin * (b_px - a_px);
    count_ = std::max(1, std::min(params.stretches, static_cast<int>((1.0 - 2.0 * margin) * length_px / 20.0)));
  }

  int count() const { return count_; }
  Eigen::Vector2d start(int k) const { return start_ + (static_cast<double>(k) / count_) * (end_ - start_); }

private:
  Eigen::Vector2d start_, end_;
  int count_ = 1;
};

/// The stretch from `from` to `to` of an edge, judged: its profile across
/// the edge, with the outward band reaching twice as far (a stereo shadow
/// beyond a step leaves the first pixels without depth).
EdgeEvidence judgeSpan(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& from,
                       const Eigen::Vector2d& to, const Eigen::Vector2d& outward, const EdgeEvidenceParams& params)
{
  const double step_m = params.stepM(plane.rms_m);
  const ProfileLine line{frame, plane, from, to, outward, profileRows(from, to, params.sample_spacing_px)};
  const Profile profile = sampleProfile(line, -params.probe_px, 2 * params.probe_px, params.probe_px);
  return judgeStretch(profile, line, step_m, params);
}

bool judgeable(double length_px, const Eigen::Vector2d& outward_px, const PlaneFit& plane)
{
  return length_px > 1.0 && outward_px.norm() > 0.0 && plane.valid;
}
}  // namespace

EdgeEvidence classifyEdge(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                          const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px,
                          const EdgeEvidenceParams& params)
{
  EdgeEvidence worst;
  const double length_px = (b_px - a_px).norm();
  if (!judgeable(length_px, outward_px, plane)) return worst;
  const Eigen::Vector2d outward = outward_px.normalized();
  const EdgeStretches spans(a_px, b_px, params);
  const int stretches = spans.count();
  double lowest_wall_m = std::numeric_limits<double>::infinity(), highest_wall_m = -lowest_wall_m;
  // (Clear walls: nothing reaches over the face inside them.)
  int walls = 0, clear_walls = 0, drops = 0, drops_beside_walls = 0;
  for (int k = 0; k < stretches; ++k)
  {
    const EdgeEvidence stretch = judgeSpan(frame, plane, spans.start(k), spans.start(k + 1), outward, params);
    if (k == 0 || badness(stretch.kind) > badness(worst.kind)) worst = stretch;
    walls += stretch.kind == EdgeKind::kStepUp ? 1 : 0;
    const bool clear = stretch.inside_above_fraction <= kMaxInsideAboveFraction;
    clear_walls += stretch.kind == EdgeKind::kStepUp && clear ? 1 : 0;
    drops_beside_walls += stretch.kind == EdgeKind::kDropBesideWall ? 1 : 0;
    drops += stretch.kind == EdgeKind::kStepDown || stretch.kind == EdgeKind::kCrease ? 1 : 0;
    if (std::isnan(stretch.lowest_wall_m)) continue;
    lowest_wall_m = std::min(lowest_wall_m, stretch.lowest_wall_m);
    highest_wall_m = std::max(highest_wall_m, stretch.highest_wall_m);
  }
  // A wall standing beside the face is one neighbour's, level with it: the
  // same height all along the edge. A wall over part of the edge only, or
  // one whose height changes along it (a tilted brick lying across the
  // face's end), may be something lying over the face, which goes on
  // beneath it: unless the surface drops away along the rest of the same
  // line. The face ends there, and a box resting on it would stand inside
  // that line, not beyond it.
  const bool walls_and_drops_only = clear_walls + drops + drops_beside_walls == stretches;
  if (walls_and_drops_only && clear_walls + drops_beside_walls > 0 && drops + drops_beside_walls > 0)
    worst.kind = EdgeKind::kDropBesideWall;
  else if (worst.kind == EdgeKind::kDropBesideWall ||
           (worst.kind == EdgeKind::kStepUp &&
            (walls < stretches || highest_wall_m - lowest_wall_m > params.min_step_m)))
    worst.kind = EdgeKind::kOcclusion;
  // Walls all along it at several heights keep their heights: RoiFilter
  // may still end the face there, when nothing resting on it could leave
  // it the size it shows (as for a wall as high as a resting box).
  const bool several_walls = clear_walls == stretches && worst.kind == EdgeKind::kOcclusion;
  const bool walled =
      several_walls || worst.kind == EdgeKind::kStepUp || worst.kind == EdgeKind::kDropBesideWall;
  worst.lowest_wall_m = walled ? lowest_wall_m : std::numeric_limits<double>::quiet_NaN();
  worst.highest_wall_m = walled ? highest_wall_m : std::numeric_limits<double>::quiet_NaN();
  return worst;
}

bool markedAlong(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                 const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px, double min_share,
                 const EdgeEvidenceParams& params)
{
  const double length_px = (b_px - a_px).norm();
  if (!judgeable(length_px, outward_px, plane)) return true;
  const Eigen::Vector2d outward = outward_px.normalized();
  const EdgeStretches spans(a_px, b_px, params);
  const int stretches = spans.count();
  // Stops as soon as the share is settled either way.
  const double needed = min_share * stretches;
  int marked = 0, unmarked = 0;
  for (int k = 0; k < stretches && marked < needed && stretches - unmarked >= needed; ++k)
  {
    const EdgeKind kind = judgeSpan(frame, plane, spans.start(k), spans.start(k + 1), outward, params).kind;
    (kind == EdgeKind::kMaskEdge ? unmarked : marked) += 1;
  }
  return marked >= needed;
}

EdgeKind occlusionAtEdgeEnds(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                             const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px,
                             const EdgeEvidenceParams& params, double lowest_wall_m, double highest_wall_m)
{
  if (std::isnan(highest_wall_m)) highest_wall_m = lowest_wall_m;
  const double length_px = (b_px - a_px).norm();
  if (!judgeable(length_px, outward_px, plane)) return EdgeKind::kUnknown;
  const Eigen::Vector2d outward = outward_px.normalized();
  const Eigen::Vector2d end_length = endMargin(length_px, params) * (b_px - a_px);
  // (NaN, no wall of the edge's own: every wall at an end is nearer.)
  const auto oneOfTheWalls = [&](const EdgeEvidence& end) {
    return end.lowest_wall_m >= lowest_wall_m - params.min_step_m &&
           end.highest_wall_m <= highest_wall_m + params.min_step_m;
  };
  // Beside an edge kept as walls, a wall of another height at an end that
  // the camera sees (a step up is one), with the face clear just inside
  // it, is another neighbour standing beside the corner, not something
  // lying across it: a wall seen face-on hides nothing behind it, and what
  // lies across the corner shows inside the edge too. (Seen walls read as
  // the height the profile meets them at, which differs along an edge by
  // more than min_step_m.) Beside an edge that drops, such a wall still
  // counts: there it let two faces of an unorganised pile through complete
  // that were not.
  const bool walled_edge = !std::isnan(lowest_wall_m);
  const auto standsBesideTheCorner = [&](const EdgeEvidence& end) {
    return walled_edge && end.inside_above_fraction <= kMaxInsideAboveFraction;
  };
  // A wall the camera sees that ends at the corner beside a level
  // neighbour (a layer's corner, where a taller box ends and one of the
  // face's height goes on: pallet frames 142 and 147) is no nearer surface
  // over the corner either, beside any edge: none of its rows drops away,
  // and the face is clear inside it.
  const auto nearerOver = [&](const EdgeEvidence& end) {
    if (end.kind == EdgeKind::kOcclusion) return !end.wall_beside_level;
    return (end.kind == EdgeKind::kStepUp || end.kind == EdgeKind::kDropBesideWall) && !oneOfTheWalls(end) &&
           !standsBesideTheCorner(end);
  };
  if (nearerOver(judgeSpan(frame, plane, a_px, a_px + end_length, outward, params)) ||
      nearerOver(judgeSpan(frame, plane, b_px - end_length, b_px, outward, params)))
    return EdgeKind::kOcclusion;
  return EdgeKind::kUnknown;
}

namespace
{
/// The edge from `a_px` to `b_px` between its end margins, to be probed
/// `reach` pixels across (none when reach is 0 or the edge cannot be read).
std::optional<ProfileLine> lineClearOfCorners(const RgbdFrame& frame, const PlaneFit& plane,
                                              const Eigen::Vector2d& a_px, const Eigen::Vector2d& b_px,
                                              const Eigen::Vector2d& outward_px, int reach,
                                              const EdgeEvidenceParams& params)
{
  const double length_px = (b_px - a_px).norm();
  if (reach <= 0 || !judgeable(length_px, outward_px, plane)) return std::nullopt;
  const double margin = endMargin(length_px, params);
  const Eigen::Vector2d from = a_px + margin * (b_px - a_px), to = b_px - margin * (b_px - a_px);
  return ProfileLine{frame, plane, from, to, outward_px.normalized(), profileRows(from, to, params.sample_spacing_px)};
}

/// The grey level and scatter of `profile`'s samples from offset `first`
/// to `last`; none from fewer than three.
std::optional<RobustSpread> greyLevel(const Profile& profile, int first, int last)
{
  std::vector<double> values;
  for (int row = 0; row < profile.rows; ++row)
    for (int offset = first; offset <= last; ++offset)
      if (const float grey = profile.grey[profile.at(row, offset)]; !std::isnan(grey)) values.push_back(grey);
  if (values.size() < 3) return std::nullopt;
  return robustSpread(values);
}

/// How far a median along the edge, over `profile`'s rows, lies off the
/// level of samples scattered by `sigma`: about 1.25 sigma / sqrt(rows).
double alongEdgeMedianError(double sigma, const Profile& profile) { return 1.25 * sigma / std::sqrt(profile.rows); }
}  // namespace

double wallFootShiftPx(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                       const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px,
                       const EdgeEvidenceParams& params)
{
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  const int reach = params.max_wall_foot_shift_px;
  const std::optional<ProfileLine> found = lineClearOfCorners(frame, plane, a_px, b_px, outward_px, reach, params);
  if (!found) return kNone;
  const ProfileLine& line = *found;
  const Profile profile = sampleProfile(line, -params.probe_px, reach, reach);
  // The face's level and noise, clear of the edge's own pixels.
  const std::optional<RobustSpread> inside = greyLevel(profile, profile.min_offset, -params.inner_gap_px - 1);
  if (!inside) return kNone;
  const RobustSpread& face = *inside;
  const double contrast =
      std::max(params.min_line_contrast, params.seam_noise_factor * alongEdgeMedianError(face.sigma, profile));
  // How far each offset's median (along the edge) lies off the face.
  const std::vector<double> medians = columnMedians(profile, profile.grey, 0, reach);
  std::vector<double> departure(static_cast<std::size_t>(reach) + 1);
  for (int offset = 0; offset <= reach; ++offset)
  {
    const double median = medians[static_cast<std::size_t>(offset - profile.min_offset)];
    if (std::isnan(median)) return kNone;  // fewer than half the rows in the image
    departure[static_cast<std::size_t>(offset)] = median - face.centre;
  }
  const auto first = std::find_if(departure.begin(), departure.end(),
                                  [contrast](double value) { return std::abs(value) > contrast; });
  if (first == departure.end()) return kNone;
  // The edge is where the first feature beyond it (a rim, the wall, a
  // seam) reaches half its peak: half a pixel inside a sharp one.
  const double sign = *first > 0.0 ? 1.0 : -1.0;
  auto peak = first;
  while (peak + 1 != departure.end() && sign * *(peak + 1) > sign * *peak) ++peak;
  const double half = 0.5 * sign * *peak;
  const auto crossing = std::find_if(departure.begin(), peak + 1, [&](double value) { return sign * value >= half; });
  if (crossing == departure.begin()) return 0.0;
  const double before = sign * *(crossing - 1), at = sign * *crossing;
  const double offset = static_cast<double>(crossing - departure.begin());
  return std::max(0.0, offset - 1.0 + (half - before) / std::max(1e-9, at - before));
}

double stepEdgeInsetPx(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                       const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px,
                       const EdgeEvidenceParams& params)
{
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  const int reach = params.max_step_inset_px;
  const std::optional<ProfileLine> found = lineClearOfCorners(frame, plane, a_px, b_px, outward_px, reach, params);
  if (!found) return kNone;
  const ProfileLine& line = *found;
  // The face clear of any rim the matcher added, and the surface beyond
  // the depth edge, past its mixed pixels.
  const int inside_last = -reach - 1, inside_first = inside_last - params.probe_px;
  const int beyond_first = 2, beyond_last = beyond_first + params.probe_px;
  const Profile profile = sampleProfile(line, inside_first, beyond_last, beyond_last);
  const std::optional<RobustSpread> face = greyLevel(profile, inside_first, inside_last);
  const std::optional<RobustSpread> beyond = greyLevel(profile, beyond_first, beyond_last);
  if (!face || !beyond) return kNone;
  const double noise = alongEdgeMedianError(std::max(face->sigma, beyond->sigma), profile);
  const double step = beyond->centre - face->centre;
  if (std::abs(step) < std::max(params.min_line_contrast, params.seam_noise_factor * noise)) return kNone;
  const std::vector<double> medians = columnMedians(profile, profile.grey, -reach, beyond_first);
  const double sign = step > 0.0 ? 1.0 : -1.0;
  double before = 0.0;
  for (int offset = -reach; offset <= beyond_first; ++offset)
  {
    const double median = medians[static_cast<std::size_t>(offset - profile.min_offset)];
    if (std::isnan(median)) return kNone;  // fewer than half the rows in the image
    const double passed = sign * (median - face->centre) / std::abs(step);
    if (passed >= 0.5)
    {
      // Half-way between the last face pixel and the first beyond it; the
      // depth edge runs through the last pixel with the face's depth.
      // Already passed at the deepest offset read: something else (a line
      // of print) lies there, or the change is deeper than reach.
      if (offset == -reach) return kNone;
      const double crossing = offset - 1.0 + (0.5 - before) / std::max(1e-9, passed - before);
      return std::max(0.0, 0.5 - crossing);
    }
    before = passed;
  }
  return kNone;
}

SeamScore scoreSeam(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                    const Eigen::Vector2d& b_px, const EdgeEvidenceParams& params)
{
  SeamScore score;
  const Eigen::Vector2d along = b_px - a_px;
  if (!(along.norm() > 1.0) || !plane.valid) return score;
  const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()).normalized();
  const ProfileLine line{frame, plane, a_px, b_px, across, profileRows(a_px, b_px, params.sample_spacing_px)};
  const Profile profile = sampleProfile(line, -params.probe_px, params.probe_px, params.probe_px);
  const SeamMeasure seam = measureSeam(profile, params);
  score.groove_m = seam.groove_m;
  score.line_contrast = seam.line_contrast;
  score.samples = profile.rows;
  const double groove_strength = seam.groove_m / std::max(seam.groove_se, 0.25 * params.min_groove_m);
  // The floors keep noise-free input finite. A line's is a tenth of the
  // smallest line: at a quarter (1.5 grey levels) every clean face's line
  // needed 9 levels to reach 6 standard errors, and a seam in low light is
  // 7-8 levels at 0.3-0.9 levels of error.
  const double line_strength = seam.line_contrast / std::max(seam.line_se, 0.1 * params.min_line_contrast);
  score.strength = std::max(groove_strength, line_strength);
  score.groove_seen = grooveSeen(seam, params);
  score.line_seen = lineSeen(seam, params);
  score.seen = score.groove_seen || score.line_seen;
  return score;
}
}  // namespace brick_pose
