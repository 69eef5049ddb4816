#include "brick_pose/frame/frame_builder.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
[[noreturn]] void fail(const std::string& message) { throw InputError("RGB-D frame: " + message); }

std::string sizeText(int width_px, int height_px)
{
  std::ostringstream text;
  text << width_px << "x" << height_px;
  return text.str();
}

int colorChannels(const std::string& encoding)
{
  if (encoding == "rgb8" || encoding == "bgr8") return 3;
  if (encoding == "rgba8" || encoding == "bgra8") return 4;
  fail("unsupported colour encoding '" + encoding + "' (expected rgb8, bgr8, rgba8 or bgra8)");
}

bool depthIsMillimetres(const std::string& encoding)
{
  if (encoding == "16UC1" || encoding == "mono16") return true;
  if (encoding == "32FC1") return false;
  fail("unsupported depth encoding '" + encoding + "' (expected 16UC1 millimetres or 32FC1 metres)");
}

void checkView(const ImageView& view, const char* what, std::size_t pixel_bytes)
{
  if (view.data == nullptr || view.width_px <= 0 || view.height_px <= 0)
    fail(std::string(what) + " image is empty (" + sizeText(view.width_px, view.height_px) + ")");
  if (view.step_bytes < static_cast<std::size_t>(view.width_px) * pixel_bytes)
    fail(std::string(what) + " image step " + std::to_string(view.step_bytes) +
         " bytes is shorter than one row");
}

/// RGB copy of the colour buffer whatever its channel order.
cv::Mat toRgb(const ImageView& color)
{
  const int channels = colorChannels(color.encoding);
  checkView(color, "colour", static_cast<std::size_t>(channels));
  const cv::Mat wrapped(color.height_px, color.width_px, CV_8UC(channels),
                        const_cast<std::uint8_t*>(color.data), color.step_bytes);
  cv::Mat rgb;
  if (color.encoding == "rgb8") rgb = wrapped.clone();
  else if (color.encoding == "bgr8") cv::cvtColor(wrapped, rgb, cv::COLOR_BGR2RGB);
  else if (color.encoding == "rgba8") cv::cvtColor(wrapped, rgb, cv::COLOR_RGBA2RGB);
  else cv::cvtColor(wrapped, rgb, cv::COLOR_BGRA2RGB);
  return rgb;
}

/// Depth in metres with NaN for every pixel without a usable measurement;
/// counts the kinds of invalid pixels so an empty image can be named.
cv::Mat toDepthMetres(const ImageView& depth, std::size_t& zero_count, std::size_t& valid_count)
{
  const bool millimetres = depthIsMillimetres(depth.encoding);
  checkView(depth, "depth", millimetres ? 2 : 4);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cv::Mat depth_m(depth.height_px, depth.width_px, CV_32FC1);
  zero_count = 0;
  valid_count = 0;
  for (int v = 0; v < depth.height_px; ++v)
  {
    const std::uint8_t* row = depth.data + static_cast<std::size_t>(v) * depth.step_bytes;
    float* out = depth_m.ptr<float>(v);
    if (millimetres)
    {
      std::uint16_t value[1];
      for (int u = 0; u < depth.width_px; ++u)
      {
        std::memcpy(value, row + 2 * u, 2);  // rows of a ROS message may be unaligned
        if (value[0] == 0) { out[u] = nan; ++zero_count; }
        else { out[u] = 0.001f * static_cast<float>(value[0]); ++valid_count; }
      }
    }
    else
    {
      float value[1];
      for (int u = 0; u < depth.width_px; ++u)
      {
        std::memcpy(value, row + 4 * u, 4);
        if (value[0] == 0.0f) { out[u] = nan; ++zero_count; }
        else if (value[0] > 0.0f && std::isfinite(value[0])) { out[u] = value[0]; ++valid_count; }
        else out[u] = nan;
      }
    }
  }
  return depth_m;
}

void checkCamera(const PinholeCamera& camera, int width_px, int height_px)
{
  try
  {
    camera.validate();
  }
  catch (const ConfigError& error)
  {
    fail(error.what());
  }
  if (camera.width_px != width_px || camera.height_px != height_px)
    fail("camera intrinsics size " + sizeText(camera.width_px, camera.height_px) +
         " differs from the image size " + sizeText(width_px, height_px));
}

std::string encodingOfColorMat(const cv::Mat& color, bool color_is_bgr)
{
  if (color.type() != CV_8UC3)
    fail("unsupported colour encoding: cv::Mat type " + std::to_string(color.type()) + " (expected CV_8UC3)");
  return color_is_bgr ? "bgr8" : "rgb8";
}

std::string encodingOfDepthMat(const cv::Mat& depth)
{
  if (depth.type() == CV_16UC1) return "16UC1";
  if (depth.type() == CV_32FC1) return "32FC1";
  fail("unsupported depth encoding: cv::Mat type " + std::to_string(depth.type()) +
       " (expected CV_16UC1 millimetres or CV_32FC1 metres)");
}

}  // namespace

RgbdFrame makeRgbdFrame(const ImageView& color, const ImageView& depth, const PinholeCamera& camera,
                        const FrameHeader& header)
{
  // Encodings and emptiness first: a size comparison of an unusable buffer
  // would give a misleading message.
  colorChannels(color.encoding);
  depthIsMillimetres(depth.encoding);
  checkView(color, "colour", 3);
  checkView(depth, "depth", 2);
  if (color.width_px != depth.width_px || color.height_px != depth.height_px)
    fail("colour size " + sizeText(color.width_px, color.height_px) + " differs from depth size " +
         sizeText(depth.width_px, depth.height_px) + " (depth must be aligned to colour)");
  checkCamera(camera, color.width_px, color.height_px);

  RgbdFrame frame;
  std::size_t zero_count = 0;
  std::size_t valid_count = 0;
  frame.depth_m = toDepthMetres(depth, zero_count, valid_count);
  if (valid_count == 0)
  {
    const std::size_t total = static_cast<std::size_t>(depth.width_px) * depth.height_px;
    fail(zero_count == total ? "depth image has no valid pixel (all zero)"
                             : "depth image has no valid pixel (all NaN or non-finite)");
  }
  frame.rgb = toRgb(color);
  frame.camera = camera;
  frame.stamp_ns = header.stamp_ns;
  frame.frame_id = header.frame_id;
  return frame;
}

RgbdFrame makeRgbdFrame(const cv::Mat& color, const cv::Mat& depth, const PinholeCamera& camera,
                        const FrameHeader& header, bool color_is_bgr)
{
  if (color.empty()) fail("colour image is empty");
  if (depth.empty()) fail("depth image is empty");
  const std::string color_encoding = encodingOfColorMat(color, color_is_bgr);
  const std::string depth_encoding = encodingOfDepthMat(depth);
  return makeRgbdFrame(imageViewOf(color, color_encoding), imageViewOf(depth, depth_encoding), camera, header);
}
ImageView imageViewOf(const cv::Mat& image, const std::string& encoding)
{
  ImageView view;
  view.data = image.data;
  view.width_px = image.cols;
  view.height_px = image.rows;
  view.step_bytes = image.step;
  view.encoding = encoding;
  return view;
}
}  // namespace brick_pose
