#include "brick_pose/roi/face_tiling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <map>
#include <memory>
#include <set>
#include <tuple>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/parallel_for.h"
#include "brick_pose/common/rounding.h"
#include "brick_pose/common/statistics.h"
#include "brick_pose/roi/cell_counts.h"
#include "brick_pose/roi/outline_axis.h"
#include "brick_pose/roi/plane_pixel_samples.h"

namespace brick_pose
{
namespace
{
enum CellState : std::uint8_t
{
  kForeign = 0,  // in the image, not the segment
  kFree = 1,     // the segment, not yet tiled
  kTiled = 2,    // the segment, taken by a tile
  kOffImage = 3,
};

/// The quad's axes are kept within this of the outline's (see gridAxis).
constexpr double kMaxQuadOffOutlineRad = 2.0 * kDegToRad;

/// A cut is confirmed by a seam this many times the tiler's
/// min_seam_strength: the tiler's search over the lines near each nominal
/// cut finds noise of about 4 standard errors on a plain face (4.4 on a
/// colour-free green, cut into two reds); a faint 1.5 mm groove scores 7.7,
/// a dark line 24-33 (test_face_tiling).
constexpr double kConfirmedSeamFactor = 1.5;

/// The values that are numbers, or an evenly strided sample of them
/// (between max_count / 2 and max_count values): a layer's grid has 10^5
/// lines x samples, whose exact median cost more than reading them, while
/// 4096-8192 samples put the median within about 0.02 standard deviations
/// of it.
std::vector<double> evenSample(const std::vector<float>& values, std::size_t max_count)
{
  const auto numbers = static_cast<std::size_t>(
      std::count_if(values.begin(), values.end(), [](float value) { return !std::isnan(value); }));
  const std::size_t stride = std::max<std::size_t>(1, (numbers + max_count - 1) / max_count);
  std::vector<double> sample;
  sample.reserve(numbers / stride + 1);
  // Every stride-th number from the first, counted down: a division per
  // value was a measurable part of the line evidence on pallet layers.
  std::size_t until_next = 0;
  for (const float value : values)
  {
    if (std::isnan(value)) continue;
    if (until_next == 0)
    {
      sample.push_back(value);
      until_next = stride;
    }
    --until_next;
  }
  return sample;
}

/// Values in the line evidence's location and scale estimates (see evenSample).
constexpr std::size_t kMaxMedianSamples = 8192;

/// A dark line with a side brighter than this many times the face's mean
/// grey is print, not a seam: a seam runs between two faces' own colour,
/// while the bars and text of a label lie on white paper (about 1.5 times
/// kraft cardboard's grey in any light), parallel to the box's edges, and
/// their lines, averaged along a cut, passed for a seam half a box off.
/// The reference is the whole face's mean: a hard shadow over half a face
/// (darker than 0.4 of the light) would leave its lit seams unread, which
/// costs cuts (the face stays whole, partial), never a cut made.
constexpr double kPrintSideGrey = 1.3;
/// ... and at least this many grey levels above it: on a dim face (a red
/// brick in a low light, grey 26) 1.3 times is within the noise.
constexpr double kPrintSideAboveGrey = 15.0;

/// Seam dips sampled along the lines of one direction of the grid. Line `l`
/// (0..lines-1) has `length` samples; integral images over lines and
/// positions give the mean over any stretch of one line, or of a band of
/// lines, in constant time.
struct LineEvidence
{
  int lines = 0;
  int length = 0;
  // Per channel (0 depth, 1 grey): sums of the clipped dips minus the
  // typical dip over lines [0, l) and positions [0, p), and their counts.
  std::array<std::vector<double>, 2> integral_sum;
  std::array<std::vector<int>, 2> integral_count;
  std::array<double, 2> sigma{{0.0, 0.0}};

  int at(int line, int position) const { return line * (length + 1) + position; }

  /// Mean dip over lines [first, last) and samples [from, to), and its count.
  double bandMean(int channel, int first, int last, int from, int to, int& count) const
  {
    first = std::max(0, first);
    last = std::min(lines, last);
    from = std::max(0, from);
    to = std::min(length, to);
    if (last <= first || to <= from)
    {
      count = 0;
      return 0.0;
    }
    auto block = [&](const auto& integral) {
      return integral[at(last, to)] - integral[at(last, from)] - integral[at(first, to)] + integral[at(first, from)];
    };
    count = block(integral_count[channel]);
    return count > 0 ? block(integral_sum[channel]) / count : 0.0;
  }

  /// Mean dip over samples [from, to) of `line` and its count.
  double mean(int channel, int line, int from, int to, int& count) const
  {
    return bandMean(channel, line, line + 1, from, to, count);
  }

  /// The mean dip of `line` over [from, to) above that of the lines a few
  /// cells to either side over the same stretch. The lowest sample of a
  /// window dips more where the face is noisier (farther, darker, more
  /// steeply seen), so a whole region of lines can dip by more than the
  /// smallest seam; a seam dips below its own neighbours.
  double contrast(int channel, int line, int from, int to, int& count) const
  {
    const double own = mean(channel, line, from, to, count);
    if (count == 0) return 0.0;
    int before = 0, after = 0;
    const double mean_before = bandMean(channel, line - kBackgroundOuter, line - kBackgroundInner + 1, from, to, before);
    const double mean_after = bandMean(channel, line + kBackgroundInner, line + kBackgroundOuter + 1, from, to, after);
    if (before + after == 0) return own;
    return own - (mean_before * before + mean_after * after) / (before + after);
  }

  /// The neighbours a line is compared with lie this many lines away: past
  /// the seam's own band (two cells of dark line at 720p, spread by the
  /// window over up to four at VGA, flanked by lines it lifts) and close
  /// enough to share its noise. Three to eight found every brick of the
  /// rig's touching rows at 720p but cost pallet boxes at 848x480 and VGA.
  static constexpr int kBackgroundInner = 5;
  static constexpr int kBackgroundOuter = 12;
};

/// The segment rasterised on its plane. One per face and thread: its const
/// queries fill caches (pixels read, cells beyond the grid) on first use.
/// The line evidence alone may be read on several threads: it reads the
/// pixels it is given (pixelSamples(), made first) and no cache.
class PlaneGrid
{
public:
  /// The grid's s axis runs along `axis_s` (on the plane).
  PlaneGrid(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
            const Eigen::Vector3d& axis_s, double cell_m_min, int max_cells)
    : frame_(frame), plane_(measured.plane)
  {
    const auto& c = measured.corners_m;
    e1_ = axis_s.normalized();
    e2_ = plane_.normal.cross(e1_).normalized();
    if (e2_.dot(c[3] - c[0]) < 0.0) e2_ = -e2_;
    double s_min = 1e9, s_max = -1e9, t_min = 1e9, t_max = -1e9;
    for (const auto& corner : c)
    {
      s_min = std::min(s_min, (corner - c[0]).dot(e1_));
      s_max = std::max(s_max, (corner - c[0]).dot(e1_));
      t_min = std::min(t_min, (corner - c[0]).dot(e2_));
      t_max = std::max(t_max, (corner - c[0]).dot(e2_));
    }
    origin_ = c[0] + s_min * e1_ + t_min * e2_;
    const double extent_s = s_max - s_min, extent_t = t_max - t_min;
    cell_m_ = std::max(cell_m_min, std::sqrt(extent_s * extent_t / std::max(1, max_cells)));
    nx_ = std::max(1, static_cast<int>(std::ceil(extent_s / cell_m_)));
    ny_ = std::max(1, static_cast<int>(std::ceil(extent_t / cell_m_)));
    const double depth_m = std::max(0.1, plane_.centroid_m.z());
    cell_px_ = cell_m_ * frame.camera.fx_px / depth_m;
    rasterise(segment);
  }

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double cellM() const { return cell_m_; }
  double cellPx() const { return cell_px_; }
  double planeRmsM() const { return plane_.rms_m; }
  const Eigen::Vector3d& e1() const { return e1_; }
  const Eigen::Vector3d& e2() const { return e2_; }

  Eigen::Vector3d point(double i, double j) const { return origin_ + i * cell_m_ * e1_ + j * cell_m_ * e2_; }
  Eigen::Vector2d pixel(double i, double j) const { return frame_.camera.project(point(i, j)); }

  bool inGrid(int i, int j) const { return i >= 0 && j >= 0 && i < nx_ && j < ny_; }
  /// The pixel (u, v) of a cell's centre; false when it is behind the
  /// camera or off the image.
  bool cellPixel(int i, int j, int& u, int& v) const
  {
    const Eigen::Vector3d point_m = point(i + 0.5, j + 0.5);
    if (point_m.z() <= 0.05) return false;
    const Eigen::Vector2d p = frame_.camera.project(point_m);
    u = roundToInt(p.x());
    v = roundToInt(p.y());
    return u >= 0 && v >= 0 && u < frame_.width_px() && v < frame_.height_px();
  }
  std::uint8_t state(int i, int j) const { return state_[static_cast<std::size_t>(j) * nx_ + i]; }
  void setState(int i, int j, std::uint8_t value) { state_[static_cast<std::size_t>(j) * nx_ + i] = value; }
  bool free(int i, int j) const { return inGrid(i, j) && state(i, j) == kFree; }
  int freeCount() const { return static_cast<int>(std::count(state_.begin(), state_.end(), kFree)); }
  /// Every cell's state, to start another tiling from (see restore()).
  const std::vector<std::uint8_t>& states() const { return state_; }
  void restore(const std::vector<std::uint8_t>& states) { state_ = states; }
  /// The cells holding `state` over any rectangle, as the grid is now.
  CellCounts counts(std::uint8_t state) const { return CellCounts(state_, nx_, ny_, state); }

