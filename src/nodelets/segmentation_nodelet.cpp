// brick_pose/Segmentation: stage 2. Finds the segments of each `frame`: HSV
// thresholding of the plate colours (mode hsv, default) or colour-free
// planar regions; publishes them on `segments`, in-process.

#include <pluginlib/class_list_macros.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/ros/stage_nodelet.h"

namespace brick_pose
{
class SegmentationNodelet : public StageNodelet
{
public:
  SegmentationNodelet() : StageNodelet("segmentation") {}

private:
  void initStage(const ParamLookup& lookup) override
  {
    front_end_ = std::make_unique<FrontEnd>(catalogueFrom(lookup), frontEndParamsFrom(lookup));
    segments_publisher_ = advertiseOutput<SegmentsMessage>("segments");
    frame_subscriber_ = subscribeInput("frame", &SegmentationNodelet::onFrame, this);
    NODELET_INFO("segmentation mode %s", toString(front_end_->params().mode).c_str());
  }

  void onFrame(const FrameMessageConstPtr& frame)
  {
    if (!acceptFrame(*frame)) return;
    const auto start = SteadyClock::now();
    auto message = outputFor<SegmentsMessage>(*frame);
    message->frame = frame;
    try
    {
      message->segments = front_end_->segment(frame->frame);
    }
    catch (const InputError& e)
    {
      frameDropped("segmentation failed");
      NODELET_ERROR_THROTTLE(2.0, "dropping %s: segmentation failed: %s", frameLabel(*frame).c_str(), e.what());
      return;
    }
    message->segmentation_ms = millisecondsSince(start);
    segments_publisher_.publish(SegmentsMessageConstPtr(message));
    frameOut(*frame, message->segmentation_ms);
  }

  std::unique_ptr<FrontEnd> front_end_;
  ros::Subscriber frame_subscriber_;
  ros::Publisher segments_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::SegmentationNodelet, nodelet::Nodelet)
