#pragma once
// A picture of what the front end decided, for rviz and for people: accepted
// plates with their least-area quad, T1, T2 and centre; dropped segments boxed
// with the reason.

#include <opencv2/core.hpp>

#include "brick_pose/pipeline/front_end.h"

namespace brick_pose
{
/// Draws `result` over a copy of `rgb` (CV_8UC3, RGB order); returns the copy.
cv::Mat drawCandidateOverlay(const cv::Mat& rgb, const FrontEndResult& result);
}  // namespace brick_pose
