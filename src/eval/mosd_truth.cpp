#include "brick_pose/eval/mosd_truth.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <opencv2/imgproc.hpp>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/statistics.h"

namespace brick_pose
{
namespace eval
{
namespace
{
/// Table points farther than this from the objects do not enter its plane:
/// the Kinect's depth bends by millimetres toward the far end of a table.
constexpr double kLocalTableRadiusM = 0.6;

struct LabelledPoints
{
  std::vector<Eigen::Vector3d> points;
  std::vector<int> pixels;
};

void addPixel(const RgbdFrame& frame, int pixel, LabelledPoints& to)
{
  const int u = pixel % frame.width_px(), v = pixel / frame.width_px();
  const float depth = frame.depthAt(u, v);
  if (!std::isfinite(depth)) return;
  to.points.push_back(frame.camera.backProject(u, v, depth));
  to.pixels.push_back(pixel);
}

FaceRole roleOf(const Eigen::Vector3d& normal, const Eigen::Vector3d& up, double max_tilt_deg)
{
  const double cos_up = normal.dot(up);
  if (cos_up >= std::cos(max_tilt_deg * kDegToRad)) return FaceRole::kTop;
  if (std::abs(cos_up) <= std::sin(max_tilt_deg * kDegToRad)) return FaceRole::kSide;
  if (cos_up <= -std::cos(max_tilt_deg * kDegToRad)) return FaceRole::kBottom;
  return FaceRole::kOther;
}

/// [low, high] of `values` trimmed by `fraction` at each end.
std::pair<double, double> trimmedRange(std::vector<double> values, double fraction)
{
  return {percentile(values, fraction), percentile(values, 1.0 - fraction)};
}

PlaneFit fitTable(const MosdScene& scene, const MosdTruthParams& params)
{
  const RgbdFrame& frame = scene.frame;
  const auto* labels = scene.labels.ptr<std::uint16_t>(0);
  const int pixel_count = static_cast<int>(scene.labels.total());
  LabelledPoints objects, table;
  for (int pixel = 0; pixel < pixel_count; ++pixel)
  {
    if (mosdObjectOfLabel(labels[pixel]) > 0) addPixel(frame, pixel, objects);
    else if (isMosdTableLabel(labels[pixel])) addPixel(frame, pixel, table);
  }
  if (table.points.size() < 100) throw InputError("mOSD " + scene.name + ": fewer than 100 table points with depth");
  // Only the table around the objects: that is what they stand on.
  if (!objects.points.empty())
  {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& point : objects.points) centre += point;
    centre /= static_cast<double>(objects.points.size());
    LabelledPoints local;
    for (std::size_t i = 0; i < table.points.size(); ++i)
      if ((table.points[i] - centre).norm() <= kLocalTableRadiusM)
      {
        local.points.push_back(table.points[i]);
        local.pixels.push_back(table.pixels[i]);
      }
    if (local.points.size() >= 100) table = std::move(local);
  }
  PlanarFaceParams table_params = params.faces;
  table_params.inlier_distance_at_1m_m = params.table_inlier_distance_m;
  table_params.iterations = params.table_iterations;
  table_params.max_faces = 1;
  table_params.sample_radius_px = 40;
  const std::vector<PlanarFace> planes =
      extractPlanarFaces(table.points, table.pixels, frame.width_px(), frame.height_px(), table_params);
  if (planes.empty()) throw InputError("mOSD " + scene.name + ": no table plane");
  return planes.front().plane;
}

/// Faces of one object with their roles.
std::vector<MosdFace> objectFaces(const LabelledPoints& object, const Eigen::Vector3d& up, const RgbdFrame& frame,
                                  const MosdTruthParams& params)
{
  std::vector<MosdFace> faces;
  for (const PlanarFace& planar :
       extractPlanarFaces(object.points, object.pixels, frame.width_px(), frame.height_px(), params.faces))
  {
    MosdFace face;
    face.plane = planar.plane;
    face.role = roleOf(planar.plane.normal, up, params.max_up_tilt_deg);
    for (const int member : planar.members) face.pixels.push_back(object.pixels[static_cast<std::size_t>(member)]);
    faces.push_back(std::move(face));
  }
  return faces;
}

/// Largest top face (faces come largest first), -1 when none.
int topFaceOf(const std::vector<MosdFace>& faces)
{
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (faces[f].role == FaceRole::kTop) return static_cast<int>(f);
  return -1;
}

Eigen::Vector3d pointAt(const RgbdFrame& frame, int pixel)
{
  const int u = pixel % frame.width_px(), v = pixel / frame.width_px();
  return frame.camera.backProject(u, v, frame.depthAt(u, v));
}

/// Horizontal axis of the box: the largest side face's normal in the top's
/// plane, or the principal axis of the top's points without a side face.
Eigen::Vector3d firstHorizontalAxis(const MosdBox& box, const Eigen::Vector3d& z, const RgbdFrame& frame)
{
  for (const MosdFace& face : box.faces)
    if (face.role == FaceRole::kSide)
    {
      const Eigen::Vector3d in_plane = face.plane.normal - z * z.dot(face.plane.normal);
      if (in_plane.norm() > 0.5) return in_plane.normalized();
    }
  if (box.top_face < 0) return Eigen::Vector3d::Zero();
  const MosdFace& top = box.faces[static_cast<std::size_t>(box.top_face)];
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const int pixel : top.pixels)
  {
    const Eigen::Vector3d d = pointAt(frame, pixel) - top.plane.centroid_m;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d major = solver.eigenvectors().col(2);
  return (major - z * z.dot(major)).normalized();
}

/// Rotation that best turns the box's canonical axes (rough frame `initial`,
/// columns x, y, z) onto its faces' normals, each face weighted by its
/// pixels (orthogonal Procrustes): the large side faces then correct the
/// narrow top's noisy normal and the other way round. `initial` unchanged
/// when fewer than two axes are seen.
Eigen::Matrix3d fitBoxAxes(const MosdBox& box, const Eigen::Matrix3d& initial)
{
  Eigen::Matrix3d correlation = Eigen::Matrix3d::Zero();
  bool axis_seen[3] = {false, false, false};
  for (const MosdFace& face : box.faces)
  {
    if (face.role != FaceRole::kTop && face.role != FaceRole::kSide) continue;
    int best_axis = -1;
    double best_cos = std::cos(30.0 * kDegToRad);
    Eigen::Vector3d best_direction;
    for (int axis = 0; axis < 3; ++axis)
      for (const double sign : {1.0, -1.0})
      {
        const Eigen::Vector3d direction = sign * initial.col(axis);
        if (face.plane.normal.dot(direction) > best_cos)
        {
          best_cos = face.plane.normal.dot(direction);
          best_axis = axis;
          best_direction = direction;
        }
      }
    if (best_axis < 0) continue;
    axis_seen[best_axis] = true;
    correlation += static_cast<double>(face.pixels.size()) * face.plane.normal * best_direction.transpose();
  }
  if (static_cast<int>(axis_seen[0]) + static_cast<int>(axis_seen[1]) + static_cast<int>(axis_seen[2]) < 2)
    return initial;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(correlation, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d sign = Eigen::Matrix3d::Identity();
  sign(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * sign * svd.matrixV().transpose() * initial;
}

/// Axes, extents, top rectangle and visible height of a box from its faces.
void measureBox(MosdBox& box, const Eigen::Vector3d& up, const RgbdFrame& frame, const MosdTruthParams& params)
{
  box.top_face = topFaceOf(box.faces);
  box.has_top = box.top_face >= 0;
  const Eigen::Vector3d rough_z = box.has_top ? box.faces[static_cast<std::size_t>(box.top_face)].plane.normal : up;
  const Eigen::Vector3d rough_x = firstHorizontalAxis(box, rough_z, frame);
  if (rough_x.isZero()) return;
  Eigen::Matrix3d rough;
  rough << rough_x, rough_z.cross(rough_x), rough_z;
  const Eigen::Matrix3d fitted = fitBoxAxes(box, rough);
  const Eigen::Vector3d e1 = fitted.col(0), e2 = fitted.col(1), z = fitted.col(2);
  const Eigen::Vector3d origin =
      box.has_top ? box.faces[static_cast<std::size_t>(box.top_face)].plane.centroid_m : Eigen::Vector3d::Zero();
  std::vector<double> along1, along2, along_z;
  for (const MosdFace& face : box.faces)
    for (const int pixel : face.pixels)
    {
      const Eigen::Vector3d offset = pointAt(frame, pixel) - origin;
      along1.push_back(offset.dot(e1));
      along2.push_back(offset.dot(e2));
      along_z.push_back(offset.dot(z));
    }
  const auto [low1, high1] = trimmedRange(along1, params.extent_trim_fraction);
  const auto [low2, high2] = trimmedRange(along2, params.extent_trim_fraction);
  const auto [low_z, high_z] = trimmedRange(along_z, params.extent_trim_fraction);
  box.visible_height_m = high_z - low_z;
  const bool first_is_long = high1 - low1 >= high2 - low2;
  box.axes.col(0) = first_is_long ? e1 : e2;
  box.axes.col(2) = z;
  box.axes.col(1) = z.cross(box.axes.col(0));
  if (!box.has_top) return;

  TopFaceGeometry& top = box.top;
  top.normal = z;
  top.long_axis = box.axes.col(0);
  top.length_m = first_is_long ? high1 - low1 : high2 - low2;
  top.width_m = first_is_long ? high2 - low2 : high1 - low1;
  top.centre_m = origin + e1 * 0.5 * (low1 + high1) + e2 * 0.5 * (low2 + high2);
  const Eigen::Vector3d half_x = 0.5 * top.length_m * box.axes.col(0);
  const Eigen::Vector3d half_y = 0.5 * top.width_m * box.axes.col(1);
  top.corners_m = {{top.centre_m + half_x + half_y, top.centre_m - half_x + half_y, top.centre_m - half_x - half_y,
                    top.centre_m + half_x - half_y}};
  for (int k = 0; k < 4; ++k) box.top_corners_px[k] = frame.camera.project(top.corners_m[k]);
}

/// Height above the table of a box's top centre.
double heightAboveTable(const MosdBox& box, const PlaneFit& table)
{
  return table.signedDistance(box.top.centre_m);
}

/// Does the vertical through `point` pass through the top rectangle of `box`
/// (grown by `margin_m`)?
bool above(const Eigen::Vector3d& point, const MosdBox& box, double margin_m)
{
  const Eigen::Vector3d offset = point - box.top.centre_m;
  return std::abs(offset.dot(box.axes.col(0))) <= 0.5 * box.top.length_m + margin_m &&
         std::abs(offset.dot(box.axes.col(1))) <= 0.5 * box.top.width_m + margin_m;
}

/// Height of each top over what it stands on: the table, or the highest top
/// under its centre that is at least 2 cm lower.
void measureHeights(std::vector<MosdBox>& boxes, const PlaneFit& table)
{
  for (MosdBox& box : boxes)
  {
    if (!box.has_top) continue;
    const double own = heightAboveTable(box, table);
    double support = 0.0;
    for (const MosdBox& other : boxes)
    {
      if (&other == &box || !other.has_top) continue;
      const double other_height = heightAboveTable(other, table);
      if (other_height < own - 0.02 && above(box.top.centre_m, other, 0.01)) support = std::max(support, other_height);
    }
    box.height_m = own - support;
  }
}

/// Pixel mask of the top's projected rectangle.
cv::Mat rectangleMask(const MosdBox& box, const cv::Size& size)
{
  cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
  std::vector<cv::Point> polygon;
  for (const Eigen::Vector2d& corner : box.top_corners_px)
    polygon.emplace_back(static_cast<int>(std::lround(corner.x())), static_cast<int>(std::lround(corner.y())));
  cv::fillConvexPoly(mask, polygon, cv::Scalar(255));
  return mask;
}

/// Whole in view, hidden, cut or uncertain, with the reason.
void judgeTop(MosdBox& box, const MosdScene& scene, const MosdTruthParams& params)
{
  if (!box.has_top) return;
  const RgbdFrame& frame = scene.frame;
  const int width = frame.width_px(), height = frame.height_px();
  const int margin = params.border_margin_px;
  for (const Eigen::Vector2d& corner : box.top_corners_px)
    if (corner.x() < margin || corner.y() < margin || corner.x() > width - 1 - margin ||
        corner.y() > height - 1 - margin)
    {
      box.not_whole_reason = "cut by the image border";
      return;
    }

  const MosdFace& top = box.faces[static_cast<std::size_t>(box.top_face)];
  cv::Mat top_mask(height, width, CV_8UC1, cv::Scalar(0));
  for (const int pixel : top.pixels) top_mask.ptr<std::uint8_t>(0)[pixel] = 255;
  const cv::Mat rectangle = rectangleMask(box, top_mask.size());
  // Two probes for other objects in front of the top's plane. Inside the
  // rectangle anything in front hides part of the face. In a ring around the
  // labelled top (which catches an occluder hiding an end the extents could
  // not measure) the margin is larger: right beyond the far edge the plane's
  // extension runs under a box standing behind and touching the face, which
  // hides nothing.
  cv::Mat inside, ring;
  cv::erode(rectangle, inside, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  cv::dilate(top_mask, ring, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * params.ring_px + 1, 2 * params.ring_px + 1)));
  ring.setTo(0, rectangle);

  std::map<int, int> occluders;  // object -> pixels in front of the top
  for (int v = 0; v < height; ++v)
  {
    const auto* inside_row = inside.ptr<std::uint8_t>(v);
    const auto* ring_row = ring.ptr<std::uint8_t>(v);
    const auto* label_row = scene.labels.ptr<std::uint16_t>(v);
    for (int u = 0; u < width; ++u)
    {
      const int object = mosdObjectOfLabel(label_row[u]);
      if ((!inside_row[u] && !ring_row[u]) || object == 0 || object == box.object) continue;
      const float depth = frame.depthAt(u, v);
      Eigen::Vector3d on_plane;
      if (!std::isfinite(depth) || !top.plane.intersectRay(frame.camera.ray(u, v), on_plane)) continue;
      const double margin_at_1m_m = inside_row[u] ? params.occluder_margin_at_1m_m : params.ring_occluder_margin_at_1m_m;
      const double margin_m = margin_at_1m_m * std::max(1.0, on_plane.z() * on_plane.z());
      if (depth < on_plane.z() - margin_m) ++occluders[object];
    }
  }
  int worst_object = 0, worst_count = 0;
  for (const auto& [object, count] : occluders)
  {
    box.occluder_px += count;
    if (count > worst_count)
    {
      worst_object = object;
      worst_count = count;
    }
  }

  // Fill of the rectangle's interior: real silhouettes wander by a pixel or
  // two, and the face's pixels next to an edge often go to the
  // neighbouring face (the Kinect rounds depth edges), which on a narrow
  // top would otherwise look like a fifth of it missing.
  cv::Mat interior;
  cv::erode(rectangle, interior, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * params.fill_erosion_px + 1, 2 * params.fill_erosion_px + 1)));
  const int rectangle_px = cv::countNonZero(interior);
  const int labelled_inside = cv::countNonZero(interior & top_mask);
  box.top_fill = rectangle_px > 0 ? static_cast<double>(labelled_inside) / rectangle_px : 0.0;
  char reason[128];
  if (box.occluder_px >= params.min_occluder_px)
  {
    std::snprintf(reason, sizeof(reason), "hidden by object %d (%d px in front of the top)", worst_object,
                  box.occluder_px);
    box.not_whole_reason = reason;
    return;
  }
  if (box.top_fill < params.min_whole_fill)
  {
    std::snprintf(reason, sizeof(reason), "top labelled over only %.0f%% of its rectangle", 100.0 * box.top_fill);
    box.not_whole_reason = reason;
    box.top_uncertain = true;
    return;
  }
  box.top_whole = true;
}

SceneTruth toSceneTruth(const MosdScene& scene, const MosdTruth& truth)
{
  SceneTruth scene_truth;
  scene_truth.face_index = cv::Mat(scene.labels.size(), CV_32SC1, cv::Scalar(-1));
  int* index = scene_truth.face_index.ptr<int>(0);
  for (const MosdBox& box : truth.boxes)
    for (std::size_t f = 0; f < box.faces.size(); ++f)
    {
      const MosdFace& face = box.faces[f];
      FaceTruth face_truth;
      face_truth.object_id = box.object;
      face_truth.role = face.role;
      face_truth.visible_px = static_cast<int>(face.pixels.size());
      if (static_cast<int>(f) == box.top_face)
      {
        face_truth.visible_fraction = box.top_fill;
        face_truth.whole_in_view = box.top_whole;
        face_truth.whole_uncertain = box.top_uncertain;
        face_truth.not_whole_reason = box.not_whole_reason;
        face_truth.has_geometry = true;
        face_truth.geometry = box.top;
      }
      else if (face.role == FaceRole::kTop)
      {
        // A second up-facing plane of one object (a lid, a step): not the box's top.
        face_truth.role = FaceRole::kOther;
      }
      const int face_number = static_cast<int>(scene_truth.faces.size());
      for (const int pixel : face.pixels) index[pixel] = face_number;
      scene_truth.faces.push_back(face_truth);
    }
  FaceTruth table;
  table.role = FaceRole::kSupport;
  const int table_number = static_cast<int>(scene_truth.faces.size());
  const auto* labels = scene.labels.ptr<std::uint16_t>(0);
  for (int pixel = 0; pixel < static_cast<int>(scene.labels.total()); ++pixel)
    if (isMosdTableLabel(labels[pixel]) && index[pixel] < 0)
    {
      index[pixel] = table_number;
      ++table.visible_px;
    }
  scene_truth.faces.push_back(table);
  return scene_truth;
}
}  // namespace

