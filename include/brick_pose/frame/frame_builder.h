#pragma once
// Builds a validated RgbdFrame from raw sensor buffers (what a nodelet gets in
// sensor_msgs/Image) or from cv::Mat. Every rejection is an InputError whose
// message names the problem, so the caller can log it and drop the frame.

#include <cstddef>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

#include "brick_pose/frame/rgbd_frame.h"

namespace brick_pose
{
/// A borrowed, non-owning view on a raw image buffer.
struct ImageView
{
  const std::uint8_t* data = nullptr;
  int width_px = 0;
  int height_px = 0;
  std::size_t step_bytes = 0;  ///< Bytes per row (>= width * pixel size).
  /// sensor_msgs encoding: colour "rgb8", "bgr8", "rgba8", "bgra8";
  /// depth "16UC1" / "mono16" (millimetres) or "32FC1" (metres).
  std::string encoding;
};

/// Stamp and frame of the images.
struct FrameHeader
{
  std::int64_t stamp_ns = 0;
  std::string frame_id;
};

/// A view on `image`'s pixels (borrowed: `image` must outlive the view).
ImageView imageViewOf(const cv::Mat& image, const std::string& encoding);

/// Copies and validates the buffers into an RgbdFrame. Depth 0 (RealSense's
/// "no data"), negative and non-finite values become NaN. Throws InputError
/// naming the problem: unsupported encoding, empty image, colour/depth size
/// mismatch, intrinsics whose size differs from the images, unusable
/// intrinsics (zero/NaN focal length, field named), depth with no valid pixel.
RgbdFrame makeRgbdFrame(const ImageView& color, const ImageView& depth,
                        const PinholeCamera& camera, const FrameHeader& header);

/// Same from cv::Mat: colour CV_8UC3 (order given by `color_is_bgr`), depth
/// CV_16UC1 millimetres or CV_32FC1 metres. The data are copied.
RgbdFrame makeRgbdFrame(const cv::Mat& color, const cv::Mat& depth,
                        const PinholeCamera& camera, const FrameHeader& header,
                        bool color_is_bgr = false);
}  // namespace brick_pose
