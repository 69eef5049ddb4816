// brick_pose/Registration: stage 5. Registers each candidate's artificial
// model (the top face of its catalogue type, origin at its centre) onto the
// segment with our Super4PCS; publishes the poses on `registrations`,
// in-process. A candidate Super4PCS cannot register is dropped with a
// throttled warning; the frame goes on with the others. Overlap, delta,
// sample size and the time budget are dynamic_reconfigure parameters.

#include <dynamic_reconfigure/server.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>

#include "brick_pose/RegistrationConfig.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/ros/param_lookup.h"
#include "brick_pose/ros/pipeline_messages.h"

namespace brick_pose
{
class RegistrationNodelet : public nodelet::Nodelet
{
private:
  void onInit() override
  {
    ros::NodeHandle& node = getNodeHandle();
    const ParamLookup lookup = rosParamLookup(getPrivateNodeHandle(), node);
    try
    {
      catalogue_ = catalogueFrom(lookup);
      estimator_ = std::make_unique<BrickPoseEstimator>(catalogue_, estimatorParamsFrom(lookup));
    }
    catch (const ConfigError& e)
    {
      NODELET_ERROR("registration not started: %s", e.what());
      return;
    }
    getPrivateNodeHandle().param("max_frame_registration_ms", max_frame_registration_ms_, 400.0);
    node.param("max_latency_ms", max_latency_ms_, 3000.0);
    registrations_publisher_ = node.advertise<RegistrationsMessage>("registrations", 2);
    candidates_subscriber_ = node.subscribe("candidates", 2, &RegistrationNodelet::onCandidates, this);
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

  void onCandidates(const CandidatesMessageConstPtr& candidates)
  {
    const ros::WallTime start = ros::WallTime::now();
    auto message = boost::make_shared<RegistrationsMessage>();
    message->header = candidates->header;
    message->candidates = candidates;
    const auto& list = candidates->front_end.candidates;
    for (std::size_t i = 0; i < list.size(); ++i)
    {
      // Each brick has Super4PCS's own budget; the frame has this one, so a
      // pile of bricks cannot hold the pipeline up.
      const double spent_ms = (ros::WallTime::now() - start).toSec() * 1e3;
      const double age_ms = frameAgeMs(*candidates->frame);
      if (spent_ms > max_frame_registration_ms_ || age_ms > max_latency_ms_)
      {
        NODELET_WARN_THROTTLE(2.0, "frame %.3f: %zu of %zu candidates skipped: registration took %.0f ms (budget %.0f), "
                              "frame %.0f ms old (budget %.0f)", candidates->header.stamp.toSec(), list.size() - i,
                              list.size(), spent_ms, max_frame_registration_ms_, age_ms, max_latency_ms_);
        break;
      }
      try
      {
        message->registered.push_back({i, estimator_->registerCandidate(list[i])});
      }
      catch (const InputError& e)
      {
        NODELET_WARN_THROTTLE(2.0, "frame %.3f: %s candidate not registered: %s", candidates->header.stamp.toSec(),
                              list[i].type_name.c_str(), e.what());
      }
    }
    message->registration_ms = (ros::WallTime::now() - start).toSec() * 1e3;
    registrations_publisher_.publish(RegistrationsMessageConstPtr(message));
  }

  BrickCatalogue catalogue_;
  double max_frame_registration_ms_ = 400.0;
  double max_latency_ms_ = 3000.0;
  // Replaced whole on reconfigure; the subscriber and the reconfigure server
  // share the nodelet's single-threaded queue, so no lock is needed.
  std::unique_ptr<BrickPoseEstimator> estimator_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<RegistrationConfig>> reconfigure_;
  ros::Subscriber candidates_subscriber_;
  ros::Publisher registrations_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::RegistrationNodelet, nodelet::Nodelet)
