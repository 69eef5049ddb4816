// brick_pose/Segmentation: stage 3. HSV thresholding of the plate colours
// (mode hsv, default) or colour-free region growing (mode region_growing) on
// each `frame`; publishes the segments on `segments`, in-process.

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/ros/param_lookup.h"
#include "brick_pose/ros/pipeline_messages.h"

namespace brick_pose
{
class SegmentationNodelet : public nodelet::Nodelet
{
private:
  void onInit() override
  {
    ros::NodeHandle& node = getNodeHandle();
    const ParamLookup lookup = rosParamLookup(getPrivateNodeHandle(), node);
    try
    {
      front_end_ = std::make_unique<FrontEnd>(catalogueFrom(lookup), frontEndParamsFrom(lookup));
    }
    catch (const ConfigError& e)
    {
      NODELET_ERROR("segmentation not started: %s", e.what());
      return;
    }
    node.param("max_latency_ms", max_latency_ms_, 3000.0);
    segments_publisher_ = node.advertise<SegmentsMessage>("segments", 2);
    frame_subscriber_ = node.subscribe("frame", 2, &SegmentationNodelet::onFrame, this);
    NODELET_INFO("segmentation mode %s", toString(front_end_->params().mode).c_str());
  }

  void onFrame(const FrameMessageConstPtr& frame)
  {
    if (frameAgeMs(*frame) > max_latency_ms_)
    {
      NODELET_WARN_THROTTLE(2.0, "dropping frame %.3f: %.0f ms old before segmentation, over the %.0f ms latency budget",
                            frame->header.stamp.toSec(), frameAgeMs(*frame), max_latency_ms_);
      return;
    }
    const ros::WallTime start = ros::WallTime::now();
    auto message = boost::make_shared<SegmentsMessage>();
    message->header = frame->header;
    message->frame = frame;
    try
    {
      message->segments = front_end_->segment(frame->frame);
    }
    catch (const InputError& e)
    {
      NODELET_ERROR_THROTTLE(2.0, "dropping frame %.3f: segmentation failed: %s", frame->header.stamp.toSec(), e.what());
      return;
    }
    message->segmentation_ms = (ros::WallTime::now() - start).toSec() * 1e3;
    if (message->segments.empty())
      NODELET_DEBUG_THROTTLE(2.0, "frame %.3f: no segment of any plate colour", frame->header.stamp.toSec());
    segments_publisher_.publish(SegmentsMessageConstPtr(message));
  }

  std::unique_ptr<FrontEnd> front_end_;
  double max_latency_ms_ = 3000.0;
  ros::Subscriber frame_subscriber_;
  ros::Publisher segments_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::SegmentationNodelet, nodelet::Nodelet)
