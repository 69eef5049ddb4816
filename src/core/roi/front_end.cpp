#include "brick_pose/roi/front_end.h"

#include <chrono>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

const BrickCatalogue& nonEmpty(const BrickCatalogue& catalogue)
{
  if (catalogue.empty()) throw ConfigError("front end: the brick catalogue is empty");
  return catalogue;
}
}  // namespace

SegmentationMode parseSegmentationMode(const std::string& name)
{
  if (name == "hsv") return SegmentationMode::kHsv;
  if (name == "region_growing") return SegmentationMode::kRegionGrowing;
  throw ConfigError("front end: segmentation mode '" + name + "' is not 'hsv' or 'region_growing'");
}

std::string toString(SegmentationMode mode)
{
  return mode == SegmentationMode::kHsv ? "hsv" : "region_growing";
}

CloudProcessorParams FrontEndParams::defaultSegmentCloudParams()
{
  CloudProcessorParams params;
  params.crop_enabled = true;
  params.voxel_enabled = true;
  params.voxel_leaf_m = 0.005;
  params.outlier_removal_enabled = false;
  params.mls_enabled = false;
  return params;
}

FrontEnd::FrontEnd(const BrickCatalogue& catalogue, const FrontEndParams& params)
  : catalogue_(nonEmpty(catalogue)),
    params_(params),
    hsv_segmenter_(params.hsv),
    region_growing_segmenter_(params.region_growing),
    roi_filter_(catalogue, params.roi, params.cloud)
{
}

FrontEndResult FrontEnd::process(const RgbdFrame& frame) const
{
  FrontEndResult result;
  const auto frame_start = Clock::now();
  const std::vector<Segment> segments = params_.mode == SegmentationMode::kHsv
                                            ? hsv_segmenter_.segment(frame, catalogue_)
                                            : region_growing_segmenter_.segment(frame);
  result.timings.segmentation_ms = millisecondsSince(frame_start);

  const auto roi_start = Clock::now();
  for (const Segment& segment : segments)
  {
    RoiResult outcome = roi_filter_.filter(frame, segment, &result.timings.cloud);
    if (auto* candidate = std::get_if<BrickCandidate>(&outcome))
      result.candidates.push_back(std::move(*candidate));
    else
      result.rejections.push_back(
          {segment.type_name, segment.bounding_box_px, segment.area_px, std::get<std::string>(outcome)});
  }
  result.timings.roi_ms = millisecondsSince(roi_start) - result.timings.cloud.total();
  result.timings.total_ms = millisecondsSince(frame_start);
  return result;
}
}  // namespace brick_pose
