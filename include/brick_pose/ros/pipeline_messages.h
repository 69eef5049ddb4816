#pragma once
// What the pipeline's nodelets pass to each other inside one manager (see
// inprocess_message.h). Each stage's output keeps a pointer to its input, so
// a later stage reaches the frame without anyone copying it.

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
/// Stage 1 output: one synchronised, validated aligned RGB-D frame.
struct FrameMessage
{
  std_msgs::Header header;
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

/// Stage 3 output: the segments of one frame.
struct SegmentsMessage
{
  std_msgs::Header header;
  FrameMessageConstPtr frame;
  std::vector<Segment> segments;
  double segmentation_ms = 0.0;
};
using SegmentsMessageConstPtr = boost::shared_ptr<const SegmentsMessage>;

/// Stages 2-4 output: the brick candidates of one frame.
struct CandidatesMessage
{
  std_msgs::Header header;
  FrameMessageConstPtr frame;
  SegmentsMessageConstPtr segments;
  FrontEndResult front_end;
};
using CandidatesMessageConstPtr = boost::shared_ptr<const CandidatesMessage>;

/// Stage 5 output: the Super4PCS pose of each candidate that registered.
struct RegisteredCandidate
{
  std::size_t candidate_index = 0;  ///< into candidates->front_end.candidates
  BrickRegistration registration;
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

BRICK_POSE_INPROCESS_MESSAGE(brick_pose::FrameMessage, "Frame")
BRICK_POSE_INPROCESS_MESSAGE(brick_pose::SegmentsMessage, "Segments")
BRICK_POSE_INPROCESS_MESSAGE(brick_pose::CandidatesMessage, "Candidates")
BRICK_POSE_INPROCESS_MESSAGE(brick_pose::RegistrationsMessage, "Registrations")
