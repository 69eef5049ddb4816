#include "brick_pose/roi/raised_layer.h"

#include <cstdint>

#include <opencv2/imgproc.hpp>

namespace brick_pose
{
namespace
{
cv::Mat dilated(const cv::Mat& mask, int radius_px)
{
  if (radius_px <= 0) return mask.clone();
  cv::Mat out;
  cv::dilate(mask, out, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * radius_px + 1, 2 * radius_px + 1)));
  return out;
}
}  // namespace

OutlineRing outlineRing(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box_px, int inner_px,
                        int outer_px)
{
  OutlineRing result;
  const cv::Rect image(0, 0, frame.width_px(), frame.height_px());
  const cv::Rect grown =
      cv::Rect(box_px.x - outer_px, box_px.y - outer_px, box_px.width + 2 * outer_px, box_px.height + 2 * outer_px) &
      image;
  const cv::Rect mask_in_image = box_px & image;
  if (grown.area() == 0 || mask_in_image.area() == 0) return result;
  cv::Mat placed = cv::Mat::zeros(grown.size(), CV_8UC1);
  mask(cv::Rect(mask_in_image.tl() - box_px.tl(), mask_in_image.size()))
      .copyTo(placed(cv::Rect(mask_in_image.tl() - grown.tl(), mask_in_image.size())));
  result.box_px = grown;
  result.ring = dilated(placed, outer_px);
  result.ring.setTo(0, dilated(placed, inner_px));
  return result;
}

OutlineSurroundings measureOutlineSurroundings(const RgbdFrame& frame, const Segment& segment, const PlaneFit& plane,
                                               double step_m, int inner_px, int outer_px)
{
  OutlineSurroundings surroundings;
  if (segment.mask.empty() || !plane.valid || outer_px <= inner_px) return surroundings;
  const OutlineRing ring = outlineRing(frame, segment.mask, segment.bounding_box_px, inner_px, outer_px);
  for (int y = 0; y < ring.ring.rows; ++y)
  {
    const std::uint8_t* on_ring = ring.ring.ptr<std::uint8_t>(y);
    const int v = ring.box_px.y + y;
    for (int x = 0; x < ring.ring.cols; ++x)
    {
      if (!on_ring[x]) continue;
      const int u = ring.box_px.x + x;
      const float z = frame.depthAt(u, v);
      if (!(z > 0.0f)) continue;
      const double offset_m = plane.signedDistance(frame.camera.backProject(u, v, z));
      if (offset_m < -step_m) ++surroundings.below;
      else if (offset_m > step_m) ++surroundings.above;
      else ++surroundings.level;
    }
  }
  return surroundings;
}

bool isRaisedLayer(const EdgeKinds& kinds, bool clear_of_image_border)
{
  int real_edges = 0, border_edges = 0;
  for (const EdgeKind kind : kinds)
  {
    real_edges += isRealEdge(kind) ? 1 : 0;
    border_edges += kind == EdgeKind::kImageBorder ? 1 : 0;
  }
  const bool opposite_borders = (kinds[0] == EdgeKind::kImageBorder && kinds[2] == EdgeKind::kImageBorder) ||
                                (kinds[1] == EdgeKind::kImageBorder && kinds[3] == EdgeKind::kImageBorder);
  return real_edges >= 3 || (real_edges == 2 && border_edges == 2 && opposite_borders) ||
         (clear_of_image_border && real_edges >= 2 && real_edges + border_edges == 4);
}

bool clearOfImageBorder(const Segment& segment, const RgbdFrame& frame, int margin_px)
{
  const cv::Rect& box = segment.bounding_box_px;
  return box.x >= margin_px && box.y >= margin_px && box.x + box.width <= frame.width_px() - margin_px &&
         box.y + box.height <= frame.height_px() - margin_px;
}
}  // namespace brick_pose
