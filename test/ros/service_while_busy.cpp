// rostest: get_brick_pose answers while every worker thread of the pipeline's
// nodelet manager is blocked (the WorkerStall test nodelet holds them), i.e.
// the service never waits for the pipeline. With the service on the manager's
// own queues the call below would hang until the workers are released, and
// the test fails at its deadline. The deadline is a liveness bound (a hang),
// generous enough that no machine load can reach it; it measures nothing.

#include <chrono>
#include <future>

#include <gtest/gtest.h>

#include <ros/ros.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/GetBrickPose.h"

namespace
{
const char* const kService = "/brick_pose/get_brick_pose";
const char* const kStall = "/worker_stall";
constexpr std::chrono::seconds kHangDeadline(30);

int param(const std::string& name)
{
  int value = -1;
  ros::param::get(std::string(kStall) + "/" + name, value);
  return value;
}

/// Waits (wall time, without spinning) until `predicate` holds or `timeout_s` passes.
template <typename Predicate>
bool waitFor(Predicate predicate, double timeout_s)
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::WallTime::now() < end)
  {
    if (predicate()) return true;
    ros::WallDuration(0.1).sleep();
  }
  return predicate();
}

/// One service call on its own thread; nullopt when it has not returned by the deadline.
std::optional<brick_pose::GetBrickPose> callWithDeadline()
{
  auto call = std::make_shared<brick_pose::GetBrickPose>();
  call->request.policy = "nearest";
  std::future<bool> answered = std::async(std::launch::async, [call] { return ros::service::call(kService, *call); });
  if (answered.wait_for(kHangDeadline) != std::future_status::ready)
  {
    // Let the workers go so that the hung call (and the test) can end.
    ros::param::set(std::string(kStall) + "/stall", false);
    answered.wait();
    return std::nullopt;
  }
  if (!answered.get()) return std::nullopt;
  return *call;
}

brick_pose::GetBrickPose::Response firstSuccess()
{
  brick_pose::GetBrickPose call;
  call.request.policy = "nearest";
  for (int attempt = 0; attempt < 300; ++attempt)
  {
    if (ros::service::call(kService, call) && call.response.success) break;
    ros::WallDuration(0.1).sleep();
  }
  return call.response;
}
}  // namespace

TEST(ServiceWhileBusy, AnswersWhileEveryManagerWorkerIsBlocked)
{
  ASSERT_TRUE(ros::service::waitForService(kService, ros::Duration(60.0)));
  const brick_pose::GetBrickPose::Response before = firstSuccess();
  ASSERT_TRUE(before.success) << "the pipeline never detected the brick: " << before.message;

  int worker_count = 0;
  ASSERT_TRUE(ros::param::get(std::string(kStall) + "/worker_count", worker_count));
  ros::param::set(std::string(kStall) + "/stall", true);
  ASSERT_TRUE(waitFor([&] { return param("blocked_workers") == worker_count; }, 60.0))
      << "only " << param("blocked_workers") << " of " << worker_count << " workers could be blocked";

  for (int call_index = 0; call_index < 5; ++call_index)
  {
    const std::optional<brick_pose::GetBrickPose> call = callWithDeadline();
    ASSERT_TRUE(call) << "call " << call_index << " hung while the manager's workers were busy";
    EXPECT_TRUE(call->response.success) << call->response.message;
    EXPECT_EQ(call->response.frame, before.frame);
  }
  EXPECT_EQ(param("blocked_workers"), worker_count) << "the workers were released before the calls ended";

  // Released, the pipeline carries on: fresh detections arrive.
  ros::param::set(std::string(kStall) + "/stall", false);
  ASSERT_TRUE(waitFor([&] { return param("blocked_workers") == 0; }, 60.0));
  const auto fresh =
      ros::topic::waitForMessage<brick_pose::BrickDetectionArray>("/brick_pose/detections", ros::Duration(30.0));
  ASSERT_TRUE(fresh);
  EXPECT_GT(fresh->header.stamp, before.frame_stamp);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "service_while_busy_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
