#include "brick_pose/segmentation/label_segments.h"

#include <algorithm>
#include <cstring>

#include "brick_pose/common/union_find.h"

namespace brick_pose
{
namespace
{
struct Run
{
  int v;
  int u_begin, u_end;  // [begin, end) in the row
  int region;
};

/// The runs of one row, gaps of unlabelled pixels up to max_gap_px bridged.
void appendRowRuns(const int* row, int v, int width, const std::vector<int>& region_of_label, int max_gap_px,
                   std::vector<Run>& runs)
{
  int u = 0;
  while (u < width)
  {
    if (row[u] < 0)
    {
      ++u;
      continue;
    }
    const int region = region_of_label[row[u]];
    int end = u + 1;  // one past the last labelled pixel of the run
    for (int next = end; next < width;)
    {
      if (row[next] >= 0)
      {
        if (region_of_label[row[next]] != region) break;
        end = ++next;
        continue;
      }
      int gap_end = next;
      while (gap_end < width && row[gap_end] < 0 && gap_end - next < max_gap_px + 1) ++gap_end;
      if (gap_end >= width || row[gap_end] < 0 || region_of_label[row[gap_end]] != region) break;
      next = gap_end;
    }
    runs.push_back({v, u, end, region});
    u = end;
  }
}
}  // namespace

std::vector<Segment> segmentsFromLabels(const cv::Mat& labels, const std::vector<int>& region_of_label,
                                        int min_area_px, int max_gap_px, std::vector<int>* segment_regions,
                                        const RegionDropper& dropped_regions)
{
  CV_Assert(labels.type() == CV_32SC1);
  const int width = labels.cols, height = labels.rows;
  // Working storage kept between frames (fresh buffers cost page faults).
  thread_local std::vector<Run> runs;
  thread_local std::vector<int> row_start, parent;
  runs.clear();
  row_start.assign(static_cast<std::size_t>(height) + 1, 0);
  for (int v = 0; v < height; ++v)
  {
    row_start[v] = static_cast<int>(runs.size());
    appendRowRuns(labels.ptr<int>(v), v, width, region_of_label, max_gap_px, runs);
  }
  row_start[height] = static_cast<int>(runs.size());

  // Runs of one region in consecutive rows that touch (8-connected) join.
  parent.resize(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) parent[i] = static_cast<int>(i);
  for (int v = 1; v < height; ++v)
  {
    int above = row_start[v - 1];
    const int above_end = row_start[v];
    for (int current = row_start[v]; current < row_start[v + 1]; ++current)
    {
      const Run& run = runs[current];
      while (above < above_end && runs[above].u_end < run.u_begin) ++above;  // ends left of this run's diagonal
      for (int other = above; other < above_end && runs[other].u_begin <= run.u_end; ++other)
        if (runs[other].region == run.region) parent[findRoot(parent, current)] = findRoot(parent, other);
    }
  }

  // Area and box of each part.
  struct Part
  {
    int area = 0;
    int u_min = 0, u_max = 0, v_min = 0, v_max = 0;
    int segment = -1;
    int region = -1;
  };
  thread_local std::vector<Part> parts;
  parts.assign(runs.size(), Part());
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    const Run& run = runs[i];
    Part& part = parts[findRoot(parent, static_cast<int>(i))];
    if (part.area == 0)
    {
      part.u_min = run.u_begin;
      part.u_max = run.u_end;
      part.v_min = run.v;
      part.region = run.region;
    }
    part.area += run.u_end - run.u_begin;
    part.u_min = std::min(part.u_min, run.u_begin);
    part.u_max = std::max(part.u_max, run.u_end);
    part.v_max = run.v;
  }
  // Segments are built in place: a vector of them that grows would copy
  // them (cv::Mat's move may throw), losing the reserved capacity.
  std::vector<bool> dropped;
  if (dropped_regions)
  {
    std::vector<int> region_area_px(region_of_label.empty()
                                        ? 0
                                        : static_cast<std::size_t>(*std::max_element(region_of_label.begin(),
                                                                                     region_of_label.end())) + 1,
                                    0);
    for (const Part& part : parts)
      if (part.area >= min_area_px) region_area_px[part.region] += part.area;
    dropped = dropped_regions(region_area_px);
  }
  auto isDropped = [&](int region) { return region < static_cast<int>(dropped.size()) && dropped[region]; };
  int segment_count = 0;
  for (Part& part : parts)
    if (part.area >= min_area_px && !isDropped(part.region)) part.segment = segment_count++;
  std::vector<Segment> segments(static_cast<std::size_t>(segment_count));
  for (const Part& part : parts)
  {
    if (part.segment < 0) continue;
    Segment& segment = segments[part.segment];
    segment.bounding_box_px = cv::Rect(part.u_min, part.v_min, part.u_max - part.u_min, part.v_max - part.v_min + 1);
    segment.area_px = part.area;
    segment.mask = cv::Mat::zeros(segment.bounding_box_px.size(), CV_8UC1);
    segment.pixel_indices.reserve(static_cast<std::size_t>(part.area));
  }
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    const int index = parts[findRoot(parent, static_cast<int>(i))].segment;
    if (index < 0) continue;
    const Run& run = runs[i];
    Segment& segment = segments[index];
    const cv::Rect& box = segment.bounding_box_px;
    std::memset(segment.mask.ptr<std::uint8_t>(run.v - box.y) + (run.u_begin - box.x), 255,
                static_cast<std::size_t>(run.u_end - run.u_begin));
    const int* row = labels.ptr<int>(run.v);
    for (int u = run.u_begin; u < run.u_end; ++u)
      if (row[u] >= 0) segment.pixel_indices.push_back(run.v * width + u);
  }
  // Largest first (stable: equal areas keep raster order).
  std::vector<int> order(segments.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return segments[a].area_px > segments[b].area_px; });
  std::vector<int> regions_of_segments(segments.size());
  for (const Part& part : parts)
    if (part.segment >= 0) regions_of_segments[part.segment] = part.region;
  std::vector<Segment> sorted;
  sorted.reserve(segments.size());
  if (segment_regions) segment_regions->clear();
  for (const int k : order)
  {
    sorted.push_back(std::move(segments[k]));
    if (segment_regions) segment_regions->push_back(regions_of_segments[k]);
  }
  return sorted;
}
}  // namespace brick_pose
