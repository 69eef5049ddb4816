// brick_pose/RgbdIngestion: stage 1. Synchronises a D415's aligned colour,
// aligned depth and camera_info (realsense2_camera names under ~camera_ns,
// remappable; image_transport for the images), validates them and publishes
// one FrameMessage on `frame`, in-process.
//
// Depth 16UC1 (mm) and 32FC1 (m) are accepted. A bad frame (wrong encoding,
// size mismatch, unusable camera_info, no valid depth, stamp going backwards)
// is dropped with a throttled error that names the problem.

#include <image_transport/image_transport.h>
#include <image_transport/subscriber_filter.h>
#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/synchronizer.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/frame/stamp_order.h"
#include "brick_pose/ros/conversions.h"
#include "brick_pose/ros/pipeline_messages.h"
#include "brick_pose/ros/camera_topics.h"

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

class RgbdIngestionNodelet : public nodelet::Nodelet
{
  using SyncPolicy = message_filters::sync_policies::ApproximateTime<sensor_msgs::Image, sensor_msgs::Image,
                                                                     sensor_msgs::CameraInfo>;

private:
  void onInit() override
  {
    ros::NodeHandle& node = getNodeHandle();
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    std::string camera_ns;
    int queue_size = 5;
    private_node.param<std::string>("camera_ns", camera_ns, "/camera");
    private_node.param("queue_size", queue_size, 5);
    queue_size = std::max(queue_size, 1);

    ros::NodeHandle camera_node(camera_ns);
    camera_transport_ = std::make_unique<image_transport::ImageTransport>(camera_node);
    color_subscriber_.subscribe(*camera_transport_, CameraTopics::kColorImage, queue_size);
    depth_subscriber_.subscribe(*camera_transport_, CameraTopics::kDepthImage, queue_size);
    info_subscriber_.subscribe(camera_node, CameraTopics::kColorInfo, queue_size);
    synchronizer_ = std::make_unique<message_filters::Synchronizer<SyncPolicy>>(
        SyncPolicy(queue_size), color_subscriber_, depth_subscriber_, info_subscriber_);
    synchronizer_->registerCallback(&RgbdIngestionNodelet::onFrame, this);
    frame_publisher_ = node.advertise<FrameMessage>("frame", 2);
    watchInputs(camera_node);
    NODELET_INFO("ingesting %s/{%s, %s, %s}", camera_node.getNamespace().c_str(), CameraTopics::kColorImage,
                 CameraTopics::kDepthImage, CameraTopics::kColorInfo);
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
    try
    {
      publish(buildFrame(*color, *depth, *info), arrival);
    }
    catch (const InputError& e)
    {
      NODELET_ERROR_THROTTLE(2.0, "dropping frame %u.%09u: %s", color->header.stamp.sec, color->header.stamp.nsec,
                             e.what());
    }
  }

  boost::shared_ptr<FrameMessage> buildFrame(const sensor_msgs::Image& color, const sensor_msgs::Image& depth,
                                             const sensor_msgs::CameraInfo& info)
  {
    checkBuffer(color, "colour");
    checkBuffer(depth, "depth");
    auto message = boost::make_shared<FrameMessage>();
    message->header = color.header;
    FrameHeader header;
    header.stamp_ns = static_cast<std::int64_t>(color.header.stamp.toNSec());
    header.frame_id = color.header.frame_id;
    message->frame =
        makeRgbdFrame(viewOf(color), viewOf(depth), ros_conversions::fromCameraInfo(info), header);
    switch (stamp_order_.admit(header.stamp_ns))
    {
      case StampOrder::Verdict::kOutOfOrder:
        throw InputError("stamp " + std::to_string(color.header.stamp.toSec()) + " is not after the previous frame's " +
                         std::to_string(stamp_order_.lastStampNs() * 1e-9) + " (late or duplicated frame)");
      case StampOrder::Verdict::kRestarted:
        NODELET_WARN("time jumped back to %.3f: a restarted or looped bag? starting over", color.header.stamp.toSec());
        break;
      case StampOrder::Verdict::kInOrder:
        break;
    }
    return message;
  }

  void publish(const boost::shared_ptr<FrameMessage>& message, const ros::WallTime& arrival)
  {
    message->arrival = arrival;
    last_frame_ = arrival;
    NODELET_DEBUG("frame %.3f ingested in %.2f ms", message->header.stamp.toSec(),
                  (ros::WallTime::now() - arrival).toSec() * 1e3);
    frame_publisher_.publish(boost::shared_ptr<const FrameMessage>(message));
  }

  StampOrder stamp_order_;
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
