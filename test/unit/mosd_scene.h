#pragma once
// Test and benchmark helper: the real Kinect scenes of mOSD
// (test/data/mosd_learn, see its README) as RgbdFrames, and what their
// per-pixel labels say about each box: which pixels are its top face (the
// highest face, parallel to the table), and the top's size and the box's
// height measured from those points.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/roi/least_area_quad.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
namespace test
{
struct MosdScene
{
  std::string name;  ///< "learn7"
  RgbdFrame frame;
  cv::Mat labels;    ///< CV_16UC1, the dataset's labels
};

/// One labelled box.
struct MosdObject
{
  int id = 0;             ///< label / 10 (2 for labels 20-29, ...)
  int pixels = 0;         ///< labelled pixels with depth
  int top_pixels = 0;
  double top_length_m = 0.0;  ///< least-area quad of the top pixels, on the top's plane
  double top_width_m = 0.0;
  double top_tilt_deg = 0.0;  ///< top's normal to the table's
  double height_m = 0.0;      ///< top above the lowest visible point of the box
  double top_above_table_m = 0.0;
  /// Another box is nearer to the camera right next to the top: part of
  /// the top may be hidden under it.
  bool top_occluded = false;
};

struct MosdTruth
{
  /// Table plane (n.p + offset = 0).
  double table_offset_m = 0.0;
  Eigen::Vector3d up = Eigen::Vector3d::Zero();  ///< the table's normal, toward the camera
  cv::Mat object;  ///< CV_32SC1: box id per pixel (0 table or nothing)
  cv::Mat top;     ///< CV_8UC1: 255 where the pixel is on its box's top face
  std::vector<MosdObject> objects;
};

inline double mosdNumber(const std::string& json, const std::string& key)
{
  const std::size_t at = json.find("\"" + key + "\"");
  if (at == std::string::npos) return std::nan("");
  const std::size_t colon = json.find(':', at);
  return std::stod(json.substr(colon + 1));
}

/// Scene `learn<index>` of `directory`; empty when its files are missing.
inline std::optional<MosdScene> loadMosdScene(const std::string& directory, int index)
{
  const std::string prefix = directory + "/learn" + std::to_string(index) + "_";
  const cv::Mat bgr = cv::imread(prefix + "color.png", cv::IMREAD_COLOR);
  const cv::Mat depth_mm = cv::imread(prefix + "depth.png", cv::IMREAD_UNCHANGED);
  cv::Mat labels = cv::imread(prefix + "labels.png", cv::IMREAD_UNCHANGED);
  std::ifstream camera_file(prefix + "camera.json");
  if (bgr.empty() || depth_mm.empty() || labels.empty() || !camera_file) return std::nullopt;
  std::stringstream json;
  json << camera_file.rdbuf();
  PinholeCamera camera;
  camera.width_px = bgr.cols;
  camera.height_px = bgr.rows;
  camera.fx_px = mosdNumber(json.str(), "fx");
  camera.fy_px = mosdNumber(json.str(), "fy");
  camera.cx_px = mosdNumber(json.str(), "cx");
  camera.cy_px = mosdNumber(json.str(), "cy");
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  FrameHeader header;
  header.stamp_ns = index;
  header.frame_id = "kinect_rgb_optical_frame";
  MosdScene scene{"learn" + std::to_string(index), makeRgbdFrame(rgb, depth_mm, camera, header), labels};
  return scene;
}

namespace mosd_detail
{
/// Least-squares plane (unit normal toward the camera, offset: n.p + d = 0).
inline bool fitPlane(const std::vector<Eigen::Vector3d>& points, Eigen::Vector3d& normal, double& offset)
{
  if (points.size() < 3) return false;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  normal = solver.eigenvectors().col(0);
  if (normal.dot(centroid) > 0.0) normal = -normal;
  offset = -normal.dot(centroid);
  return true;
}

inline double quantile(std::vector<double> values, double q)
{
  if (values.empty()) return 0.0;
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(std::min(values.size() - 1.0, q * values.size()));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}
}  // namespace mosd_detail

/// Table, boxes and their top faces from the labels.
inline MosdTruth analyseMosdScene(const MosdScene& scene)
{
  using namespace mosd_detail;
  MosdTruth truth;
  const RgbdFrame& frame = scene.frame;
  truth.object = cv::Mat::zeros(scene.labels.size(), CV_32SC1);
  truth.top = cv::Mat::zeros(scene.labels.size(), CV_8UC1);
  std::vector<Eigen::Vector3d> table;
  std::map<int, std::vector<std::pair<cv::Point, Eigen::Vector3d>>> boxes;
  for (int v = 0; v < scene.labels.rows; ++v)
    for (int u = 0; u < scene.labels.cols; ++u)
    {
      const int label = scene.labels.at<std::uint16_t>(v, u);
      const float z = frame.depthAt(u, v);
      if (label >= 20) truth.object.at<int>(v, u) = label / 10;
      if (std::isnan(z)) continue;
      const Eigen::Vector3d p = frame.camera.backProject(u, v, z);
      if (label >= 1 && label <= 9) table.push_back(p);
      else if (label >= 20) boxes[label / 10].push_back({cv::Point(u, v), p});
    }
  Eigen::Vector3d up;
  double offset = 0.0;
  if (!fitPlane(table, up, offset)) return truth;
  // One refit without the points far off the first plane (edge pixels).
  std::vector<Eigen::Vector3d> near;
  for (const auto& p : table)
    if (std::abs(up.dot(p) + offset) < 0.01) near.push_back(p);
  fitPlane(near, up, offset);
  truth.up = up;
  truth.table_offset_m = offset;

  for (const auto& [id, points] : boxes)
  {
    MosdObject object;
    object.id = id;
    object.pixels = static_cast<int>(points.size());
    std::vector<double> heights;
    for (const auto& entry : points) heights.push_back(up.dot(entry.second) + offset);
    // The top is the densest height among the highest points: a face
    // parallel to the table puts all its points at one height, a side face
    // spreads them (2 mm bins, the top 3 cm).
    const double highest = quantile(heights, 0.99);
    constexpr double kBinM = 0.002;
    std::vector<int> histogram(16, 0);
    for (const double h : heights)
    {
      const int bin = static_cast<int>(std::floor((highest - h) / kBinM));
      if (bin >= 0 && bin < static_cast<int>(histogram.size())) ++histogram[static_cast<std::size_t>(bin)];
    }
    int peak = 0;
    for (int bin = 1; bin < static_cast<int>(histogram.size()); ++bin)
      if (histogram[static_cast<std::size_t>(bin)] > histogram[static_cast<std::size_t>(peak)]) peak = bin;
    const double top_height = highest - (peak + 0.5) * kBinM;
    std::vector<Eigen::Vector3d> top_points;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (std::abs(heights[i] - top_height) <= 0.006) top_points.push_back(points[i].second);
    Eigen::Vector3d top_normal;
    double top_offset = 0.0;
    if (!fitPlane(top_points, top_normal, top_offset)) continue;
    object.top_tilt_deg = std::acos(std::min(1.0, std::abs(top_normal.dot(up)))) * 180.0 / M_PI;
    cv::Mat top_mask = cv::Mat::zeros(scene.labels.size(), CV_8UC1);
    for (const auto& entry : points)
      if (std::abs(top_normal.dot(entry.second) + top_offset) < 0.006)
      {
        top_mask.at<std::uint8_t>(entry.first) = 255;
        ++object.top_pixels;
      }
    truth.top.setTo(255, top_mask);
    // Occluded: pixels of another box within a few pixels of the top that
    // are nearer than the top's plane there.
    cv::Mat ring;
    cv::dilate(top_mask, ring, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(7, 7)));
    for (int v = 0; v < ring.rows && !object.top_occluded; ++v)
      for (int u = 0; u < ring.cols; ++u)
      {
        if (!ring.at<std::uint8_t>(v, u) || top_mask.at<std::uint8_t>(v, u)) continue;
        const int other = truth.object.at<int>(v, u);
        const float z = frame.depthAt(u, v);
        if (other == 0 || other == id || std::isnan(z)) continue;
        const Eigen::Vector3d ray = frame.camera.ray(u, v);
        const double plane_z = (-top_offset / top_normal.dot(ray)) * ray.z();
        if (z < plane_z - 0.02)
        {
          object.top_occluded = true;
          break;
        }
      }
    object.top_above_table_m = top_height;
    object.height_m = top_height - quantile(heights, 0.01);
    const std::optional<QuadCorners> quad = fitLeastAreaQuad(largestOutline(top_mask));
    if (quad)
    {
      std::array<Eigen::Vector3d, 4> corners;
      for (int k = 0; k < 4; ++k)
      {
        const Eigen::Vector3d ray = frame.camera.ray((*quad)[k].x(), (*quad)[k].y());
        corners[k] = ray * (-top_offset / top_normal.dot(ray));
      }
      const double a = 0.5 * ((corners[1] - corners[0]).norm() + (corners[3] - corners[2]).norm());
      const double b = 0.5 * ((corners[2] - corners[1]).norm() + (corners[0] - corners[3]).norm());
      object.top_length_m = std::max(a, b);
      object.top_width_m = std::min(a, b);
    }
    truth.objects.push_back(object);
  }
  return truth;
}
/// The catalogue type whose top is `object`'s whole top: its measured size
/// within 1.5 cm (the catalogue's are face-plane sizes, the mask's bleed a
/// little), its height within 2.5 cm, level within 10 deg, and no other box
/// nearer right next to it (a strip of a top hidden under another box, or a
/// top whose box is hidden below it, is not whole); nullptr when none.
inline const BrickType* catalogueTopOf(const MosdObject& object, const BrickCatalogue& catalogue)
{
  if (object.top_occluded) return nullptr;
  for (const BrickType& type : catalogue.types())
    if (std::abs(object.top_length_m - type.length_m) <= 0.015 && std::abs(object.top_width_m - type.width_m) <= 0.015 &&
        object.top_tilt_deg <= 10.0 && std::abs(object.height_m - type.height_m) <= 0.025)
      return &type;
  return nullptr;
}

