#pragma once
// What one pipeline stage did over a reporting period: frames in and out,
// drops by reason, processing time and latency. Stages feed it as they
// work; the ROS adapter turns a snapshot into a /diagnostics status and one
// log line per period ("42 frames in, 40 out; dropped: 2 over the latency
// budget; 14 segments -> 3 bricks: 6 cut by the border, 4 too small").
// ROS-free so that the summaries are unit-tested.

#include <cstddef>
#include <deque>
#include <map>
#include <string>
#include <vector>

namespace brick_pose
{
/// Counts of items by reason, printed largest first.
class ReasonCounts
{
public:
  void add(const std::string& reason, int count = 1);
  bool empty() const { return counts_.empty(); }
  int total() const;
  const std::map<std::string, int>& counts() const { return counts_; }
  /// "6 cut by the border, 4 too small" (largest first, ties by name).
  std::string summary() const;

private:
  std::map<std::string, int> counts_;
};

/// Percentiles of the last `capacity` samples.
class SampleWindow
{
public:
  explicit SampleWindow(std::size_t capacity = 300) : capacity_(capacity) {}
  void add(double value);
  std::size_t size() const { return samples_.size(); }
  /// NaN when empty (see common/statistics.h for the definition).
  double percentile(double fraction) const;

private:
  std::size_t capacity_;
  std::deque<double> samples_;
};

/// A snapshot of one stage over a period, for diagnostics and the log.
struct StageReport
{
  std::string stage;
  double period_s = 0.0;
  int frames_in = 0;
  int frames_out = 0;
  double input_rate_hz = 0.0;
  double output_rate_hz = 0.0;
  double processing_p50_ms = 0.0, processing_p95_ms = 0.0;
  double latency_p50_ms = 0.0, latency_p95_ms = 0.0;  ///< frame arrival to this stage's output
  ReasonCounts frame_drops;                           ///< whole frames not passed on, by reason
  int items_in = 0;                                   ///< e.g. segments considered
  int items_out = 0;                                  ///< e.g. candidates passed on
  std::string item_in_name, item_out_name;            ///< "segments", "candidates"
  ReasonCounts item_drops;                            ///< items not passed on, by reason

  /// One line: "30.0 Hz in, 30.0 Hz out, 12.1/15.3 ms (p50/p95), latency ...;
  /// dropped 2 frames: 2 over the latency budget; 140 segments -> 30
  /// candidates: 60 cut by the border, 50 too small".
  std::string summary() const;
  /// True when something was dropped (the log line is then a warning).
  bool hasDrops() const { return !frame_drops.empty() || !item_drops.empty(); }
};

/// Accumulates one stage's activity; not thread-safe (a stage's callbacks
/// run one at a time).
class StageStats
{
public:
  explicit StageStats(std::string stage, std::string item_in_name = "", std::string item_out_name = "");

  void frameIn() { ++frames_in_; }
  void frameOut(double processing_ms, double latency_ms);
  void frameDropped(const std::string& reason) { frame_drops_.add(reason); }
  void items(int in, int out) { items_in_ += in; items_out_ += out; }
  void itemDropped(const std::string& reason, int count = 1) { item_drops_.add(reason, count); }

  /// The period since the last report (`elapsed_s` long); counts restart,
  /// the time windows keep their last samples.
  StageReport report(double elapsed_s);

private:
  std::string stage_, item_in_name_, item_out_name_;
  int frames_in_ = 0, frames_out_ = 0, items_in_ = 0, items_out_ = 0;
  ReasonCounts frame_drops_, item_drops_;
  SampleWindow processing_ms_, latency_ms_;
};
}  // namespace brick_pose
