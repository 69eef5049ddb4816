#include "brick_pose/eval/planar_faces.h"

#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/sim/fast_random.h"

namespace brick_pose
{
namespace eval
{
namespace
{
/// Index of the point at each pixel, -1 where none, restricted to `active`.
class PixelIndex
{
public:
  PixelIndex(const std::vector<int>& pixels, int width_px, int height_px)
    : width_px_(width_px), height_px_(height_px), index_(static_cast<std::size_t>(width_px) * height_px, -1)
  {
    for (std::size_t i = 0; i < pixels.size(); ++i) index_[static_cast<std::size_t>(pixels[i])] = static_cast<int>(i);
  }

  /// Point at (u, v), -1 outside the image or where there is none.
  int at(int u_px, int v_px) const
  {
    if (u_px < 0 || v_px < 0 || u_px >= width_px_ || v_px >= height_px_) return -1;
    return index_[static_cast<std::size_t>(v_px) * width_px_ + u_px];
  }

private:
  int width_px_, height_px_;
  std::vector<int> index_;
};

PlaneFit planeThrough(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  PlaneFit plane;
  Eigen::Vector3d normal = (b - a).cross(c - a);
  // Nearly collinear samples give no usable plane.
  if (normal.norm() < 1e-9 || normal.norm() < 1e-3 * (b - a).norm() * (c - a).norm()) return plane;
  normal.normalize();
  plane.centroid_m = (a + b + c) / 3.0;
  plane.normal = normal.dot(plane.centroid_m) > 0.0 ? -normal : normal;
  plane.valid = true;
  return plane;
}

/// Least-squares plane of the selected points, normal toward the camera.
PlaneFit leastSquaresPlane(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& selected)
{
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.reserve(selected.size());
  for (const int i : selected)
    cloud.push_back(pcl::PointXYZ(static_cast<float>(points[i].x()), static_cast<float>(points[i].y()),
                                  static_cast<float>(points[i].z())));
  PlaneFitParams fit;
  fit.refit_iterations = 0;  // the RANSAC inliers are already free of outliers
  return fitPlane(cloud, fit);
}

bool isInlier(const PlaneFit& plane, const Eigen::Vector3d& point, const PlanarFaceParams& params)
{
  return std::abs(plane.signedDistance(point)) <= params.inlierDistance(point.z());
}

/// The best plane of the `remaining` points, or an invalid one.
PlaneFit ransacPlane(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& pixels,
                     const std::vector<int>& remaining, const std::vector<char>& is_remaining,
                     const PixelIndex& pixel_index, int width_px, const PlanarFaceParams& params,
                     sim::FastRandom& random)
{
  // Score hypotheses on at most ~4000 points: enough to rank planes.
  const std::size_t stride = std::max<std::size_t>(1, remaining.size() / 4000);
  PlaneFit best;
  std::size_t best_score = 0;
  for (int iteration = 0; iteration < params.iterations; ++iteration)
  {
    const int first = remaining[static_cast<std::size_t>(random.next() % remaining.size())];
    const int u = pixels[first] % width_px, v = pixels[first] / width_px;
    int sample[2] = {-1, -1};
    for (int slot = 0, attempt = 0; slot < 2 && attempt < 40; ++attempt)
    {
      const int span = 2 * params.sample_radius_px + 1;
      const int du = static_cast<int>(random.next() % span) - params.sample_radius_px;
      const int dv = static_cast<int>(random.next() % span) - params.sample_radius_px;
      const int candidate = pixel_index.at(u + du, v + dv);
      if (candidate < 0 || candidate == first || !is_remaining[candidate] || (slot == 1 && candidate == sample[0]))
        continue;
      sample[slot++] = candidate;
    }
    if (sample[1] < 0) continue;
    const PlaneFit plane = planeThrough(points[first], points[sample[0]], points[sample[1]]);
    if (!plane.valid) continue;
    std::size_t score = 0;
    for (std::size_t k = 0; k < remaining.size(); k += stride)
      if (isInlier(plane, points[remaining[k]], params)) ++score;
    if (score > best_score)
    {
      best_score = score;
      best = plane;
    }
  }
  return best;
}

/// Members whose image component (4-connected among members) has at least `min_px` pixels.
std::vector<int> withoutSmallComponents(const std::vector<int>& members, const std::vector<int>& pixels,
                                        int width_px, int height_px, int min_px)
{
  if (members.empty()) return members;
  cv::Mat mask(height_px, width_px, CV_8UC1, cv::Scalar(0));
  for (const int i : members) mask.ptr<std::uint8_t>(0)[pixels[i]] = 255;
  cv::Mat labels, stats, centroids;
  cv::connectedComponentsWithStats(mask, labels, stats, centroids, 4, CV_32S);
  std::vector<int> kept;
  for (const int i : members)
  {
    const int label = labels.ptr<int>(0)[pixels[i]];
    if (stats.at<int>(label, cv::CC_STAT_AREA) >= min_px) kept.push_back(i);
  }
  return kept;
}
}  // namespace

void PlanarFaceParams::validate() const
{
  if (!(inlier_distance_at_1m_m > 0.0)) throw ConfigError("inlier_distance_at_1m_m must be > 0");
  if (iterations < 1) throw ConfigError("iterations must be >= 1");
  if (min_face_points < 3) throw ConfigError("min_face_points must be >= 3");
  if (sample_radius_px < 1) throw ConfigError("sample_radius_px must be >= 1");
  if (max_faces < 1) throw ConfigError("max_faces must be >= 1");
  if (min_component_px < 1) throw ConfigError("min_component_px must be >= 1");
}

std::vector<PlanarFace> extractPlanarFaces(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& pixels,
                                           int image_width_px, int image_height_px, const PlanarFaceParams& params)
{
  params.validate();
  if (points.size() != pixels.size()) throw InputError("extractPlanarFaces: points and pixels differ in number");
  const PixelIndex pixel_index(pixels, image_width_px, image_height_px);
  sim::FastRandom random(params.seed);

  // 1. Sequential RANSAC: the largest plane of what is left, until too few points remain.
  std::vector<PlaneFit> planes;
  std::vector<char> is_remaining(points.size(), 1);
  std::vector<int> remaining(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) remaining[i] = static_cast<int>(i);
  while (static_cast<int>(planes.size()) < params.max_faces &&
         static_cast<int>(remaining.size()) >= params.min_face_points)
  {
    const PlaneFit hypothesis = ransacPlane(points, pixels, remaining, is_remaining, pixel_index, image_width_px,
                                            params, random);
    if (!hypothesis.valid) break;
    std::vector<int> inliers;
    for (const int i : remaining)
      if (isInlier(hypothesis, points[i], params)) inliers.push_back(i);
    inliers = withoutSmallComponents(inliers, pixels, image_width_px, image_height_px, params.min_component_px);
    if (static_cast<int>(inliers.size()) < params.min_face_points) break;
    PlaneFit plane = leastSquaresPlane(points, inliers);
    if (!plane.valid) break;
    planes.push_back(plane);
    for (const int i : inliers) is_remaining[i] = 0;
    std::vector<int> still;
    for (const int i : remaining)
      if (is_remaining[i]) still.push_back(i);
    remaining.swap(still);
  }

  // 2. Each point to the nearest plane that holds it: the sequential pass
  // gives the first (largest) face a strip of each neighbouring face along
  // their common edge, which would shorten the narrow faces.
  std::vector<std::vector<int>> members(planes.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    int nearest = -1;
    double nearest_distance = std::numeric_limits<double>::max();
    for (std::size_t p = 0; p < planes.size(); ++p)
    {
      const double distance = std::abs(planes[p].signedDistance(points[i]));
      if (distance <= params.inlierDistance(points[i].z()) && distance < nearest_distance)
      {
        nearest = static_cast<int>(p);
        nearest_distance = distance;
      }
    }
    if (nearest >= 0) members[static_cast<std::size_t>(nearest)].push_back(static_cast<int>(i));
  }

  // 3. Refit on the final members, drop crumbs.
  std::vector<PlanarFace> faces;
  for (std::vector<int>& face_members : members)
  {
    face_members = withoutSmallComponents(face_members, pixels, image_width_px, image_height_px,
                                          params.min_component_px);
    if (static_cast<int>(face_members.size()) < params.min_face_points) continue;
    PlanarFace face;
    face.plane = leastSquaresPlane(points, face_members);
    if (!face.plane.valid) continue;
    face.members = std::move(face_members);
    faces.push_back(std::move(face));
  }
  std::sort(faces.begin(), faces.end(),
            [](const PlanarFace& a, const PlanarFace& b) { return a.members.size() > b.members.size(); });
  return faces;
}
}  // namespace eval
}  // namespace brick_pose
