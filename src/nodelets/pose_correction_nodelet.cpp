// brick_pose/PoseCorrection: stage 6 and the product. Refines each Super4PCS
// pose (constant-time correction by default, ICP or none by ~refinement),
// then publishes every brick of the frame:
//  - tf frames brick_<type>_<n>, children of the camera's optical frame, n in
//    nearest-first order per type;
//  - `detections` (brick_pose/BrickDetectionArray) with timings and latency;
//  - `markers` (visualization_msgs/MarkerArray, only when subscribed);
//  - the `get_brick_pose` service (brick_pose/GetBrickPose), answered from
//    the latest detections on a thread of its own: the manager's workers may
//    all be busy (long frames in every stage, or a camera driver sharing the
//    manager) and a grasp planner must still get its answer.

#include <map>
#include <mutex>
#include <sstream>

#include <dynamic_reconfigure/server.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/GetBrickPose.h"
#include "brick_pose/PoseCorrectionConfig.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/pose/brick_selection.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/ros/brick_markers.h"
#include "brick_pose/ros/conversions.h"
#include "brick_pose/ros/param_lookup.h"
#include "brick_pose/ros/pipeline_messages.h"

namespace brick_pose
{
namespace
{
geometry_msgs::Vector3 toVector3(const Eigen::Vector3d& vector)
{
  geometry_msgs::Vector3 message;
  message.x = vector.x();
  message.y = vector.y();
  message.z = vector.z();
  return message;
}

std::vector<DetectedBrick> detectedBricksOf(const BrickDetectionArray& detections)
{
  std::vector<DetectedBrick> bricks;
  for (const BrickDetection& detection : detections.detections)
  {
    DetectedBrick brick;
    brick.type_name = detection.type;
    brick.T_cam_brick = ros_conversions::fromPose(detection.pose.pose);
    brick.dimensions_m = Eigen::Vector3d(detection.dimensions.x, detection.dimensions.y, detection.dimensions.z);
    brick.fitness = detection.fitness;
    bricks.push_back(brick);
  }
  return bricks;
}

/// "2 green, 1 blue" for a failure message.
std::string typeCounts(const BrickDetectionArray& detections)
{
  std::map<std::string, int> counts;
  for (const BrickDetection& detection : detections.detections)
    ++counts[detection.type];
  std::ostringstream text;
  for (const auto& [type, count] : counts)
    text << (text.tellp() > 0 ? ", " : "") << count << " " << type;
  return counts.empty() ? "none" : text.str();
}
}  // namespace

class PoseCorrectionNodelet : public nodelet::Nodelet
{
public:
  ~PoseCorrectionNodelet() override
  {
    // Stop answering before the members the service reads go away.
    if (service_spinner_) service_spinner_->stop();
    service_.shutdown();
  }

private:
  void onInit() override
  {
    ros::NodeHandle& node = getNodeHandle();
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    const ParamLookup lookup = rosParamLookup(private_node, node);
    try
    {
      catalogue_ = catalogueFrom(lookup);
      estimator_ = std::make_unique<BrickPoseEstimator>(catalogue_, estimatorParamsFrom(lookup));
    }
    catch (const ConfigError& e)
    {
      NODELET_ERROR("pose correction not started: %s", e.what());
      return;
    }
    tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, getMTNodeHandle());
    detections_publisher_ = node.advertise<BrickDetectionArray>("detections", 5);
    markers_publisher_ = node.advertise<visualization_msgs::MarkerArray>("markers", 2);
    registrations_subscriber_ = node.subscribe("registrations", 2, &PoseCorrectionNodelet::onRegistrations, this);
    advertiseService(node);
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

  /// Refinement method and correction mode are switched live; the server
  /// starts from the values loaded above, not from the .cfg defaults.
  void startReconfigure()
  {
    reconfigure_ = std::make_unique<dynamic_reconfigure::Server<PoseCorrectionConfig>>(reconfigure_mutex_, getPrivateNodeHandle());
    const BrickPoseEstimatorParams& params = estimator_->params();
    PoseCorrectionConfig config;
    config.refinement = toString(params.refinement);
    config.correction_mode = toString(params.correction.mode);
    config.icp_max_correspondence_m = params.icp.max_correspondence_distance_m;
    config.icp_max_iterations = params.icp.max_iterations;
    reconfigure_->updateConfig(config);
    reconfigure_->setCallback([this](const PoseCorrectionConfig& update, std::uint32_t) { reconfigure(update); });
  }

