// Fuzz target: FrontEnd::process (segmentation, cloud processing, ROI
// filtration, face-piece merging) on a small fuzzed frame.
//
// Raw random pixels almost never form a plate, so the input is a small scene
// grammar: a background plane, up to four rectangles painted in a catalogue
// plate colour (or any colour) on planes with a fuzzed depth and slope, then
// single-pixel overrides (holes, 65535 mm, stray colours) from the rest of
// the input. Frames are small (<= 96x72) with a short focal length so a brick
// spans tens of pixels and one run takes milliseconds.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "fuzz_support.h"

namespace
{
using brick_pose::BrickCatalogue;

cv::Vec3b consumeColor(FuzzedDataProvider& input, const BrickCatalogue& catalogue)
{
  const int pick = input.ConsumeIntegralInRange<int>(0, static_cast<int>(catalogue.types().size()));
  if (pick < static_cast<int>(catalogue.types().size()))
  {
    const auto& rgb = catalogue.types()[pick].plate_rgb;
    return {rgb[0], rgb[1], rgb[2]};
  }
  return {input.ConsumeIntegral<std::uint8_t>(), input.ConsumeIntegral<std::uint8_t>(),
          input.ConsumeIntegral<std::uint8_t>()};
}

/// Paints a rectangle on a plane: depth = base + slope_u * du + slope_v * dv (mm).
void paintRectangle(FuzzedDataProvider& input, const BrickCatalogue& catalogue, cv::Mat& rgb, cv::Mat& depth_mm)
{
  const int u0 = input.ConsumeIntegralInRange<int>(0, rgb.cols - 1);
  const int v0 = input.ConsumeIntegralInRange<int>(0, rgb.rows - 1);
  const int u1 = input.ConsumeIntegralInRange<int>(u0, rgb.cols - 1);
  const int v1 = input.ConsumeIntegralInRange<int>(v0, rgb.rows - 1);
  const cv::Vec3b color = consumeColor(input, catalogue);
  const int base_mm = input.ConsumeIntegralInRange<int>(0, 65535);
  const int slope_u_mm = input.ConsumeIntegralInRange<int>(-40, 40);
  const int slope_v_mm = input.ConsumeIntegralInRange<int>(-40, 40);
  for (int v = v0; v <= v1; ++v)
    for (int u = u0; u <= u1; ++u)
    {
      rgb.at<cv::Vec3b>(v, u) = color;
      depth_mm.at<std::uint16_t>(v, u) =
          static_cast<std::uint16_t>(std::clamp(base_mm + slope_u_mm * (u - u0) + slope_v_mm * (v - v0), 0, 65535));
    }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace brick_pose;
  static const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  FuzzedDataProvider input(data, size);

  FrontEndParams params;
  params.mode = input.ConsumeBool() ? SegmentationMode::kRegionGrowing : SegmentationMode::kHsv;
  if (input.ConsumeBool())
  {
    // Thresholds scaled to the small frame so that the ROI stage is reached.
    params.hsv.min_area_px = 40;
    params.roi.min_points = 20;
    params.roi.min_part_area_px = 40;
  }
  params.merge_face_pieces = input.ConsumeBool();

  const int width_px = input.ConsumeIntegralInRange<int>(1, 96);
  const int height_px = input.ConsumeIntegralInRange<int>(1, 72);
  PinholeCamera camera;
  camera.width_px = width_px;
  camera.height_px = height_px;
  camera.fx_px = input.ConsumeFloatingPointInRange<double>(20.0, 300.0);
  camera.fy_px = input.ConsumeBool() ? camera.fx_px : input.ConsumeFloatingPointInRange<double>(20.0, 300.0);
  camera.cx_px = 0.5 * width_px + input.ConsumeFloatingPointInRange<double>(-8.0, 8.0);
  camera.cy_px = 0.5 * height_px + input.ConsumeFloatingPointInRange<double>(-8.0, 8.0);

  cv::Mat rgb(height_px, width_px, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::Mat depth_mm(height_px, width_px, CV_16UC1, cv::Scalar(input.ConsumeIntegralInRange<int>(0, 65535)));
  const int rectangles = input.ConsumeIntegralInRange<int>(0, 4);
  for (int i = 0; i < rectangles; ++i) paintRectangle(input, catalogue, rgb, depth_mm);
  while (input.remaining_bytes() >= 4)
  {
    const int index = input.ConsumeIntegralInRange<int>(0, width_px * height_px - 1);
    const int u = index % width_px, v = index / width_px;
    switch (input.ConsumeIntegralInRange<int>(0, 2))
    {
      case 0: depth_mm.at<std::uint16_t>(v, u) = 0; break;
      case 1: depth_mm.at<std::uint16_t>(v, u) = 65535; break;
      default: rgb.at<cv::Vec3b>(v, u) = consumeColor(input, catalogue); break;
    }
  }

  RgbdFrame frame;
  try
  {
    frame = makeRgbdFrame(rgb, depth_mm, camera, FrameHeader());
  }
  catch (const InputError&)
  {
    return 0;  // not the target of this fuzzer (see fuzz_frame_builder)
  }

  try
  {
    const FrontEnd front_end(catalogue, params);
    const FrontEndResult result = front_end.process(frame);
    for (const BrickCandidate& candidate : result.candidates)
      fuzz::require(std::isfinite(candidate.length_m) && std::isfinite(candidate.width_m) &&
                    candidate.centroid_m.allFinite());
  }
  catch (const InputError&)
  {
  }
  return 0;
}
