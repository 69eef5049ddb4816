// brick_pose/PoseCorrection: stage 5 and the product. Refines each initial
// pose (constant-time correction by default, ICP or none by ~refinement),
// gives every brick a stable identity, then publishes the frame's bricks:
//  - tf frames brick_<type>_<id>, children of the camera's optical frame;
//    an id stays with the same physical brick (pose/brick_tracker.h);
//  - `detections` (brick_pose/BrickDetectionArray) with timings and latency;
//  - `markers` (visualization_msgs/MarkerArray, only when subscribed);
//  - the `get_brick_pose` service (brick_pose/GetBrickPose), answered from
//    the latest detections on a thread of its own: the manager's workers may
//    all be busy (long frames in every stage, or a camera driver sharing the
//    manager) and a grasp planner must still get its answer. Which brick it
//    answers with is the core's rule (pose/brick_selection.h).

#include <algorithm>
#include <mutex>

#include <pluginlib/class_list_macros.hpp>
#include <ros/callback_queue.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/GetBrickPose.h"
#include "brick_pose/PoseCorrectionConfig.h"
#include "brick_pose/catalogue/resting.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/pose/brick_selection.h"
#include "brick_pose/pose/brick_tracker.h"
#include "brick_pose/ros/brick_markers.h"
#include "brick_pose/ros/conversions.h"
#include "brick_pose/ros/estimator_stage_nodelet.h"

namespace brick_pose
{
namespace
{
using ros_conversions::fromPose;

geometry_msgs::Vector3 toVector3(const Eigen::Vector3d& vector)
{
  geometry_msgs::Vector3 message;
  tf2::toMsg(vector, message);
  return message;
}

/// The selection's view of a frame's detections.
std::vector<DetectedBrick> detectedBricksOf(const BrickDetectionArray& detections)
{
  std::vector<DetectedBrick> bricks;
  for (const BrickDetection& detection : detections.detections)
  {
    DetectedBrick brick;
    brick.type_name = detection.type;
    brick.T_cam_brick = fromPose(detection.pose.pose);
    brick.dimensions_m = Eigen::Vector3d(detection.dimensions.x, detection.dimensions.y, detection.dimensions.z);
    brick.fitness = detection.fitness;
    brick.complete_face = detection.complete_face;
    brick.id = detection.id;
    bricks.push_back(brick);
  }
  return bricks;
}

std::size_t findFrame(const BrickDetectionArray& detections, const std::string& frame)
{
  for (std::size_t i = 0; i < detections.detections.size(); ++i)
    if (detections.detections[i].frame == frame) return i;
  throw InputError("no brick '" + frame + "' in the latest frame (seen: " +
                   describeBricks(detectedBricksOf(detections)) + ")");
}
}  // namespace

class PoseCorrectionNodelet : public EstimatorStageNodelet<PoseCorrectionConfig>
{
public:
  PoseCorrectionNodelet() : EstimatorStageNodelet("pose_correction", "registered", "bricks") {}

  ~PoseCorrectionNodelet() override
  {
    // Stop answering before the members the service reads go away.
    if (service_spinner_) service_spinner_->stop();
    service_.shutdown();
  }

private:
  void initStage(const ParamLookup& lookup) override
  {
    initEstimator(lookup);
    tracker_ = BrickTracker(trackerParamsFrom(lookup));
    tracked_params_ = trackedPoseParamsFrom(lookup);
    tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, getMTNodeHandle());
    detections_publisher_ = node().advertise<BrickDetectionArray>("detections", 5);
    markers_publisher_ = node().advertise<visualization_msgs::MarkerArray>("markers", 2);
    registrations_subscriber_ = subscribeInput("registrations", &PoseCorrectionNodelet::onRegistrations, this);
    advertiseService(node());
    startReconfigure();
  }