  /// Whether a cell beyond the grid could belong to a brick cut off from
  /// view: outside the image, or behind a nearer surface. Within
  /// reserveBeyond()'s reach each cell is projected once per face: the
  /// tilers ask about the same cells for every anchor, type and tiling.
  bool hiddenBeyondGrid(int i, int j) const
  {
    const int a = i + beyond_reach_, b = j + beyond_reach_;
    const int cache_nx = nx_ + 2 * beyond_reach_;
    if (a < 0 || b < 0 || a >= cache_nx || b >= ny_ + 2 * beyond_reach_) return projectHidden(i, j);
    // The reach is a whole brick's length on every side, mostly never
    // asked about: the cache is made block by block as it is read.
    auto& block = beyond_blocks_[static_cast<std::size_t>(b / kBeyondBlock) * beyond_blocks_nx_ + a / kBeyondBlock];
    if (!block)
    {
      block = std::make_unique<std::array<std::int8_t, kBeyondBlock * kBeyondBlock>>();
      block->fill(-1);
    }
    std::int8_t& known = (*block)[static_cast<std::size_t>(b % kBeyondBlock) * kBeyondBlock + a % kBeyondBlock];
    if (known < 0) known = projectHidden(i, j) ? 1 : 0;
    return known == 1;
  }

  /// Cells up to `reach_cells` beyond the grid are remembered by
  /// hiddenBeyondGrid().
  void reserveBeyond(int reach_cells)
  {
    beyond_reach_ = std::max(0, reach_cells);
    beyond_blocks_nx_ = (nx_ + 2 * beyond_reach_ + kBeyondBlock - 1) / kBeyondBlock;
    const int blocks_ny = (ny_ + 2 * beyond_reach_ + kBeyondBlock - 1) / kBeyondBlock;
    beyond_blocks_.clear();
    beyond_blocks_.resize(static_cast<std::size_t>(beyond_blocks_nx_) * blocks_ny);
  }

  /// Dips across lines of constant s (along_s = true: lines i = 0..nx,
  /// samples along t) or of constant t, read from `pixels`
  /// (pixelSamples(arm_px)).
  LineEvidence lineEvidence(const PlanePixelSamples& pixels, bool constant_s, int arm_px, double on_plane_m,
                            const std::array<double, 2>& sigma_floor) const;

  /// The pixels the line evidence with arms of `arm_px` reads: the grid's
  /// image and a margin around it, made on first use.
  const PlanePixelSamples& pixelSamples(int arm_px) const { return pixelSamplesWithin(arm_px + halfWindowPx() + 2); }

private:
  /// The lines lie a cell apart, possibly more than a pixel: the middle of a
  /// dip is the lowest sample within half a cell, so a one-pixel dark line
  /// between two lines still shows.
  int halfWindowPx() const { return std::max(0, static_cast<int>(std::ceil(0.5 * cell_px_ - 0.5))); }

  /// The grid's image and `margin_px` around it, made on first use.
  const PlanePixelSamples& pixelSamplesWithin(int margin_px) const
  {
    if (!pixel_samples_)
    {
      // A plane rectangle in front of the camera projects to a convex
      // quadrilateral; with a corner behind it, the whole image is read.
      std::vector<Eigen::Vector2d> outline_px;
      for (const auto& [i, j] : {std::pair<double, double>{0.0, 0.0}, {1.0 * nx_, 0.0}, {1.0 * nx_, 1.0 * ny_}, {0.0, 1.0 * ny_}})
      {
        const Eigen::Vector3d corner_m = point(i, j);
        if (!(corner_m.z() > 0.05))
        {
          outline_px.clear();
          break;
        }
        outline_px.push_back(frame_.camera.project(corner_m));
      }
      pixel_samples_.emplace(frame_, plane_, outline_px, margin_px);
    }
    return *pixel_samples_;
  }

  bool projectHidden(int i, int j) const
  {
    int u = 0, v = 0;
    if (!cellPixel(i, j, u, v)) return true;
    const float z = frame_.depthAt(u, v);
    return std::isnan(z) || z < point(i + 0.5, j + 0.5).z() - 0.02;
  }

  void rasterise(const Segment& segment)
  {
    state_.assign(static_cast<std::size_t>(nx_) * ny_, kForeign);
    const cv::Rect& box = segment.bounding_box_px;
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i)
      {
        int u = 0, v = 0;
        if (!cellPixel(i, j, u, v)) setState(i, j, kOffImage);
        else if (box.contains(cv::Point(u, v)) && segment.mask.at<std::uint8_t>(v - box.y, u - box.x))
          setState(i, j, kFree);
      }
  }

  const RgbdFrame& frame_;
  PlaneFit plane_;
  Eigen::Vector3d origin_, e1_, e2_;
  double cell_m_ = 0.005;
  double cell_px_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint8_t> state_;
  static constexpr int kBeyondBlock = 32;  ///< cells along a side of a block of the cache
  int beyond_reach_ = 0;
  int beyond_blocks_nx_ = 0;
  /// hiddenBeyondGrid()'s answers (-1 unknown), in blocks made on first use.
  mutable std::vector<std::unique_ptr<std::array<std::int8_t, kBeyondBlock * kBeyondBlock>>> beyond_blocks_;
  mutable std::optional<PlanePixelSamples> pixel_samples_;
};

LineEvidence PlaneGrid::lineEvidence(const PlanePixelSamples& pixels, bool constant_s, int arm_px, double on_plane_m,
                                     const std::array<double, 2>& sigma_floor) const
{
  LineEvidence evidence;
  evidence.lines = (constant_s ? nx_ : ny_) + 1;
  evidence.length = constant_s ? ny_ : nx_;
  const int width = frame_.width_px(), height = frame_.height_px();
  const int half_window = halfWindowPx();
  const double mean_grey = pixels.meanFaceGrey();
  const double print_side_grey = mean_grey > 0.0 ? std::max(kPrintSideGrey * mean_grey, mean_grey + kPrintSideAboveGrey)
                                                 : std::numeric_limits<double>::infinity();
  std::array<std::vector<float>, 2> raw;
  for (auto& channel : raw)
    channel.assign(static_cast<std::size_t>(evidence.lines) * evidence.length, std::numeric_limits<float>::quiet_NaN());
  auto sample = [&](const Eigen::Vector2d& p, double& offset_m, double& grey) {
    const int u = roundToInt(p.x()), v = roundToInt(p.y());
    if (u < 0 || v < 0 || u >= width || v >= height) return false;
    pixels.read(u, v, offset_m, grey);
    return true;
  };
  // The pixel of each sample on a line, and on the next line, whose
  // difference is the step across: each row of pixels is projected once.
  auto project_line = [&](int line, std::vector<Eigen::Vector2d>& row) {
    for (int k = 0; k < evidence.length; ++k) row[k] = constant_s ? pixel(line, k + 0.5) : pixel(k + 0.5, line);
  };
  std::vector<Eigen::Vector2d> row(evidence.length), next_row(evidence.length);
  project_line(0, next_row);
  for (int line = 0; line < evidence.lines; ++line)
  {
    row.swap(next_row);
    project_line(line + 1, next_row);
    for (int k = 0; k < evidence.length; ++k)
    {
      const Eigen::Vector2d& centre = row[k];
      const Eigen::Vector2d step = next_row[k] - centre;
      if (!(step.norm() > 1e-9)) continue;
      const Eigen::Vector2d across = step.normalized();
      double left_d, left_g, right_d, right_g;
      if (!sample(centre - arm_px * across, left_d, left_g) || !sample(centre + arm_px * across, right_d, right_g)) continue;
      // A seam lies between two faces on the plane: both sides must be on
      // it (at the segment's border one side is another surface, whose
      // slope would pass for a groove). Checked before the window is read.
      if (std::isnan(left_d) || std::isnan(right_d) || std::abs(left_d) > on_plane_m || std::abs(right_d) > on_plane_m)
        continue;
      double low_d = std::numeric_limits<double>::infinity(), low_g = low_d;
      for (int w = -half_window; w <= half_window; ++w)
      {
        double d, g;
        if (!sample(centre + w * across, d, g)) continue;
        if (!std::isnan(d)) low_d = std::min(low_d, d);
        low_g = std::min(low_g, g);
      }
      const std::size_t cell = static_cast<std::size_t>(line) * evidence.length + k;
      // Both sides above the middle: a line or a groove, not a step. A
      // dark line beside paper is print (see kPrintSideGrey), not a seam.
      if (std::isfinite(low_g) && !(std::max(left_g, right_g) > print_side_grey))
        raw[1][cell] = static_cast<float>(std::min(left_g, right_g) - low_g);
      if (std::isfinite(low_d)) raw[0][cell] = static_cast<float>(std::min(left_d, right_d) - low_d);
    }
  }
  // Centre each channel on its typical dip (the lowest of a window is
  // biased) and clip at 4 sigma so flying pixels do not make a seam, but
  // never below twice the smallest seam: on a clean face 4 sigma is less
  // than the smallest seam, and a clipped dark line would never count. The
  // sigma has a floor (a quarter of the smallest seam) for noise-free input.
  for (int channel = 0; channel < 2; ++channel)
  {
    std::vector<double> values = evenSample(raw[channel], kMaxMedianSamples);
    const RobustSpread spread = values.empty() ? RobustSpread{} : robustSpread(std::move(values));
    const double centre = spread.centre;
    const double sigma = std::max(0.25 * sigma_floor[channel], spread.sigma);
    evidence.sigma[channel] = sigma;
    auto& sums = evidence.integral_sum[channel];
    auto& counts = evidence.integral_count[channel];
    sums.assign(static_cast<std::size_t>(evidence.lines + 1) * (evidence.length + 1), 0.0);
    counts.assign(sums.size(), 0);
    const double clip = std::max(4.0 * sigma, 2.0 * sigma_floor[channel]);
    for (int line = 0; line < evidence.lines; ++line)
    {
      // Row line + 1 of the integral: the row above plus this line's prefix.
      double line_sum = 0.0;
      int line_count = 0;
      for (int k = 0; k < evidence.length; ++k)
      {
        const float value = raw[channel][static_cast<std::size_t>(line) * evidence.length + k];
        if (!std::isnan(value))
        {
          line_sum += std::max(-clip, std::min(clip, value - centre));
          ++line_count;
        }
        sums[evidence.at(line + 1, k + 1)] = sums[evidence.at(line, k + 1)] + line_sum;
        counts[evidence.at(line + 1, k + 1)] = counts[evidence.at(line, k + 1)] + line_count;
      }
    }
  }
  return evidence;
}

/// A tile in grid cells: [i0, i1) x [j0, j1), possibly reaching beyond the grid.
struct CellRect
{
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  /// The line edge k lies on, in rectangle order: s = i0, t = j0, s = i1, t = j1.
  int edgeLine(int k) const { return k == 0 ? i0 : k == 1 ? j0 : k == 2 ? i1 : j1; }
  /// Whether this rectangle and `other` share cells along the axis edge k
  /// spans (the other axis than its line's).
  bool overlapsAlongEdge(const CellRect& other, int k) const
  {
    return k % 2 == 0 ? std::min(j1, other.j1) > std::max(j0, other.j0)
                      : std::min(i1, other.i1) > std::max(i0, other.i0);
  }
};

class Tiler
{
public:
  /// The seam evidence along either axis of `grid` (type-independent, so
  /// shared by the tilers of one face).
  struct Evidence
  {
    LineEvidence along_s, along_t;
  };

