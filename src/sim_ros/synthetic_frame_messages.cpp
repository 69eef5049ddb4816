#include "brick_pose/sim_ros/synthetic_frame_messages.h"

#include <boost/make_shared.hpp>
#include <cv_bridge/cv_bridge.h>
#include <tf2_eigen/tf2_eigen.h>

#include "brick_pose/ros/conversions.h"

namespace brick_pose
{
std::string truthFrameName(const sim::BrickTruth& truth)
{
  return "truth_" + truth.type + "_" + std::to_string(truth.instance_id);
}

SyntheticFrameMessages toMessages(const sim::SyntheticFrame& frame, const ros::Time& stamp,
                                  const std::string& optical_frame_id)
{
  std_msgs::Header header;
  header.stamp = stamp;
  header.frame_id = optical_frame_id;
  SyntheticFrameMessages messages;
  messages.color = cv_bridge::CvImage(header, "rgb8", frame.rgb).toImageMsg();
  messages.depth = cv_bridge::CvImage(header, "16UC1", frame.depth_mm).toImageMsg();
  messages.color_info = boost::make_shared<sensor_msgs::CameraInfo>(ros_conversions::toCameraInfo(frame.camera, header));
  messages.depth_info = boost::make_shared<sensor_msgs::CameraInfo>(*messages.color_info);
  messages.truth = boost::make_shared<BrickTruthArray>();
  messages.truth->header = header;
  for (const sim::BrickTruth& truth : frame.truth)
  {
    BrickTruth brick;
    brick.instance_id = truth.instance_id;
    brick.type = truth.type;
    brick.pose = tf2::toMsg(truth.camera_T_brick);
    brick.dimensions.x = truth.dimensions_m.x();
    brick.dimensions.y = truth.dimensions_m.y();
    brick.dimensions.z = truth.dimensions_m.z();
    brick.visible_fraction = truth.visible_fraction;
    brick.top_face_complete = truth.top_face_complete;
    brick.top_face_cut_by_border = truth.top_face.cut_by_border;
    brick.top_face_occluded = truth.top_face.occluded;
    brick.top_face_tilt_deg = truth.top_face.tilt_deg;
    brick.touching_neighbours = truth.touching_neighbours;
    messages.truth->bricks.push_back(brick);

    geometry_msgs::TransformStamped transform;
    transform.header = header;
    transform.child_frame_id = truthFrameName(truth);
    transform.transform = tf2::eigenToTransform(truth.camera_T_brick).transform;
    messages.truth_frames.push_back(transform);
  }
  geometry_msgs::TransformStamped ground;
  ground.header = header;
  ground.child_frame_id = kTruthGroundFrame;
  ground.transform = tf2::eigenToTransform(frame.camera_T_ground).transform;
  messages.truth_frames.push_back(ground);
  return messages;
}

geometry_msgs::TransformStamped cameraLinkToOptical(const ros::Time& stamp, const std::string& camera_link,
                                                    const std::string& optical_frame_id)
{
  Eigen::Isometry3d link_T_optical = Eigen::Isometry3d::Identity();
  // Columns: optical x (right) = -link y, optical y (down) = -link z, optical z (forward) = link x.
  link_T_optical.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  geometry_msgs::TransformStamped transform;
  transform.header.stamp = stamp;
  transform.header.frame_id = camera_link;
  transform.child_frame_id = optical_frame_id;
  transform.transform = tf2::eigenToTransform(link_T_optical).transform;
  return transform;
}
}  // namespace brick_pose
