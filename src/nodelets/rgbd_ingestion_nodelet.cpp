// brick_pose/RgbdIngestion: stage 1. Synchronises a D415's aligned colour,
// aligned depth and camera_info (realsense2_camera names under ~camera_ns,
// remappable; image_transport for the images), validates them and publishes
// one FrameMessage on `frame`, in-process. With ~up_frame set (e.g.
// base_link, whose +z points up), each frame carries "up" in the camera
// frame from tf, for the front end's top-face check. With ~support_frame set
// (a frame whose xy-plane the pile stands on: a pallet's deck, a table),
// each frame carries that plane too (and up, its +z, when up_frame is not
// set): colour-free, a face's height above it tells boxes that share a top
// apart.
//
// Depth 16UC1 (mm) and 32FC1 (m) are accepted. A bad frame (wrong encoding,
// size mismatch, unusable camera_info, no valid depth, stamp going backwards)
// is dropped with a throttled error that names the problem. Stamps that go
// back to a bag's start (a looped or restarted bag, or /clock going back)
// start a new sequence.

#include <image_transport/image_transport.h>
#include <image_transport/subscriber_filter.h>
#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/synchronizer.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/frame/stamp_order.h"
#include "brick_pose/roi/up_direction.h"
#include "brick_pose/ros/camera_topics.h"
#include "brick_pose/ros/conversions.h"
#include "brick_pose/ros/stage_nodelet.h"

namespace brick_pose
{
namespace
{
ImageView viewOf(const sensor_msgs::Image& image)
{
  ImageView view;
  view.data = image.data.data();
  view.width_px = static_cast<int>(image.width);
  view.height_px = static_cast<int>(image.height);
  view.step_bytes = image.step;
  view.encoding = image.encoding;
  return view;
}

/// Throws InputError when the message's buffer is shorter than its header says.
void checkBuffer(const sensor_msgs::Image& image, const char* which)
{
  if (image.data.size() < static_cast<std::size_t>(image.step) * image.height)
    throw InputError(std::string(which) + " image: buffer of " + std::to_string(image.data.size()) +
                     " bytes is shorter than step x height = " + std::to_string(std::size_t(image.step) * image.height));
}
}  // namespace

class RgbdIngestionNodelet : public StageNodelet
{
  using SyncPolicy = message_filters::sync_policies::ApproximateTime<sensor_msgs::Image, sensor_msgs::Image,
                                                                     sensor_msgs::CameraInfo>;

public:
  RgbdIngestionNodelet() : StageNodelet("ingestion") {}

private:
  void initStage(const ParamLookup& lookup) override
  {
    // The camera's namespace (realsense2_camera's "camera"); a child of the
    // stage's node handle, so the stage's remappings apply to its topics.
    const std::string camera_ns = lookup("camera_ns").value_or("/camera");
    up_frame_ = lookup("up_frame").value_or("");
    support_frame_ = lookup("support_frame").value_or("");
    const int queue_size = std::max(stageParams().queue_size, 5);  // the synchroniser needs some slack
    ros::NodeHandle camera_node(node(), camera_ns);
    camera_transport_ = std::make_unique<image_transport::ImageTransport>(camera_node);
    color_subscriber_.subscribe(*camera_transport_, CameraTopics::kColorImage, queue_size);
    depth_subscriber_.subscribe(*camera_transport_, CameraTopics::kDepthImage, queue_size);
    info_subscriber_.subscribe(camera_node, CameraTopics::kColorInfo, queue_size);
    synchronizer_ = std::make_unique<message_filters::Synchronizer<SyncPolicy>>(
        SyncPolicy(queue_size), color_subscriber_, depth_subscriber_, info_subscriber_);
    synchronizer_->registerCallback(&RgbdIngestionNodelet::onFrame, this);
    frame_publisher_ = advertiseOutput<FrameMessage>("frame");
    if (!up_frame_.empty() || !support_frame_.empty())
    {
      tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
      tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_);
    }
    watchInputs(camera_node);
    NODELET_INFO("ingesting %s/{%s, %s, %s}%s", camera_node.getNamespace().c_str(), CameraTopics::kColorImage,
                 CameraTopics::kDepthImage, CameraTopics::kColorInfo,
                 (up_frame_.empty() && support_frame_.empty() ? "; no up_frame: up is inferred from the scene"
                  : !up_frame_.empty()                        ? "; up is +z of " + up_frame_
                                                              : "; up is +z of " + support_frame_)
                     .c_str());
    if (!support_frame_.empty())
      NODELET_INFO("the pile stands on the xy-plane of %s (support_frame)", support_frame_.c_str());
  }