  static Evidence evidenceOf(const PlaneGrid& grid, const FaceTilingParams& params,
                             const EdgeEvidenceParams& evidence_params)
  {
    const std::array<double, 2> floor{{evidence_params.min_groove_m, evidence_params.min_line_contrast}};
    // The two directions read the same pixels, made here, and nothing the
    // grid caches: each goes on its own thread.
    const PlanePixelSamples& pixels = grid.pixelSamples(params.seam_arm_px);
    Evidence evidence;
    parallelFor(2, params.worker_threads, [&](int direction) {
      (direction == 0 ? evidence.along_s : evidence.along_t) =
          grid.lineEvidence(pixels, direction == 0, params.seam_arm_px, onPlaneM(grid, evidence_params), floor);
    });
    return evidence;
  }

  Tiler(PlaneGrid& grid, const Evidence& evidence, const std::vector<const BrickType*>& types, double tolerance_m,
        const FaceTilingParams& params, const EdgeEvidenceParams& evidence_params,
        TileOrientation orientation = TileOrientation::kEither)
    : grid_(grid),
      types_(types),
      orientation_(orientation),
      params_(params),
      evidence_params_(evidence_params),
      along_s_(evidence.along_s),
      along_t_(evidence.along_t),
      tolerance_cells_(std::max(1, roundToInt(tolerance_m / grid.cellM()))),
      free_(grid.counts(kFree)),
      off_image_(grid.counts(kOffImage)),
      narrowest_cells_(narrowestCells(types, grid.cellM()))
  {
    s_lines_ = {0, grid.nx()};
    t_lines_ = {0, grid.ny()};
  }

  struct Placed
  {
    const BrickType* type = nullptr;
    CellRect rect;
    // Edges in rectangle order: s = i0 (0), t = j0 (1), s = i1 (2), t = j1 (3).
    std::array<bool, 4> cut{{false, false, false, false}};
    std::array<bool, 4> seen{{false, false, false, false}};
    std::array<bool, 4> groove{{false, false, false, false}};
    /// Edges at the anchor the tile grew from (the others were snapped).
    std::array<bool, 4> anchored{{false, false, false, false}};
    double score = -1e9;
  };

  std::vector<Placed> run()
  {
    std::vector<Placed> placed;
    const int total_free = grid_.freeCount();
    while (static_cast<int>(placed.size()) < params_.max_tiles)
    {
      Placed best;
      for (const Anchor& anchor : anchors())
        for (const BrickType* type : types_)
          for (const bool long_along_s : {true, false})
          {
            if (orientation_ != TileOrientation::kEither && long_along_s != (orientation_ == TileOrientation::kLongAlongAxis))
              continue;
            Placed candidate = place(type, long_along_s, anchor, best.score);
            if (candidate.type && candidate.score > best.score) best = candidate;
          }
      if (!best.type)
      {
        if (extent_lines_added_) break;
        addExtentLines();
        extent_lines_added_ = true;
        continue;
      }
      take(best);
      placed.push_back(best);
      if (free_.count(0, grid_.nx(), 0, grid_.ny()) < 0.05 * total_free) break;
    }
    const CellCounts tiled = grid_.counts(kTiled);
    for (Placed& tile : placed) uncutFringes(tile, tiled);
    return placed;
  }

private:
  /// Where a tile may start: on a boundary line of the untiled region (the
  /// quad's sides, earlier tiles' edges), at the first untiled cells met
  /// sliding along the line from either end. The tile grows toward (di, dj).
  /// An anchor is open along the line when the region is cut off there (by
  /// the image border or an occluder) rather than ending: the brick may
  /// start anywhere before it.
  struct Anchor
  {
    int i = 0, j = 0, di = 1, dj = 1;
    bool open_s = false, open_t = false;
    /// Open where the image ends (not at an occluder): the brick may lie
    /// mostly out of view. (Beyond an "occluder" a box is often whole: a
    /// taller neighbour's wall rises from its edge.)
    bool off_image = false;
  };

  /// Whether the cell lies off the image (or behind the camera).
  bool offImageCell(int i, int j) const
  {
    int u = 0, v = 0;
    return grid_.inGrid(i, j) ? grid_.state(i, j) == kOffImage : !grid_.cellPixel(i, j, u, v);
  }

  /// Whether the cell ends the region for good (another surface or tile),
  /// as opposed to hiding it (off the image, behind an occluder).
  bool closedCell(int i, int j) const
  {
    if (!grid_.inGrid(i, j)) return !grid_.hiddenBeyondGrid(i, j);
    const std::uint8_t state = grid_.state(i, j);
    return state == kForeign || state == kTiled;
  }

  std::vector<Anchor> anchors() const
  {
    std::vector<Anchor> found;
    for (const bool along_t_lines : {true, false})
    {
      const std::set<int>& lines = along_t_lines ? t_lines_ : s_lines_;
      const int across_limit = along_t_lines ? grid_.ny() : grid_.nx();
      const int along_limit = along_t_lines ? grid_.nx() : grid_.ny();
      auto freeAt = [&](int along, int across) {
        return along_t_lines ? grid_.free(along, across) : grid_.free(across, along);
      };
      for (const int line : lines)
        for (const int grow : {1, -1})
        {
          const int inside = grow > 0 ? line : line - 1, outside = grow > 0 ? line - 1 : line;
          if (inside < 0 || inside >= across_limit) continue;
          for (const int slide : {1, -1})
          {
            // The first two columns mostly untiled over the band of rows next
            // to the line (one row alone follows every ragged or slightly
            // tilted outline pixel).
            auto bandFree = [&](int along) {
              int count = 0, rows = 0;
              for (int depth = 0; depth < kAnchorBand; ++depth)
              {
                const int across = inside + grow * depth;
                if (across < 0 || across >= across_limit) break;
                ++rows;
                count += freeAt(along, across) ? 1 : 0;
              }
              return rows > 0 && count * 4 >= rows * 3;
            };
            int at = slide > 0 ? 0 : along_limit - 1;
            while (at >= 0 && at < along_limit && !(bandFree(at) && bandFree(at + slide))) at += slide;
            if (at < 0 || at >= along_limit) continue;
            // The line must bound the region there.
            if (freeAt(at, outside) && freeAt(at + slide, outside)) continue;
            Anchor anchor;
            const int start = slide > 0 ? at : at + 1;
            const int before_i = along_t_lines ? at - slide : inside, before_j = along_t_lines ? inside : at - slide;
            const bool open = !closedCell(before_i, before_j);
            if (along_t_lines)
              anchor = {start, line, slide, grow, open, false};
            else
              anchor = {line, start, grow, slide, false, open};
            anchor.off_image = open && offImageCell(before_i, before_j);
            found.push_back(anchor);
          }
        }
    }
    return found;
  }

  /// The first untiled column (toward di) over rows [j0, j1), or of rows
  /// over columns: where an open tile starts.
  int firstFree(bool along_s, int from, int to, int direction) const
  {
    const int limit = along_s ? grid_.nx() : grid_.ny();
    int best = direction > 0 ? limit : -1;
    for (int k = std::max(0, from); k < std::min(along_s ? grid_.ny() : grid_.nx(), to); ++k)
    {
      // Rows with nothing untiled before `best` cannot move it.
      const int scan_from = direction > 0 ? 0 : best + 1, scan_to = direction > 0 ? best : limit;
      if ((along_s ? free_.count(scan_from, scan_to, k, k + 1) : free_.count(k, k + 1, scan_from, scan_to)) == 0)
        continue;
      if (direction > 0)
      {
        for (int a = 0; a < best; ++a)
          if (along_s ? grid_.free(a, k) : grid_.free(k, a))
          {
            best = a;
            break;
          }
      }
      else
        for (int a = limit - 1; a > best; --a)
          if (along_s ? grid_.free(a, k) : grid_.free(k, a))
          {
            best = a;
            break;
          }
    }
    return direction > 0 ? best : best + 1;
  }