void MosdTruthParams::validate() const
{
  faces.validate();
  if (!(table_inlier_distance_m > 0.0)) throw ConfigError("table_inlier_distance_m must be > 0");
  if (table_iterations < 1) throw ConfigError("table_iterations must be >= 1");
  if (!(max_up_tilt_deg > 0.0 && max_up_tilt_deg < 45.0)) throw ConfigError("max_up_tilt_deg must be in (0, 45)");
  if (!(extent_trim_fraction >= 0.0 && extent_trim_fraction < 0.1)) throw ConfigError("extent_trim_fraction must be in [0, 0.1)");
  if (border_margin_px < 0) throw ConfigError("border_margin_px must be >= 0");
  if (ring_px < 1) throw ConfigError("ring_px must be >= 1");
  if (!(occluder_margin_at_1m_m >= 0.0)) throw ConfigError("occluder_margin_at_1m_m must be >= 0");
  if (!(ring_occluder_margin_at_1m_m >= 0.0)) throw ConfigError("ring_occluder_margin_at_1m_m must be >= 0");
  if (min_occluder_px < 1) throw ConfigError("min_occluder_px must be >= 1");
  if (fill_erosion_px < 0) throw ConfigError("fill_erosion_px must be >= 0");
  if (!(min_whole_fill > 0.0 && min_whole_fill <= 1.0)) throw ConfigError("min_whole_fill must be in (0, 1]");
}

