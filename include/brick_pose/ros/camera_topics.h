#pragma once
// Topic names relative to the camera namespace, as realsense2_camera
// publishes them with align_depth:=true. The ingestion stage subscribes to
// them; the synthetic camera and the bag writer publish them.

namespace brick_pose
{
struct CameraTopics
{
  static constexpr const char* kColorImage = "color/image_raw";
  static constexpr const char* kColorInfo = "color/camera_info";
  static constexpr const char* kDepthImage = "aligned_depth_to_color/image_raw";
  static constexpr const char* kDepthInfo = "aligned_depth_to_color/camera_info";
};
}  // namespace brick_pose