  /// How well the image supports a tile edge on line `line` (of constant s
  /// when constant_s) over cells [from, to) of the other axis, for a tile
  /// lying on side `inward` (-1: lower indices, +1: higher) of it.
  struct LineSupport
  {
    double strength = 0.0;
    bool boundary = false;  // untiled segment on the tile's side only
    bool seam = false;      // a groove or a line
    bool groove = false;    // a groove in depth
  };

  LineSupport support(bool constant_s, int line, int from, int to, int inward) const
  {
    LineSupport result;
    // Boundary: beyond the line there is little untiled segment (inward 0:
    // a line inside a tile, never a boundary).
    // Two lines of cells on either side, over [from, to).
    int beyond = 0, inside = 0, counted = 0;
    if (inward != 0 && to > from)
    {
      const int in_first = inward > 0 ? line : line - 2, out_first = inward > 0 ? line - 2 : line;
      inside = constant_s ? free_.count(in_first, in_first + 2, from, to) : free_.count(from, to, in_first, in_first + 2);
      beyond =
          constant_s ? free_.count(out_first, out_first + 2, from, to) : free_.count(from, to, out_first, out_first + 2);
      counted = 2 * (to - from);
    }
    if (counted > 0 && beyond * 10 < counted * 3 && inside * 10 > counted * 3)
    {
      result.boundary = true;
      result.strength = kBoundaryStrength;
      return result;
    }
    const LineEvidence& evidence = constant_s ? along_s_ : along_t_;
    const double root_px = std::sqrt(std::max(1.0, grid_.cellPx()));
    int count = 0;
    const double groove = evidence.contrast(0, line, from, to, count);
    const double groove_z = count > 0 ? groove / (evidence.sigma[0] / (std::sqrt(count) * root_px)) : 0.0;
    const double line_dip = evidence.contrast(1, line, from, to, count);
    const double line_z = count > 0 ? line_dip / (evidence.sigma[1] / (std::sqrt(count) * root_px)) : 0.0;
    const bool groove_seen = groove >= evidence_params_.min_groove_m && groove_z >= params_.min_seam_strength;
    const bool line_seen = line_dip >= evidence_params_.min_line_contrast && line_z >= params_.min_seam_strength;
    result.seam = groove_seen || line_seen;
    result.groove = groove_seen;
    result.strength = std::min(kBoundaryStrength + 2.0, std::max(groove_seen ? groove_z : 0.0, line_seen ? line_z : 0.0));
    return result;
  }

  /// Moves a far edge from `nominal` to the best supported line within the
  /// tolerance; returns the line and its support. A tile whose start is cut
  /// off by the image border may be mostly out of view: where nothing near
  /// `nominal` clearly bounds it, its far edge is looked for on to
  /// `open_from` (kMinOpenCells in from its first visible line) among the
  /// lines that clearly bound: the segment's end, or a seam as strong as a
  /// confirmed cut's (many lines are read there, and the search's noise
  /// lines reach min_seam_strength). The penalty there is flat: any line
  /// between is as likely as another for a brick mostly out of view, so the
  /// strongest wins.
  int snap(bool constant_s, int nominal, int from, int to, int inward, LineSupport& best_support,
           std::optional<int> open_from = std::nullopt) const
  {
    int best_line = nominal;
    double best_score = -1e9;
    best_support = LineSupport();
    const int limit = constant_s ? grid_.nx() : grid_.ny();
    auto clearlyBounds = [&](const LineSupport& s) {
      return s.boundary || (s.seam && s.strength >= kConfirmedSeamFactor * params_.min_seam_strength);
    };
    auto consider = [&](int line, double penalty, bool bounds_only) {
      // Beyond the grid a line can only be the boundary the grid already has.
      if (line < 0 || line > limit) return;
      const LineSupport s = support(constant_s, line, from, to, inward);
      if (bounds_only && !clearlyBounds(s)) return;
      if (s.seam && !s.boundary && !roomBeyond(constant_s, line, from, to, inward)) return;
      const double score = s.strength - penalty;
      if (score > best_score)
      {
        best_score = score;
        best_line = line;
        best_support = s;
      }
    };
    for (int line = nominal - tolerance_cells_; line <= nominal + tolerance_cells_; ++line)
      consider(line, 0.5 * std::abs(line - nominal) / tolerance_cells_, false);
    if (open_from && !clearlyBounds(best_support))
    {
      // From the near end of the tolerance band back to open_from.
      const int step = inward > 0 ? 1 : -1;
      for (int line = nominal + step * (tolerance_cells_ + 1); (line - *open_from) * step <= 0; line += step)
        consider(line, 0.5, true);
    }
    if (best_score <= 0.0)
    {
      best_support = LineSupport();
      return nominal;
    }
    return best_line;
  }

  /// The tile of `type` grown from `anchor`, or none (type null) when it
  /// does not fit or cannot score above `score_to_beat`. The greedy loop
  /// asks again for every anchor after each tile it takes, and most anchors
  /// are far from that tile: a fit is kept until a tile is taken within the
  /// cells it read (anchors open along a side, which scan whole rows, are
  /// fitted anew).
  Placed place(const BrickType* type, bool long_along_s, const Anchor& anchor, double score_to_beat)
  {
    Fit fitted;
    Fit* fit_of = &fitted;
    if (!anchor.open_s && !anchor.open_t)
    {
      const FitKey key{anchor.i, anchor.j, anchor.di, anchor.dj, type, long_along_s};
      auto known = fits_.find(key);
      if (known == fits_.end())
        known = fits_.emplace(key, KeptFit{fit(type, long_along_s, anchor), cellsRead(type, long_along_s, anchor)}).first;
      fit_of = &known->second.fit;
    }
    else
      fitted = fit(type, long_along_s, anchor);
    Fit& f = *fit_of;
    // A seam running through the tile's inside says it is two bricks. It
    // only lowers the score, and reading it costs a line per cell of the
    // tile: a tile that cannot win without it is not read.
    // (Summed in the order the score always was, so ties fall as before.)
    if (!f.tile.type || f.edge_strength + f.visible_bonus <= score_to_beat) return Placed();
    if (f.inside_seam < 0.0) f.inside_seam = strongestInsideSeam(f.tile.rect);
    Placed result = f.tile;
    result.score = f.edge_strength - std::max(0.0, f.inside_seam - params_.min_seam_strength) + f.visible_bonus;
    return result;
  }

  /// A tile fitted from an anchor, before its inside is read.
  struct Fit
  {
    Placed tile;  ///< type null when it does not fit; score unset
    double edge_strength = 0.0;  ///< the far edges' support
    double visible_bonus = 0.0;  ///< a thousandth of the visible share, to break ties
    double inside_seam = -1.0;  ///< < 0: not read yet (it depends on the rectangle alone)
  };
  using FitKey = std::tuple<int, int, int, int, const BrickType*, bool>;
  struct KeptFit
  {
    Fit fit;
    CellRect reads;  ///< every cell whose state fit() may have read
  };

  /// The tile's size in cells along s and t.
  std::pair<int, int> tileCells(const BrickType* type, bool long_along_s) const
  {
    return {roundToInt((long_along_s ? type->length_m : type->width_m) / grid_.cellM()),
            roundToInt((long_along_s ? type->width_m : type->length_m) / grid_.cellM())};
  }

  /// The cells fit() reads for a closed anchor: each far edge within the
  /// tolerance of its nominal line, two cells either side of it (support()),
  /// over the tile's extent along the other axis.
  CellRect cellsRead(const BrickType* type, bool long_along_s, const Anchor& anchor) const
  {
    const auto [length_s, length_t] = tileCells(type, long_along_s);
    const int far_i = anchor.i + anchor.di * length_s, far_j = anchor.j + anchor.dj * length_t;
    const int margin = 3;  // support()'s band of two cells either side of a line, and one spare
    return {std::min(anchor.i, far_i - tolerance_cells_) - margin, std::max(anchor.i, far_i + tolerance_cells_) + margin,
            std::min(anchor.j, far_j - tolerance_cells_) - margin, std::max(anchor.j, far_j + tolerance_cells_) + margin};
  }

