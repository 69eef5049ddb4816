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

/// The strongest dip in robust standard deviations of all dips (with a
/// floor of a quarter of `smallest_seam` for noise-free input), counting
/// only dips of at least `min_dip`; and how many dips were read.
double strongestDip(const std::vector<double>& bin_dips, double smallest_seam, double min_dip, int& read)
{
  std::vector<double> values;
  for (const double dip : bin_dips)
    if (!std::isnan(dip)) values.push_back(dip);
  read = static_cast<int>(values.size());
  if (values.size() < 3) return 0.0;
  const RobustSpread spread = robustSpread(values);
  const double centre = spread.centre;
  const double sigma = std::max(0.25 * smallest_seam, spread.sigma);
  double strongest = 0.0;
  for (const double dip : values)
    if (dip >= min_dip) strongest = std::max(strongest, (dip - centre) / sigma);
  return strongest;
}
}  // namespace

SeamProbe probeSeamsAcross(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& face,
                           double smallest_line_contrast, double smallest_groove_m, const SeamProbeParams& params)
{
  SeamProbe probe;
  const Eigen::Vector3d& origin_m = face.corners_m[0];
  const Eigen::Vector3d along = face.corners_m[1] - face.corners_m[0];
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
  const double dark = strongestDip(dips(grey_means, params.arm_px), smallest_line_contrast, min_line, dark_read);
  const double bright = strongestDip(dips(inverted, params.arm_px), smallest_line_contrast, min_line, bright_read);
  const double groove = strongestDip(dips(offset_means, params.arm_px), smallest_groove_m, min_groove, groove_read);
  probe.bins = dark_read;
  probe.strongest = std::max({dark, bright, groove});
  probe.seam_possible = probe.bins < min_bins || probe.strongest >= params.min_strength;
  return probe;
}
}  // namespace brick_pose
