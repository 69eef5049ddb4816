#pragma once
// What the pipeline's nodelets pass to each other inside one manager (see
// inprocess_message.h). Each stage's output keeps a pointer to its input, so
// a later stage reaches the frame without anyone copying it.

#include <cstdint>
#include <vector>

#include <boost/shared_ptr.hpp>
#include <ros/time.h>
#include <std_msgs/Header.h>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/pose/brick_pose_estimator.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/ros/inprocess_message.h"

namespace brick_pose
{
/// Stage 1 (ingestion) output: one synchronised, validated aligned RGB-D frame.
struct FrameMessage
{
  std_msgs::Header header;
  /// Frames ingested before this one since the pipeline started (log lines
  /// name frames by it).
  std::uint64_t sequence = 0;
  RgbdFrame frame;
  /// Wall time the last of its three input messages arrived; latency is
  /// measured from here to the tf broadcast.
  ros::WallTime arrival;
};
using FrameMessageConstPtr = boost::shared_ptr<const FrameMessage>;

/// Milliseconds since the frame arrived: each stage drops a frame that is
/// already older than the pipeline's latency budget, instead of spending the
/// CPU on a result that would come too late and delay the fresher frames.
inline double frameAgeMs(const FrameMessage& frame)
{
  return (ros::WallTime::now() - frame.arrival).toSec() * 1e3;
}

/// Stage 2 (segmentation) output: the segments of one frame.
struct SegmentsMessage
{
  std_msgs::Header header;
  FrameMessageConstPtr frame;
  std::vector<Segment> segments;
  double segmentation_ms = 0.0;
  /// Set when nothing in view changed since the keyframe (the last frame the
  /// front end ran on): `segments` is then empty, and the keyframe's, of the
  /// keyframe's frame, stand for this frame.
  boost::shared_ptr<const SegmentsMessage> keyframe;
};
using SegmentsMessageConstPtr = boost::shared_ptr<const SegmentsMessage>;

/// Stage 3 (cloud processing and ROI filtration) output: the brick candidates of one frame.
struct CandidatesMessage
{
  std_msgs::Header header;
  FrameMessageConstPtr frame;
  SegmentsMessageConstPtr segments;
  FrontEndResult front_end;
  /// The candidates are the keyframe's, reused (see SegmentsMessage::keyframe);
  /// keyframe_stamp_ns is the stamp of the frame they were measured in.
  bool front_end_reused = false;
  std::int64_t keyframe_stamp_ns = 0;
};
using CandidatesMessageConstPtr = boost::shared_ptr<const CandidatesMessage>;

/// Stage 4 (registration) output: the Super4PCS pose of each candidate that registered.
struct RegisteredCandidate
{
  std::size_t candidate_index = 0;  ///< into candidates->front_end.candidates
  BrickRegistration registration;
  /// The registration is the brick's last final pose (the tracked path),
  /// not a Super4PCS search.
  bool tracked = false;
};

struct RegistrationsMessage
{
  std_msgs::Header header;
  CandidatesMessageConstPtr candidates;
  std::vector<RegisteredCandidate> registered;
  double registration_ms = 0.0;  ///< all candidates of the frame
};
using RegistrationsMessageConstPtr = boost::shared_ptr<const RegistrationsMessage>;
}  // namespace brick_pose

BRICK_POSE_INPROCESS_MESSAGE(brick_pose::FrameMessage, "Frame", "a9ec6ff9696138c60c58099cbb669f7f")
BRICK_POSE_INPROCESS_MESSAGE(brick_pose::SegmentsMessage, "Segments", "134bbee6f82322accbf9194376569002")
BRICK_POSE_INPROCESS_MESSAGE(brick_pose::CandidatesMessage, "Candidates", "7d2d53592db0d7aa2c9c4226908f7e75")
BRICK_POSE_INPROCESS_MESSAGE(brick_pose::RegistrationsMessage, "Registrations", "3659e75aded1e6359f4cbd369b1d23f8")
