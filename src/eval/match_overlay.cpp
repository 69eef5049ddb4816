#include "brick_pose/eval/match_overlay.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace brick_pose
{
namespace eval
{
namespace
{
cv::Point pixel(const Eigen::Vector2d& point) { return {static_cast<int>(std::lround(point.x())), static_cast<int>(std::lround(point.y()))}; }

/// Short outcome tag for the picture.
const char* tag(CandidateOutcome outcome)
{
  switch (outcome)
  {
    case CandidateOutcome::kWholeTop: return "top";
    case CandidateOutcome::kPartialTop: return "half";
    case CandidateOutcome::kHiddenTop: return "hidden";
    case CandidateOutcome::kSideFace: return "side";
    case CandidateOutcome::kOtherFace: return "other";
    case CandidateOutcome::kSupport: return "table";
    case CandidateOutcome::kMixed: return "mixed";
    case CandidateOutcome::kWrongType: return "type";
    case CandidateOutcome::kDuplicate: return "dup";
    case CandidateOutcome::kUncertainTop: return "unsure";
  }
  return "?";
}
}  // namespace

cv::Mat drawMatchOverlay(const cv::Mat& rgb, const SceneTruth& truth, const std::vector<BrickCandidate>& candidates,
                         const FrameMatch& match, const PinholeCamera& camera)
{
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  bgr *= 0.5;
  for (const FaceTruth& face : truth.faces)
  {
    if (face.role != FaceRole::kTop || !face.has_geometry) continue;
    const cv::Scalar colour = face.whole_in_view ? cv::Scalar(0, 200, 0)
                              : face.whole_uncertain ? cv::Scalar(0, 220, 220)
                                                     : cv::Scalar(0, 140, 255);
    std::vector<cv::Point> outline;
    for (const Eigen::Vector3d& corner : face.geometry.corners_m) outline.push_back(pixel(camera.project(corner)));
    cv::polylines(bgr, outline, true, colour, 1, cv::LINE_AA);
  }
  for (std::size_t c = 0; c < candidates.size() && c < match.candidates.size(); ++c)
  {
    const CandidateMatch& verdict = match.candidates[c];
    const cv::Scalar colour = verdict.outcome == CandidateOutcome::kWholeTop ? cv::Scalar(80, 255, 80)
                              : verdict.false_complete                        ? cv::Scalar(60, 60, 255)
                                                                              : cv::Scalar(200, 200, 200);
    std::vector<cv::Point> quad;
    for (const Eigen::Vector2d& corner : candidates[c].corners_px) quad.push_back(pixel(corner));
    cv::polylines(bgr, quad, true, colour, 2, cv::LINE_AA);
    const std::string label = std::string(tag(verdict.outcome)) + (verdict.complete ? " C" : " p");
    cv::putText(bgr, label, pixel(candidates[c].centroid_px), cv::FONT_HERSHEY_SIMPLEX, 0.45, colour, 1, cv::LINE_AA);
  }
  return bgr;
}
}  // namespace eval
}  // namespace brick_pose
