// brick_pose_demo: the client side of `make demo`. Watches the synthetic D415
// for a few seconds and prints what it publishes: topics, encodings, rates and
// the ground truth of the scene.

#include <cstdio>
#include <map>
#include <mutex>
#include <string>

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "brick_pose/BrickTruthArray.h"

namespace
{
class TopicWatch
{
public:
  TopicWatch(ros::NodeHandle& node, const std::string& topic) : topic_(topic)
  {
    subscriber_ = node.subscribe<sensor_msgs::Image>(topic, 5, [this](const sensor_msgs::ImageConstPtr& image) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (count_ == 0) first_ = ros::WallTime::now();
      last_ = ros::WallTime::now();
      ++count_;
      description_ = std::to_string(image->width) + "x" + std::to_string(image->height) + " " + image->encoding +
                     " frame " + image->header.frame_id;
    });
  }

  void print()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const double span_s = (last_ - first_).toSec();
    const double rate_hz = count_ > 1 && span_s > 0.0 ? (count_ - 1) / span_s : 0.0;
    std::printf("  %-45s %5.1f Hz  %s\n", topic_.c_str(), rate_hz, description_.c_str());
  }

private:
  std::string topic_;
  ros::Subscriber subscriber_;
  std::mutex mutex_;
  int count_ = 0;
  ros::WallTime first_, last_;
  std::string description_ = "(nothing received)";
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "brick_pose_demo", ros::init_options::AnonymousName);
  ros::NodeHandle node;
  ros::AsyncSpinner spinner(2);
  spinner.start();

  TopicWatch color(node, "/camera/color/image_raw");
  TopicWatch depth(node, "/camera/aligned_depth_to_color/image_raw");
  const auto truth = ros::topic::waitForMessage<brick_pose::BrickTruthArray>(
      "/camera/synthetic_camera/ground_truth", node, ros::Duration(20.0));
  ros::WallDuration(3.0).sleep();

  std::printf("\nThe synthetic D415 publishes (realsense2_camera names, align_depth:=true):\n");
  color.print();
  depth.print();
  std::printf("  %-45s (sensor_msgs/CameraInfo)\n", "/camera/color/camera_info");
  std::printf("  %-45s (sensor_msgs/CameraInfo)\n", "/camera/aligned_depth_to_color/camera_info");
  if (!truth)
  {
    std::printf("no ground truth received\n");
    return 1;
  }
  std::printf("\nGround truth (/camera/synthetic_camera/ground_truth and tf truth_<type>_<n>), frame %s:\n",
              truth->header.frame_id.c_str());
  std::printf("  %-16s %8s %8s %8s %9s\n", "brick", "x [m]", "y [m]", "z [m]", "visible");
  for (const auto& brick : truth->bricks)
    std::printf("  %-16s %8.3f %8.3f %8.3f %8.0f%%\n", ("truth_" + brick.type + "_" + std::to_string(brick.instance_id)).c_str(),
                brick.pose.position.x, brick.pose.position.y, brick.pose.position.z, 100.0 * brick.visible_fraction);
  return 0;
}
