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

#include <cstdio>

#include <pluginlib/class_list_macros.hpp>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/RegistrationConfig.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/pose/registration_order.h"
#include "brick_pose/pose/tracked_pose.h"
#include "brick_pose/ros/conversions.h"
#include "brick_pose/ros/estimator_stage_nodelet.h"

namespace brick_pose
{
class RegistrationNodelet : public EstimatorStageNodelet<RegistrationConfig>
{
public:
  RegistrationNodelet() : EstimatorStageNodelet("registration", "candidates", "registered") {}

private:
  void initStage(const ParamLookup& lookup) override
  {
    initEstimator(lookup);
    budget_ = registrationStageParamsFrom(lookup);
    previous_poses_ = PreviousPoses(trackedPoseParamsFrom(lookup));
    detections_subscriber_ = node().subscribe("detections", 1, &RegistrationNodelet::onDetections, this);
    registrations_publisher_ = advertiseOutput<RegistrationsMessage>("registrations");
    candidates_subscriber_ = subscribeInput("candidates", &RegistrationNodelet::onCandidates, this);
    startReconfigure();
  }

  // Super4PCS's accuracy and budget are tuned live.
  RegistrationConfig configOf(const BrickPoseEstimatorParams& params) const override
  {
    RegistrationConfig config;
    config.overlap = params.super4pcs.overlap;
    config.delta_m = params.super4pcs.delta_m;
    config.sample_size = params.super4pcs.sample_size;
    config.max_time_s = params.super4pcs.max_time_s;
    return config;
  }

  BrickPoseEstimatorParams applied(const RegistrationConfig& config, BrickPoseEstimatorParams params) const override
  {
    params.super4pcs.overlap = config.overlap;
    params.super4pcs.delta_m = config.delta_m;
    params.super4pcs.sample_size = config.sample_size;
    params.super4pcs.max_time_s = config.max_time_s;
    return params;
  }

  std::string describe(const BrickPoseEstimatorParams& params) const override
  {
    const registration::Super4PCSParams& super4pcs = params.super4pcs;
    char text[160];
    std::snprintf(text, sizeof(text), "Super4PCS: overlap %.2f, delta %.1f mm, %d samples, budget %.0f ms",
                  super4pcs.overlap, super4pcs.delta_m * 1e3, super4pcs.sample_size, super4pcs.max_time_s * 1e3);
    return text;
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
    const FrameMessage& frame = *candidates->frame;
    if (!acceptFrame(frame)) return;
    const auto start = SteadyClock::now();
    auto message = outputFor<RegistrationsMessage>(*candidates);
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
      const double spent_ms = millisecondsSince(start);
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
                    millisecondsSince(start), budget_.max_frame_registration_ms);
    }
    itemsProcessed(static_cast<int>(list.size()), static_cast<int>(message->registered.size()));
    message->registration_ms = millisecondsSince(start);
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

  RegistrationStageParams budget_;
  RegistrationOrder order_;
  PreviousPoses previous_poses_;
  ros::Subscriber candidates_subscriber_;
  ros::Subscriber detections_subscriber_;
  ros::Publisher registrations_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::RegistrationNodelet, nodelet::Nodelet)
