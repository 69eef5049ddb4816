#include "brick_pose/pipeline/candidate_overlay.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace brick_pose
{
namespace
{
const cv::Scalar kComplete(40, 255, 40);  // RGB order
const cv::Scalar kPartial(255, 200, 0);
const cv::Scalar kAxis(255, 0, 255);
const cv::Scalar kRejected(255, 60, 60);
const cv::Scalar kLabelBackground(0, 0, 0);

cv::Point toPoint(const Eigen::Vector2d& pixel)
{
  return cv::Point(static_cast<int>(std::lround(pixel.x())), static_cast<int>(std::lround(pixel.y())));
}

/// Places short labels on a dark band, wholly inside the image and clear of
/// each other: a label that would cover an earlier one moves down a line
/// (then up), so piles of segments stay readable.
class LabelPlacer
{
public:
  explicit LabelPlacer(cv::Mat& image)
    : image_(image), scale_(std::clamp(image.cols / 1600.0, 0.35, 0.8)), thickness_(image.cols >= 1000 ? 2 : 1)
  {
  }

  void place(const std::string& text, cv::Point anchor, const cv::Scalar& colour)
  {
    int baseline = 0;
    const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale_, thickness_, &baseline);
    const cv::Size box(size.width + 6, size.height + baseline + 6);
    cv::Rect rect = clamped(cv::Rect(anchor, box));
    for (int step = 1; step < 40 && overlaps(rect); ++step)
    {
      const int shift = (step % 2 ? 1 : -1) * ((step + 1) / 2) * box.height;
      rect = clamped(cv::Rect(anchor + cv::Point(0, shift), box));
    }
    cv::rectangle(image_, rect, kLabelBackground, cv::FILLED);
    cv::putText(image_, text, rect.tl() + cv::Point(3, 3 + size.height), cv::FONT_HERSHEY_SIMPLEX, scale_, colour,
                thickness_, cv::LINE_AA);
    placed_.push_back(rect);
  }

  const std::vector<cv::Rect>& placed() const { return placed_; }

private:
  cv::Rect clamped(cv::Rect rect) const
  {
    rect.width = std::min(rect.width, image_.cols);
    rect.height = std::min(rect.height, image_.rows);
    rect.x = std::clamp(rect.x, 0, image_.cols - rect.width);
    rect.y = std::clamp(rect.y, 0, image_.rows - rect.height);
    return rect;
  }

  bool overlaps(const cv::Rect& rect) const
  {
    return std::any_of(placed_.begin(), placed_.end(), [&](const cv::Rect& other) { return (rect & other).area() > 0; });
  }

  cv::Mat& image_;
  double scale_;
  int thickness_;
  std::vector<cv::Rect> placed_;
};

void drawCandidate(cv::Mat& image, const BrickCandidate& candidate, LabelPlacer& labels)
{
  const cv::Scalar& colour = candidate.complete ? kComplete : kPartial;
  for (std::size_t k = 0; k < candidate.corners_px.size(); ++k)
    cv::line(image, toPoint(candidate.corners_px[k]), toPoint(candidate.corners_px[(k + 1) % candidate.corners_px.size()]),
             colour, 2, cv::LINE_AA);
  cv::line(image, toPoint(candidate.t1_px), toPoint(candidate.t2_px), kAxis, 1, cv::LINE_AA);
  for (const Eigen::Vector2d& point : {candidate.t1_px, candidate.t2_px, candidate.centroid_px})
    cv::circle(image, toPoint(point), 4, kAxis, -1, cv::LINE_AA);
  char label[96];
  std::snprintf(label, sizeof(label), "%s %.0fx%.0f mm%s", candidate.type_name.c_str(), candidate.length_m * 1e3,
                candidate.width_m * 1e3, candidate.complete ? "" : " partial");
  labels.place(label, toPoint(candidate.centroid_px) + cv::Point(8, -8), colour);
}

void drawRejection(cv::Mat& image, const Rejection& rejection, LabelPlacer& labels)
{
  cv::rectangle(image, rejection.bounding_box_px, kRejected, 1, cv::LINE_AA);
  // The category, not the whole reason (which is in the debug log): short
  // enough to stay inside the image and not cover its neighbours.
  const std::string text = (rejection.type_name.empty() ? "" : rejection.type_name + ": ") +
                           (rejection.category.empty() ? rejection.reason.substr(0, 32) : rejection.category);
  labels.place(text, rejection.bounding_box_px.tl() + cv::Point(2, 2), kRejected);
}
}  // namespace

cv::Mat drawCandidateOverlay(const cv::Mat& rgb, const FrontEndResult& result, std::vector<cv::Rect>* label_boxes)
{
  cv::Mat image = rgb.clone();
  LabelPlacer labels(image);
  for (const BrickCandidate& candidate : result.candidates)
    drawCandidate(image, candidate, labels);
  for (const Rejection& rejection : result.rejections)
    drawRejection(image, rejection, labels);
  if (label_boxes) *label_boxes = labels.placed();
  return image;
}
}  // namespace brick_pose
