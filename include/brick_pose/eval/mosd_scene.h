#pragma once
// One scene of the mOSD "learn" set (test/data/mosd_learn, README there):
// real Kinect v1 colour, depth in millimetres and a per-pixel object label,
// read into the RgbdFrame every stage consumes plus the label image.
//
// Label values: 0 no depth / unlabelled, 1-9 the table, 10k..10k+9 object k
// (k >= 2 in the data: 20-29 is the first object; a last digit other than 0
// marks another disjoint part of the same object).

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/frame/rgbd_frame.h"

namespace brick_pose
{
namespace eval
{
struct MosdScene
{
  std::string name;  ///< e.g. "learn0"
  RgbdFrame frame;   ///< Depth in metres, NaN where the Kinect had none.
  cv::Mat labels;    ///< CV_16UC1, same size as the frame.
};

/// The table's labels are 1-9.
inline bool isMosdTableLabel(std::uint16_t label) { return label >= 1 && label <= 9; }

/// Object number of a label (label / 10, so 2 for 20-29), 0 for the table and "none".
inline int mosdObjectOfLabel(std::uint16_t label) { return label >= 10 ? label / 10 : 0; }

/// Reads `<directory>/<name>_camera.json` (flat object with width, height,
/// fx, fy, cx, cy). Throws InputError naming the file and the missing or
/// malformed field.
PinholeCamera readMosdCamera(const std::string& path);

/// Loads `<directory>/<name>_{color,depth,labels}.png` and the camera.
/// Throws InputError naming the file when one is missing, has the wrong
/// type (colour 8-bit 3-channel, depth and labels 16-bit single channel) or
/// a size different from the camera's.
MosdScene loadMosdScene(const std::string& directory, const std::string& name);

/// Names of the scenes in `directory` ("learn0", "learn1", ...) in numeric
/// order: every learnN whose colour image exists, N counted up from 0 until
/// the first gap.
std::vector<std::string> mosdSceneNames(const std::string& directory);

/// test/data/mosd_learn under `source_dir`.
std::string mosdLearnDirectory(const std::string& source_dir);
}  // namespace eval
}  // namespace brick_pose