  Fit fit(const BrickType* type, bool long_along_s, const Anchor& anchor) const
  {
    Fit result;
    const int di = anchor.di, dj = anchor.dj;
    int i = anchor.i, j = anchor.j;
    const auto [length_s, length_t] = tileCells(type, long_along_s);
    int far_i = i + di * length_s;
    int far_j = j + dj * length_t;
    LineSupport support_i, support_j;
    // The arguments of each edge's last snap: the second pass repeats a
    // snap whose arguments did not move only in cost.
    constexpr int kNone = std::numeric_limits<int>::min();
    std::array<int, 4> snapped_i{{kNone, kNone, kNone, kNone}}, snapped_j = snapped_i;
    auto snapOnce = [&](bool constant_s, int nominal, int from, int to, int inward, std::optional<int> open_from,
                        std::array<int, 4>& last, int& far, LineSupport& support) {
      const std::array<int, 4> args{{nominal, from, to, open_from.value_or(kNone)}};
      if (args == last) return;
      far = snap(constant_s, nominal, from, to, inward, support, open_from);
      last = args;
    };
    // Snap each far edge over the other's current extent, twice. An open
    // side starts at the first untiled cell over the tile's other extent.
    // Where the image border cuts the tile's start off, the far edge may lie
    // anywhere from kMinOpenCells past its first visible line (see snap()).
    auto openFrom = [&](bool open, int start, int direction) {
      return open && anchor.off_image ? std::optional<int>(start + direction * kMinOpenCells) : std::nullopt;
    };
    for (int pass = 0; pass < 2; ++pass)
    {
      if (anchor.open_s) i = firstFree(true, std::min(j, far_j), std::max(j, far_j), di);
      snapOnce(true, i + di * length_s, std::min(j, far_j), std::max(j, far_j), -di, openFrom(anchor.open_s, i, di),
               snapped_i, far_i, support_i);
      if (anchor.open_t) j = firstFree(false, std::min(i, far_i), std::max(i, far_i), dj);
      snapOnce(false, j + dj * length_t, std::min(i, far_i), std::max(i, far_i), -dj, openFrom(anchor.open_t, j, dj),
               snapped_j, far_j, support_j);
    }
    CellRect rect{std::min(i, far_i), std::max(i, far_i), std::min(j, far_j), std::max(j, far_j)};
    if (rect.i1 - rect.i0 < 2 || rect.j1 - rect.j0 < 2) return result;

    // Inside the grid from the counts; beyond it, sample sparsely whether
    // it is hidden.
    const int total = (rect.i1 - rect.i0) * (rect.j1 - rect.j0);
    const int in_i0 = std::max(rect.i0, 0), in_i1 = std::min(rect.i1, grid_.nx());
    const int in_j0 = std::max(rect.j0, 0), in_j1 = std::min(rect.j1, grid_.ny());
    const int in_grid = std::max(0, in_i1 - in_i0) * std::max(0, in_j1 - in_j0);
    const int untiled = free_.count(rect.i0, rect.i1, rect.j0, rect.j1);
    const int hidden = off_image_.count(rect.i0, rect.i1, rect.j0, rect.j1);
    const int other = in_grid - untiled - hidden;
    // Refused before the cells beyond the grid are sampled when the counts
    // inside it already refuse: too little of the tile is untiled segment,
    // or the segment's share is too low even if every cell out there were
    // hidden (each visible cell found there only lowers it).
    const double visible = static_cast<double>(untiled) / total;
    if (visible < params_.min_visible_fraction) return result;  // so untiled > 0
    if (static_cast<double>(untiled) / (untiled + other) < params_.min_coverage) return result;
    int visible_other = 0;
    // Every third cell (those with a + b divisible by 3) stands for three.
    auto sampleBeyond = [&](int from_a, int to_a, int b) {
      int a = from_a;
      while (a < to_a && (a + b) % 3 != 0) ++a;
      for (; a < to_a; a += 3) visible_other += grid_.hiddenBeyondGrid(a, b) ? 0 : 3;
    };
    for (int b = rect.j0; b < rect.j1; ++b)
    {
      if (b < 0 || b >= grid_.ny())
      {
        sampleBeyond(rect.i0, rect.i1, b);
        continue;
      }
      sampleBeyond(rect.i0, std::min(rect.i1, 0), b);
      sampleBeyond(std::max(rect.i0, grid_.nx()), rect.i1, b);
    }
    const int seen = untiled + other + visible_other;
    if (seen == 0) return result;
    const double coverage = static_cast<double>(untiled) / seen;
    const double foreign = static_cast<double>(other + visible_other) / seen;
    if (coverage < params_.min_coverage || foreign > params_.max_foreign_fraction) return result;

    result.edge_strength = support_i.strength + support_j.strength;
    result.visible_bonus = 1e-3 * visible;
    Placed& tile = result.tile;
    tile.type = type;
    tile.rect = rect;
    // Edge order: s = i0, t = j0, s = i1, t = j1; the anchor edges are the
    // region's boundary or earlier cuts.
    const int far_i_edge = di > 0 ? 2 : 0, far_j_edge = dj > 0 ? 3 : 1;
    tile.cut[far_i_edge] = !support_i.boundary;
    tile.seen[far_i_edge] = support_i.seam;
    tile.groove[far_i_edge] = support_i.groove;
    tile.cut[far_j_edge] = !support_j.boundary;
    tile.seen[far_j_edge] = support_j.seam;
    tile.groove[far_j_edge] = support_j.groove;
    tile.anchored[2 - far_i_edge] = true;
    tile.anchored[4 - far_j_edge] = true;
    return result;
  }

  double strongestInsideSeam(const CellRect& rect) const
  {
    double strongest = 0.0;
    const int margin = tolerance_cells_ + 1;
    for (int line = std::max(0, rect.i0 + margin); line <= std::min(grid_.nx(), rect.i1 - margin); ++line)
    {
      const LineSupport s = support(true, line, std::max(0, rect.j0), std::min(grid_.ny(), rect.j1), 0);
      if (s.seam) strongest = std::max(strongest, s.strength);
    }
    for (int line = std::max(0, rect.j0 + margin); line <= std::min(grid_.ny(), rect.j1 - margin); ++line)
    {
      const LineSupport s = support(false, line, std::max(0, rect.i0), std::min(grid_.nx(), rect.i1), 0);
      if (s.seam) strongest = std::max(strongest, s.strength);
    }
    return strongest;
  }

  void take(const Placed& tile)
  {
    // The fits that read a cell this tile takes are stale.
    for (auto kept = fits_.begin(); kept != fits_.end();)
    {
      const CellRect& r = kept->second.reads;
      const bool overlaps = r.i0 < tile.rect.i1 && tile.rect.i0 < r.i1 && r.j0 < tile.rect.j1 && tile.rect.j0 < r.j1;
      kept = overlaps ? fits_.erase(kept) : std::next(kept);
    }
    for (int b = std::max(0, tile.rect.j0); b < std::min(grid_.ny(), tile.rect.j1); ++b)
      for (int a = std::max(0, tile.rect.i0); a < std::min(grid_.nx(), tile.rect.i1); ++a)
        if (grid_.state(a, b) == kFree) grid_.setState(a, b, kTiled);
    free_.update(grid_.states(), tile.rect.j0);
    for (const int line : {tile.rect.i0, tile.rect.i1})
      if (line >= 0 && line <= grid_.nx()) s_lines_.insert(line);
    for (const int line : {tile.rect.j0, tile.rect.j1})
      if (line >= 0 && line <= grid_.ny()) t_lines_.insert(line);
  }

  /// A cut with nothing beyond it but a strip of the segment at most
  /// kMaxFringeM deep, which then ends, is the segment's edge: D4xx depth
  /// fattens a face a few pixels over each step down, and the line where
  /// the face really ends can pass for a seam with that fringe beyond it.
  /// No brick is that narrow, so the strip is no neighbour; the edge is left
  /// to the tile's own edge test (a step down, or an occluder, beyond the
  /// strip) like any side along the segment's boundary.
  void uncutFringes(Placed& tile, const CellCounts& tiled) const
  {
    for (int k = 0; k < 4; ++k)
    {
      if (!tile.cut[k]) continue;
      const bool constant_s = k % 2 == 0;
      const int outward = k < 2 ? -1 : 1;
      const int line = tile.rect.edgeLine(k);
      const int from = constant_s ? tile.rect.j0 : tile.rect.i0, to = constant_s ? tile.rect.j1 : tile.rect.i1;
      if (fringeOnly(tiled, constant_s, line, outward, from, to))
      {
        tile.cut[k] = false;
        tile.seen[k] = false;
        tile.groove[k] = false;
      }
    }
  }

  /// Whether the cells beyond `line` (toward `outward`) over [from, to) are
  /// a strip of untiled segment at most kMaxFringeM deep that ends in cells
  /// of another surface (not the image border: the segment may go on
  /// there), with no tile in it or just past its end (a tile beyond a thin
  /// line of dropouts is a neighbour, and the cut is shared with it).
  bool fringeOnly(const CellCounts& tiled, bool constant_s, int line, int outward, int from, int to) const
  {
    const int length_cells = to - from;
    if (length_cells <= 0) return false;
    const int limit = constant_s ? grid_.nx() : grid_.ny();
    const int max_depth_cells = std::min(tolerance_cells_, static_cast<int>(std::ceil(kMaxFringeM / grid_.cellM())));
    auto column = [&](int depth) { return columnBeyond(line, outward, depth); };
    auto countIn = [&](const CellCounts& counts, int c) { return countOnColumn(counts, constant_s, c, from, to); };
    for (int depth = 0; depth <= max_depth_cells; ++depth)
    {
      const int c = column(depth);
      if (c < 0 || c >= limit) return depth > 0 && !beyondHidden(constant_s, c, from, to);
      if (countIn(tiled, c) > 0 || countIn(off_image_, c) > 0) return false;
      // The strip ends where (almost) nothing of the segment is left.
      if (countIn(free_, c) <= kFringeEndFreeShare * length_cells)
        return depth > 0 && countIn(tiled, column(depth + 1)) == 0 && countIn(tiled, column(depth + 2)) == 0;
    }
    return false;
  }

  /// The column (of constant s when constant_s, else the row) `depth` cells
  /// beyond `line` toward `outward` (+1: higher indices).
  static int columnBeyond(int line, int outward, int depth) { return outward > 0 ? line + depth : line - 1 - depth; }

  /// The cells holding `counts`' state on column `c` over [from, to) of
  /// the other axis.
  static int countOnColumn(const CellCounts& counts, bool constant_s, int c, int from, int to)
  {
    return constant_s ? counts.count(c, c + 1, from, to) : counts.count(from, to, c, c + 1);
  }

