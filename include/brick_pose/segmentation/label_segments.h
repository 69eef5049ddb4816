#pragma once
// Segments from a label image: the 8-connected parts of each region, found
// on runs of pixels (a row's consecutive pixels of one region), so the cost
// is one pass over the image plus a union-find over the runs.

#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
/// `labels` (CV_32SC1) holds a label per pixel (-1 none); label l belongs to
/// region `region_of_label[l]`. Each 8-connected part of a region with at
/// least `min_area_px` mask pixels becomes a segment, largest first. Within
/// a row, a gap of at most `max_gap_px` unlabelled pixels between two pixels
/// of one region (a dropout, an outlier) is part of the mask but not of
/// pixel_indices, which lists the labelled pixels in raster order.
/// `segment_regions` (optional) receives each segment's region.
/// `dropped_regions` (optional) is called once the parts are measured, with
/// the mask area of each region's parts of at least min_area_px (indexed by
/// region), and names the regions (true) whose segments are not built: a
/// segment of most of the image costs more to build than all the others.
using RegionDropper = std::function<std::vector<bool>(const std::vector<int>& region_area_px)>;
std::vector<Segment> segmentsFromLabels(const cv::Mat& labels, const std::vector<int>& region_of_label,
                                        int min_area_px, int max_gap_px, std::vector<int>* segment_regions = nullptr,
                                        const RegionDropper& dropped_regions = RegionDropper());
}  // namespace brick_pose
