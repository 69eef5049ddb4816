// brick_pose/RoiFilter: stage 4 (with the per-segment cloud processing of
// stage 2). Checks each segment's OBB against the catalogue, fits the
// least-area quadrilateral, inverse-projects its corners, T1, T2 and centre;
// publishes the brick candidates on `candidates`, in-process. Dropped
// segments are logged at debug level with the reason. `debug_image` shows
// the quads, T1/T2 and the dropped segments, and `debug_cloud` the accepted
// segments' points; both are made only when someone subscribes.

#include <nodelet/nodelet.h>
#include <pcl_conversions/pcl_conversions.h>
#include <sensor_msgs/PointCloud2.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/roi/candidate_overlay.h"
#include "brick_pose/ros/conversions.h"
#include "brick_pose/ros/param_lookup.h"
#include "brick_pose/ros/pipeline_messages.h"

namespace brick_pose
{
class RoiFilterNodelet : public nodelet::Nodelet
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
      NODELET_ERROR("ROI filter not started: %s", e.what());
      return;
    }
    node.param("max_latency_ms", max_latency_ms_, 3000.0);
    candidates_publisher_ = node.advertise<CandidatesMessage>("candidates", 2);
    debug_image_publisher_ = node.advertise<sensor_msgs::Image>("debug_image", 1);
    debug_cloud_publisher_ = node.advertise<sensor_msgs::PointCloud2>("debug_cloud", 1);
    segments_subscriber_ = node.subscribe("segments", 2, &RoiFilterNodelet::onSegments, this);
  }

  void onSegments(const SegmentsMessageConstPtr& segments)
  {
    if (frameAgeMs(*segments->frame) > max_latency_ms_)
    {
      NODELET_WARN_THROTTLE(2.0, "dropping frame %.3f: %.0f ms old before ROI filtration, over the %.0f ms latency budget",
                            segments->header.stamp.toSec(), frameAgeMs(*segments->frame), max_latency_ms_);
      return;
    }
    const ros::WallTime start = ros::WallTime::now();
    auto message = boost::make_shared<CandidatesMessage>();
    message->header = segments->header;
    message->frame = segments->frame;
    message->segments = segments;
    message->front_end.timings.segmentation_ms = segments->segmentation_ms;
    try
    {
      front_end_->filterSegments(segments->frame->frame, segments->segments, message->front_end);
    }
    catch (const InputError& e)
    {
      NODELET_ERROR_THROTTLE(2.0, "dropping frame %.3f: ROI filtration failed: %s", segments->header.stamp.toSec(),
                             e.what());
      return;
    }
    const double roi_ms = (ros::WallTime::now() - start).toSec() * 1e3;
    message->front_end.timings.total_ms = segments->segmentation_ms + roi_ms;
    for (const Rejection& rejection : message->front_end.rejections)
      NODELET_DEBUG("frame %.3f: dropped %s segment of %d px at (%d, %d): %s", segments->header.stamp.toSec(),
                    rejection.type_name.empty() ? "colour-free" : rejection.type_name.c_str(), rejection.area_px,
                    rejection.bounding_box_px.x, rejection.bounding_box_px.y, rejection.reason.c_str());
    NODELET_DEBUG("frame %.3f: %zu candidates, %zu rejected, front end %.1f ms", segments->header.stamp.toSec(),
                  message->front_end.candidates.size(), message->front_end.rejections.size(),
                  message->front_end.timings.total_ms);
    candidates_publisher_.publish(CandidatesMessageConstPtr(message));
    if (debug_cloud_publisher_.getNumSubscribers() > 0) publishDebugCloud(*message);
    // Drawing costs a frame copy: only for someone watching.
    if (debug_image_publisher_.getNumSubscribers() > 0)
      debug_image_publisher_.publish(ros_conversions::toImageMessage(
          drawCandidateOverlay(segments->frame->frame.rgb, message->front_end), "rgb8", segments->header));
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
  double max_latency_ms_ = 3000.0;
  ros::Subscriber segments_subscriber_;
  ros::Publisher candidates_publisher_;
  ros::Publisher debug_image_publisher_;
  ros::Publisher debug_cloud_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::RoiFilterNodelet, nodelet::Nodelet)
