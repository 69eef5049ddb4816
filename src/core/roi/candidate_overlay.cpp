#include "brick_pose/roi/candidate_overlay.h"

#include <opencv2/imgproc.hpp>

namespace brick_pose
{
namespace
{
const cv::Scalar kAccepted(40, 255, 40);  // RGB order
const cv::Scalar kAxis(255, 0, 255);
const cv::Scalar kRejected(255, 60, 60);

cv::Point toPoint(const Eigen::Vector2d& pixel)
{
  return cv::Point(static_cast<int>(std::lround(pixel.x())), static_cast<int>(std::lround(pixel.y())));
}

void drawCandidate(cv::Mat& image, const BrickCandidate& candidate)
{
  for (std::size_t k = 0; k < candidate.corners_px.size(); ++k)
    cv::line(image, toPoint(candidate.corners_px[k]), toPoint(candidate.corners_px[(k + 1) % candidate.corners_px.size()]),
             kAccepted, 2, cv::LINE_AA);
  cv::line(image, toPoint(candidate.t1_px), toPoint(candidate.t2_px), kAxis, 1, cv::LINE_AA);
  for (const Eigen::Vector2d& point : {candidate.t1_px, candidate.t2_px, candidate.centroid_px})
    cv::circle(image, toPoint(point), 4, kAxis, -1, cv::LINE_AA);
  char label[96];
  std::snprintf(label, sizeof(label), "%s %.0fx%.0f mm", candidate.type_name.c_str(), candidate.length_m * 1e3,
                candidate.width_m * 1e3);
  cv::putText(image, label, toPoint(candidate.centroid_px) + cv::Point(8, -8), cv::FONT_HERSHEY_SIMPLEX, 0.6,
              kAccepted, 2, cv::LINE_AA);
}

void drawRejection(cv::Mat& image, const Rejection& rejection)
{
  cv::rectangle(image, rejection.bounding_box_px, kRejected, 1, cv::LINE_AA);
  const std::string text = (rejection.type_name.empty() ? "" : rejection.type_name + ": ") + rejection.reason;
  cv::putText(image, text.substr(0, 60), rejection.bounding_box_px.tl() + cv::Point(2, 16), cv::FONT_HERSHEY_SIMPLEX,
              0.45, kRejected, 1, cv::LINE_AA);
}
}  // namespace

cv::Mat drawCandidateOverlay(const cv::Mat& rgb, const FrontEndResult& result)
{
  cv::Mat image = rgb.clone();
  for (const Rejection& rejection : result.rejections)
    drawRejection(image, rejection);
  for (const BrickCandidate& candidate : result.candidates)
    drawCandidate(image, candidate);
  return image;
}
}  // namespace brick_pose
