// brick_pose/Registration: stage 4. Gives each candidate an initial pose:
// a brick measured in recent frames (the latest `detections`) continues from
// its last final pose (the tracked path, with refinement: correction);
// any other gets our Super4PCS registration of its artificial model (the top
// face of its catalogue type, origin at its centre) onto the segment.
// Publishes the poses on `registrations`, in-process. Each Super4PCS search
// has its own budget and the frame has
// max_frame_registration_ms, so a pile cannot hold the pipeline up; the
// candidates a frame's budget skipped go first in the next frame. A
// candidate Super4PCS cannot register is dropped, counted by reason; the
// frame goes on with the others. Overlap, delta, sample size and the time
// budget are dynamic_reconfigure parameters.

#include <dynamic_reconfigure/server.h>
#include <pluginlib/class_list_macros.hpp>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/RegistrationConfig.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/pose/registration_order.h"
#include "brick_pose/pose/tracked_pose.h"
#include "brick_pose/ros/conversions.h"
#include "brick_pose/ros/stage_nodelet.h"

namespace brick_pose
{
class RegistrationNodelet : public StageNodelet
{
public:
  RegistrationNodelet() : StageNodelet("registration", "candidates", "registered") {}

private:
  void initStage(const ParamLookup& lookup) override
  {
    catalogue_ = catalogueFrom(lookup);
    estimator_ = std::make_unique<BrickPoseEstimator>(catalogue_, estimatorParamsFrom(lookup));
    budget_ = registrationStageParamsFrom(lookup);
    previous_poses_ = PreviousPoses(trackedPoseParamsFrom(lookup));
    detections_subscriber_ = node().subscribe("detections", 1, &RegistrationNodelet::onDetections, this);
    registrations_publisher_ = advertiseOutput<RegistrationsMessage>("registrations");
    candidates_subscriber_ = subscribeInput("candidates", &RegistrationNodelet::onCandidates, this);
    startReconfigure();
  }

  /// Super4PCS's accuracy and budget are tuned live; the server starts from
  /// the values loaded above, not from the .cfg defaults.
  void startReconfigure()
  {
    reconfigure_ = std::make_unique<dynamic_reconfigure::Server<RegistrationConfig>>(reconfigure_mutex_, getPrivateNodeHandle());
    const auto& params = estimator_->params().super4pcs;
    RegistrationConfig config;
    config.overlap = params.overlap;
    config.delta_m = params.delta_m;
    config.sample_size = params.sample_size;
    config.max_time_s = params.max_time_s;
    reconfigure_->updateConfig(config);
    reconfigure_->setCallback([this](const RegistrationConfig& update, std::uint32_t) { reconfigure(update); });
  }

  void reconfigure(const RegistrationConfig& config)
  {
    BrickPoseEstimatorParams params = estimator_->params();
    params.super4pcs.overlap = config.overlap;
    params.super4pcs.delta_m = config.delta_m;
    params.super4pcs.sample_size = config.sample_size;
    params.super4pcs.max_time_s = config.max_time_s;
    try
    {
      estimator_ = std::make_unique<BrickPoseEstimator>(catalogue_, params);
      NODELET_INFO("Super4PCS: overlap %.2f, delta %.1f mm, %d samples, budget %.0f ms", params.super4pcs.overlap,
                   params.super4pcs.delta_m * 1e3, params.super4pcs.sample_size, params.super4pcs.max_time_s * 1e3);
    }
    catch (const ConfigError& e)
    {
      NODELET_ERROR("reconfigure rejected, keeping the previous parameters: %s", e.what());
    }
  }

  /// The latest final poses, for the tracked path (only the correction
  /// refines a tracked pose: with ICP or none it would never change).
  void onDetections(const BrickDetectionArrayConstPtr& detections)
  {
    std::vector<PreviousPose> poses;
    if (estimator_->params().refinement == RefinementMethod::kCorrection)
      for (const BrickDetection& detection : detections->detections)
        poses.push_back({detection.type, detection.id, ros_conversions::fromPose(detection.pose.pose),
                         Eigen::Vector3d(detection.dimensions.x, detection.dimensions.y, detection.dimensions.z),
                         detection.fitness});
    previous_poses_.update(std::move(poses));
  }

  void onCandidates(const CandidatesMessageConstPtr& candidates)
  {
    frameIn();
    const FrameMessage& frame = *candidates->frame;
    if (!withinLatencyBudget(frame)) return;
    const ros::WallTime start = ros::WallTime::now();
    auto message = boost::make_shared<RegistrationsMessage>();
    message->header = candidates->header;
    message->candidates = candidates;
    const auto& list = candidates->front_end.candidates;
    // Tracked bricks cost nothing here; the rest share the frame's budget.
    std::vector<BrickCandidate> searched;
    std::vector<std::size_t> searched_index;
    for (std::size_t i = 0; i < list.size(); ++i)
    {
      if (const std::optional<PreviousPose> previous = previous_poses_.match(list[i]))
      {
        message->registered.push_back({i, registrationFromPrevious(*previous), true});
        continue;
      }
      searched.push_back(list[i]);
      searched_index.push_back(i);
    }
    const std::vector<std::size_t> order = order_.order(searched);
    std::size_t skipped = 0;
    for (std::size_t rank = 0; rank < order.size(); ++rank)
    {
      const double spent_ms = (ros::WallTime::now() - start).toSec() * 1e3;
      if (spent_ms > budget_.max_frame_registration_ms)
      {
        skipped = order.size() - rank;
        break;
      }
      registerOne(frame, searched[order[rank]], searched_index[order[rank]], *message);
    }
    if (skipped > 0)
    {
      itemDropped("skipped for the frame budget (first in the next frame)", static_cast<int>(skipped));
      NODELET_DEBUG("%s: %zu of %zu candidates skipped after %.0f ms (max_frame_registration_ms %.0f); "
                    "they go first in the next frame", frameLabel(frame).c_str(), skipped, searched.size(),
                    (ros::WallTime::now() - start).toSec() * 1e3, budget_.max_frame_registration_ms);
    }
    itemsProcessed(static_cast<int>(list.size()), static_cast<int>(message->registered.size()));
    message->registration_ms = (ros::WallTime::now() - start).toSec() * 1e3;
    registrations_publisher_.publish(RegistrationsMessageConstPtr(message));
    frameOut(frame, message->registration_ms);
  }

  void registerOne(const FrameMessage& frame, const BrickCandidate& candidate, std::size_t index,
                   RegistrationsMessage& message)
  {
    order_.attempted(candidate);
    try
    {
      message.registered.push_back({index, estimator_->registerCandidate(candidate), false});
    }
    catch (const InputError& e)
    {
      itemDropped("not registered");
      NODELET_WARN_THROTTLE(2.0, "%s: %s candidate not registered: %s", frameLabel(frame).c_str(),
                            candidate.type_name.c_str(), e.what());
    }
  }

  BrickCatalogue catalogue_;
  RegistrationStageParams budget_;
  RegistrationOrder order_;
  PreviousPoses previous_poses_;
  // Replaced whole on reconfigure; the subscriber and the reconfigure server
  // share the nodelet's single-threaded queue, so no lock is needed.
  std::unique_ptr<BrickPoseEstimator> estimator_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<RegistrationConfig>> reconfigure_;
  ros::Subscriber candidates_subscriber_;
  ros::Subscriber detections_subscriber_;
  ros::Publisher registrations_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::RegistrationNodelet, nodelet::Nodelet)
