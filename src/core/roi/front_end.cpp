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
  params.voxel_enabled = false;
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

std::vector<Segment> FrontEnd::segment(const RgbdFrame& frame) const
{
  return params_.mode == SegmentationMode::kHsv ? hsv_segmenter_.segment(frame, catalogue_)
                                                : region_growing_segmenter_.segment(frame);
}

void FrontEnd::filterSegments(const RgbdFrame& frame, const std::vector<Segment>& segments,
                              FrontEndResult& result) const
{
  const auto roi_start = Clock::now();
  const double cloud_ms_before = result.timings.cloud.total();
  for (const Segment& segment : segments)
  {
    RoiOutcome outcome = roi_filter_.filterSplitting(frame, segment, &result.timings.cloud);
    std::move(outcome.candidates.begin(), outcome.candidates.end(), std::back_inserter(result.candidates));
    for (std::string& reason : outcome.rejections)
      result.rejections.push_back({segment.type_name, segment.bounding_box_px, segment.area_px, std::move(reason)});
  }
  result.timings.roi_ms = millisecondsSince(roi_start) - (result.timings.cloud.total() - cloud_ms_before);
}

FrontEndResult FrontEnd::process(const RgbdFrame& frame) const
{
  FrontEndResult result;
  const auto frame_start = Clock::now();
  const std::vector<Segment> segments = segment(frame);
  result.timings.segmentation_ms = millisecondsSince(frame_start);
  filterSegments(frame, segments, result);
  result.timings.total_ms = millisecondsSince(frame_start);
  return result;
}
}  // namespace brick_pose
