#pragma once
// Each pixel's signed distance from a face's plane and its grey level, made
// once over the image region a face's seam evidence reads. That evidence
// reads most pixels several times (two directions, the window across each
// line and its arms), so the pixels are computed ahead; but only those near
// the face: the image box of a face seen askew is several times its area,
// and computing (and zeroing) the whole box cost more than the reading.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/geometry/plane_fit.h"
#include "brick_pose/roi/face_grey.h"

namespace brick_pose
{
class PlanePixelSamples
{
public:
  PlanePixelSamples() = default;

  /// Computes the pixels within `margin_px` of the convex polygon
  /// `outline_px` (image coordinates, vertices in order around it), clipped
  /// to the image; with an empty outline, every pixel of the image. `frame`
  /// must outlive this.
  PlanePixelSamples(const RgbdFrame& frame, const PlaneFit& plane, const std::vector<Eigen::Vector2d>& outline_px,
                    int margin_px);

  /// The pixel (u, v), which must lie in the image: its signed distance from
  /// the plane (NaN without depth) and its grey level in the face's own
  /// colour (FaceGrey, weighted by the mean colour of the computed pixels
  /// within a centimetre of the plane). Pixels not computed ahead are
  /// computed here, with the same result.
  void read(int u_px, int v_px, double& offset_m, double& grey) const
  {
    // Inline: the seam evidence reads a face's pixels about ten times each.
    if (std::size_t at = 0; storedAt(u_px, v_px, at))
    {
      offset_m = offset_m_[at];
      grey = grey_[at];
      return;
    }
    offset_m = offsetM(u_px, v_px);
    grey = face_grey_(frame_->rgb.ptr<cv::Vec3b>(v_px)[u_px]);
  }

  /// Whether (u, v) was computed ahead.
  bool stored(int u_px, int v_px) const
  {
    std::size_t at = 0;
    return storedAt(u_px, v_px, at);
  }
  /// How many pixels were computed ahead.
  std::size_t storedCount() const { return offset_m_.size(); }
  /// The weighting grey levels are read in.
  const FaceGrey& faceGrey() const { return face_grey_; }
  /// The mean grey level of the computed pixels within a centimetre of the
  /// plane (the face's own mean colour in its grey); 0 without such pixels.
  double meanFaceGrey() const { return mean_face_grey_; }

private:
  /// Row v's stored pixels: u in [u_begin, u_end), from offset_m_[first] on.
  struct RowSpan
  {
    int u_begin = 0, u_end = 0;
    std::size_t first = 0;
  };

  /// Whether (u, v) was computed ahead, and where it is stored.
  bool storedAt(int u_px, int v_px, std::size_t& at) const
  {
    const int row = v_px - v_begin_;
    if (row < 0 || row >= static_cast<int>(rows_.size())) return false;
    const RowSpan& span = rows_[static_cast<std::size_t>(row)];
    if (u_px < span.u_begin || u_px >= span.u_end) return false;
    at = span.first + static_cast<std::size_t>(u_px - span.u_begin);
    return true;
  }

  /// Signed distance of the pixel's depth from the plane; NaN without depth.
  double offsetM(int u_px, int v_px) const;

  const RgbdFrame* frame_ = nullptr;
  PlaneFit plane_;
  int v_begin_ = 0;
  std::vector<RowSpan> rows_;  ///< rows v_begin_, v_begin_ + 1, ...
  std::vector<double> offset_m_;
  std::vector<float> grey_;
  FaceGrey face_grey_;
  double mean_face_grey_ = 0.0;
};
}  // namespace brick_pose