  /// The synchroniser is silent when one input is missing; these light
  /// subscriptions (shared pointers, no copies) tell the user which one.
  void watchInputs(ros::NodeHandle& camera_node)
  {
    const auto stamp_now = [](ros::WallTime& last) { return [&last](const auto&) { last = ros::WallTime::now(); }; };
    watch_subscribers_.push_back(camera_node.subscribe<sensor_msgs::Image>(CameraTopics::kColorImage, 1,
                                                                           stamp_now(last_color_)));
    watch_subscribers_.push_back(camera_node.subscribe<sensor_msgs::Image>(CameraTopics::kDepthImage, 1,
                                                                           stamp_now(last_depth_)));
    watch_subscribers_.push_back(camera_node.subscribe<sensor_msgs::CameraInfo>(CameraTopics::kColorInfo, 1,
                                                                                stamp_now(last_info_)));
    watchdog_ = camera_node.createWallTimer(ros::WallDuration(2.0), &RgbdIngestionNodelet::checkInputs, this);
    camera_ns_ = camera_node.getNamespace();
  }

  void checkInputs(const ros::WallTimerEvent&)
  {
    const ros::WallTime now = ros::WallTime::now();
    const auto recent = [&now](const ros::WallTime& last) { return !last.isZero() && (now - last).toSec() < 2.0; };
    if (!recent(last_color_) && !recent(last_depth_)) return;  // camera off: nothing to say every 2 s
    if (!recent(last_color_))
      NODELET_ERROR_THROTTLE(10.0, "no colour image on %s/%s: frames cannot be built", camera_ns_.c_str(),
                             CameraTopics::kColorImage);
    if (!recent(last_depth_))
      NODELET_ERROR_THROTTLE(10.0, "no aligned depth on %s/%s (is align_depth enabled?)", camera_ns_.c_str(),
                             CameraTopics::kDepthImage);
    if (!recent(last_info_))
      NODELET_ERROR_THROTTLE(10.0, "no camera_info on %s/%s: frames cannot be built", camera_ns_.c_str(),
                             CameraTopics::kColorInfo);
    if (recent(last_color_) && recent(last_depth_) && recent(last_info_) && !recent(last_frame_))
      NODELET_ERROR_THROTTLE(10.0, "colour, depth and camera_info arrive but no synchronised frame for 2 s: "
                             "their stamps do not match, or every frame is rejected (see errors above)");
  }

  void onFrame(const sensor_msgs::ImageConstPtr& color, const sensor_msgs::ImageConstPtr& depth,
               const sensor_msgs::CameraInfoConstPtr& info)
  {
    const ros::WallTime arrival = ros::WallTime::now();
    frameIn();
    try
    {
      publish(buildFrame(*color, *depth, *info), arrival);
    }
    catch (const InputError& e)
    {
      frameDropped(rejection_category_);
      NODELET_ERROR_THROTTLE(2.0, "dropping frame %u.%09u: %s", color->header.stamp.sec, color->header.stamp.nsec,
                             e.what());
    }
  }

  boost::shared_ptr<FrameMessage> buildFrame(const sensor_msgs::Image& color, const sensor_msgs::Image& depth,
                                             const sensor_msgs::CameraInfo& info)
  {
    rejection_category_ = "invalid input";
    checkBuffer(color, "colour");
    checkBuffer(depth, "depth");
    auto message = boost::make_shared<FrameMessage>();
    message->header = color.header;
    FrameHeader header;
    header.stamp_ns = static_cast<std::int64_t>(color.header.stamp.toNSec());
    header.frame_id = color.header.frame_id;
    message->frame = makeRgbdFrame(viewOf(color), viewOf(depth), ros_conversions::fromCameraInfo(info), header);
    admitStamp(color.header.stamp);
    message->frame.up_in_camera = upInCamera(color.header);
    message->frame.support_in_camera = supportInCamera(color.header);
    if (!message->frame.up_in_camera && message->frame.support_in_camera)
      message->frame.up_in_camera = message->frame.support_in_camera->head<3>();
    return message;
  }

