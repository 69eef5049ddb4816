#include "brick_pose/roi/seam_probe.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "brick_pose/common/statistics.h"
#include "brick_pose/roi/colour_uniformity.h"

namespace brick_pose
{
namespace
{
/// Sums of one quantity per bin.
struct BinSums
{
  std::vector<double> sum;
  std::vector<int> count;

  explicit BinSums(int bins) : sum(static_cast<std::size_t>(bins), 0.0), count(static_cast<std::size_t>(bins), 0) {}
  void add(int bin, double value)
  {
    sum[static_cast<std::size_t>(bin)] += value;
    ++count[static_cast<std::size_t>(bin)];
  }
  /// The bin means, NaN where a bin has fewer than `min_count` values.
  std::vector<double> means(int min_count) const
  {
    std::vector<double> result(sum.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t b = 0; b < sum.size(); ++b)
      if (count[b] >= std::max(1, min_count)) result[b] = sum[b] / count[b];
    return result;
  }
};

/// Each bin's dip: the lower of the bins `arm` to either side less the
/// lowest within a bin of it (the seam may fall between two bins); NaN where
/// a bin it needs has no mean.
std::vector<double> dips(const std::vector<double>& means, int arm)
{
  const int bins = static_cast<int>(means.size());
  std::vector<double> result(means.size(), std::numeric_limits<double>::quiet_NaN());
  for (int b = arm; b + arm < bins; ++b)
  {
    const std::array<double, 5> read{{means[b - arm], means[b - 1], means[b], means[b + 1], means[b + arm]}};
    if (std::any_of(read.begin(), read.end(), [](double mean) { return std::isnan(mean); })) continue;
    const double low = std::min({read[1], read[2], read[3]});
    result[static_cast<std::size_t>(b)] = std::min(read[0], read[4]) - low;
  }
  return result;
}

/// Each bin's dip in robust standard deviations of all dips (with a floor
/// of a quarter of `smallest_seam` for noise-free input), NaN where unread
/// or below `min_dip`; and how many dips were read.
std::vector<double> dipStrengths(const std::vector<double>& bin_dips, double smallest_seam, double min_dip, int& read)
{
  std::vector<double> values;
  for (const double dip : bin_dips)
    if (!std::isnan(dip)) values.push_back(dip);
  read = static_cast<int>(values.size());
  std::vector<double> strengths(bin_dips.size(), std::numeric_limits<double>::quiet_NaN());
  if (values.size() < 3) return strengths;
  const RobustSpread spread = robustSpread(values);
  const double sigma = std::max(0.25 * smallest_seam, spread.sigma);
  for (std::size_t b = 0; b < bin_dips.size(); ++b)
    if (bin_dips[b] >= min_dip) strengths[b] = (bin_dips[b] - spread.centre) / sigma;
  return strengths;
}
}  // namespace

SeamProbe probeSeamsAcross(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& face,
                           double smallest_line_contrast, double smallest_groove_m, const SeamProbeParams& params)
{
  SeamProbe probe;
  // Along the face's long edge, whichever pair of corners bounds it.
  const std::array<Eigen::Vector3d, 4>& corners_m = face.corners_m;
  const bool from_corner_1 = (corners_m[2] - corners_m[1]).norm() > (corners_m[1] - corners_m[0]).norm();
  const Eigen::Vector3d& origin_m = from_corner_1 ? corners_m[1] : corners_m[0];
  const Eigen::Vector3d along = from_corner_1 ? Eigen::Vector3d(corners_m[2] - corners_m[1])
                                              : Eigen::Vector3d(corners_m[1] - corners_m[0]);
  probe.end_edges = from_corner_1 ? std::array<int, 2>{{0, 2}} : std::array<int, 2>{{3, 1}};
  const double depth_m = face.plane.centroid_m.z();
  if (!(along.norm() > 1e-6) || !(depth_m > 0.0) || segment.mask.empty()) return probe;
  const Eigen::Vector3d axis = along.normalized();
  // Bins about a pixel long at the face's depth; the face's pixels reach a
  // little beyond its quad (a ragged outline).
  const double bin_m = depth_m / frame.camera.fx_px;
  const double margin_m = 0.05 * along.norm();
  const int bins = static_cast<int>(std::ceil((along.norm() + 2.0 * margin_m) / bin_m));
  // Fewer bins than four arms cannot show a dip against the strip's own
  // scatter: too short a strip to tell noise from a seam, so the tiler
  // decides (seam_possible stays true).
  const int min_bins = 4 * params.arm_px;
  if (bins < min_bins) return probe;
  BinSums grey(bins), offset(bins);
  const cv::Rect& box = segment.bounding_box_px;
  // Read in the face's own colour, as the tiler's seam evidence is.
  const FaceGrey face_grey = faceGreyOf(frame, segment.mask, box);
  // A pixel's ray r = (x, y, 1) meets the plane at (n.c / n.r) r, and its
  // depth z lies z n.r - n.c off the plane: both need only n.r and axis.r,
  // a row's term plus a column's (this loop reads every pixel of the face).
  const Eigen::Vector3d& normal = face.plane.normal;
  const double normal_dot_centroid = normal.dot(face.plane.centroid_m);
  const double origin_along_m = origin_m.dot(axis) - margin_m;
  const PinholeCamera& camera = frame.camera;
  std::vector<double> x_of_col(static_cast<std::size_t>(segment.mask.cols));
  for (int col = 0; col < segment.mask.cols; ++col) x_of_col[col] = (box.x + col - camera.cx_px) / camera.fx_px;
  for (int row = 0; row < segment.mask.rows; ++row)
  {
    const std::uint8_t* inside = segment.mask.ptr<std::uint8_t>(row);
    const int v = box.y + row;
    const double y = (v - camera.cy_px) / camera.fy_px;
    const double normal_dot_ray_row = normal.y() * y + normal.z(), axis_dot_ray_row = axis.y() * y + axis.z();
    const cv::Vec3b* rgb_row = frame.rgb.ptr<cv::Vec3b>(v) + box.x;
    const float* depth_row = frame.depth_m.ptr<float>(v) + box.x;
    for (int col = 0; col < segment.mask.cols; ++col)
    {
      if (!inside[col]) continue;
      const double x = x_of_col[col];
      const double normal_dot_ray = normal.x() * x + normal_dot_ray_row;
      if (std::abs(normal_dot_ray) < 1e-9) continue;
      const double scale = normal_dot_centroid / normal_dot_ray;
      if (!(scale > 0.0)) continue;  // the ray meets the plane behind the camera
      const int bin = static_cast<int>(std::floor((scale * (axis.x() * x + axis_dot_ray_row) - origin_along_m) / bin_m));
      if (bin < 0 || bin >= bins) continue;
      grey.add(bin, face_grey(rgb_row[col]));
      const float z = depth_row[col];
      if (!std::isnan(z)) offset.add(bin, z * normal_dot_ray - normal_dot_centroid);
    }
  }
  // Bins short of half the typical count (the face's ends, cut slantwise)
  // average too few pixels to compare.
  std::vector<double> counts(grey.count.begin(), grey.count.end());
  const int typical = static_cast<int>(upperMedianInPlace(counts));
  const std::vector<double> grey_means = grey.means(typical / 2);
  const std::vector<double> offset_means = offset.means(typical / 2);
  std::vector<double> inverted(grey_means.size());
  std::transform(grey_means.begin(), grey_means.end(), inverted.begin(), [](double g) { return -g; });
  const double min_line = params.min_share_of_smallest_seam * smallest_line_contrast;
  const double min_groove = params.min_share_of_smallest_seam * smallest_groove_m;
  int dark_read = 0, bright_read = 0, groove_read = 0;
  const std::array<std::vector<double>, 3> strengths{
      {dipStrengths(dips(grey_means, params.arm_px), smallest_line_contrast, min_line, dark_read),
       dipStrengths(dips(inverted, params.arm_px), smallest_line_contrast, min_line, bright_read),
       dipStrengths(dips(offset_means, params.arm_px), smallest_groove_m, min_groove, groove_read)}};
  probe.bins = dark_read;
  probe.length_m = along.norm();
  for (int b = 0; b < bins; ++b)
  {
    double strongest = 0.0;  // NaN (unread) compares false
    for (const std::vector<double>& kind : strengths) strongest = std::max(strongest, kind[b]);
    probe.strongest = std::max(probe.strongest, strongest);
    if (strongest >= params.min_strength) probe.possible_seams_m.push_back((b + 0.5) * bin_m - margin_m);
  }
  probe.located = probe.bins >= min_bins;
  probe.seam_possible = !probe.located || probe.strongest >= params.min_strength;
  return probe;
}

bool seamsMayBoundABrick(const SeamProbe& probe, const std::array<bool, 2>& end_seen,
                         const std::vector<double>& lengths_m, double tolerance_m)
{
  if (!probe.located) return true;
  std::vector<double> ends_m = probe.possible_seams_m;
  if (end_seen[0]) ends_m.push_back(0.0);
  if (end_seen[1]) ends_m.push_back(probe.length_m);
  for (std::size_t i = 0; i < ends_m.size(); ++i)
    for (std::size_t j = i + 1; j < ends_m.size(); ++j)
      for (const double length_m : lengths_m)
        if (std::abs(std::abs(ends_m[i] - ends_m[j]) - length_m) <= tolerance_m) return true;
  return false;
}
}  // namespace brick_pose
