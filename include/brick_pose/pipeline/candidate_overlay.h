#pragma once
// A picture of what the front end decided, for rviz and for people: accepted
// faces with their least-area quad, T1, T2 and centre (green when complete,
// amber when partial); dropped segments boxed with the category of the
// reason. One label per segment, on a dark band, inside the image and clear
// of the others.

#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/pipeline/front_end.h"

namespace brick_pose
{
/// Draws `result` over a copy of `rgb` (CV_8UC3, RGB order); returns the
/// copy. `label_boxes` (optional) receives where each label went.
cv::Mat drawCandidateOverlay(const cv::Mat& rgb, const FrontEndResult& result,
                             std::vector<cv::Rect>* label_boxes = nullptr);
}  // namespace brick_pose
