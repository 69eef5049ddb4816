#pragma once
// A stage that runs the BrickPoseEstimator (registration, pose correction):
// it builds the catalogue and the estimator from the stage's parameters, and
// serves some of the estimator's parameters through dynamic_reconfigure. The
// server starts from the values in effect (not from the .cfg defaults); an
// update rebuilds the estimator, or keeps the old one and logs why.

#include <cstdint>
#include <memory>
#include <string>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/pose/brick_pose_estimator.h"
#include "brick_pose/ros/stage_nodelet.h"

namespace brick_pose
{
template <typename ReconfigureConfig>
class EstimatorStageNodelet : public StageNodelet
{
protected:
  using StageNodelet::StageNodelet;

  /// Builds the catalogue and the estimator; call first in initStage().
  void initEstimator(const ParamLookup& lookup)
  {
    catalogue_ = catalogueFrom(lookup);
    estimator_ = std::make_unique<BrickPoseEstimator>(catalogue_, estimatorParamsFrom(lookup));
  }

  /// Starts the reconfigure server; call last in initStage().
  void startReconfigure()
  {
    reconfigure_ = std::make_unique<dynamic_reconfigure::Server<ReconfigureConfig>>(reconfigure_mutex_,
                                                                                   getPrivateNodeHandle());
    reconfigure_->updateConfig(configOf(estimator_->params()));
    reconfigure_->setCallback([this](const ReconfigureConfig& update, std::uint32_t) { reconfigure(update); });
  }

  /// The server's values taken from the estimator's parameters.
  virtual ReconfigureConfig configOf(const BrickPoseEstimatorParams& params) const = 0;
  /// `params` with the server's values applied; throws ConfigError on a bad one.
  virtual BrickPoseEstimatorParams applied(const ReconfigureConfig& config, BrickPoseEstimatorParams params) const = 0;
  /// What is in effect after an update, for the log.
  virtual std::string describe(const BrickPoseEstimatorParams& params) const = 0;

  // Read by the stage's callbacks. The catalogue is never replaced (a
  // service thread may read it); the estimator is replaced whole on
  // reconfigure, which runs on the same single-threaded queue as the
  // stage's subscriber, so no lock is needed.
  BrickCatalogue catalogue_;
  std::unique_ptr<BrickPoseEstimator> estimator_;

private:
  void reconfigure(const ReconfigureConfig& config)
  {
    try
    {
      const BrickPoseEstimatorParams params = applied(config, estimator_->params());
      estimator_ = std::make_unique<BrickPoseEstimator>(catalogue_, params);
      NODELET_INFO("%s", describe(params).c_str());
    }
    catch (const ConfigError& e)
    {
      NODELET_ERROR("reconfigure rejected, keeping the previous parameters: %s", e.what());
    }
  }

  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ReconfigureConfig>> reconfigure_;
};
}  // namespace brick_pose
