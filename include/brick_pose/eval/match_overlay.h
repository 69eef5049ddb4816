#pragma once
// Debug picture of one frame's candidates as the matcher judged them: the
// colour image dimmed, each truth top outlined (green whole, orange not,
// yellow uncertain), each candidate's quad drawn in the colour of its
// outcome (green a whole top, red a false complete, grey anything else
// not marked complete) with a short label.

#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/eval/candidate_matching.h"
#include "brick_pose/eval/scene_truth.h"
#include "brick_pose/roi/brick_candidate.h"

namespace brick_pose
{
namespace eval
{
/// `rgb` is the frame's colour (R, G, B); the result is BGR for cv::imwrite.
cv::Mat drawMatchOverlay(const cv::Mat& rgb, const SceneTruth& truth, const std::vector<BrickCandidate>& candidates,
                         const FrameMatch& match, const PinholeCamera& camera);
}  // namespace eval
}  // namespace brick_pose