  void admitStamp(const ros::Time& stamp)
  {
    // rosbag play --clock restarts /clock with every loop of the bag.
    const ros::Time now = ros::Time::now();
    const bool clock_went_back = !last_clock_.isZero() && now < last_clock_;
    last_clock_ = now;
    switch (stamp_order_.admit(static_cast<std::int64_t>(stamp.toNSec()), clock_went_back))
    {
      case StampOrder::Verdict::kOutOfOrder:
        rejection_category_ = "late or duplicated";
        throw InputError("stamp " + std::to_string(stamp.toSec()) + " is not after the previous frame's " +
                         std::to_string(stamp_order_.lastStampNs() * 1e-9) + " (late or duplicated frame)");
      case StampOrder::Verdict::kRestarted:
        NODELET_INFO("time went back to %.3f: a looped or restarted bag; starting a new sequence", stamp.toSec());
        break;
      case StampOrder::Verdict::kInOrder:
        break;
    }
  }

  /// +z of up_frame in the camera frame at the frame's stamp (the latest
  /// transform when none at that stamp); nothing without up_frame or tf.
  std::optional<Eigen::Vector3d> upInCamera(const std_msgs::Header& header)
  {
    const std::optional<Eigen::Isometry3d> camera_T_up = cameraTransform(header, up_frame_, "up_frame");
    if (!camera_T_up) return std::nullopt;
    return camera_T_up->linear().col(2);
  }

  /// The xy-plane of support_frame in the camera frame, as (n, d) with
  /// n . p + d = 0 and n its +z; nothing without support_frame or tf.
  std::optional<Eigen::Vector4d> supportInCamera(const std_msgs::Header& header)
  {
    const std::optional<Eigen::Isometry3d> camera_T_support =
        cameraTransform(header, support_frame_, "support_frame");
    if (!camera_T_support) return std::nullopt;
    return xyPlaneInCamera(*camera_T_support);
  }

  /// The pose of `target` in the camera frame at the frame's stamp (the
  /// latest transform when none at that stamp); nothing when `target` is
  /// empty or tf has no transform (a throttled warning naming `param`).
  std::optional<Eigen::Isometry3d> cameraTransform(const std_msgs::Header& header, const std::string& target,
                                                   const char* param)
  {
    if (!tf_buffer_ || target.empty()) return std::nullopt;
    try
    {
      const ros::Time stamp =
          tf_buffer_->canTransform(header.frame_id, target, header.stamp) ? header.stamp : ros::Time(0);
      return tf2::transformToEigen(tf_buffer_->lookupTransform(header.frame_id, target, stamp));
    }
    catch (const tf2::TransformException& e)
    {
      NODELET_WARN_THROTTLE(10.0, "no tf from %s to %s %s (%s): %s", header.frame_id.c_str(), param, target.c_str(),
                            e.what(),
                            std::string(param) == "up_frame" ? "up is inferred from the scene"
                                                             : "boxes are not typed by their height above it");
      return std::nullopt;
    }
  }

  void publish(const boost::shared_ptr<FrameMessage>& message, const ros::WallTime& arrival)
  {
    message->arrival = arrival;
    message->sequence = next_sequence_++;
    last_frame_ = arrival;
    frame_publisher_.publish(boost::shared_ptr<const FrameMessage>(message));
    frameOut(*message, (ros::WallTime::now() - arrival).toSec() * 1e3);
  }

  StampOrder stamp_order_;
  ros::Time last_clock_;
  std::uint64_t next_sequence_ = 0;
  const char* rejection_category_ = "invalid input";
  std::string up_frame_;
  std::string support_frame_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  std::string camera_ns_;
  std::vector<ros::Subscriber> watch_subscribers_;
  ros::WallTimer watchdog_;
  ros::WallTime last_color_, last_depth_, last_info_, last_frame_;
  std::unique_ptr<image_transport::ImageTransport> camera_transport_;
  image_transport::SubscriberFilter color_subscriber_;
  image_transport::SubscriberFilter depth_subscriber_;
  message_filters::Subscriber<sensor_msgs::CameraInfo> info_subscriber_;
  std::unique_ptr<message_filters::Synchronizer<SyncPolicy>> synchronizer_;
  ros::Publisher frame_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::RgbdIngestionNodelet, nodelet::Nodelet)
