// brick_pose_demo: the client side of `make demo`. Waits for the pipeline's
// detections on the synthetic D415, calls the get_brick_pose service for every
// detected brick, and prints the estimated pose beside the ground truth with
// the error (modulo the face's half-turn symmetry). Exits non-zero when the
// pipeline produced nothing.

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/BrickTruthArray.h"
#include "brick_pose/GetBrickPose.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/ros/conversions.h"

namespace
{
using brick_pose::ros_conversions::fromPose;

struct Options
{
  std::string service = "/brick_pose/get_brick_pose";
  std::string detections = "/brick_pose/detections";
  std::string truth = "/camera/synthetic_camera/ground_truth";
  double timeout_s = 60.0;
};

/// The ground-truth brick a detection is of: same type, its estimated top-face
/// centre on that brick's top-face plane (within 3 cm) and inside the face
/// grown by half its length (a partial face's centre is a guess along the
/// hidden part); the closest such brick, or nullptr.
const brick_pose::BrickTruth* matchTruth(const brick_pose::BrickTruthArray& truth, const std::string& type,
                                         const Eigen::Isometry3d& pose)
{
  const brick_pose::BrickTruth* best = nullptr;
  double best_distance_m = std::numeric_limits<double>::max();
  for (const auto& brick : truth.bricks)
  {
    if (brick.type != type) continue;
    const Eigen::Vector3d in_brick = fromPose(brick.pose).inverse() * pose.translation();
    const bool on_face = std::abs(in_brick.z()) < 0.03 && std::abs(in_brick.x()) < brick.dimensions.x &&
                         std::abs(in_brick.y()) < brick.dimensions.y;
    if (on_face && in_brick.norm() < best_distance_m)
    {
      best_distance_m = in_brick.norm();
      best = &brick;
    }
  }
  return best;
}

std::string truthName(const brick_pose::BrickTruth& truth)
{
  return "truth_" + truth.type + "_" + std::to_string(truth.instance_id);
}

/// "pickable", "covered" or "partial" (top face not wholly in view: its centre is a guess).
const char* faceState(const brick_pose::BrickDetection& detection)
{
  if (!detection.complete_face) return "partial";
  return detection.pickable ? "pickable" : "covered";
}

void printStreams(const brick_pose::BrickDetectionArray& detections)
{
  std::printf("\nThe synthetic D415 publishes /camera/color/image_raw (rgb8), /camera/aligned_depth_to_color/image_raw\n"
              "(16UC1, mm) and their camera_info; the pipeline publishes /brick_pose/detections, /brick_pose/markers,\n"
              "tf brick_<type>_<id> and serves %s.\n",
              "/brick_pose/get_brick_pose");
  std::printf("Last frame: front end %.1f ms, Super4PCS %.1f ms, refinement %.3f ms, latency %.1f ms\n",
              detections.frontend_ms, detections.registration_ms, detections.refinement_ms, detections.latency_ms);
}

int run(ros::NodeHandle& node, const Options& options)
{
  const auto detections = ros::topic::waitForMessage<brick_pose::BrickDetectionArray>(
      options.detections, node, ros::Duration(options.timeout_s));
  const auto truth =
      ros::topic::waitForMessage<brick_pose::BrickTruthArray>(options.truth, node, ros::Duration(options.timeout_s));
  if (!detections || !truth)
  {
    std::fprintf(stderr, "brick_pose_demo: no %s within %.0f s\n", !detections ? "detections" : "ground truth",
                 options.timeout_s);
    return 1;
  }
  printStreams(*detections);
  if (!ros::service::waitForService(options.service, ros::Duration(10.0)))
  {
    std::fprintf(stderr, "brick_pose_demo: service %s not available\n", options.service.c_str());
    return 1;
  }
  std::printf("\n%-18s %-9s %24s   %-16s %9s %9s %8s\n", "brick (service)", "face", "estimate x y z [m]",
              "ground truth", "rot [deg]", "pos [mm]", "fitness");
  int answered = 0;
  for (const auto& detection : detections->detections)
  {
    brick_pose::GetBrickPose call;
    call.request.frame = detection.frame;
    if (!ros::service::call(options.service, call) || !call.response.success)
    {
      std::printf("%-18s service failed: %s\n", detection.frame.c_str(), call.response.message.c_str());
      continue;
    }
    ++answered;
    const Eigen::Isometry3d estimate = fromPose(call.response.pose.pose);
    const brick_pose::BrickTruth* match = matchTruth(*truth, call.response.type, estimate);
    const Eigen::Vector3d& p = estimate.translation();
    if (match == nullptr)
    {
      std::printf("%-18s %-9s %8.3f %7.3f %7.3f   %-16s\n", call.response.frame.c_str(), faceState(detection),
                  p.x(), p.y(), p.z(), "(none: a false detection)");
      continue;
    }
    const Eigen::Isometry3d truth_pose = fromPose(match->pose);
    const auto error = brick_pose::registration::poseErrorModuloSymmetry(estimate, truth_pose);
    std::printf("%-18s %-9s %8.3f %7.3f %7.3f   %-16s %9.2f %9.2f %8.2f\n", call.response.frame.c_str(),
                faceState(detection), p.x(), p.y(), p.z(), truthName(*match).c_str(), error.rotation_deg,
                error.translation_mm(), call.response.fitness);
  }
  std::printf("(partial: the top face is not wholly in view, so its centre is a guess and the error above is\n"
              " not a measure of accuracy; the service's policies choose only among whole faces)\n");
  for (const auto& brick : truth->bricks)
    std::printf("  truth_%s_%d: %.0f%% of its top face visible\n", brick.type.c_str(), brick.instance_id,
                100.0 * brick.visible_fraction);
  brick_pose::GetBrickPose pick;
  pick.request.policy = "pickable";
  ros::service::call(options.service, pick);
  std::printf("\nget_brick_pose(policy: pickable) -> %s: %s\n", pick.response.success ? "success" : "failure",
              pick.response.message.c_str());
  if (pick.response.success)
    if (const brick_pose::BrickTruth* match = matchTruth(*truth, pick.response.type, fromPose(pick.response.pose.pose)))
    {
      const auto error =
          brick_pose::registration::poseErrorModuloSymmetry(fromPose(pick.response.pose.pose), fromPose(match->pose));
      std::printf("  the grasp planner gets %s = %s, %.2f deg and %.2f mm from the truth\n",
                  pick.response.frame.c_str(), truthName(*match).c_str(), error.rotation_deg, error.translation_mm());
    }
  brick_pose::GetBrickPose absent;
  absent.request.type = "purple";
  ros::service::call(options.service, absent);
  std::printf("\nget_brick_pose(type: purple) -> success %s, \"%s\"\n", absent.response.success ? "true" : "false",
              absent.response.message.c_str());
  return answered > 0 ? 0 : 1;
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "brick_pose_demo", ros::init_options::AnonymousName);
  ros::NodeHandle node;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return run(node, Options());
}
