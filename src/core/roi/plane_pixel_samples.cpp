#include "brick_pose/roi/plane_pixel_samples.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace brick_pose
{
namespace
{
/// The u extent of the convex polygon over rows [y_lo, y_hi]; false when it
/// does not reach them. The extent of a convex region in a band is reached
/// on its boundary, so clipping each side to the band finds it.
bool extentWithin(const std::vector<Eigen::Vector2d>& polygon, double y_lo, double y_hi, double& u_min, double& u_max)
{
  u_min = std::numeric_limits<double>::infinity();
  u_max = -u_min;
  for (std::size_t k = 0; k < polygon.size(); ++k)
  {
    const Eigen::Vector2d& a = polygon[k];
    const Eigen::Vector2d& b = polygon[(k + 1) % polygon.size()];
    const double dy = b.y() - a.y();
    double t0 = 0.0, t1 = 1.0;
    if (std::abs(dy) < 1e-12)
    {
      if (a.y() < y_lo || a.y() > y_hi) continue;
    }
    else
    {
      double ta = (y_lo - a.y()) / dy, tb = (y_hi - a.y()) / dy;
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(0.0, ta);
      t1 = std::min(1.0, tb);
      if (t0 > t1) continue;
    }
    for (const double t : {t0, t1})
    {
      const double u = a.x() + t * (b.x() - a.x());
      u_min = std::min(u_min, u);
      u_max = std::max(u_max, u);
    }
  }
  return u_min <= u_max;
}

/// floor(value) + offset as an index in [lo, hi]: clamped before the cast,
/// so a corner projected from near the camera plane cannot overflow it.
int clampedFloor(double value, int offset, int lo, int hi)
{
  return static_cast<int>(std::clamp(std::floor(value) + offset, static_cast<double>(lo), static_cast<double>(hi)));
}

int clampedCeil(double value, int offset, int lo, int hi)
{
  return static_cast<int>(std::clamp(std::ceil(value) + offset, static_cast<double>(lo), static_cast<double>(hi)));
}

bool allFinite(const std::vector<Eigen::Vector2d>& points)
{
  return std::all_of(points.begin(), points.end(), [](const Eigen::Vector2d& p) { return p.allFinite(); });
}
}  // namespace

PlanePixelSamples::PlanePixelSamples(const RgbdFrame& frame, const PlaneFit& plane,
                                     const std::vector<Eigen::Vector2d>& outline_px, int margin_px)
  : frame_(&frame), plane_(plane)
{
  const int width = frame.width_px(), height = frame.height_px();
  const bool whole_image = outline_px.empty() || !allFinite(outline_px);
  int v_end = height;
  if (!whole_image)
  {
    double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
    for (const Eigen::Vector2d& p : outline_px)
    {
      y_min = std::min(y_min, p.y());
      y_max = std::max(y_max, p.y());
    }
    v_begin_ = clampedFloor(y_min, -margin_px, 0, height);
    v_end = clampedCeil(y_max, margin_px + 1, v_begin_, height);
  }
  rows_.resize(static_cast<std::size_t>(v_end - v_begin_));
  std::size_t total = 0;
  for (int v = v_begin_; v < v_end; ++v)
  {
    RowSpan& span = rows_[static_cast<std::size_t>(v - v_begin_)];
    span.first = total;
    if (whole_image)
      span.u_end = width;
    else if (double u_min, u_max; extentWithin(outline_px, v - margin_px - 0.5, v + margin_px + 0.5, u_min, u_max))
    {
      span.u_begin = clampedFloor(u_min, -margin_px, 0, width);
      span.u_end = clampedCeil(u_max, margin_px + 1, span.u_begin, width);
    }
    total += static_cast<std::size_t>(span.u_end - span.u_begin);
  }
  // Filled in order, never zeroed first. The depth first: the pixels on the
  // face give the colour the grey levels are weighted by.
  offset_m_.reserve(total);
  FaceColourSum on_face;
  for (int v = v_begin_; v < v_end; ++v)
  {
    const RowSpan& span = rows_[static_cast<std::size_t>(v - v_begin_)];
    const cv::Vec3b* row = frame.rgb.ptr<cv::Vec3b>(v);
    for (int u = span.u_begin; u < span.u_end; ++u)
    {
      const double offset_m = offsetM(u, v);
      offset_m_.push_back(offset_m);
      if (std::abs(offset_m) < kFaceColourOnPlaneM) on_face.add(row[u]);
    }
  }
  face_grey_ = on_face.grey();
  mean_face_grey_ = face_grey_(on_face.mean());
  grey_.reserve(total);
  for (int v = v_begin_; v < v_end; ++v)
  {
    const RowSpan& span = rows_[static_cast<std::size_t>(v - v_begin_)];
    const cv::Vec3b* row = frame.rgb.ptr<cv::Vec3b>(v);
    for (int u = span.u_begin; u < span.u_end; ++u) grey_.push_back(static_cast<float>(face_grey_(row[u])));
  }
}

double PlanePixelSamples::offsetM(int u_px, int v_px) const
{
  const float z = frame_->depthAt(u_px, v_px);
  return std::isnan(z) ? std::numeric_limits<double>::quiet_NaN()
                       : plane_.signedDistance(frame_->camera.backProject(u_px, v_px, z));
}
}  // namespace brick_pose