  void reconfigure(const PoseCorrectionConfig& config)
  {
    BrickPoseEstimatorParams params = estimator_->params();
    try
    {
      params.refinement = parseRefinementMethod(config.refinement);
      params.correction.mode = parseCorrectionMode(config.correction_mode);
      params.icp.max_correspondence_distance_m = config.icp_max_correspondence_m;
      params.icp.max_iterations = config.icp_max_iterations;
      estimator_ = std::make_unique<BrickPoseEstimator>(catalogue_, params);
      NODELET_INFO("refinement %s (correction mode %s)", toString(params.refinement), toString(params.correction.mode));
    }
    catch (const ConfigError& e)
    {
      NODELET_ERROR("reconfigure rejected, keeping the previous parameters: %s", e.what());
    }
  }

  void onRegistrations(const RegistrationsMessageConstPtr& registrations)
  {
    const ros::WallTime start = ros::WallTime::now();
    const auto& candidates = registrations->candidates->front_end.candidates;
    std::vector<BrickPoseEstimate> estimates;
    for (const RegisteredCandidate& registered : registrations->registered)
    {
      try
      {
        estimates.push_back(estimator_->refine(candidates[registered.candidate_index], registered.registration));
      }
      catch (const InputError& e)
      {
        NODELET_WARN_THROTTLE(2.0, "frame %.3f: %s brick not refined: %s", registrations->header.stamp.toSec(),
                              candidates[registered.candidate_index].type_name.c_str(), e.what());
      }
    }
    const double refinement_ms = (ros::WallTime::now() - start).toSec() * 1e3;
    auto detections = makeDetections(*registrations, estimates);
    detections->refinement_ms = refinement_ms;
    publish(detections, registrations->candidates->frame->arrival);
  }

  boost::shared_ptr<BrickDetectionArray> makeDetections(const RegistrationsMessage& registrations,
                                                        const std::vector<BrickPoseEstimate>& estimates) const
  {
    auto detections = boost::make_shared<BrickDetectionArray>();
    detections->header = registrations.header;
    detections->frontend_ms = registrations.candidates->front_end.timings.total_ms;
    detections->registration_ms = registrations.registration_ms;
    const auto& candidates = registrations.candidates->front_end.candidates;
    std::vector<DetectedBrick> bricks;
    for (std::size_t i = 0; i < estimates.size(); ++i)
    {
      const BrickPoseEstimate& estimate = estimates[i];
      BrickDetection detection;
      detection.type = estimate.type_name;
      detection.pose.header = registrations.header;
      detection.pose.pose = ros_conversions::toPose(estimate.pose);
      detection.dimensions = toVector3(estimate.dimensions_m);
      detection.fitness = estimate.registration.result.lcp_score;
      detection.registration_pose = ros_conversions::toPose(estimate.registration.pose);
      detection.refinement = toString(estimate.refinement);
      detection.correction_yaw_deg = estimate.correction.yawDeg();
      detection.correction_tilt_deg = estimate.correction.tiltDeg();
      detection.correction_translation_mm = toVector3(1000.0 * estimate.correction.offset_m);
      detection.registration_ms = estimate.registration.elapsed_ms;
      detection.refinement_ms = estimate.refinement_ms;
      detection.complete_face = candidates[registrations.registered[i].candidate_index].complete;
      detections->detections.push_back(detection);
      bricks.push_back({estimate.type_name, estimate.pose, estimate.dimensions_m, detection.fitness});
    }
    nameFramesAndMarkPickable(bricks, *detections);
    return detections;
  }

  /// brick_<type>_<n>, n counting each type's bricks nearest first.
  static void nameFramesAndMarkPickable(const std::vector<DetectedBrick>& bricks, BrickDetectionArray& detections)
  {
    if (bricks.empty()) return;
    std::map<std::string, int> next_number;
    for (std::size_t index : orderBricks(bricks, SelectionPolicy::kNearest))
    {
      BrickDetection& detection = detections.detections[index];
      detection.frame = "brick_" + detection.type + "_" + std::to_string(next_number[detection.type]++);
    }
    try
    {
      const std::vector<bool> pickable = pickableMask(bricks);
      for (std::size_t i = 0; i < bricks.size(); ++i)
        detections.detections[i].pickable = pickable[i];
    }
    catch (const InputError&)
    {
      // No usable "up" from the bricks (e.g. they cancel out): leave pickable false.
    }
  }