  /// Deepest strip of segment beyond a cut that is taken for fattening: a
  /// D4xx fattens a step by a few pixels, 1-1.5 cm at 2 m in VGA.
  static constexpr double kMaxFringeM = 0.02;
  /// A column of the strip holding at most this share of segment cells ends it.
  static constexpr double kFringeEndFreeShare = 0.05;

  /// Whether the segment could go on out of view beyond the grid, past
  /// column (or row) `c` over [from, to): any of its cells off the image
  /// (the segment may run on there), or a quarter of them behind a nearer
  /// surface or without depth. A few dropouts are the stereo shadow a step
  /// down casts, not a hidden neighbour: a neighbour's top runs at least a
  /// brick's width along the cut.
  bool beyondHidden(bool constant_s, int c, int from, int to) const
  {
    int samples = 0, hidden = 0;
    for (int k = from; k < to; k += 3)
    {
      const int i = constant_s ? c : k, j = constant_s ? k : c;
      if (offImageCell(i, j)) return true;
      ++samples;
      hidden += grid_.hiddenBeyondGrid(i, j) ? 1 : 0;
    }
    return hidden > 0 && hidden * 4 >= samples;
  }

  /// Whether a seam on `line` could part a tile lying on side `inward` of
  /// it, over [from, to), from a neighbour. Beyond the line the untiled
  /// segment must run on for the narrowest tile's width less the tolerance,
  /// or go out of view (off the image, behind a nearer surface), or end
  /// within a fattening fringe (kMaxFringeM, see fringeOnly()). A strip
  /// wider than a fringe and narrower than any brick, closed by another
  /// surface, holds no brick: a line there (a crease the stereo matching
  /// draws by a step, a line of print) is no cut, and the tile's edge lies
  /// beyond it.
  bool roomBeyond(bool constant_s, int line, int from, int to, int inward) const
  {
    const int length_cells = to - from;
    if (length_cells <= 0) return true;
    const int outward = -inward;
    const int limit = constant_s ? grid_.nx() : grid_.ny();
    const int fringe_cells = static_cast<int>(std::ceil(kMaxFringeM / grid_.cellM()));
    auto column = [&](int depth) { return columnBeyond(line, outward, depth); };
    auto countIn = [&](const CellCounts& counts, int c) { return countOnColumn(counts, constant_s, c, from, to); };
    for (int depth = 0; depth < narrowest_cells_ - tolerance_cells_; ++depth)
    {
      const int c = column(depth);
      const bool in_grid = c >= 0 && c < limit;
      if (in_grid && countIn(off_image_, c) > 0) return true;
      if (in_grid && countIn(free_, c) > kFringeEndFreeShare * length_cells) continue;
      // The strip ends here: in a fringe, or where the segment may go on
      // out of sight.
      return depth <= fringe_cells || beyondHidden(constant_s, c, from, to);
    }
    return true;
  }

  /// The grid spans the quad's corners. Where its axis is the outline's and
  /// not the quad's (two rows offset along their length: the least-area quad
  /// of that Z lies askew), the grid's sides touch the segment nowhere, and
  /// the outer corners of its bricks lie on no line to anchor a tile at.
  /// When no tile fits any more, the lines where the untiled region starts
  /// and ends are added once, and the tiling goes on from them. Only then:
  /// from the start, their anchors would also compete where the quad's own
  /// serve, and change tilings that were right. A line counts from
  /// kAnchorBand cells of the region on (a stray cell of noise is no side);
  /// one within the tolerance of the grid's own side adds nothing new.
  void addExtentLines()
  {
    auto extent = [&](bool along_s, std::set<int>& lines) {
      const int count = along_s ? grid_.nx() : grid_.ny();
      auto cellsAt = [&](int k) {
        return along_s ? free_.count(k, k + 1, 0, grid_.ny()) : free_.count(0, grid_.nx(), k, k + 1);
      };
      int first = 0, last = count - 1;
      while (first < count && cellsAt(first) < kAnchorBand) ++first;
      while (last > first && cellsAt(last) < kAnchorBand) --last;
      if (first >= last) return;
      if (first > tolerance_cells_) lines.insert(first);
      if (last + 1 < count - tolerance_cells_) lines.insert(last + 1);
    };
    extent(true, s_lines_);
    extent(false, t_lines_);
  }

  static int narrowestCells(const std::vector<const BrickType*>& types, double cell_m)
  {
    double narrowest_m = std::numeric_limits<double>::infinity();
    for (const BrickType* type : types) narrowest_m = std::min(narrowest_m, std::min(type->width_m, type->length_m));
    return std::isfinite(narrowest_m) ? roundToInt(narrowest_m / cell_m) : 0;
  }

  static constexpr double kBoundaryStrength = 6.0;
  /// The least a tile shows of itself where its start is cut off (cells).
  static constexpr int kMinOpenCells = 2;
  /// Rows next to a line that decide where a tile may start along it.
  static constexpr int kAnchorBand = 4;

  /// Depth samples within this of the plane are on it.
  static double onPlaneM(const PlaneGrid& grid, const EdgeEvidenceParams& params)
  {
    return params.stepM(grid.planeRmsM());
  }

  PlaneGrid& grid_;
  const std::vector<const BrickType*>& types_;
  TileOrientation orientation_;
  const FaceTilingParams& params_;
  const EdgeEvidenceParams& evidence_params_;
  const LineEvidence& along_s_;
  const LineEvidence& along_t_;
  int tolerance_cells_;
  CellCounts free_;       ///< untiled cells of the segment, rebuilt as tiles are taken
  CellCounts off_image_;  ///< cells off the image (fixed)
  int narrowest_cells_;   ///< the narrowest tile's width (see roomBeyond())
  std::set<int> s_lines_, t_lines_;
  bool extent_lines_added_ = false;  ///< see addExtentLines()
  std::map<FitKey, KeptFit> fits_;  ///< see place()
};

/// The pixels of `segment` inside the image of a plane rectangle, boxed
/// tightly: a tile is one brick of a merged row, and the work on it (its
/// outline, its measurement) then scales with the brick, not the row.
Segment tileSegment(const RgbdFrame& frame, const Segment& segment, const std::array<Eigen::Vector3d, 4>& corners_m)
{
  constexpr int kShift = 4;  // polygon corners in 1/16 px
  const cv::Rect& box = segment.bounding_box_px;
  std::vector<cv::Point> polygon;
  for (const Eigen::Vector3d& corner : corners_m)
  {
    const Eigen::Vector3d in_front(corner.x(), corner.y(), std::max(0.05, corner.z()));
    const Eigen::Vector2d p = frame.camera.project(in_front);
    polygon.emplace_back(roundToInt((p.x() - box.x) * 16.0), roundToInt((p.y() - box.y) * 16.0));
  }
  // Only the polygon's part of the box is rasterised. Moving the polygon by
  // whole pixels moves its fill with it, and the box's own edges still clip
  // it where they did, so the pixels are those of a fill over the whole box.
  const cv::Rect reach_16 = cv::boundingRect(polygon);
  const cv::Point from_px((reach_16.x >> kShift) - 2, (reach_16.y >> kShift) - 2);
  const cv::Point to_px(((reach_16.x + reach_16.width) >> kShift) + 3, ((reach_16.y + reach_16.height) >> kShift) + 3);
  const cv::Rect reach = cv::Rect(from_px, to_px) & cv::Rect(cv::Point(0, 0), box.size());
  if (reach.area() == 0) return segmentFromMask(cv::Mat::zeros(box.size(), CV_8UC1), box, frame.depth_m, segment.type_name);
  for (cv::Point& corner : polygon) corner -= reach.tl() * (1 << kShift);
  cv::Mat inside = cv::Mat::zeros(reach.size(), CV_8UC1);
  cv::fillConvexPoly(inside, polygon, cv::Scalar(255), cv::LINE_8, kShift);
  cv::Mat part_mask;
  cv::bitwise_and(segment.mask(reach), inside, part_mask);
  return croppedSegmentFromMask(part_mask, reach + box.tl(), frame.depth_m, segment.type_name);
}
}  // namespace

void FaceTilingParams::validate() const
{
  const ParamCheck check("face tiling");
  check.require(cell_m > 0.0, "cell_m", "must be > 0");
  check.require(max_cells >= 100, "max_cells", "must be >= 100");
  check.require(seam_arm_px >= 1, "seam_arm_px", "must be >= 1");
  check.require(min_seam_strength > 0.0, "min_seam_strength", "must be > 0");
  check.require(min_coverage > 0.0 && min_coverage <= 1.0, "min_coverage", "must be in (0, 1]");
  check.require(max_foreign_fraction >= 0.0 && max_foreign_fraction < 1.0, "max_foreign_fraction", "must be in [0, 1)");
  check.require(min_visible_fraction > 0.0 && min_visible_fraction <= 1.0, "min_visible_fraction", "must be in (0, 1]");
  check.require(max_tiles >= 1, "max_tiles", "must be >= 1");
  check.require(worker_threads >= 1, "worker_threads", "must be >= 1");
}

