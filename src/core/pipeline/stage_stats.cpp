#include "brick_pose/pipeline/stage_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "brick_pose/common/statistics.h"

namespace brick_pose
{
void ReasonCounts::add(const std::string& reason, int count)
{
  if (count > 0) counts_[reason] += count;
}

int ReasonCounts::total() const
{
  int total = 0;
  for (const auto& entry : counts_) total += entry.second;
  return total;
}

std::string ReasonCounts::summary() const
{
  std::vector<std::pair<std::string, int>> sorted(counts_.begin(), counts_.end());
  std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  std::ostringstream text;
  for (std::size_t i = 0; i < sorted.size(); ++i)
    text << (i > 0 ? ", " : "") << sorted[i].second << " " << sorted[i].first;
  return text.str();
}

void SampleWindow::add(double value)
{
  if (!std::isfinite(value)) return;
  samples_.push_back(value);
  while (samples_.size() > capacity_) samples_.pop_front();
}

double SampleWindow::percentile(double fraction) const
{
  return brick_pose::percentile(std::vector<double>(samples_.begin(), samples_.end()), fraction);
}

std::string StageReport::summary() const
{
  char head[256];
  std::snprintf(head, sizeof(head), "%.1f Hz in, %.1f Hz out, %.1f/%.1f ms (p50/p95), latency %.1f/%.1f ms",
                input_rate_hz, output_rate_hz, processing_p50_ms, processing_p95_ms, latency_p50_ms, latency_p95_ms);
  std::ostringstream text;
  text << head;
  if (!frame_drops.empty()) text << "; dropped " << frame_drops.total() << " frames: " << frame_drops.summary();
  if (!item_in_name.empty() && items_in > 0)
  {
    text << "; " << items_in << " " << item_in_name << " -> " << items_out << " " << item_out_name;
    if (!item_drops.empty()) text << ": " << item_drops.summary();
  }
  return text.str();
}

StageStats::StageStats(std::string stage, std::string item_in_name, std::string item_out_name)
  : stage_(std::move(stage)), item_in_name_(std::move(item_in_name)), item_out_name_(std::move(item_out_name))
{
}

void StageStats::frameOut(double processing_ms, double latency_ms)
{
  ++frames_out_;
  processing_ms_.add(processing_ms);
  latency_ms_.add(latency_ms);
}

StageReport StageStats::report(double elapsed_s)
{
  StageReport report;
  report.stage = stage_;
  report.period_s = elapsed_s;
  report.frames_in = frames_in_;
  report.frames_out = frames_out_;
  report.input_rate_hz = elapsed_s > 0.0 ? frames_in_ / elapsed_s : 0.0;
  report.output_rate_hz = elapsed_s > 0.0 ? frames_out_ / elapsed_s : 0.0;
  const auto orZero = [](double value) { return std::isnan(value) ? 0.0 : value; };
  report.processing_p50_ms = orZero(processing_ms_.percentile(0.5));
  report.processing_p95_ms = orZero(processing_ms_.percentile(0.95));
  report.latency_p50_ms = orZero(latency_ms_.percentile(0.5));
  report.latency_p95_ms = orZero(latency_ms_.percentile(0.95));
  report.frame_drops = frame_drops_;
  report.items_in = items_in_;
  report.items_out = items_out_;
  report.item_in_name = item_in_name_;
  report.item_out_name = item_out_name_;
  report.item_drops = item_drops_;
  frames_in_ = frames_out_ = items_in_ = items_out_ = 0;
  frame_drops_ = ReasonCounts();
  item_drops_ = ReasonCounts();
  return report;
}
}  // namespace brick_pose