MosdTruth extractMosdTruth(const MosdScene& scene, const MosdTruthParams& params)
{
  params.validate();
  const RgbdFrame& frame = scene.frame;
  if (scene.labels.type() != CV_16UC1 || scene.labels.size() != frame.depth_m.size())
    throw InputError("mOSD " + scene.name + ": the label image is not 16-bit or not the frame's size");
  MosdTruth truth;
  truth.table = fitTable(scene, params);
  truth.has_table = true;
  truth.up = truth.table.normal;

  std::map<int, LabelledPoints> objects;
  const auto* labels = scene.labels.ptr<std::uint16_t>(0);
  for (int pixel = 0; pixel < static_cast<int>(scene.labels.total()); ++pixel)
    if (const int object = mosdObjectOfLabel(labels[pixel]); object > 0) addPixel(frame, pixel, objects[object]);
  for (const auto& [object, points] : objects)
  {
    MosdBox box;
    box.object = object;
    box.pixels = points.pixels;
    box.faces = objectFaces(points, truth.up, frame, params);
    measureBox(box, truth.up, frame, params);
    truth.boxes.push_back(std::move(box));
  }
  measureHeights(truth.boxes, truth.table);
  for (MosdBox& box : truth.boxes) judgeTop(box, scene, params);
  truth.scene = toSceneTruth(scene, truth);
  return truth;
}