namespace
{
/// A tile starts where an earlier one's cut ended it, so that cut is its
/// edge too: marked cut on the later tile, seen as it was seen on the
/// earlier one (the tiling's counts keep each cut once).
void markSharedCuts(const std::vector<Tiler::Placed>& placed, FaceTiling& tiling)
{
  // Edge k of a rectangle lies on line (s = i0, t = j0, s = i1, t = j1)[k]
  // and spans the other axis.
  for (std::size_t a = 1; a < placed.size(); ++a)
    for (int k = 0; k < 4; ++k)
    {
      FaceTile& tile = tiling.tiles[a];
      if (tile.cut[k]) continue;
      const int facing = (k + 2) % 4;
      for (std::size_t b = 0; b < a; ++b)
        if (tiling.tiles[b].cut[facing] && placed[b].rect.edgeLine(facing) == placed[a].rect.edgeLine(k) &&
            placed[a].rect.overlapsAlongEdge(placed[b].rect, k))
        {
          // Seen only where every stretch of it was.
          tile.seam_seen[k] = (tile.cut[k] ? tile.seam_seen[k] : true) && tiling.tiles[b].seam_seen[facing];
          tile.cut[k] = true;
        }
    }
}

/// The stretches of edge k of `rect` (a tile's cut) with a neighbour beyond
/// it, where the segment goes on past the edge for more than a D4xx fringe:
/// [first, last) cells of the other axis, gaps of a few cells (dropouts
/// along the seam) bridged, stretches too short to read a seam along left
/// out. Along the rest of the edge it bounds the segment (a row of bricks
/// offset from the next, one brick longer than its neighbour): no seam is
/// there to see, and a seam clear where the bricks meet was diluted out of
/// sight when read there too. Cells without depth count as no neighbour,
/// so a cut with nothing seen beyond it is read whole, as before.
std::vector<std::pair<int, int>> cutNeighbours(const PlaneGrid& grid, const CellRect& rect, int k)
{
  // Past the deepest D4xx fringe of a step down (Tiler::kMaxFringeM, 2 cm)
  // and a tile ending a little short of the segment's end.
  constexpr double kBeyondM = 0.024;
  constexpr int kReadCells = 3;
  constexpr double kMinStretchM = 0.03;
  constexpr int kMaxGapCells = 2;
  const bool constant_s = k % 2 == 0;
  const int outward = k < 2 ? -1 : 1;
  const int line = rect.edgeLine(k);
  const int limit = constant_s ? grid.ny() : grid.nx();
  const int from = std::max(0, constant_s ? rect.j0 : rect.i0), to = std::min(limit, constant_s ? rect.j1 : rect.i1);
  const int depth_cells = std::max(2, static_cast<int>(std::ceil(kBeyondM / grid.cellM())));
  const int min_stretch_cells = std::max(3, static_cast<int>(std::ceil(kMinStretchM / grid.cellM())));
  auto segmentAt = [&](int across, int along) {
    const int i = constant_s ? across : along, j = constant_s ? along : across;
    if (!grid.inGrid(i, j)) return false;
    const std::uint8_t state = grid.state(i, j);
    return state == kFree || state == kTiled;
  };
  // The segment goes on past depth_cells beyond the edge (one hole allowed).
  auto neighbourAt = [&](int along) {
    int held = 0;
    for (int d = depth_cells; d < depth_cells + kReadCells; ++d)
      held += segmentAt(outward > 0 ? line + d : line - 1 - d, along) ? 1 : 0;
    return held >= kReadCells - 1;
  };
  std::vector<std::pair<int, int>> stretches;
  int start = -1, last = -1;
  auto close = [&]() {
    if (start >= 0 && last + 1 - start >= min_stretch_cells) stretches.emplace_back(start, last + 1);
    start = -1;
  };
  for (int along = from; along < to; ++along)
  {
    if (!neighbourAt(along)) continue;
    if (start >= 0 && along - last - 1 > kMaxGapCells) close();
    if (start < 0) start = along;
    last = along;
  }
  close();
  return stretches;
}

/// Whether `seam` confirms a cut: seen, and at least `confirmed_strength`
/// standard errors strong.
bool confirmsCut(const SeamScore& seam, double confirmed_strength)
{
  return seam.seen && seam.strength >= confirmed_strength;
}

/// The seam between two pixels, or along the line through them turned by
/// up to a few pixels at each end when it is not confirmed straight: a
/// brick laid a degree askew of the tiling's axes draws its seam across
/// the columns of a straight profile, and no column is dark in most rows.
/// Four more readings raise the noise's best a little; a confirmed seam is
/// 1.5 times the tiler's threshold, and on bench_frontend's 100 frames per
/// class no false complete face came of them.
SeamScore tiltedSeam(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                     const Eigen::Vector2d& b_px, const EdgeEvidenceParams& evidence_params, double confirmed_strength)
{
  SeamScore best = scoreSeam(frame, plane, a_px, b_px, evidence_params);
  if (confirmsCut(best, confirmed_strength)) return best;
  const Eigen::Vector2d along = b_px - a_px;
  if (!(along.norm() > 1.0)) return best;
  const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()).normalized();
  for (const double turn_px : {-2.0, -1.0, 1.0, 2.0})
  {
    const SeamScore seam = scoreSeam(frame, plane, a_px + turn_px * across, b_px - turn_px * across, evidence_params);
    const bool now = confirmsCut(seam, confirmed_strength), before = confirmsCut(best, confirmed_strength);
    if (now != before ? now : seam.strength > best.strength) best = seam;
  }
  return best;
}

/// A tile's cut as read: confirmed where every stretch read shows a seam;
/// the faintest line along them (grey levels).
struct CutReading
{
  bool confirmed = true;
  /// Every read a seam on its own (min_seam_strength standard errors and
  /// the floors): one that only falls short of the confirmation.
  bool seen = true;
  double line_contrast = std::numeric_limits<double>::infinity();
};

/// Reads the seam along a tile's cut edge k over `stretches` (see
/// cutNeighbours), each in the edge's own direction; an edge with none, or
/// with one along all of it, is read whole, corner to corner.
CutReading readCut(const RgbdFrame& frame, const PlaneFit& plane, const PlaneGrid& grid, const CellRect& rect, int k,
                   const std::vector<std::pair<int, int>>& stretches, const std::array<Eigen::Vector3d, 4>& corners_m,
                   const EdgeEvidenceParams& evidence_params, double seen_strength, double confirmed_strength)
{
  const bool constant_s = k % 2 == 0;
  const int along_from = std::max(0, constant_s ? rect.j0 : rect.i0);
  const int along_to = std::min(constant_s ? grid.ny() : grid.nx(), constant_s ? rect.j1 : rect.i1);
  const bool whole = stretches.empty() || (stretches.size() == 1 && stretches.front().first <= along_from &&
                                           stretches.front().second >= along_to);
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> reads_px;
  if (whole)
    reads_px.emplace_back(frame.camera.project(corners_m[k]), frame.camera.project(corners_m[(k + 1) % 4]));
  const int line = rect.edgeLine(k);
  auto pixelAt = [&](int along) {
    return frame.camera.project(constant_s ? grid.point(line, along) : grid.point(along, line));
  };
  // Edges 0 and 3 run toward lower indices.
  const bool descending = k == 0 || k == 3;
  if (!whole)
    for (const auto& [first, last] : stretches)
      reads_px.emplace_back(pixelAt(descending ? last : first), pixelAt(descending ? first : last));
  CutReading reading;
  for (const auto& [a_px, b_px] : reads_px)
  {
    const SeamScore seam = tiltedSeam(frame, plane, a_px, b_px, evidence_params, confirmed_strength);
    reading.confirmed = reading.confirmed && confirmsCut(seam, confirmed_strength);
    reading.seen = reading.seen && seam.seen && seam.strength >= seen_strength;
    reading.line_contrast = std::min(reading.line_contrast, seam.line_contrast);
  }
  return reading;
}

/// The direction the tiling's rectangles run along: the quad's, unless the
/// outline's straight stretches agree on another (see outline_axis.h). On a
/// single rectangle the two agree within a degree, and the quad, fitted to
/// the edges, is kept.
Eigen::Vector3d gridAxis(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured)
{
  const Eigen::Vector3d quad_axis = (measured.corners_m[1] - measured.corners_m[0]).normalized();
  const std::optional<OutlineAxis> outline = dominantOutlineAxis(frame, segment, measured.plane);
  if (!outline) return quad_axis;
  // The angle between the two, modulo a quarter turn.
  const Eigen::Vector3d across = measured.plane.normal.cross(quad_axis).normalized();
  const double angle_rad = std::atan2(outline->direction.dot(across), outline->direction.dot(quad_axis));
  const double off_rad = std::remainder(angle_rad, 0.5 * kPi);
  return std::abs(off_rad) > kMaxQuadOffOutlineRad ? outline->direction : quad_axis;
}

