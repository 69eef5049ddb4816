// brick_pose_latency: measures the running pipeline from outside. Listens to
// /brick_pose/detections for a while and reports the end-to-end latency (frame
// arrival to tf broadcast, as the PoseCorrection nodelet stamps it), the
// per-stage times, the rate of detections against the camera's rate, and
// answers to get_brick_pose calls made meanwhile. Prints one JSON line.
//
//   brick_pose_latency [--duration-s 20] [--warmup-s 3] [--service-hz 5] [--label pile_]

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
using brick_pose::mean;
using brick_pose::percentile;

/// One series per stage of the profile, in run order.
struct Samples
{
  std::mutex mutex;
  std::vector<double> latency_ms, segmentation_ms, cloud_ms, roi_ms, registration_ms, refinement_ms, other_ms;
  std::vector<double> bricks, tracked;
  int frames_with_bricks = 0;
  int camera_frames = 0;
  /// Frames whose front end was the keyframe's (nothing in view changed).
  int reused_frames = 0;

  void add(const brick_pose::BrickDetectionArray& message)
  {
    latency_ms.push_back(message.latency_ms);
    segmentation_ms.push_back(message.segmentation_ms);
    cloud_ms.push_back(message.cloud_ms);
    roi_ms.push_back(message.roi_ms);
    registration_ms.push_back(message.registration_ms);
    refinement_ms.push_back(message.refinement_ms);
    // Queues between stages, ingestion, message building and publishing.
    other_ms.push_back(message.latency_ms - message.frontend_ms - message.registration_ms - message.refinement_ms);
    bricks.push_back(static_cast<double>(message.detections.size()));
    int from_previous = 0;
    for (const auto& detection : message.detections) from_previous += detection.pose_source == "tracked" ? 1 : 0;
    tracked.push_back(from_previous);
    if (!message.detections.empty()) ++frames_with_bricks;
    if (message.front_end_reused) ++reused_frames;
  }
};

struct Options
{
  double duration_s = 20.0;
  double warmup_s = 3.0;
  double service_hz = 5.0;
  std::string label;  ///< prefix of the JSON keys, e.g. "pile_"
};

Options parseOptions(int argc, char** argv)
{
  Options options;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string flag = argv[i];
    if (flag == "--label") options.label = argv[i + 1];
    else if (flag == "--duration-s") options.duration_s = std::atof(argv[i + 1]);
    else if (flag == "--warmup-s") options.warmup_s = std::atof(argv[i + 1]);
    else if (flag == "--service-hz") options.service_hz = std::atof(argv[i + 1]);
    else std::fprintf(stderr, "brick_pose_latency: ignoring unknown option %s\n", flag.c_str());
  }
  return options;
}

void printProfile(const Samples& samples)
{
  std::printf("stage profile, ms (p50 / p95):\n");
  const std::vector<std::pair<const char*, const std::vector<double>*>> stages = {
      {"segmentation", &samples.segmentation_ms}, {"cloud processing", &samples.cloud_ms},
      {"ROI filtration", &samples.roi_ms},       {"registration", &samples.registration_ms},
      {"correction", &samples.refinement_ms},    {"queues + publishing", &samples.other_ms},
      {"frame to tf", &samples.latency_ms}};
  for (const auto& [name, values] : stages)
    std::printf("  %-20s %7.2f / %7.2f\n", name, percentile(*values, 0.5), percentile(*values, 0.95));
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "brick_pose_latency", ros::init_options::AnonymousName);
  const Options options = parseOptions(argc, argv);
  ros::NodeHandle node;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  Samples samples;
  bool recording = false;
  ros::Subscriber detections = node.subscribe<brick_pose::BrickDetectionArray>(
      "/brick_pose/detections", 50, [&](const brick_pose::BrickDetectionArrayConstPtr& message) {
        std::lock_guard<std::mutex> lock(samples.mutex);
        if (recording) samples.add(*message);
      });
  // Counting camera frames: the header only, but it needs the image message.
  ros::Subscriber camera = node.subscribe<sensor_msgs::Image>(
      "/camera/color/image_raw", 50, [&](const sensor_msgs::ImageConstPtr&) {
        std::lock_guard<std::mutex> lock(samples.mutex);
        if (recording) ++samples.camera_frames;
      });
  ros::WallDuration(options.warmup_s).sleep();
  recording = true;
  int calls = 0, answered = 0;
  std::vector<double> call_ms;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(options.duration_s);
  while (ros::ok() && ros::WallTime::now() < end)
  {
    brick_pose::GetBrickPose call;
    const ros::WallTime start = ros::WallTime::now();
    ++calls;
    if (ros::service::call("/brick_pose/get_brick_pose", call) && call.response.success) ++answered;
    call_ms.push_back((ros::WallTime::now() - start).toSec() * 1e3);
    ros::WallDuration(1.0 / options.service_hz).sleep();
  }
  recording = false;
  std::lock_guard<std::mutex> lock(samples.mutex);
  const double detection_hz = samples.latency_ms.size() / options.duration_s;
  const double camera_hz = samples.camera_frames / options.duration_s;
  std::printf("frames %zu (%.1f Hz of a %.1f Hz camera), with bricks %d, bricks per frame %.1f (%.1f tracked)\n",
              samples.latency_ms.size(), detection_hz, camera_hz, samples.frames_with_bricks, mean(samples.bricks),
              mean(samples.tracked));
  const double reused_fraction =
      samples.latency_ms.empty() ? 0.0 : static_cast<double>(samples.reused_frames) / samples.latency_ms.size();
  std::printf("latency ms: p50 %.1f p95 %.1f p99 %.1f max %.1f; front end reused (scene unchanged) in %.0f %% of frames\n",
              percentile(samples.latency_ms, 0.5), percentile(samples.latency_ms, 0.95),
              percentile(samples.latency_ms, 0.99), percentile(samples.latency_ms, 1.0), 100.0 * reused_fraction);
  printProfile(samples);
  std::printf("service: %d calls, %d answered with a pose, p95 %.1f ms\n", calls, answered, percentile(call_ms, 0.95));
  const char* l = options.label.c_str();
  std::printf("{\"%slatency_p50_ms\": %.2f, \"%slatency_p95_ms\": %.2f, \"%srate_hz\": %.2f, \"%scamera_rate_hz\": %.2f, "
              "\"%sbricks_mean\": %.2f, \"%stracked_mean\": %.2f, \"%sfrontend_p50_ms\": %.2f, "
              "\"%sregistration_p50_ms\": %.2f, \"%sservice_calls\": %d, \"%sservice_answered\": %d, "
              "\"%sservice_p95_ms\": %.2f, \"%slatency_max_ms\": %.2f, \"%sreused_fraction\": %.3f}\n",
              l, percentile(samples.latency_ms, 0.5), l, percentile(samples.latency_ms, 0.95), l, detection_hz, l,
              camera_hz, l, mean(samples.bricks), l, mean(samples.tracked), l,
              percentile(samples.segmentation_ms, 0.5) + percentile(samples.cloud_ms, 0.5) +
                  percentile(samples.roi_ms, 0.5),
              l, percentile(samples.registration_ms, 0.5), l, calls, l, answered, l, percentile(call_ms, 0.95), l,
              percentile(samples.latency_ms, 1.0), l, reused_fraction);
  return samples.latency_ms.empty() ? 1 : 0;
}
