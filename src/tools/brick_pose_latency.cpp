// brick_pose_latency: measures the running pipeline from outside. Listens to
// /brick_pose/detections for a while and reports the end-to-end latency (frame
// arrival to tf broadcast, as the PoseCorrection nodelet stamps it), the
// per-stage times, the rate of detections against the camera's rate, and
// answers to get_brick_pose calls made meanwhile. Prints one JSON line.
//
//   brick_pose_latency [--duration-s 20] [--warmup-s 3] [--service-hz 5]

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/GetBrickPose.h"
#include "brick_pose/common/statistics.h"

namespace
{
using brick_pose::percentile;

struct Samples
{
  std::mutex mutex;
  std::vector<double> latency_ms, frontend_ms, registration_ms, refinement_ms;
  int frames_with_bricks = 0;
  int camera_frames = 0;
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "brick_pose_latency", ros::init_options::AnonymousName);
  double duration_s = 20.0, warmup_s = 3.0, service_hz = 5.0;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string flag = argv[i];
    const double value = std::atof(argv[i + 1]);
    if (flag == "--duration-s") duration_s = value;
    else if (flag == "--warmup-s") warmup_s = value;
    else if (flag == "--service-hz") service_hz = value;
  }
  ros::NodeHandle node;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  Samples samples;
  bool recording = false;
  ros::Subscriber detections = node.subscribe<brick_pose::BrickDetectionArray>(
      "/brick_pose/detections", 50, [&](const brick_pose::BrickDetectionArrayConstPtr& message) {
        std::lock_guard<std::mutex> lock(samples.mutex);
        if (!recording) return;
        samples.latency_ms.push_back(message->latency_ms);
        samples.frontend_ms.push_back(message->frontend_ms);
        samples.registration_ms.push_back(message->registration_ms);
        samples.refinement_ms.push_back(message->refinement_ms);
        if (!message->detections.empty()) ++samples.frames_with_bricks;
      });
  // Counting camera frames: the header only, but it needs the image message.
  ros::Subscriber camera = node.subscribe<sensor_msgs::Image>(
      "/camera/color/image_raw", 50, [&](const sensor_msgs::ImageConstPtr&) {
        std::lock_guard<std::mutex> lock(samples.mutex);
        if (recording) ++samples.camera_frames;
      });
  ros::WallDuration(warmup_s).sleep();
  recording = true;
  int calls = 0, answered = 0;
  std::vector<double> call_ms;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(duration_s);
  while (ros::ok() && ros::WallTime::now() < end)
  {
    brick_pose::GetBrickPose call;
    const ros::WallTime start = ros::WallTime::now();
    ++calls;
    if (ros::service::call("/brick_pose/get_brick_pose", call) && call.response.success) ++answered;
    call_ms.push_back((ros::WallTime::now() - start).toSec() * 1e3);
    ros::WallDuration(1.0 / service_hz).sleep();
  }
  recording = false;
  std::lock_guard<std::mutex> lock(samples.mutex);
  const double detection_hz = samples.latency_ms.size() / duration_s;
  const double camera_hz = samples.camera_frames / duration_s;
  std::printf("frames %zu (%.1f Hz of a %.1f Hz camera), with bricks %d\n", samples.latency_ms.size(), detection_hz,
              camera_hz, samples.frames_with_bricks);
  std::printf("latency ms: p50 %.1f p95 %.1f | front end p50 %.1f | Super4PCS p50 %.1f | refinement p50 %.3f\n",
              percentile(samples.latency_ms, 0.5), percentile(samples.latency_ms, 0.95),
              percentile(samples.frontend_ms, 0.5), percentile(samples.registration_ms, 0.5),
              percentile(samples.refinement_ms, 0.5));
  std::printf("service: %d calls, %d answered with a pose, p95 %.1f ms\n", calls, answered, percentile(call_ms, 0.95));
  std::printf("{\"latency_p50_ms\": %.2f, \"latency_p95_ms\": %.2f, \"detection_rate_hz\": %.2f, \"camera_rate_hz\": %.2f, "
              "\"frontend_p50_ms\": %.2f, \"registration_p50_ms\": %.2f, \"service_calls\": %d, \"service_answered\": %d, "
              "\"service_p95_ms\": %.2f}\n",
              percentile(samples.latency_ms, 0.5), percentile(samples.latency_ms, 0.95), detection_hz, camera_hz,
              percentile(samples.frontend_ms, 0.5), percentile(samples.registration_ms, 0.5), calls, answered,
              percentile(call_ms, 0.95));
  return samples.latency_ms.empty() ? 1 : 0;
}