/// Confirms cuts seen but too short to confirm alone together with the cuts
/// that continue them on the same line: in a grid of touching bricks one
/// seam runs past several of them, while a brick's width holds too few
/// pixels in a low light (about 45 at 640x480) for its own stretch to reach
/// the confirmation. Each stretch must be seen on its own (`seen`): a row
/// laid in bond, whose seams do not line up, gains nothing, and a strong
/// seam beside it does not carry a stretch where nothing is.
void confirmAlongLines(const RgbdFrame& frame, const PlaneFit& plane, const PlaneGrid& grid,
                       const std::vector<Tiler::Placed>& placed, const std::vector<std::array<bool, 4>>& seen,
                       const EdgeEvidenceParams& evidence_params, double confirmed_strength, FaceTiling& tiling)
{
  struct Piece
  {
    std::size_t tile;
    int k, line, from, to;
  };
  // Cuts by the direction they run in (constant s or t), then by line:
  // each tile snaps its edge to the best line on its own, so the stretches
  // of one seam lie on lines a cell apart.
  std::map<bool, std::vector<Piece>> by_direction;
  for (std::size_t a = 0; a < placed.size(); ++a)
    for (int k = 0; k < 4; ++k)
    {
      if (!tiling.tiles[a].cut[k] || !seen[a][k]) continue;
      const CellRect& r = placed[a].rect;
      const bool constant_s = k % 2 == 0;
      by_direction[constant_s].push_back({a, k, r.edgeLine(k), std::max(0, constant_s ? r.j0 : r.i0),
                                          std::min(constant_s ? grid.ny() : grid.nx(), constant_s ? r.j1 : r.i1)});
    }
  std::vector<std::pair<bool, std::vector<Piece>>> lines;
  for (auto& [constant_s, pieces] : by_direction)
  {
    std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.line < b.line; });
    for (const Piece& piece : pieces)
      if (lines.empty() || lines.back().first != constant_s || piece.line > lines.back().second.front().line + 1)
        lines.push_back({constant_s, {piece}});
      else
        lines.back().second.push_back(piece);
  }
  for (auto& [constant_s, pieces] : lines)
  {
    std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.from < b.from; });
    int line_sum = 0;
    for (const Piece& piece : pieces) line_sum += piece.line;
    const int line = roundToInt(static_cast<double>(line_sum) / pieces.size());
    auto pixelAt = [&, cs = constant_s](int along) {
      return frame.camera.project(cs ? grid.point(line, along) : grid.point(along, line));
    };
    for (std::size_t first = 0; first < pieces.size();)
    {
      // A run of pieces each reaching the one before (within a cell).
      std::size_t last = first;
      int run_to = pieces[first].to, longest = pieces[first].to - pieces[first].from;
      while (last + 1 < pieces.size() && pieces[last + 1].from <= run_to + 1)
      {
        ++last;
        run_to = std::max(run_to, pieces[last].to);
        longest = std::max(longest, pieces[last].to - pieces[last].from);
      }
      const bool longer_than_any = run_to - pieces[first].from > longest + 1;
      const bool any_unconfirmed = std::any_of(pieces.begin() + first, pieces.begin() + last + 1, [&](const Piece& p) {
        return !tiling.tiles[p.tile].seam_seen[p.k];
      });
      if (longer_than_any && any_unconfirmed &&
          confirmsCut(tiltedSeam(frame, plane, pixelAt(pieces[first].from), pixelAt(run_to), evidence_params,
                                 confirmed_strength),
                      confirmed_strength))
        for (std::size_t n = first; n <= last; ++n) tiling.tiles[pieces[n].tile].seam_seen[pieces[n].k] = true;
      first = last + 1;
    }
  }
}

/// The placed tiles as a FaceTiling: corners, cuts and the seams confirmed
/// along each cut (the tiles' pixels are cut by cutTileSegments).
/// Two tiles anchored on one line from either side, overlapping along it,
/// are neighbours there, though neither tile made that edge a cut: a Z of
/// two bricks side by side and offset along their length has each tile
/// anchored at the line they share (its anchor slid along the outline to
/// the first untiled cells), and an anchor edge is taken for the region's
/// boundary. The line is a cut of both; it is read along the stretch they
/// share like any cut. (An edge the tiler snapped and found a boundary
/// stays one: made a cut there, it lost pallet tops.)
std::vector<Tiler::Placed> withFacingCuts(std::vector<Tiler::Placed> placed)
{
  for (std::size_t a = 0; a < placed.size(); ++a)
    for (std::size_t b = a + 1; b < placed.size(); ++b)
      for (int k = 0; k < 4; ++k)
      {
        const int facing = (k + 2) % 4;
        const CellRect& ra = placed[a].rect;
        const CellRect& rb = placed[b].rect;
        // Edge k of one on the line of the other's opposite edge: they touch.
        if (!placed[a].anchored[k] || !placed[b].anchored[facing] || ra.edgeLine(k) != rb.edgeLine(facing) ||
            !ra.overlapsAlongEdge(rb, k))
          continue;
        placed[a].cut[k] = true;
        placed[b].cut[facing] = true;
      }
  return placed;
}

FaceTiling describeTiling(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                          const PlaneGrid& grid, const std::vector<Tiler::Placed>& tiler_placed, int segment_cells,
                          const EdgeEvidenceParams& evidence_params, const FaceTilingParams& params)
{
  const std::vector<Tiler::Placed> placed = withFacingCuts(tiler_placed);
  FaceTiling tiling;
  tiling.untiled_fraction = static_cast<double>(grid.freeCount()) / segment_cells;
  tiling.tiles.reserve(placed.size());
  std::vector<std::array<bool, 4>> seen(placed.size(), {{false, false, false, false}});
  std::vector<std::array<bool, 4>> grooves(placed.size());
  const double confirmed_strength = kConfirmedSeamFactor * params.min_seam_strength;
  for (const Tiler::Placed& tile : placed)
  {
    FaceTile face;
    face.type_name = tile.type->name;
    const CellRect& r = tile.rect;
    // Corners in rectangle order (s = i0 edge first), matching `cut`.
    face.corners_m = {grid.point(r.i0, r.j1), grid.point(r.i0, r.j0), grid.point(r.i1, r.j0), grid.point(r.i1, r.j1)};
    face.cut = tile.cut;
    std::array<bool, 4> groove = tile.groove;
    for (int k = 0; k < 4; ++k)
    {
      if (!tile.cut[k]) continue;
      // Every cut is tested along itself, whether or not the tiler saw a
      // seam there: the tiler's cell raster samples one pixel per cell and
      // can miss a line one pixel wide that the profiles across the cut
      // see. Its own score, the largest of several noisy lines near each
      // nominal cut, is not trusted either: the seam must pass the edge
      // test along the cut, whose standard error comes from the scatter
      // along the line, and only where a neighbour lies beyond the cut.
      const CutReading cut = readCut(frame, measured.plane, grid, r, k, cutNeighbours(grid, r, k), face.corners_m,
                                     evidence_params, params.min_seam_strength, confirmed_strength);
      face.seam_seen[k] = cut.confirmed;
      seen[tiling.tiles.size()][k] = cut.seen;
      groove[k] = groove[k] && cut.confirmed;
      tiling.weakest_cut_line = std::min(tiling.weakest_cut_line, cut.line_contrast);
    }
    grooves[tiling.tiles.size()] = groove;
    tiling.tiles.push_back(std::move(face));
  }
  if (params.confirm_along_lines)
    confirmAlongLines(frame, measured.plane, grid, placed, seen, evidence_params, confirmed_strength, tiling);
  for (std::size_t a = 0; a < tiling.tiles.size(); ++a)
    for (int k = 0; k < 4; ++k)
    {
      const FaceTile& face = tiling.tiles[a];
      tiling.cuts += face.cut[k] ? 1 : 0;
      tiling.seen_cuts += face.cut[k] && face.seam_seen[k] ? 1 : 0;
      tiling.grooved_cuts += face.cut[k] && grooves[a][k] ? 1 : 0;
    }
  markSharedCuts(placed, tiling);
  return tiling;
}
}  // namespace

FaceTiling tileFace(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                    const std::vector<const BrickType*>& types, double tolerance_m, const FaceTilingParams& params,
                    const EdgeEvidenceParams& evidence_params)
{
  std::vector<FaceTiling> tilings =
      tileFaceEach(frame, segment, measured, {types}, tolerance_m, params, evidence_params,
                   [](std::size_t, const std::vector<FaceTiling>&) { return true; });
  if (tilings.empty()) return FaceTiling();
  cutTileSegments(frame, segment, tilings.front());
  return std::move(tilings.front());
}

void cutTileSegments(const RgbdFrame& frame, const Segment& segment, FaceTiling& tiling)
{
  for (FaceTile& tile : tiling.tiles) tile.segment = tileSegment(frame, segment, tile.corners_m);
}

std::vector<FaceTiling> tileFaceEach(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                                     const std::vector<std::vector<const BrickType*>>& type_sets, double tolerance_m,
                                     const FaceTilingParams& params, const EdgeEvidenceParams& evidence_params,
                                     const std::function<bool(std::size_t set, const std::vector<FaceTiling>& made)>& wanted,
                                     const std::vector<TileOrientation>& orientations)
{
  std::vector<FaceTiling> tilings;
  if (!measured.plane.valid) return tilings;
  PlaneGrid grid(frame, segment, measured, gridAxis(frame, segment, measured), params.cell_m, params.max_cells);
  const int segment_cells = grid.freeCount();
  if (segment_cells == 0) return tilings;
  // A tile reaches beyond the grid by at most its length and the tolerance.
  double longest_m = 0.0;
  for (const auto& types : type_sets)
    for (const BrickType* type : types) longest_m = std::max(longest_m, type->length_m);
  grid.reserveBeyond(static_cast<int>(std::ceil((longest_m + tolerance_m) / grid.cellM())) + 2);
  const Tiler::Evidence evidence = Tiler::evidenceOf(grid, params, evidence_params);
  const std::vector<std::uint8_t> untiled = grid.states();
  for (std::size_t set = 0; set < type_sets.size(); ++set)
  {
    if (!wanted(set, tilings)) continue;
    for (const TileOrientation orientation : orientations)
    {
      grid.restore(untiled);
      std::vector<Tiler::Placed> placed;
      if (!type_sets[set].empty())
        placed = Tiler(grid, evidence, type_sets[set], tolerance_m, params, evidence_params, orientation).run();
      tilings.push_back(describeTiling(frame, segment, measured, grid, placed, segment_cells, evidence_params, params));
    }
  }
  return tilings;
}
}  // namespace brick_pose