  /// The service gets its own queue and thread, not the manager's worker
  /// pool: it only reads the latest detections, so nothing the pipeline does
  /// can make it wait. (tf2's listener also runs on a thread of its own.)
  void advertiseService(const ros::NodeHandle& node)
  {
    ros::NodeHandle service_node(node);
    service_node.setCallbackQueue(&service_queue_);
    service_ = service_node.advertiseService("get_brick_pose", &PoseCorrectionNodelet::onGetBrickPose, this);
    service_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &service_queue_);
    service_spinner_->start();
    NODELET_INFO("service %s (own thread)", service_.getService().c_str());
  }

  // Refinement method and correction mode are switched live.
  PoseCorrectionConfig configOf(const BrickPoseEstimatorParams& params) const override
  {
    PoseCorrectionConfig config;
    config.refinement = toString(params.refinement);
    config.correction_mode = toString(params.correction.mode);
    config.icp_max_correspondence_m = params.icp.max_correspondence_distance_m;
    config.icp_max_iterations = params.icp.max_iterations;
    return config;
  }

  BrickPoseEstimatorParams applied(const PoseCorrectionConfig& config, BrickPoseEstimatorParams params) const override
  {
    params.refinement = parseRefinementMethod(config.refinement);
    params.correction.mode = parseCorrectionMode(config.correction_mode);
    params.icp.max_correspondence_distance_m = config.icp_max_correspondence_m;
    params.icp.max_iterations = config.icp_max_iterations;
    return params;
  }

  std::string describe(const BrickPoseEstimatorParams& params) const override
  {
    return std::string("refinement ") + toString(params.refinement) + " (correction mode " +
           toString(params.correction.mode) + ")";
  }

  void onRegistrations(const RegistrationsMessageConstPtr& registrations)
  {
    frameIn();
    const FrameMessage& frame = *registrations->candidates->frame;
    const auto start = SteadyClock::now();
    const auto& candidates = registrations->candidates->front_end.candidates;
    std::vector<BrickPoseEstimate> estimates;
    std::vector<const BrickCandidate*> refined;
    std::vector<std::string> sources;
    for (const RegisteredCandidate& registered : registrations->registered)
    {
      const BrickCandidate& candidate = candidates[registered.candidate_index];
      try
      {
        std::string source = registered.tracked ? "tracked" : "registered";
        estimates.push_back(refineTrackingMoves(candidate, registered, source));
        refined.push_back(&candidate);
        sources.push_back(source);
      }
      catch (const InputError& e)
      {
        itemDropped("not refined");
        NODELET_WARN_THROTTLE(2.0, "%s: %s brick not refined: %s", frameLabel(frame).c_str(),
                              candidate.type_name.c_str(), e.what());
      }
    }
    itemsProcessed(static_cast<int>(registrations->registered.size()), static_cast<int>(estimates.size()));
    const double refinement_ms = millisecondsSince(start);
    auto detections = makeDetections(*registrations, estimates, refined, sources);
    detections->refinement_ms = refinement_ms;
    publish(detections, frame);
  }

  /// Refines the initial pose. A tracked pose whose correction is larger
  /// than a static brick's noise says the brick moved or its pose jumped: it
  /// is registered afresh with Super4PCS and refined from there.
  BrickPoseEstimate refineTrackingMoves(const BrickCandidate& candidate, const RegisteredCandidate& registered,
                                        std::string& source)
  {
    BrickPoseEstimate estimate = estimator_->refine(candidate, registered.registration);
    if (!registered.tracked || !correctionSaysMoved(estimate.correction, tracked_params_)) return estimate;
    NODELET_DEBUG("%s brick moved (correction %.1f mm, %.2f deg): registered afresh", candidate.type_name.c_str(),
                  1e3 * estimate.correction.offset_m.norm(), estimate.correction.yawDeg());
    source = "registered (moved)";
    return estimator_->refine(candidate, estimator_->registerCandidate(candidate));
  }

  boost::shared_ptr<BrickDetectionArray> makeDetections(const RegistrationsMessage& registrations,
                                                        const std::vector<BrickPoseEstimate>& estimates,
                                                        const std::vector<const BrickCandidate*>& candidates,
                                                        const std::vector<std::string>& sources)
  {
    auto detections = boost::make_shared<BrickDetectionArray>();
    detections->header = registrations.header;
    const FrontEndTimings& timings = registrations.candidates->front_end.timings;
    detections->frontend_ms = timings.total_ms;
    detections->segmentation_ms = timings.segmentation_ms;
    detections->cloud_ms = timings.cloud.total();
    detections->roi_ms = timings.roi_ms;
    detections->registration_ms = registrations.registration_ms;
    const CandidatesMessage& front_end = *registrations.candidates;
    detections->front_end_reused = front_end.front_end_reused;
    if (front_end.front_end_reused)
      detections->front_end_age_s =
          static_cast<double>(front_end.frame->frame.stamp_ns - front_end.keyframe_stamp_ns) * 1e-9;
    std::vector<TrackerObservation> observations;
    for (const BrickPoseEstimate& estimate : estimates) observations.push_back({estimate.type_name, estimate.pose});
    const std::vector<TrackedBrick> tracked = tracker_.update(observations, registrations.header.stamp.toSec());
    for (std::size_t i = 0; i < estimates.size(); ++i)
      detections->detections.push_back(
          makeDetection(estimates[i], *candidates[i], tracked[i], sources[i], registrations.header));
    markPickable(*detections);
    return detections;
  }

  static BrickDetection makeDetection(const BrickPoseEstimate& estimate, const BrickCandidate& candidate,
                                      const TrackedBrick& tracked, const std::string& source,
                                      const std_msgs::Header& header)
  {
    BrickDetection detection;
    // A box on a side keeps its catalogue type's name: tf names one box.
    detection.type = estimate.catalogue_type;
    detection.resting = toString(estimate.resting);
    detection.id = tracked.id;
    detection.frame = "brick_" + estimate.catalogue_type + "_" + std::to_string(tracked.id);
    detection.pose.header = header;
    detection.pose.pose = tf2::toMsg(tracked.pose);
    detection.dimensions = toVector3(estimate.dimensions_m);
    detection.fitness = estimate.registration.result.lcp_score;
    detection.complete_face = candidate.complete;
    detection.partial_reason =
        candidate.complete ? "" : (candidate.partial_reason.empty() ? "top face not wholly in view" : candidate.partial_reason);
    detection.other_possible_types = candidate.other_possible_types;
    detection.pose_source = source;
    detection.registration_pose = tf2::toMsg(estimate.registration.pose);
    detection.refinement = toString(estimate.refinement);
    detection.correction_yaw_deg = estimate.correction.yawDeg();
    detection.correction_tilt_deg = estimate.correction.tiltDeg();
    detection.correction_translation_mm = toVector3(1000.0 * estimate.correction.offset_m);
    detection.registration_ms = estimate.registration.elapsed_ms;
    detection.refinement_ms = estimate.refinement_ms;
    return detection;
  }

  /// Pickable: a complete face that nothing rests on (every brick, complete
  /// or not, counts for covering).
  static void markPickable(BrickDetectionArray& detections)
  {
    const std::vector<DetectedBrick> bricks = detectedBricksOf(detections);
    if (bricks.empty()) return;
    try
    {
      const std::vector<bool> uncovered = pickableMask(bricks);
      for (std::size_t i = 0; i < bricks.size(); ++i)
        detections.detections[i].pickable = uncovered[i] && bricks[i].complete_face;
    }
    catch (const InputError&)
    {
      // No usable "up" from the bricks (e.g. they cancel out): leave pickable false.
    }
  }

  void publish(const boost::shared_ptr<BrickDetectionArray>& detections, const FrameMessage& frame)
  {
    std::vector<geometry_msgs::TransformStamped> frames;
    for (const BrickDetection& detection : detections->detections)
    {
      geometry_msgs::TransformStamped transform = tf2::eigenToTransform(fromPose(detection.pose.pose));
      transform.header = detections->header;
      transform.child_frame_id = detection.frame;
      frames.push_back(transform);
    }
    if (!frames.empty()) broadcaster_.sendTransform(frames);
    detections->latency_ms = frameAgeMs(frame);
    {
      std::lock_guard<std::mutex> lock(latest_mutex_);
      latest_ = detections;
    }
    detections_publisher_.publish(BrickDetectionArrayConstPtr(detections));
    if (markers_publisher_.getNumSubscribers() > 0)
      markers_publisher_.publish(makeBrickMarkers(*detections, catalogue_));
    NODELET_DEBUG("%s: %zu bricks, front end %.1f ms, registration %.1f ms, refinement %.3f ms, latency %.1f ms",
                  frameLabel(frame).c_str(), detections->detections.size(), detections->frontend_ms,
                  detections->registration_ms, detections->refinement_ms, detections->latency_ms);
    frameOut(frame, detections->refinement_ms);
  }

  bool onGetBrickPose(GetBrickPose::Request& request, GetBrickPose::Response& response)
  {
    response.success = false;
    try
    {
      answer(request, response);
      response.success = true;
    }
    catch (const std::exception& e)
    {
      response.message = e.what();
      NODELET_WARN_THROTTLE(1.0, "get_brick_pose(type '%s', policy '%s'): %s", request.type.c_str(),
                            request.policy.c_str(), e.what());
    }
    return true;  // the failure is in the response, not a failed call
  }

  void answer(const GetBrickPose::Request& request, GetBrickPose::Response& response) const
  {
    const SelectionPolicy policy = parseSelectionPolicy(request.policy);
    if (!request.type.empty() && catalogue_.find(request.type) == nullptr)
      throw InputError("unknown brick type '" + request.type + "' (known: " + catalogue_.namesJoined() + ")");
    BrickDetectionArrayConstPtr detections;
    {
      std::lock_guard<std::mutex> lock(latest_mutex_);
      detections = latest_;
    }
    if (!detections) throw InputError("no detections yet: is the camera publishing?");
    // ROS time: a bag's own time when one plays with --clock. rosbag
    // publishes /clock every 10 ms, so the clock can trail the newest
    // frame's stamp by a few milliseconds: that frame is new (age 0).
    const double age_s = std::max(0.0, (ros::Time::now() - detections->header.stamp).toSec());
    if (request.max_age_s > 0.0 && age_s > request.max_age_s)
      throw InputError("data too old: the latest detections are " + std::to_string(age_s) + " s old (max_age_s " +
                       std::to_string(request.max_age_s) + ")");
    const std::optional<Eigen::Isometry3d> camera_T_target = targetFrameInCamera(request.target_frame, *detections);
    std::optional<Eigen::Vector3d> up_in_camera;
    if (camera_T_target) up_in_camera = camera_T_target->linear().col(2);
    const std::vector<DetectedBrick> bricks = detectedBricksOf(*detections);
    const std::size_t chosen = request.id != 0        ? findBrickById(bricks, request.id)
                               : !request.frame.empty() ? findFrame(*detections, request.frame)
                                                        : chooseBrick(bricks, policy, request.type, up_in_camera);
    fillResponse(detections->detections[chosen], *detections, camera_T_target, request.target_frame, response);
    response.age_s = age_s;
    char age[48];
    std::snprintf(age, sizeof(age), ", from a frame %.2f s old", age_s);
    response.message += age;
  }

  /// T_camera_target when a target frame is asked for; throws when tf cannot tell.
  std::optional<Eigen::Isometry3d> targetFrameInCamera(const std::string& target_frame,
                                                       const BrickDetectionArray& detections) const
  {
    if (target_frame.empty() || target_frame == detections.header.frame_id) return std::nullopt;
    try
    {
      const geometry_msgs::TransformStamped transform = tf_buffer_->lookupTransform(
          detections.header.frame_id, target_frame, detections.header.stamp, ros::Duration(0.2));
      return tf2::transformToEigen(transform);
    }
    catch (const tf2::TransformException& e)
    {
      throw InputError("tf lookup failed from " + detections.header.frame_id + " to " + target_frame + ": " + e.what());
    }
  }

  static void fillResponse(const BrickDetection& detection, const BrickDetectionArray& detections,
                           const std::optional<Eigen::Isometry3d>& camera_T_target, const std::string& target_frame,
                           GetBrickPose::Response& response)
  {
    response.pose = detection.pose;
    if (camera_T_target)
    {
      response.pose.header.frame_id = target_frame;
      response.pose.pose = tf2::toMsg(Eigen::Isometry3d(camera_T_target->inverse() * fromPose(detection.pose.pose)));
    }
    response.type = detection.type;
    response.other_possible_types = detection.other_possible_types;
    response.resting = detection.resting;
    response.id = detection.id;
    response.frame = detection.frame;
    response.dimensions = detection.dimensions;
    response.fitness = detection.fitness;
    response.complete_face = detection.complete_face;
    response.pickable = detection.pickable;
    response.frame_stamp = detections.header.stamp;
    const std::string state = detection.pickable        ? "pickable"
                              : detection.complete_face ? "covered"
                                                        : "partial: " + detection.partial_reason;
    response.message = "ok: " + detection.frame + " (" + state + ")";
  }

  // The service thread reads only catalogue_ (never replaced) and latest_.
  BrickTracker tracker_;
  TrackedPoseParams tracked_params_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  tf2_ros::TransformBroadcaster broadcaster_;
  ros::Subscriber registrations_subscriber_;
  ros::Publisher detections_publisher_;
  ros::Publisher markers_publisher_;
  ros::CallbackQueue service_queue_;
  ros::ServiceServer service_;
  std::unique_ptr<ros::AsyncSpinner> service_spinner_;
  mutable std::mutex latest_mutex_;
  BrickDetectionArrayConstPtr latest_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::PoseCorrectionNodelet, nodelet::Nodelet)