cv::Mat drawMosdTruthOverlay(const MosdScene& scene, const MosdTruth& truth)
{
  cv::Mat bgr;
  cv::cvtColor(scene.frame.rgb, bgr, cv::COLOR_RGB2BGR);
  bgr *= 0.45;
  auto tint = [&](const std::vector<int>& pixels, const cv::Vec3b& colour) {
    for (const int pixel : pixels)
    {
      cv::Vec3b& value = bgr.at<cv::Vec3b>(pixel / bgr.cols, pixel % bgr.cols);
      for (int c = 0; c < 3; ++c) value[c] = static_cast<std::uint8_t>(std::min(255, value[c] / 2 + colour[c] * 3 / 5));
    }
  };
  const auto* labels = scene.labels.ptr<std::uint16_t>(0);
  std::vector<int> table;
  for (int pixel = 0; pixel < static_cast<int>(scene.labels.total()); ++pixel)
    if (isMosdTableLabel(labels[pixel])) table.push_back(pixel);
  tint(table, cv::Vec3b(120, 120, 120));
  for (const MosdBox& box : truth.boxes)
  {
    for (std::size_t f = 0; f < box.faces.size(); ++f)
    {
      const MosdFace& face = box.faces[f];
      cv::Vec3b colour(200, 0, 200);  // other: magenta
      if (face.role == FaceRole::kSide) colour = cv::Vec3b(255, 120, 0);
      if (static_cast<int>(f) == box.top_face)
        colour = box.top_whole ? cv::Vec3b(0, 230, 0) : box.top_uncertain ? cv::Vec3b(0, 230, 230) : cv::Vec3b(0, 140, 255);
      tint(face.pixels, colour);
    }
    if (!box.has_top) continue;
    std::vector<cv::Point> polygon;
    for (const Eigen::Vector2d& corner : box.top_corners_px)
      polygon.emplace_back(static_cast<int>(std::lround(corner.x())), static_cast<int>(std::lround(corner.y())));
    cv::polylines(bgr, polygon, true, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    char text[96];
    std::snprintf(text, sizeof(text), "%d: %.0fx%.0fx%.0f", box.object, 1000.0 * box.top.length_m,
                  1000.0 * box.top.width_m, 1000.0 * box.height_m);
    const Eigen::Vector2d centre = scene.frame.camera.project(box.top.centre_m);
    cv::putText(bgr, text, cv::Point(static_cast<int>(centre.x()) - 40, static_cast<int>(centre.y()) - 12),
                cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
  return bgr;
}
}  // namespace eval
}  // namespace brick_pose
