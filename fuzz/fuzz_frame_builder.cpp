// Fuzz target: makeRgbdFrame from raw image buffers and intrinsics, the
// first thing every camera message goes through.
//
// Input layout (FuzzedDataProvider): geometry and encodings first, then the
// intrinsics, then pixel bytes. The buffers are allocated here with exactly
// step x height bytes, as the ingestion nodelet guarantees (it checks the
// message buffer against step x height before building the view), so any
// out-of-bounds access is the builder's own.

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "fuzz_support.h"

namespace
{
const char* const kEncodings[] = {"rgb8", "bgr8", "rgba8", "bgra8", "16UC1", "mono16", "32FC1", "8UC1", "", "yuv422"};

std::string consumeEncoding(FuzzedDataProvider& input)
{
  const int pick = input.ConsumeIntegralInRange<int>(0, 10);
  if (pick < 10) return kEncodings[pick];
  return input.ConsumeRandomLengthString(12);
}

/// Bytes per pixel the encoding claims, 1 when unknown (the builder must
/// reject it before reading anyway).
int pixelBytes(const std::string& encoding)
{
  if (encoding == "rgb8" || encoding == "bgr8") return 3;
  if (encoding == "rgba8" || encoding == "bgra8" || encoding == "32FC1") return 4;
  if (encoding == "16UC1" || encoding == "mono16") return 2;
  return 1;
}

/// The view's step: usually width x pixel size plus padding, sometimes short
/// (must be rejected), sometimes zero.
std::size_t consumeStepBytes(FuzzedDataProvider& input, int width_px, int pixel_bytes)
{
  const std::size_t row_bytes = static_cast<std::size_t>(width_px) * pixel_bytes;
  const int mode = input.ConsumeIntegralInRange<int>(0, 7);
  if (mode == 0) return 0;
  if (mode == 1) return row_bytes > 0 ? row_bytes - 1 : 0;
  return row_bytes + input.ConsumeIntegralInRange<std::size_t>(0, 9);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace brick_pose;
  FuzzedDataProvider input(data, size);

  // Sizes include 0 and negatives: a ROS message's uint32 width cast to int.
  const int width_px = input.ConsumeIntegralInRange<int>(-2, 48);
  const int height_px = input.ConsumeIntegralInRange<int>(-2, 48);
  const bool depth_same_size = input.ConsumeIntegralInRange<int>(0, 7) != 0;
  const int depth_width_px = depth_same_size ? width_px : input.ConsumeIntegralInRange<int>(-2, 48);
  const int depth_height_px = depth_same_size ? height_px : input.ConsumeIntegralInRange<int>(-2, 48);

  ImageView color;
  color.encoding = consumeEncoding(input);
  color.width_px = width_px;
  color.height_px = height_px;
  color.step_bytes = consumeStepBytes(input, std::max(width_px, 0), pixelBytes(color.encoding));
  ImageView depth;
  depth.encoding = consumeEncoding(input);
  depth.width_px = depth_width_px;
  depth.height_px = depth_height_px;
  depth.step_bytes = consumeStepBytes(input, std::max(depth_width_px, 0), pixelBytes(depth.encoding));

  PinholeCamera camera;
  const bool camera_matches = input.ConsumeIntegralInRange<int>(0, 7) != 0;
  camera.width_px = camera_matches ? width_px : input.ConsumeIntegralInRange<int>(-1, 64);
  camera.height_px = camera_matches ? height_px : input.ConsumeIntegralInRange<int>(-1, 64);
  camera.fx_px = fuzz::consumeDouble(input, -10.0, 2000.0);
  camera.fy_px = fuzz::consumeDouble(input, -10.0, 2000.0);
  camera.cx_px = fuzz::consumeDouble(input, -100.0, 200.0);
  camera.cy_px = fuzz::consumeDouble(input, -100.0, 200.0);

  FrameHeader header;
  header.stamp_ns = input.ConsumeIntegral<std::int64_t>();
  header.frame_id = input.ConsumeRandomLengthString(16);

  // Exactly step x height bytes each (none when the height is not positive),
  // filled from the rest of the input.
  const auto buffer_bytes = [](const ImageView& view) {
    return view.height_px > 0 ? view.step_bytes * static_cast<std::size_t>(view.height_px) : 0;
  };
  std::vector<std::uint8_t> color_bytes(buffer_bytes(color));
  std::vector<std::uint8_t> depth_bytes(buffer_bytes(depth));
  const std::vector<std::uint8_t> pixels = input.ConsumeRemainingBytes<std::uint8_t>();
  for (std::size_t i = 0; i < depth_bytes.size() && !pixels.empty(); ++i) depth_bytes[i] = pixels[i % pixels.size()];
  for (std::size_t i = 0; i < color_bytes.size() && !pixels.empty(); ++i)
    color_bytes[i] = pixels[(i * 7 + 3) % pixels.size()];
  color.data = color_bytes.empty() ? nullptr : color_bytes.data();
  depth.data = depth_bytes.empty() ? nullptr : depth_bytes.data();

  try
  {
    const RgbdFrame frame = makeRgbdFrame(color, depth, camera, header);
    // What the header promises of an accepted frame.
    fuzz::require(frame.rgb.type() == CV_8UC3 && frame.depth_m.type() == CV_32FC1);
    fuzz::require(frame.rgb.cols == width_px && frame.rgb.rows == height_px);
    fuzz::require(frame.depth_m.size() == frame.rgb.size());
    bool any_valid = false;
    for (int v = 0; v < frame.depth_m.rows; ++v)
      for (int u = 0; u < frame.depth_m.cols; ++u)
      {
        const float z_m = frame.depthAt(u, v);
        fuzz::require(std::isnan(z_m) || (std::isfinite(z_m) && z_m > 0.0f));
        any_valid = any_valid || !std::isnan(z_m);
      }
    fuzz::require(any_valid);
  }
  catch (const InputError&)
  {
  }
  return 0;
}
