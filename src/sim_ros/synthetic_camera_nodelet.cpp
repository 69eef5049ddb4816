// brick_pose/SyntheticCamera: a simulated RealSense D415 (align_depth:=true).
//
// Publishes, in its namespace (launch it in "camera" to get realsense2_camera's
// names): color/image_raw (rgb8), color/camera_info,
// aligned_depth_to_color/image_raw (16UC1, mm), aligned_depth_to_color/camera_info;
// ground truth on ~ground_truth and as tf frames truth_<type>_<n>.
//
// Rendering a 1280x720 frame costs ~0.1 s, so a few noise realisations of the
// current scene are rendered once and then cycled at ~rate_hz: the stream
// looks live (fresh noise, fresh stamps) while costing the pipeline's CPU
// almost nothing.

#include <memory>
#include <mutex>
#include <vector>

#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/ros/param_lookup.h"
#include "brick_pose/sim_ros/synthetic_frame_messages.h"
#include "brick_pose/sim/rig_config.h"

namespace brick_pose
{
class SyntheticCameraNodelet : public nodelet::Nodelet
{
private:
  void onInit() override
  {
    ros::NodeHandle& node = getNodeHandle();
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    try
    {
      readParameters(private_node);
    }
    catch (const ConfigError& e)
    {
      NODELET_ERROR("synthetic camera not started: %s", e.what());
      return;  // stays loaded and idle; the manager and its other nodelets carry on
    }
    image_transport::ImageTransport transport(node);
    color_publisher_ = transport.advertiseCamera(CameraTopics::kColorImage, 1);
    depth_publisher_ = transport.advertiseCamera(CameraTopics::kDepthImage, 1);
    truth_publisher_ = private_node.advertise<BrickTruthArray>("ground_truth", 1);
    next_scene_service_ = private_node.advertiseService("next_scene", &SyntheticCameraNodelet::nextScene, this);
    if (publish_camera_link_)
      static_broadcaster_.sendTransform(cameraLinkToOptical(ros::Time::now(), camera_link_, frame_id_));
    timer_ = node.createTimer(ros::Duration(1.0 / rate_hz_), &SyntheticCameraNodelet::tick, this);
    NODELET_INFO("synthetic D415 %dx%d at %.1f Hz, scene %s (seed %llu), lighting %s, frame %s",
                 config_.camera.width_px, config_.camera.height_px, rate_hz_, sim::toString(config_.scene.kind).c_str(),
                 static_cast<unsigned long long>(config_.seed), sim::toString(config_.sensor.lighting).c_str(),
                 frame_id_.c_str());
  }

  void readParameters(const ros::NodeHandle& private_node)
  {
    const ParamLookup lookup = [&](const std::string& name) { return paramAsText(private_node, name); };
    config_ = sim::rigConfigFrom(lookup);
    const ParamReader read(lookup);
    read.number("rate_hz", rate_hz_);
    if (!(rate_hz_ > 0.0) || rate_hz_ > 1000.0)
      throw ConfigError("parameter 'rate_hz' = " + std::to_string(rate_hz_) + " must be in (0, 1000]");
    read.integer("noise_variants", noise_variants_);
    if (noise_variants_ < 1) throw ConfigError("parameter 'noise_variants' must be >= 1");
    read.number("scene_change_period_s", scene_change_period_s_);
    if (scene_change_period_s_ < 0.0) throw ConfigError("parameter 'scene_change_period_s' must be >= 0");
    frame_id_ = lookup("frame_id").value_or(frame_id_);
    camera_link_ = lookup("camera_link").value_or(camera_link_);
    read.flag("publish_camera_link", publish_camera_link_);
    if (frame_id_.empty()) throw ConfigError("parameter 'frame_id' must not be empty");
    rig_ = std::make_unique<sim::SyntheticRig>(config_.camera, config_.sensor);
    generator_ = std::make_unique<sim::SceneGenerator>(config_.catalogue, config_.scene);
    scene_ = generator_->generate(config_.seed);
  }

  bool nextScene(std_srvs::Empty::Request&, std_srvs::Empty::Response&)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    advanceScene();
    return true;
  }

  void advanceScene()
  {
    ++config_.seed;
    scene_ = generator_->generate(config_.seed);
    frames_.clear();
    scene_started_ = ros::Time::now();
    NODELET_INFO("new scene: seed %llu, %zu bricks", static_cast<unsigned long long>(config_.seed),
                 scene_.bricks.size());
  }

  const sim::SyntheticFrame& nextFrame()
  {
    // Render the noise variants lazily, one per tick, then cycle them.
    if (static_cast<int>(frames_.size()) < noise_variants_)
    {
      const ros::WallTime start = ros::WallTime::now();
      frames_.push_back(rig_->render(scene_, config_.seed * 1000 + frames_.size()));
      NODELET_DEBUG("rendered noise variant %zu in %.1f ms", frames_.size(),
                    (ros::WallTime::now() - start).toSec() * 1e3);
      return frames_.back();
    }
    return frames_[cycle_++ % frames_.size()];
  }

  void tick(const ros::TimerEvent&)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const ros::Time now = ros::Time::now();
    if (scene_started_.isZero()) scene_started_ = now;
    if (scene_change_period_s_ > 0.0 && (now - scene_started_).toSec() >= scene_change_period_s_) advanceScene();
    const SyntheticFrameMessages messages = toMessages(nextFrame(), now, frame_id_);
    color_publisher_.publish(messages.color, messages.color_info);
    depth_publisher_.publish(messages.depth, messages.depth_info);
    truth_publisher_.publish(messages.truth);
    if (!messages.truth_frames.empty()) broadcaster_.sendTransform(messages.truth_frames);
  }

  sim::RigConfig config_;
  double rate_hz_ = 15.0;
  int noise_variants_ = 4;
  double scene_change_period_s_ = 0.0;
  std::string frame_id_ = "camera_color_optical_frame";
  std::string camera_link_ = "camera_link";
  bool publish_camera_link_ = true;

  std::unique_ptr<sim::SyntheticRig> rig_;
  std::unique_ptr<sim::SceneGenerator> generator_;
  std::mutex mutex_;
  sim::Scene scene_;
  std::vector<sim::SyntheticFrame> frames_;
  std::size_t cycle_ = 0;
  ros::Time scene_started_;

  image_transport::CameraPublisher color_publisher_;
  image_transport::CameraPublisher depth_publisher_;
  ros::Publisher truth_publisher_;
  ros::ServiceServer next_scene_service_;
  tf2_ros::TransformBroadcaster broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  ros::Timer timer_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::SyntheticCameraNodelet, nodelet::Nodelet)
