#include "brick_pose/eval/mosd_scene.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"

namespace brick_pose
{
namespace eval
{
namespace
{
std::string readText(const std::string& path)
{
  std::ifstream file(path);
  if (!file) throw InputError("mOSD: cannot open " + path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

/// The number after `"key":` in a flat JSON object. The camera files hold
/// nothing but such pairs, so a full JSON parser would buy nothing.
double jsonNumberField(const std::string& text, const std::string& key, const std::string& path)
{
  const std::string quoted = "\"" + key + "\"";
  const std::size_t at = text.find(quoted);
  if (at == std::string::npos) throw InputError("mOSD: " + path + " has no field '" + key + "'");
  const std::size_t colon = text.find(':', at + quoted.size());
  if (colon == std::string::npos) throw InputError("mOSD: " + path + ": field '" + key + "' has no value");
  const char* begin = text.c_str() + colon + 1;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (end == begin || errno != 0 || !std::isfinite(value))
    throw InputError("mOSD: " + path + ": field '" + key + "' is not a number");
  return value;
}

cv::Mat readImage(const std::string& path, int flags, int expected_type, const char* what)
{
  const cv::Mat image = cv::imread(path, flags);
  if (image.empty()) throw InputError("mOSD: cannot read " + std::string(what) + " image " + path);
  if (image.type() != expected_type)
    throw InputError("mOSD: " + path + " is not a " + what + " image of the expected type");
  return image;
}

void checkSize(const cv::Mat& image, const PinholeCamera& camera, const std::string& path)
{
  if (image.cols != camera.width_px || image.rows != camera.height_px)
    throw InputError("mOSD: " + path + " is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                     ", the camera file says " + std::to_string(camera.width_px) + "x" +
                     std::to_string(camera.height_px));
}

bool fileExists(const std::string& path) { return std::ifstream(path).good(); }
}  // namespace

PinholeCamera readMosdCamera(const std::string& path)
{
  const std::string text = readText(path);
  PinholeCamera camera;
  camera.width_px = static_cast<int>(std::lround(jsonNumberField(text, "width", path)));
  camera.height_px = static_cast<int>(std::lround(jsonNumberField(text, "height", path)));
  camera.fx_px = jsonNumberField(text, "fx", path);
  camera.fy_px = jsonNumberField(text, "fy", path);
  camera.cx_px = jsonNumberField(text, "cx", path);
  camera.cy_px = jsonNumberField(text, "cy", path);
  try
  {
    camera.validate();
  }
  catch (const ConfigError& error)
  {
    throw InputError("mOSD: " + path + ": " + error.what());
  }
  return camera;
}

MosdScene loadMosdScene(const std::string& directory, const std::string& name)
{
  const std::string prefix = directory + "/" + name + "_";
  const PinholeCamera camera = readMosdCamera(prefix + "camera.json");
  // imread gives BGR; the frame builder turns it into RGB.
  const cv::Mat bgr = readImage(prefix + "color.png", cv::IMREAD_COLOR, CV_8UC3, "colour");
  const cv::Mat depth_mm = readImage(prefix + "depth.png", cv::IMREAD_ANYDEPTH, CV_16UC1, "16-bit depth");
  const cv::Mat labels = readImage(prefix + "labels.png", cv::IMREAD_ANYDEPTH, CV_16UC1, "16-bit label");
  checkSize(bgr, camera, prefix + "color.png");
  checkSize(depth_mm, camera, prefix + "depth.png");
  checkSize(labels, camera, prefix + "labels.png");

  MosdScene scene;
  scene.name = name;
  FrameHeader header;
  header.frame_id = "kinect_rgb_optical_frame";
  scene.frame = makeRgbdFrame(bgr, depth_mm, camera, header, /*color_is_bgr=*/true);
  scene.labels = labels;
  return scene;
}

std::vector<std::string> mosdSceneNames(const std::string& directory)
{
  std::vector<std::string> names;
  for (int index = 0;; ++index)
  {
    const std::string name = "learn" + std::to_string(index);
    if (!fileExists(directory + "/" + name + "_color.png")) break;
    names.push_back(name);
  }
  return names;
}

std::string mosdLearnDirectory(const std::string& source_dir) { return source_dir + "/test/data/mosd_learn"; }
}  // namespace eval
}  // namespace brick_pose
