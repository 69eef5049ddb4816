// rostest: frames, segments and candidates travel between the pipeline's
// nodelets as shared pointers to one object, never serialised or copied.

#include <gtest/gtest.h>

#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "brick_pose/BrickDetectionArray.h"

TEST(PipelineZeroCopy, DownstreamStagesReceiveTheUpstreamObjects)
{
  // Let the chain run until some bricks came out of it.
  int frames_with_bricks = 0;
  for (int i = 0; i < 100 && frames_with_bricks < 5; ++i)
  {
    const auto detections =
        ros::topic::waitForMessage<brick_pose::BrickDetectionArray>("/brick_pose/detections", ros::Duration(30.0));
    ASSERT_NE(detections, nullptr) << "the pipeline published no detections";
    if (!detections->detections.empty()) ++frames_with_bricks;
  }
  ASSERT_GE(frames_with_bricks, 5);
  ASSERT_TRUE(ros::service::waitForService("/brick_pose/zero_copy_probe/report", ros::Duration(10.0)));
  std_srvs::Trigger report;
  ASSERT_TRUE(ros::service::call("/brick_pose/zero_copy_probe/report", report));
  EXPECT_TRUE(report.response.success) << report.response.message;
  RecordProperty("probe", report.response.message);
  std::printf("zero-copy probe: %s\n", report.response.message.c_str());
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "pipeline_zero_copy_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
