// The debug image's labels: one per segment, inside the image, not on top of
// each other, whatever the segments' places.

#include <gtest/gtest.h>

#include "brick_pose/pipeline/candidate_overlay.h"

namespace brick_pose
{
TEST(CandidateOverlay, LabelsStayInsideTheImageAndApart)
{
  const cv::Mat rgb(480, 640, CV_8UC3, cv::Scalar(90, 90, 90));
  FrontEndResult result;
  // A crowd of rejected segments, some at the image's corners and edges.
  for (int i = 0; i < 12; ++i)
    result.rejections.push_back({"", cv::Rect(600 + i, 460, 40, 20), 800, "segment fills 0.63 of its quad, less than 0.85",
                                 "not a rectangle"});
  result.rejections.push_back({"red", cv::Rect(0, 0, 30, 30), 900, "red: visible part 0.1 x 0.1 m is below ...",
                               "too small a part"});
  std::vector<cv::Rect> boxes;
  const cv::Mat image = drawCandidateOverlay(rgb, result, &boxes);
  ASSERT_EQ(boxes.size(), result.rejections.size()) << "one label per segment";
  const cv::Rect inside(0, 0, image.cols, image.rows);
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    EXPECT_EQ(boxes[i] & inside, boxes[i]) << "label " << i << " leaves the image";
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      EXPECT_EQ((boxes[i] & boxes[j]).area(), 0) << "labels " << i << " and " << j << " overlap";
  }
  EXPECT_GT(cv::norm(image, rgb, cv::NORM_L1), 0.0);
}
}  // namespace brick_pose
