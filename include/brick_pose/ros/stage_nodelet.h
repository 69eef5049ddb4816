#pragma once
// What every pipeline stage nodelet shares, in the spirit of pcl_ros's
// PCLNodelet: parameters through one validated lookup (the stage's private
// namespace first, then the pipeline's), "<stage> not started: <reason>"
// when they are unusable, the latency-budget drop, stage timing, one summary
// line per report period (a warning when something was dropped) and a
// /diagnostics status. A stage implements initStage() and its callbacks.

#include <memory>
#include <string>

#include <boost/make_shared.hpp>
#include <diagnostic_updater/diagnostic_updater.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>

#include "brick_pose/common/elapsed.h"
#include "brick_pose/common/param_parsing.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/pipeline/stage_stats.h"
#include "brick_pose/ros/pipeline_messages.h"

namespace brick_pose
{
class StageNodelet : public nodelet::Nodelet
{
public:
  ~StageNodelet() override;

protected:
  /// `stage` names it in logs and diagnostics ("roi_filter"); `item_in` and
  /// `item_out` name what it turns into what ("segments", "candidates"),
  /// empty when it passes frames only.
  StageNodelet(std::string stage, std::string item_in = "", std::string item_out = "");

  /// The stage's own set-up: read its parameters from `lookup`, create its
  /// publishers and subscribers. Throw ConfigError to leave it idle.
  virtual void initStage(const ParamLookup& lookup) = 0;

  const StageParams& stageParams() const { return stage_params_; }
  /// The manager's worker-pool node handle in the pipeline's namespace.
  ros::NodeHandle& node() { return getNodeHandle(); }

  /// A publisher of the stage's output on the relative `topic`, queue_size deep.
  template <typename Message>
  ros::Publisher advertiseOutput(const std::string& topic)
  {
    return node().advertise<Message>(topic, stage_params_.queue_size);
  }

  /// A subscriber to the stage's input on the relative `topic`, queue_size deep.
  template <typename Message, typename Stage>
  ros::Subscriber subscribeInput(const std::string& topic,
                                 void (Stage::*callback)(const boost::shared_ptr<const Message>&), Stage* stage)
  {
    return node().subscribe(topic, stage_params_.queue_size, callback, stage);
  }

  /// False, counted and warned about (throttled), when `frame` is already
  /// older than max_latency_ms: a stage spends no time on it.
  bool withinLatencyBudget(const FrameMessage& frame);

  /// The stage's output for `input`: a new message with the input's header
  /// (the camera frame's stamp and optical frame all the way down).
  template <typename Output, typename Input>
  static boost::shared_ptr<Output> outputFor(const Input& input)
  {
    auto output = boost::make_shared<Output>();
    output->header = input.header;
    return output;
  }

  /// frameIn(), then withinLatencyBudget(): whether to work on `frame`.
  bool acceptFrame(const FrameMessage& frame)
  {
    frameIn();
    return withinLatencyBudget(frame);
  }

  /// Bookkeeping of the stage's work, reported every report_period_s.
  void frameIn();
  void frameOut(const FrameMessage& frame, double processing_ms);
  void frameDropped(const std::string& reason);
  void itemsProcessed(int in, int out);
  void itemDropped(const std::string& reason, int count = 1);

  /// "frame 1523 (t 12.345)" for log lines.
  static std::string frameLabel(const FrameMessage& frame);

private:
  void onInit() final;
  void report(const ros::WallTimerEvent&);
  void fillDiagnostics(diagnostic_updater::DiagnosticStatusWrapper& status);

  std::string stage_;
  StageParams stage_params_;
  StageStats log_stats_;
  StageStats diagnostic_stats_;
  StageReport last_diagnostic_report_;
  bool started_ = false;
  std::string not_started_reason_;
  ros::WallTime last_log_, last_diagnostics_;
  ros::WallTimer report_timer_;
  std::unique_ptr<diagnostic_updater::Updater> diagnostics_;
};
}  // namespace brick_pose
