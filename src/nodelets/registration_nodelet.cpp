// brick_pose/Registration: stage 5. Registers each candidate's artificial
// model (the top face of its catalogue type, origin at its centre) onto the
// segment with our Super4PCS; publishes the poses on `registrations`,
// in-process. A candidate Super4PCS cannot register is dropped with a
// throttled warning; the frame goes on with the others.

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/pose/pipeline_config.h"
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
      estimator_ = std::make_unique<BrickPoseEstimator>(catalogueFrom(lookup), estimatorParamsFrom(lookup));
    }
    catch (const ConfigError& e)
    {
      NODELET_ERROR("registration not started: %s", e.what());
      return;
    }
    registrations_publisher_ = node.advertise<RegistrationsMessage>("registrations", 2);
    candidates_subscriber_ = node.subscribe("candidates", 2, &RegistrationNodelet::onCandidates, this);
    const auto& params = estimator_->params().super4pcs;
    NODELET_INFO("Super4PCS: overlap %.2f, delta %.1f mm, %d samples, budget %.0f ms", params.overlap,
                 params.delta_m * 1e3, params.sample_size, params.max_time_s * 1e3);
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

  std::unique_ptr<BrickPoseEstimator> estimator_;
  ros::Subscriber candidates_subscriber_;
  ros::Publisher registrations_publisher_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::RegistrationNodelet, nodelet::Nodelet)
