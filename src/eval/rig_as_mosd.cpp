#include "brick_pose/eval/rig_as_mosd.h"

#include "brick_pose/frame/frame_builder.h"

namespace brick_pose
{
namespace eval
{
MosdScene mosdSceneFromRig(const sim::SyntheticFrame& frame, const std::string& name)
{
  MosdScene scene;
  scene.name = name;
  FrameHeader header;
  header.frame_id = "camera_color_optical_frame";
  scene.frame = makeRgbdFrame(frame.rgb, frame.depth_mm, frame.camera, header);
  scene.labels = cv::Mat(frame.depth_mm.size(), CV_16UC1, cv::Scalar(0));
  for (int v = 0; v < frame.depth_mm.rows; ++v)
    for (int u = 0; u < frame.depth_mm.cols; ++u)
    {
      if (frame.depth_mm.at<std::uint16_t>(v, u) == 0) continue;
      const int instance = frame.instance_labels.at<std::uint16_t>(v, u);
      scene.labels.at<std::uint16_t>(v, u) =
          static_cast<std::uint16_t>(instance == 0 ? 1 : 10 * mosdObjectOfRigInstance(instance));
    }
  return scene;
}
}  // namespace eval
}  // namespace brick_pose