  void publish(const boost::shared_ptr<BrickDetectionArray>& detections, const ros::WallTime& arrival)
  {
    std::vector<geometry_msgs::TransformStamped> frames;
    for (const BrickDetection& detection : detections->detections)
    {
      geometry_msgs::TransformStamped transform;
      transform.header = detections->header;
      transform.child_frame_id = detection.frame;
      transform.transform = ros_conversions::toTransform(ros_conversions::fromPose(detection.pose.pose));
      frames.push_back(transform);
    }
    if (!frames.empty()) broadcaster_.sendTransform(frames);
    detections->latency_ms = (ros::WallTime::now() - arrival).toSec() * 1e3;
    {
      std::lock_guard<std::mutex> lock(latest_mutex_);
      latest_ = detections;
    }
    detections_publisher_.publish(BrickDetectionArrayConstPtr(detections));
    if (markers_publisher_.getNumSubscribers() > 0)
      markers_publisher_.publish(makeBrickMarkers(*detections, catalogue_));
    NODELET_DEBUG("frame %.3f: %zu bricks, front end %.1f ms, registration %.1f ms, refinement %.3f ms, latency %.1f ms",
                  detections->header.stamp.toSec(), detections->detections.size(), detections->frontend_ms,
                  detections->registration_ms, detections->refinement_ms, detections->latency_ms);
    logThroughput(*detections);
  }

  /// One INFO line every 10 s: frames, bricks and latency, so an operator sees it run.
  void logThroughput(const BrickDetectionArray& detections)
  {
    ++frames_since_log_;
    latency_sum_ms_ += detections.latency_ms;
    const ros::WallTime now = ros::WallTime::now();
    if (last_log_.isZero()) last_log_ = now;
    const double elapsed_s = (now - last_log_).toSec();
    if (elapsed_s < 10.0) return;
    NODELET_INFO("%.1f frames/s, last frame %zu bricks, mean latency %.1f ms", frames_since_log_ / elapsed_s,
                 detections.detections.size(), latency_sum_ms_ / frames_since_log_);
    frames_since_log_ = 0;
    latency_sum_ms_ = 0.0;
    last_log_ = now;
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
    const double age_s = (ros::Time::now() - detections->header.stamp).toSec();
    if (request.max_age_s > 0.0 && age_s > request.max_age_s)
      throw InputError("data too old: the latest detections are " + std::to_string(age_s) + " s old (max_age_s " +
                       std::to_string(request.max_age_s) + ")");
    const std::optional<Eigen::Isometry3d> camera_T_target = targetFrameInCamera(request.target_frame, *detections);
    std::optional<Eigen::Vector3d> up_in_camera;
    if (camera_T_target) up_in_camera = camera_T_target->linear().col(2);
    const std::size_t chosen = request.frame.empty() ? choose(*detections, policy, request.type, up_in_camera)
                                                     : findFrame(*detections, request.frame);
    fillResponse(detections->detections[chosen], *detections, camera_T_target, request.target_frame, response);
  }

  /// Picks by policy among the bricks whose whole top face was measured: a
  /// partly hidden face gives a good orientation but a guessed centre, not
  /// something to grasp. They can still be asked for by their frame name.
  static std::size_t choose(const BrickDetectionArray& detections, SelectionPolicy policy, const std::string& type,
                            const std::optional<Eigen::Vector3d>& up_in_camera)
  {
    // Every brick counts for covering others; only complete ones can be chosen.
    const std::vector<DetectedBrick> bricks = detectedBricksOf(detections);
    const bool pickable_only = policy == SelectionPolicy::kPickable;
    const std::vector<bool> pickable = pickable_only ? pickableMask(bricks, up_in_camera) : std::vector<bool>();
    for (std::size_t index : orderBricks(bricks, policy, type, up_in_camera))
      if (detections.detections[index].complete_face && (!pickable_only || pickable[index])) return index;
    throw InputError("no " + std::string(type.empty() ? "" : type + " ") + "brick" +
                     (policy == SelectionPolicy::kPickable ? " that nothing rests on" : "") +
                     " with its whole top face in view in the latest frame (seen: " + typeCounts(detections) + ")");
  }

  static std::size_t findFrame(const BrickDetectionArray& detections, const std::string& frame)
  {
    for (std::size_t i = 0; i < detections.detections.size(); ++i)
      if (detections.detections[i].frame == frame) return i;
    throw InputError("no brick '" + frame + "' in the latest frame (seen: " + typeCounts(detections) + ")");
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
      response.pose.pose = ros_conversions::toPose(camera_T_target->inverse() * ros_conversions::fromPose(detection.pose.pose));
    }
    response.type = detection.type;
    response.frame = detection.frame;
    response.dimensions = detection.dimensions;
    response.fitness = detection.fitness;
    response.frame_stamp = detections.header.stamp;
    response.message = "ok: " + detection.frame + (detection.pickable ? " (pickable)" : " (covered)");
  }

  // The service thread reads only catalogue_ (never replaced) and latest_.
  BrickCatalogue catalogue_;
  // Replaced whole on reconfigure, on the same single-threaded queue as the
  // registrations callback that uses it.
  std::unique_ptr<BrickPoseEstimator> estimator_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<PoseCorrectionConfig>> reconfigure_;
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
  int frames_since_log_ = 0;
  double latency_sum_ms_ = 0.0;
  ros::WallTime last_log_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::PoseCorrectionNodelet, nodelet::Nodelet)
