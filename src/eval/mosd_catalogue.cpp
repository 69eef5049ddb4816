#include "brick_pose/eval/mosd_catalogue.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/common/statistics.h"

namespace brick_pose
{
namespace eval
{
namespace
{
constexpr int kHueCount = 180;  // OpenCV's 8-bit hue: 0..179

bool sameBox(const MosdTopMeasurement& a, const MosdTopMeasurement& b, const MosdCatalogueParams& params)
{
  return std::abs(a.length_m - b.length_m) <= params.max_length_difference_m &&
         std::abs(a.width_m - b.width_m) <= params.max_width_difference_m &&
         std::abs(a.height_m - b.height_m) <= params.max_height_difference_m;
}

double medianOf(const std::vector<MosdTopMeasurement>& members, double MosdTopMeasurement::*field)
{
  std::vector<double> values;
  for (const MosdTopMeasurement& member : members) values.push_back(member.*field);
  return percentile(values, 0.5);
}

double spreadOf(const std::vector<MosdTopMeasurement>& members, double MosdTopMeasurement::*field)
{
  std::vector<double> values;
  for (const MosdTopMeasurement& member : members) values.push_back(member.*field);
  return *std::max_element(values.begin(), values.end()) - *std::min_element(values.begin(), values.end());
}

/// Shortest circular hue interval [first, last] (last < first when it
/// wraps) holding `share` of the histogram.
std::pair<int, int> shortestHueInterval(const std::vector<int>& histogram, double share)
{
  long total = 0;
  for (const int count : histogram) total += count;
  const long needed = static_cast<long>(std::ceil(share * static_cast<double>(total)));
  std::pair<int, int> best{0, kHueCount - 1};
  int best_width = kHueCount;
  for (int first = 0; first < kHueCount; ++first)
  {
    long held = 0;
    for (int width = 1; width <= kHueCount; ++width)
    {
      held += histogram[static_cast<std::size_t>((first + width - 1) % kHueCount)];
      if (held >= needed)
      {
        if (width < best_width)
        {
          best_width = width;
          best = {first, (first + width - 1) % kHueCount};
        }
        break;
      }
    }
  }
  return best;
}

/// The HSV range of the members' top pixels; none when there are no pixels.
std::optional<HsvRange> fitHsvRange(const std::vector<MosdTopMeasurement>& members, const std::vector<const MosdScene*>& scenes,
                     const MosdCatalogueParams& params)
{
  std::vector<int> hue_histogram(kHueCount, 0);
  std::vector<double> saturation, value;
  for (const MosdTopMeasurement& member : members)
  {
    const auto scene = std::find_if(scenes.begin(), scenes.end(),
                                    [&](const MosdScene* s) { return s->name == member.scene; });
    if (scene == scenes.end()) continue;
    cv::Mat hsv;
    cv::cvtColor((*scene)->frame.rgb, hsv, cv::COLOR_RGB2HSV);
    for (const int pixel : member.top_pixels)
    {
      const cv::Vec3b& colour = hsv.at<cv::Vec3b>(pixel / hsv.cols, pixel % hsv.cols);
      ++hue_histogram[std::min<int>(colour[0], kHueCount - 1)];
      saturation.push_back(colour[1]);
      value.push_back(colour[2]);
    }
  }
  if (saturation.empty()) return std::nullopt;
  HsvRange range;
  const auto [hue_first, hue_last] = shortestHueInterval(hue_histogram, params.hue_share);
  const double low = params.saturation_value_low_percentile;
  range.min = {hue_first, static_cast<int>(std::floor(percentile(saturation, low))),
               static_cast<int>(std::floor(percentile(value, low)))};
  range.max = {hue_last, static_cast<int>(std::ceil(percentile(saturation, 1.0 - low))),
               static_cast<int>(std::ceil(percentile(value, 1.0 - low)))};
  return range;
}

std::string typeName(double length_m, double width_m, double height_m)
{
  char name[64];
  std::snprintf(name, sizeof(name), "box_%.0fx%.0fx%.0f", 1000.0 * length_m, 1000.0 * width_m, 1000.0 * height_m);
  return name;
}
}  // namespace

void MosdCatalogueParams::validate() const
{
  if (!(max_length_difference_m > 0.0)) throw ConfigError("max_length_difference_m must be > 0");
  if (!(max_width_difference_m > 0.0)) throw ConfigError("max_width_difference_m must be > 0");
  if (!(max_height_difference_m > 0.0)) throw ConfigError("max_height_difference_m must be > 0");
  if (!(hue_share > 0.0 && hue_share <= 1.0)) throw ConfigError("hue_share must be in (0, 1]");
  if (!(saturation_value_low_percentile >= 0.0 && saturation_value_low_percentile < 0.5))
    throw ConfigError("saturation_value_low_percentile must be in [0, 0.5)");
}

std::vector<MosdTopMeasurement> topMeasurements(const MosdScene& scene, const MosdTruth& truth)
{
  std::vector<MosdTopMeasurement> measurements;
  for (const MosdBox& box : truth.boxes)
  {
    if (!box.has_top) continue;
    MosdTopMeasurement measurement;
    measurement.scene = scene.name;
    measurement.object = box.object;
    measurement.length_m = box.top.length_m;
    measurement.width_m = box.top.width_m;
    measurement.height_m = box.height_m;
    measurement.whole = box.top_whole;
    measurement.top_pixels = box.faces[static_cast<std::size_t>(box.top_face)].pixels;
    measurements.push_back(std::move(measurement));
  }
  return measurements;
}

std::vector<MosdBoxGroup> groupMosdBoxes(const std::vector<MosdTopMeasurement>& measurements,
                                         const std::vector<const MosdScene*>& scenes,
                                         const MosdCatalogueParams& params)
{
  params.validate();
  // Whole tops first: they are measured best, and each group is anchored
  // on its first member.
  std::vector<MosdTopMeasurement> ordered = measurements;
  std::stable_sort(ordered.begin(), ordered.end(),
                   [](const MosdTopMeasurement& a, const MosdTopMeasurement& b) { return a.whole && !b.whole; });
  std::vector<MosdBoxGroup> groups;
  for (const MosdTopMeasurement& measurement : ordered)
  {
    auto group = std::find_if(groups.begin(), groups.end(),
                              [&](const MosdBoxGroup& g) { return sameBox(g.members.front(), measurement, params); });
    if (group == groups.end()) group = groups.insert(groups.end(), MosdBoxGroup());
    group->members.push_back(measurement);
  }
  for (MosdBoxGroup& group : groups)
  {
    // The size from the whole tops when there are any: a partly hidden top
    // can measure short.
    std::vector<MosdTopMeasurement> sized;
    for (const MosdTopMeasurement& member : group.members)
      if (member.whole) sized.push_back(member);
    if (sized.empty()) sized = group.members;
    BrickType& type = group.type;
    type.length_m = medianOf(sized, &MosdTopMeasurement::length_m);
    type.width_m = std::min(type.length_m, medianOf(sized, &MosdTopMeasurement::width_m));
    type.height_m = medianOf(sized, &MosdTopMeasurement::height_m);
    type.name = typeName(type.length_m, type.width_m, type.height_m);
    type.plate_hsv = fitHsvRange(group.members, scenes, params);
    group.length_spread_m = spreadOf(group.members, &MosdTopMeasurement::length_m);
    group.width_spread_m = spreadOf(group.members, &MosdTopMeasurement::width_m);
    group.height_spread_m = spreadOf(group.members, &MosdTopMeasurement::height_m);
  }
  return groups;
}

std::string catalogueYaml(const std::vector<BrickType>& types, const std::string& header_comment)
{
  std::ostringstream yaml;
  std::istringstream comment(header_comment);
  for (std::string line; std::getline(comment, line);) yaml << "# " << line << "\n";
  yaml << "bricks:\n";
  char line[256];
  for (const BrickType& type : types)
  {
    std::snprintf(line, sizeof(line), "  - name: %s\n    length_m: %.4f\n    width_m: %.4f\n    height_m: %.4f\n",
                  type.name.c_str(), type.length_m, type.width_m, type.height_m);
    yaml << line;
    if (!type.plate_hsv) continue;  // a type without a plate colour
    const HsvRange& hsv = *type.plate_hsv;
    std::snprintf(line, sizeof(line), "    hsv_min: [%d, %d, %d]\n    hsv_max: [%d, %d, %d]\n", hsv.min[0], hsv.min[1],
                  hsv.min[2], hsv.max[0], hsv.max[1], hsv.max[2]);
    yaml << line;
  }
  return yaml.str();
}

std::string mosdCataloguePath(const std::string& source_dir) { return source_dir + "/test/data/mosd_learn/catalogue.yaml"; }
}  // namespace eval
}  // namespace brick_pose
