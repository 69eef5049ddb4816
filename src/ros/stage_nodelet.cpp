#include "brick_pose/ros/stage_nodelet.h"

#include <cstdio>
#include <utility>

#include "brick_pose/common/errors.h"
#include "brick_pose/ros/param_lookup.h"

namespace brick_pose
{
namespace
{
/// /diagnostics is refreshed this often; the log line every report_period_s.
constexpr double kDiagnosticsPeriodS = 1.0;
}  // namespace

StageNodelet::StageNodelet(std::string stage, std::string item_in, std::string item_out)
  : stage_(std::move(stage)), log_stats_(stage_, item_in, item_out), diagnostic_stats_(stage_, item_in, item_out)
{
}

StageNodelet::~StageNodelet() = default;

void StageNodelet::onInit()
{
  const ParamLookup lookup = rosParamLookup(getPrivateNodeHandle(), getNodeHandle());
  diagnostics_ = std::make_unique<diagnostic_updater::Updater>(getNodeHandle(), getPrivateNodeHandle());
  diagnostics_->setHardwareID("brick_pose");
  diagnostics_->add(stage_, this, &StageNodelet::fillDiagnostics);
  try
  {
    stage_params_ = stageParamsFrom(lookup);
    initStage(lookup);
    started_ = true;
  }
  catch (const ConfigError& e)
  {
    not_started_reason_ = e.what();
    NODELET_ERROR("%s not started: %s", stage_.c_str(), e.what());
  }
  last_log_ = last_diagnostics_ = ros::WallTime::now();
  report_timer_ = getNodeHandle().createWallTimer(ros::WallDuration(kDiagnosticsPeriodS), &StageNodelet::report, this);
  diagnostics_->force_update();
}

bool StageNodelet::withinLatencyBudget(const FrameMessage& frame)
{
  const double age_ms = frameAgeMs(frame);
  if (age_ms <= stage_params_.max_latency_ms) return true;
  frameDropped("over the latency budget");
  NODELET_WARN_THROTTLE(2.0, "%s: dropping %s: %.0f ms old on arrival, over the %.0f ms latency budget",
                        stage_.c_str(), frameLabel(frame).c_str(), age_ms, stage_params_.max_latency_ms);
  return false;
}

void StageNodelet::frameIn()
{
  log_stats_.frameIn();
  diagnostic_stats_.frameIn();
}

void StageNodelet::frameOut(const FrameMessage& frame, double processing_ms)
{
  const double latency_ms = frameAgeMs(frame);
  log_stats_.frameOut(processing_ms, latency_ms);
  diagnostic_stats_.frameOut(processing_ms, latency_ms);
}

void StageNodelet::frameDropped(const std::string& reason)
{
  log_stats_.frameDropped(reason);
  diagnostic_stats_.frameDropped(reason);
}

void StageNodelet::itemsProcessed(int in, int out)
{
  log_stats_.items(in, out);
  diagnostic_stats_.items(in, out);
}

void StageNodelet::itemDropped(const std::string& reason, int count)
{
  log_stats_.itemDropped(reason, count);
  diagnostic_stats_.itemDropped(reason, count);
}

std::string StageNodelet::frameLabel(const FrameMessage& frame)
{
  char label[64];
  std::snprintf(label, sizeof(label), "frame %llu (t %.3f)", static_cast<unsigned long long>(frame.sequence),
                frame.header.stamp.toSec());
  return label;
}

void StageNodelet::report(const ros::WallTimerEvent&)
{
  const ros::WallTime now = ros::WallTime::now();
  last_diagnostic_report_ = diagnostic_stats_.report((now - last_diagnostics_).toSec());
  last_diagnostics_ = now;
  diagnostics_->force_update();
  const double since_log_s = (now - last_log_).toSec();
  if (!started_ || since_log_s < stage_params_.report_period_s) return;
  const StageReport period = log_stats_.report(since_log_s);
  last_log_ = now;
  if (period.frames_in == 0 && !period.hasDrops()) return;  // idle: nothing to say
  if (period.hasDrops())
    NODELET_WARN("%s: %s", stage_.c_str(), period.summary().c_str());
  else
    NODELET_INFO("%s: %s", stage_.c_str(), period.summary().c_str());
}

void StageNodelet::fillDiagnostics(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  using diagnostic_msgs::DiagnosticStatus;
  const StageReport& report = last_diagnostic_report_;
  if (!started_)
    status.summary(DiagnosticStatus::ERROR, "not started: " + not_started_reason_);
  else if (report.frames_in == 0)
    status.summary(DiagnosticStatus::OK, "idle: no input");
  else if (report.frame_drops.total() > 0)
    status.summary(DiagnosticStatus::WARN, "dropping frames: " + report.frame_drops.summary());
  else
    status.summary(DiagnosticStatus::OK, "running");
  status.add("input rate (Hz)", report.input_rate_hz);
  status.add("output rate (Hz)", report.output_rate_hz);
  status.add("processing p50 (ms)", report.processing_p50_ms);
  status.add("processing p95 (ms)", report.processing_p95_ms);
  status.add("latency p50 (ms)", report.latency_p50_ms);
  status.add("latency p95 (ms)", report.latency_p95_ms);
  for (const auto& [reason, count] : report.frame_drops.counts()) status.add("frames dropped: " + reason, count);
  if (!report.item_in_name.empty())
  {
    status.add(report.item_in_name + " in", report.items_in);
    status.add(report.item_out_name + " out", report.items_out);
  }
  for (const auto& [reason, count] : report.item_drops.counts()) status.add("dropped: " + reason, count);
}
}  // namespace brick_pose