/// A colour-free segment of the given mask's pixels.
inline Segment segmentOf(const cv::Mat& mask, const RgbdFrame& frame)
{
  Segment segment;
  segment.bounding_box_px = cv::boundingRect(mask);
  segment.mask = mask(segment.bounding_box_px).clone();
  for (int v = segment.bounding_box_px.y; v < segment.bounding_box_px.br().y; ++v)
    for (int u = segment.bounding_box_px.x; u < segment.bounding_box_px.br().x; ++u)
    {
      if (!mask.at<std::uint8_t>(v, u)) continue;
      ++segment.area_px;
      if (!std::isnan(frame.depthAt(u, v))) segment.pixel_indices.push_back(v * frame.width_px() + u);
    }
  return segment;
}

/// The planar faces the labels show, as an ideal colour-free segmenter
/// would return them: each box's top (MosdTruth::top) and its other faces
/// (planes fitted one after another to its remaining pixels, each the
/// largest connected piece, at least `min_area_px`), and the table. The
/// ROI stage can then be judged on its own.
inline std::vector<Segment> labelledFaceSegments(const MosdScene& scene, const MosdTruth& truth, int min_area_px = 300)
{
  using namespace mosd_detail;
  const RgbdFrame& frame = scene.frame;
  std::vector<Segment> segments;
  auto addLargestPiece = [&](const cv::Mat& mask) {
    cv::Mat labels, stats, centroids;
    const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 4);
    int best = 0;
    for (int k = 1; k < count; ++k)
      if (best == 0 || stats.at<int>(k, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = k;
    if (best == 0 || stats.at<int>(best, cv::CC_STAT_AREA) < min_area_px) return cv::Mat();
    const cv::Mat piece = labels == best;
    segments.push_back(segmentOf(piece, frame));
    return piece;
  };
  cv::Mat table = cv::Mat::zeros(scene.labels.size(), CV_8UC1);
  for (int v = 0; v < scene.labels.rows; ++v)
    for (int u = 0; u < scene.labels.cols; ++u)
    {
      const int label = scene.labels.at<std::uint16_t>(v, u);
      if (label >= 1 && label <= 9) table.at<std::uint8_t>(v, u) = 255;
    }
  addLargestPiece(table);
  for (const MosdObject& object : truth.objects)
  {
    const cv::Mat top = (truth.object == object.id) & truth.top;
    addLargestPiece(top);
    // The other faces: planes through the remaining pixels, largest first.
    cv::Mat rest = (truth.object == object.id) & ~truth.top;
    for (int face = 0; face < 4; ++face)
    {
      std::vector<cv::Point> pixels;
      std::vector<Eigen::Vector3d> points;
      for (int v = 0; v < rest.rows; ++v)
        for (int u = 0; u < rest.cols; ++u)
          if (rest.at<std::uint8_t>(v, u) && !std::isnan(frame.depthAt(u, v)))
          {
            pixels.emplace_back(u, v);
            points.push_back(frame.camera.backProject(u, v, frame.depthAt(u, v)));
          }
      if (static_cast<int>(points.size()) < min_area_px) break;
      // RANSAC over a fixed pseudo-random sequence (deterministic).
      std::size_t state = 12345;
      auto next = [&]() {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<std::size_t>(state >> 33) % points.size();
      };
      Eigen::Vector3d best_normal = Eigen::Vector3d::UnitZ();
      double best_offset = 0.0;
      int best_count = -1;
      for (int iteration = 0; iteration < 200; ++iteration)
      {
        const Eigen::Vector3d a = points[next()], b = points[next()], c = points[next()];
        Eigen::Vector3d normal = (b - a).cross(c - a);
        if (normal.norm() < 1e-9) continue;
        normal.normalize();
        const double offset = -normal.dot(a);
        int count = 0;
        for (std::size_t i = 0; i < points.size(); i += 3) count += std::abs(normal.dot(points[i]) + offset) < 0.006;
        if (count > best_count)
        {
          best_count = count;
          best_normal = normal;
          best_offset = offset;
        }
      }
      cv::Mat plane_mask = cv::Mat::zeros(rest.size(), CV_8UC1);
      for (std::size_t i = 0; i < points.size(); ++i)
        if (std::abs(best_normal.dot(points[i]) + best_offset) < 0.006) plane_mask.at<std::uint8_t>(pixels[i]) = 255;
      const cv::Mat piece = addLargestPiece(plane_mask);
      if (piece.empty()) break;
      rest &= ~piece;
    }
  }
  return segments;
}
}  // namespace test
}  // namespace brick_pose
