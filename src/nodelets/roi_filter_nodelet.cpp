// brick_pose/RoiFilter: stage 3. For each segment: cloud processing of its
// points, the OBB dimension check against the catalogue, the least-area
// quadrilateral, and its corners, T1, T2 and centre inverse-projected onto
// the fitted plane; publishes the brick candidates on `candidates`,
// in-process. What it drops is counted by reason in its summary line and
// /diagnostics, and listed one by one at debug level. `debug_image` shows
// the quads, T1/T2 and the dropped segments, and `debug_cloud` the accepted
// segments' points; both are made only when someone subscribes. Segments
// that are a keyframe's (nothing in view changed) get the keyframe's
// candidates again, filtered once.

#include <cv_bridge/cv_bridge.h>
#include <pcl_conversions/pcl_conversions.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/PointCloud2.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/pipeline/candidate_overlay.h"
#include "brick_pose/ros/stage_nodelet.h"

namespace brick_pose
{
class RoiFilterNodelet : public StageNodelet
{
public:
  RoiFilterNodelet() : StageNodelet("roi_filter", "segments", "candidates") {}

private:
  void initStage(const ParamLookup& lookup) override
  {
    front_end_ = std::make_unique<FrontEnd>(catalogueFrom(lookup), frontEndParamsFrom(lookup));
    candidates_publisher_ = advertiseOutput<CandidatesMessage>("candidates");
    debug_image_publisher_ = node().advertise<sensor_msgs::Image>("debug_image", 1);
    debug_cloud_publisher_ = node().advertise<sensor_msgs::PointCloud2>("debug_cloud", 1);
    segments_subscriber_ = subscribeInput("segments", &RoiFilterNodelet::onSegments, this);
  }

  void onSegments(const SegmentsMessageConstPtr& segments)
  {
    const FrameMessage& frame = *segments->frame;
    if (!acceptFrame(frame)) return;
    const auto start = SteadyClock::now();
    auto message = outputFor<CandidatesMessage>(*segments);
    message->frame = segments->frame;
    message->segments = segments;
    try
    {
      message->front_end = filtered(segments->keyframe ? segments->keyframe : segments);
    }
    catch (const InputError& e)
    {
      frameDropped("ROI filtration failed");
      NODELET_ERROR_THROTTLE(2.0, "dropping %s: ROI filtration failed: %s", frameLabel(frame).c_str(), e.what());
      return;
    }
    const double roi_ms = millisecondsSince(start);
    if (segments->keyframe)
    {
      message->front_end_reused = true;
      message->keyframe_stamp_ns = segments->keyframe->frame->frame.stamp_ns;
      // This frame's own cost: the scene comparison and the copy.
      message->front_end.timings = FrontEndTimings();
      message->front_end.timings.roi_ms = roi_ms;
    }
    message->front_end.timings.segmentation_ms = segments->segmentation_ms;
    message->front_end.timings.total_ms = segments->segmentation_ms + roi_ms;
    account(frame, *message);
    candidates_publisher_.publish(CandidatesMessageConstPtr(message));
    frameOut(frame, roi_ms);
    if (debug_cloud_publisher_.getNumSubscribers() > 0) publishDebugCloud(*message);
    // Drawing costs a frame copy: only for someone watching.
    if (debug_image_publisher_.getNumSubscribers() > 0)
      debug_image_publisher_.publish(
          cv_bridge::CvImage(segments->header, "rgb8", drawCandidateOverlay(frame.frame.rgb, message->front_end))
              .toImageMsg());
  }

  /// The candidates of `keyframe`'s segments (in its own frame): filtered
  /// once, then the same result again while the scene stays unchanged.
  FrontEndResult filtered(const SegmentsMessageConstPtr& keyframe)
  {
    if (keyframe == last_keyframe_) return last_result_;
    FrontEndResult result;
    front_end_->filterSegments(keyframe->frame->frame, keyframe->segments, result);
    last_keyframe_ = keyframe;
    last_result_ = result;
    return result;
  }

  /// Counts for the summary line; each rejection, with its own size and
  /// place, at debug level.
  void account(const FrameMessage& frame, const CandidatesMessage& message)
  {
    const FrontEndResult& result = message.front_end;
    itemsProcessed(static_cast<int>(result.candidates.size() + result.rejections.size()),
                   static_cast<int>(result.candidates.size()));
    for (const Rejection& rejection : result.rejections)
    {
      itemDropped(rejection.category);
      NODELET_DEBUG("%s: dropped %s segment of %d px at (%d, %d) %dx%d: %s", frameLabel(frame).c_str(),
                    rejection.type_name.empty() ? "colour-free" : rejection.type_name.c_str(), rejection.area_px,
                    rejection.bounding_box_px.x, rejection.bounding_box_px.y, rejection.bounding_box_px.width,
                    rejection.bounding_box_px.height, rejection.reason.c_str());
    }
  }

  /// The accepted segments' points, one cloud for rviz.
  void publishDebugCloud(const CandidatesMessage& message)
  {
    pcl::PointCloud<pcl::PointXYZ> merged;
    for (const BrickCandidate& candidate : message.front_end.candidates)
      if (candidate.points) merged += *candidate.points;
    sensor_msgs::PointCloud2 cloud;
    pcl::toROSMsg(merged, cloud);
    cloud.header = message.header;
    debug_cloud_publisher_.publish(cloud);
  }

  std::unique_ptr<FrontEnd> front_end_;
  SegmentsMessageConstPtr last_keyframe_;
  FrontEndResult last_result_;
  ros::Subscriber segments_subscriber_;
  ros::Publisher candidates_publisher_;
  ros::Publisher debug_image_publisher_;
  ros::Publisher debug_cloud_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::RoiFilterNodelet, nodelet::Nodelet)
