// brick_pose/Segmentation: stage 2. Finds the segments of each `frame`: HSV
// thresholding of the plate colours (mode hsv, default) or colour-free
// planar regions; publishes them on `segments`, in-process. While nothing in
// view changes (SceneChange against the keyframe, the last frame it
// segmented), it segments nothing and passes the keyframe's segments on.

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
    reuse_ = frontEndReuseParamsFrom(lookup);
    segments_publisher_ = advertiseOutput<SegmentsMessage>("segments");
    frame_subscriber_ = subscribeInput("frame", &SegmentationNodelet::onFrame, this);
    NODELET_INFO("segmentation mode %s; %s", toString(front_end_->params().mode).c_str(),
                 reuse_.enabled ? "a static scene's segments are reused" : "every frame segmented");
  }

  /// The keyframe, when `frame` shows nothing changed since it and it is
  /// young enough; otherwise null, and `frame` becomes the keyframe.
  SegmentsMessageConstPtr unchangedKeyframe(const FrameMessage& frame)
  {
    if (!reuse_.enabled) return nullptr;
    SceneSignature signature = SceneSignature::of(frame.frame, reuse_.change);
    if (keyframe_)
    {
      const double age_s = static_cast<double>(frame.frame.stamp_ns - keyframe_->frame->frame.stamp_ns) * 1e-9;
      const SceneChange change = compareScenes(keyframe_signature_, signature, reuse_.change);
      const bool young = reuse_.keyframe_max_age_s <= 0.0 || (age_s >= 0.0 && age_s < reuse_.keyframe_max_age_s);
      if (!change.changed && young) return keyframe_;
      NODELET_DEBUG("%s: segmented afresh: %s", frameLabel(frame).c_str(),
                    change.changed ? change.reason.c_str() : "keyframe too old");
    }
    keyframe_signature_ = std::move(signature);
    keyframe_.reset();
    return nullptr;
  }

  void onFrame(const FrameMessageConstPtr& frame)
  {
    if (!acceptFrame(*frame)) return;
    const auto start = SteadyClock::now();
    auto message = outputFor<SegmentsMessage>(*frame);
    message->frame = frame;
    try
    {
      message->keyframe = unchangedKeyframe(*frame);
      if (!message->keyframe) message->segments = front_end_->segment(frame->frame);
    }
    catch (const InputError& e)
    {
      frameDropped("segmentation failed");
      NODELET_ERROR_THROTTLE(2.0, "dropping %s: segmentation failed: %s", frameLabel(*frame).c_str(), e.what());
      return;
    }
    message->segmentation_ms = millisecondsSince(start);
    const SegmentsMessageConstPtr published(message);
    if (reuse_.enabled && !published->keyframe) keyframe_ = published;
    segments_publisher_.publish(published);
    frameOut(*frame, message->segmentation_ms);
  }

  std::unique_ptr<FrontEnd> front_end_;
  FrontEndReuseParams reuse_;
  SceneSignature keyframe_signature_;
  SegmentsMessageConstPtr keyframe_;
  ros::Subscriber frame_subscriber_;
  ros::Publisher segments_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::SegmentationNodelet, nodelet::Nodelet)
