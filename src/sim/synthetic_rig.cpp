#include "brick_pose/sim/synthetic_rig.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "brick_pose/catalogue/resting.h"
#include "brick_pose/sim/box_print.h"
#include "brick_pose/sim/fast_random.h"
#include "brick_pose/sim/ray_caster.h"
#include "brick_pose/sim/stereo_matching.h"
#include "brick_pose/sim/top_face_visibility.h"
#include "brick_pose/sim/touching.h"

namespace brick_pose
{
namespace sim
{
namespace
{
constexpr float kNoDepth = std::numeric_limits<float>::quiet_NaN();
/// Values of the face label image: CuboidFace::kNone .. kMinusY.
constexpr int kCuboidFaceLabels = static_cast<int>(CuboidFace::kMinusY) + 1;

/// Per-pixel result of the geometry pass.
struct GeometryBuffers
{
  cv::Mat depth_m;         // CV_32FC1, NaN where nothing
  cv::Mat brick_index;     // CV_32SC1, RayHit::kGround / kNothing / index
  cv::Mat face;            // CV_8UC1
  cv::Mat normal_dot_ray;  // CV_32FC1, |cos| between the normal and the viewing ray
  cv::Mat lambert;         // CV_32FC1, max(0, n . light)
  cv::Mat rounding;        // CV_32FC1, 0..1: how far into a rounded top edge (0 = flat)
};

struct LightingProfile
{
  double ambient;
  double diffuse;
  double washout;       // blend toward white of lit surfaces (sunlight)
  double noise_scale;   // multiplies SensorModel::colour_noise_sigma
  double bright_dropout_probability;  // extra depth holes on bright pixels
};

LightingProfile profileFor(Lighting lighting)
{
  switch (lighting)
  {
    case Lighting::kSunlight:
      return {0.45, 0.95, 0.25, 1.5, 0.06};
    case Lighting::kLowLight:
      return {0.10, 0.22, 0.0, 4.0, 0.0};
    case Lighting::kNormal:
    default:
      return {0.35, 0.70, 0.0, 1.0, 0.0};
  }
}

/// Deterministic texture of the ground (5 cm tiles of varying brightness),
/// fixed to the world so it does not move with the camera.
double groundTexture(const Eigen::Vector3d& point_world)
{
  const auto tile = [](double value) { return static_cast<std::int64_t>(std::floor(value / 0.05)); };
  std::uint64_t hash = static_cast<std::uint64_t>(tile(point_world.x()) * 73856093LL) ^
                       static_cast<std::uint64_t>(tile(point_world.y()) * 19349663LL);
  FastRandom random(hash);
  return 0.85 + 0.3 * random.uniform();
}

class Renderer
{
public:
  Renderer(const PinholeCamera& camera, const SensorModel& sensor, const Scene& scene, std::uint64_t seed)
    : camera_(camera)
    , sensor_(sensor)
    , scene_(scene)
    , caster_(scene, camera)
    , profile_(profileFor(sensor.lighting))
    , random_(seed)
  {
    // The sun (or lamp) shines from above and a little behind the camera.
    const Eigen::Vector3d toward_light_world = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
    toward_light_ = scene.world_T_camera.linear().transpose() * toward_light_world;
    for (const PlacedBrick& brick : scene.bricks)
      prints_.push_back(brick.markings.cardboard ? std::optional<BoxPrint>(BoxPrint(brick.type, brick.markings))
                                                 : std::nullopt);
    for (const Eigen::Isometry3d& camera_T_brick : caster_.cameraTBricks())
      brick_T_camera_.push_back(camera_T_brick.inverse());
  }

  SyntheticFrame render()
  {
    SyntheticFrame frame;
    frame.camera = camera_;
    const GeometryBuffers geometry = castPrimaryRays();
    frame.depth_clean_m = geometry.depth_m;
    frame.instance_labels = instanceLabels(geometry);
    frame.face_labels = geometry.face;
    frame.rgb = shade(geometry);
    frame.depth_mm = measureDepth(geometry);
    frame.truth = groundTruth(frame);
    frame.camera_T_ground = scene_.world_T_camera.inverse();
    return frame;
  }

private:
  GeometryBuffers castPrimaryRays() const
  {
    const int width = camera_.width_px, height = camera_.height_px;
    GeometryBuffers buffers{cv::Mat(height, width, CV_32FC1, cv::Scalar(kNoDepth)),
                            cv::Mat(height, width, CV_32SC1, cv::Scalar(RayHit::kNothing)),
                            cv::Mat(height, width, CV_8UC1, cv::Scalar(0)), cv::Mat(height, width, CV_32FC1, cv::Scalar(0)),
                            cv::Mat(height, width, CV_32FC1, cv::Scalar(0)), cv::Mat(height, width, CV_32FC1, cv::Scalar(0))};
    const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    for (int v = 0; v < height; ++v)
      for (int u = 0; u < width; ++u)
        store(buffers, u, v, caster_.castGround(origin, camera_.ray(u, v)));
    // Bricks: only the pixels their projection can cover.
    for (int i = 0; i < static_cast<int>(scene_.bricks.size()); ++i)
    {
      const Eigen::Vector4i bounds = caster_.pixelBounds(i);
      for (int v = bounds[1]; v <= bounds[3]; ++v)
        for (int u = bounds[0]; u <= bounds[2]; ++u)
        {
          const RayHit hit = caster_.castBrick(i, origin, camera_.ray(u, v));
          const float current = buffers.depth_m.at<float>(v, u);
          if (hit.hitSomething() && (std::isnan(current) || hit.ray_t < current)) store(buffers, u, v, hit);
        }
    }
    return buffers;
  }

  void store(GeometryBuffers& buffers, int u, int v, const RayHit& hit) const
  {
    if (!hit.hitSomething()) return;
    const Eigen::Vector3d ray = camera_.ray(u, v);
    const double rounding = roundingOf(hit);
    double depth = hit.ray_t;
    // Along the ray (z = 1) the rounding's dip below the face is sink / |n . ray|.
    if (rounding > 0.0) depth += roundingSink(rounding) / std::max(0.05, std::abs(hit.normal.dot(ray)));
    buffers.rounding.at<float>(v, u) = static_cast<float>(rounding);
    buffers.depth_m.at<float>(v, u) = static_cast<float>(depth);
    buffers.brick_index.at<int>(v, u) = hit.brick_index;
    buffers.face.at<unsigned char>(v, u) = static_cast<unsigned char>(hit.face);
    buffers.normal_dot_ray.at<float>(v, u) = static_cast<float>(std::abs(hit.normal.dot(ray.normalized())));
    buffers.lambert.at<float>(v, u) = static_cast<float>(std::max(0.0, hit.normal.dot(toward_light_)));
  }

  static cv::Mat instanceLabels(const GeometryBuffers& geometry)
  {
    cv::Mat labels(geometry.brick_index.size(), CV_16UC1, cv::Scalar(0));
    for (int v = 0; v < labels.rows; ++v)
      for (int u = 0; u < labels.cols; ++u)
      {
        const int index = geometry.brick_index.at<int>(v, u);
        if (index >= 0) labels.at<unsigned short>(v, u) = static_cast<unsigned short>(index + 1);
      }
    return labels;
  }

  /// 0 on the flat of a face, rising to 1 at a top edge within
  /// Scene::edge_radius_m of it: (r - d) / r at distance d from the nearest edge.
  double roundingOf(const RayHit& hit) const
  {
    if (scene_.edge_radius_m <= 0.0 || !hit.hitBrick() || hit.face != CuboidFace::kTop) return 0.0;
    const BrickType& type = scene_.bricks[hit.brick_index].type;
    const double to_edge = std::min(0.5 * type.length_m - std::abs(hit.point_brick.x()),
                                    0.5 * type.width_m - std::abs(hit.point_brick.y()));
    return std::clamp(1.0 - to_edge / scene_.edge_radius_m, 0.0, 1.0);
  }

  /// How far a rounded edge lies below its face's plane: r - sqrt(r^2 - (r - d)^2)
  /// at distance d from the edge, with rounding = (r - d) / r.
  double roundingSink(double rounding) const
  {
    const double radius = scene_.edge_radius_m;
    return radius - std::sqrt(std::max(0.0, radius * radius * (1.0 - rounding * rounding)));
  }

  /// A rounded edge turns away from the light and shadows its neighbour's:
  /// it darkens toward the edge, to half at the edge itself.
  static double roundingShade(double rounding) { return 1.0 - 0.5 * rounding * rounding; }

  /// Noise-free colour of what a ray hit, in 0..255 per channel (may exceed 255).
  /// `footprint_m`: the size on the surface of what the sample stands for.
  Eigen::Vector3d radiance(const RayHit& hit, const Eigen::Vector3d& ray, double footprint_m) const
  {
    if (!hit.hitSomething()) return Eigen::Vector3d::Zero();
    const double lambert = std::max(0.0, hit.normal.dot(toward_light_));
    return albedo(hit, ray, footprint_m) * (profile_.ambient + profile_.diffuse * lambert) *
           roundingShade(roundingOf(hit));
  }

  /// Size of one pixel (times `fraction`) on a surface at `depth_m` seen at |cos| `normal_dot_ray`.
  double footprintOf(double depth_m, double normal_dot_ray, double fraction = 1.0) const
  {
    return fraction * depth_m / camera_.fx_px / std::max(0.3, normal_dot_ray);
  }

  Eigen::Vector3d albedo(const RayHit& hit, const Eigen::Vector3d& ray, double footprint_m) const
  {
    if (hit.brick_index == RayHit::kGround)
    {
      const Eigen::Vector3d point_world = scene_.world_T_camera * (hit.ray_t * ray);
      const auto& rgb = scene_.ground_rgb;
      return Eigen::Vector3d(rgb[0], rgb[1], rgb[2]) * groundTexture(point_world);
    }
    const BrickType& type = scene_.bricks[hit.brick_index].type;
    const auto& rgb = hit.face == CuboidFace::kTop ? type.plate_rgb : type.body_rgb;
    const Eigen::Vector3d base(rgb[0], rgb[1], rgb[2]);
    const std::optional<BoxPrint>& print = prints_[hit.brick_index];
    return print ? print->colourAt(base, hit.face, hit.point_brick, footprint_m) : base;
  }

  /// A pixel whose 4-neighbours see another surface is a mix of surfaces in a
  /// real camera; render it from 4x4 sub-samples so edges fall at sub-pixel
  /// positions, as the quad fitting will see them on a real image.
  bool onSurfaceEdge(const GeometryBuffers& geometry, int u, int v) const
  {
    const int index = geometry.brick_index.at<int>(v, u);
    const unsigned char face = geometry.face.at<unsigned char>(v, u);
    const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k)
    {
      const int nu = u + du[k], nv = v + dv[k];
      if (nu < 0 || nv < 0 || nu >= camera_.width_px || nv >= camera_.height_px) continue;
      if (geometry.brick_index.at<int>(nv, nu) != index || geometry.face.at<unsigned char>(nv, nu) != face)
        return true;
    }
    return false;
  }

  Eigen::Vector3d pixelRadiance(const GeometryBuffers& geometry, int u, int v) const
  {
    if (onSurfaceEdge(geometry, u, v))
    {
      constexpr int kSamples = 4;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int j = 0; j < kSamples; ++j)
        for (int i = 0; i < kSamples; ++i)
        {
          const Eigen::Vector3d ray = camera_.ray(u - 0.5 + (i + 0.5) / kSamples, v - 0.5 + (j + 0.5) / kSamples);
          const RayHit hit = caster_.cast(Eigen::Vector3d::Zero(), ray);
          const double footprint_m = footprintOf(hit.ray_t, std::abs(hit.normal.dot(ray.normalized())), 1.0 / kSamples);
          sum += radiance(hit, ray, footprint_m);
        }
      return sum / (kSamples * kSamples);
    }
    RayHit hit;
    hit.brick_index = geometry.brick_index.at<int>(v, u);
    if (!hit.hitSomething()) return Eigen::Vector3d::Zero();
    hit.face = static_cast<CuboidFace>(geometry.face.at<unsigned char>(v, u));
    hit.ray_t = geometry.depth_m.at<float>(v, u);
    const Eigen::Vector3d ray = camera_.ray(u, v);
    if (hit.hitBrick() && prints_[hit.brick_index]) hit.point_brick = brick_T_camera_[hit.brick_index] * (hit.ray_t * ray);
    const double lambert = geometry.lambert.at<float>(v, u);
    const double footprint_m = footprintOf(hit.ray_t, geometry.normal_dot_ray.at<float>(v, u));
    return albedo(hit, ray, footprint_m) * (profile_.ambient + profile_.diffuse * lambert) *
           roundingShade(geometry.rounding.at<float>(v, u));
  }

  cv::Mat shade(const GeometryBuffers& geometry)
  {
    cv::Mat rgb(geometry.depth_m.size(), CV_8UC3);
    const double sigma = sensor_.colour_noise_sigma * profile_.noise_scale;
    for (int v = 0; v < rgb.rows; ++v)
    {
      auto* row = rgb.ptr<cv::Vec3b>(v);
      for (int u = 0; u < rgb.cols; ++u)
      {
        Eigen::Vector3d colour = pixelRadiance(geometry, u, v);
        // Sunlight washes lit colours out toward white.
        colour = colour * (1.0 - profile_.washout) + Eigen::Vector3d::Constant(255.0 * profile_.washout);
        for (int c = 0; c < 3; ++c)
          row[u][c] = cv::saturate_cast<unsigned char>(colour[c] + sigma * random_.normal());
      }
    }
    return rgb;
  }

  /// Spatially correlated part of the stereo noise: a coarse grid of normal
  /// samples, bilinearly interpolated. Real D4xx noise is correlated over the
  /// matching window; white noise alone would average out too well over a face.
  cv::Mat correlatedNoise(int cell_px)
  {
    const int grid_w = camera_.width_px / cell_px + 2, grid_h = camera_.height_px / cell_px + 2;
    cv::Mat grid(grid_h, grid_w, CV_32FC1);
    for (int j = 0; j < grid_h; ++j)
      for (int i = 0; i < grid_w; ++i)
        grid.at<float>(j, i) = static_cast<float>(random_.normal());
    cv::Mat noise(camera_.height_px, camera_.width_px, CV_32FC1);
    for (int v = 0; v < noise.rows; ++v)
      for (int u = 0; u < noise.cols; ++u)
      {
        const double gx = double(u) / cell_px, gy = double(v) / cell_px;
        const int i = static_cast<int>(gx), j = static_cast<int>(gy);
        const double fx = gx - i, fy = gy - j;
        const double top = grid.at<float>(j, i) * (1 - fx) + grid.at<float>(j, i + 1) * fx;
        const double bottom = grid.at<float>(j + 1, i) * (1 - fx) + grid.at<float>(j + 1, i + 1) * fx;
        // Bilinear interpolation shrinks the variance; 1.5 restores roughly unit sigma.
        noise.at<float>(v, u) = static_cast<float>(1.5 * (top * (1 - fy) + bottom * fy));
      }
    return noise;
  }

  /// Depth of the neighbour that differs most, when it differs by more than
  /// the edge threshold; NaN otherwise.
  double edgeNeighbourDepth(const cv::Mat& depth_m, int u, int v) const
  {
    const double depth = depth_m.at<float>(v, u);
    double best = kNoDepth, best_gap = sensor_.depth_edge_threshold_m;
    const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k)
    {
      const int nu = u + du[k], nv = v + dv[k];
      if (nu < 0 || nv < 0 || nu >= depth_m.cols || nv >= depth_m.rows) continue;
      const double other = depth_m.at<float>(nv, nu);
      if (std::isnan(other)) continue;
      if (std::abs(other - depth) > best_gap)
      {
        best_gap = std::abs(other - depth);
        best = other;
      }
    }
    return best;
  }

  bool inStereoShadow(const GeometryBuffers& geometry, int u, int v) const
  {
    if (!sensor_.stereo_shadow) return false;
    double depth = geometry.depth_m.at<float>(v, u);
    // A rounded edge dips below its face's plane, where the neighbour's
    // corner would hide it; the edge itself is in plain sight: test the plane.
    const double rounding = geometry.rounding.at<float>(v, u);
    if (rounding > 0.0)
      depth -= roundingSink(rounding) /
               std::max(0.05, geometry.normal_dot_ray.at<float>(v, u) * camera_.ray(u, v).norm());
    const Eigen::Vector3d point = camera_.backProject(u, v, depth);
    // The second imager sits one baseline to the right of the reference one.
    const Eigen::Vector3d right_imager(sensor_.baseline_m, 0.0, 0.0);
    return caster_.blocked(point, right_imager);
  }

  /// Pixels where the stereo window can change the depth: next to another
  /// surface or on a rounded edge.
  static cv::Mat surfaceBoundaries(const GeometryBuffers& geometry)
  {
    cv::Mat boundaries(geometry.depth_m.size(), CV_8UC1, cv::Scalar(0));
    for (int v = 0; v < boundaries.rows; ++v)
      for (int u = 0; u < boundaries.cols; ++u)
      {
        const int index = geometry.brick_index.at<int>(v, u);
        const unsigned char face = geometry.face.at<unsigned char>(v, u);
        bool boundary = geometry.rounding.at<float>(v, u) > 0.0f;
        if (u + 1 < boundaries.cols)
          boundary |= geometry.brick_index.at<int>(v, u + 1) != index || geometry.face.at<unsigned char>(v, u + 1) != face;
        if (v + 1 < boundaries.rows)
          boundary |= geometry.brick_index.at<int>(v + 1, u) != index || geometry.face.at<unsigned char>(v + 1, u) != face;
        if (!boundary) continue;
        boundaries.at<unsigned char>(v, u) = 255;
        if (u + 1 < boundaries.cols) boundaries.at<unsigned char>(v, u + 1) = 255;
        if (v + 1 < boundaries.rows) boundaries.at<unsigned char>(v + 1, u) = 255;
      }
    return boundaries;
  }

  /// The depth the stereo matcher reports before noise (the clean depth when
  /// the window and fattening are off).
  cv::Mat matchedDepth(const GeometryBuffers& geometry) const
  {
    if (sensor_.stereo_window_px <= 1 && sensor_.edge_fattening_px <= 0) return geometry.depth_m;
    StereoWindow window;
    window.window_px = sensor_.stereo_window_px;
    window.fattening_px = sensor_.edge_fattening_px;
    window.focal_baseline_px_m = camera_.fx_px * sensor_.baseline_m;
    return stereoMatchedDepth(geometry.depth_m, surfaceBoundaries(geometry), window);
  }

  /// Aligned depth `offset` pixels off the colour image; pixels shifted in
  /// from outside have no depth.
  cv::Mat misregistered(const cv::Mat& depth_mm) const
  {
    const int du = sensor_.depth_offset_u_px, dv = sensor_.depth_offset_v_px;
    if (du == 0 && dv == 0) return depth_mm;
    cv::Mat shifted(depth_mm.size(), depth_mm.type(), cv::Scalar(0));
    const int width = depth_mm.cols - std::abs(du), height = depth_mm.rows - std::abs(dv);
    if (width <= 0 || height <= 0) return shifted;
    depth_mm(cv::Rect(std::max(0, -du), std::max(0, -dv), width, height))
        .copyTo(shifted(cv::Rect(std::max(0, du), std::max(0, dv), width, height)));
    return shifted;
  }

  cv::Mat measureDepth(const GeometryBuffers& geometry)
  {
    cv::Mat depth_mm(geometry.depth_m.size(), CV_16UC1, cv::Scalar(0));
    const cv::Mat matched = matchedDepth(geometry);
    const cv::Mat correlated = correlatedNoise(8);
    // Split the axial sigma between a white and a correlated part.
    const double white_share = std::sqrt(0.5), correlated_share = std::sqrt(0.5);
    for (int v = 0; v < depth_mm.rows; ++v)
      for (int u = 0; u < depth_mm.cols; ++u)
      {
        double depth = matched.at<float>(v, u);
        if (std::isnan(depth) || depth < sensor_.min_depth_m || depth > sensor_.max_depth_m) continue;
        // A pixel the window moved by more than its noise (a closed gap, a
        // fattened edge) shows the surface that won the window: the grazing
        // and shadow tests of what its ray really hit do not apply to it.
        const float clean = geometry.depth_m.at<float>(v, u);
        const bool taken_over =
            std::isnan(clean) || std::abs(clean - depth) > std::max(0.002, sensor_.axialSigma(clean, camera_.fx_px));
        if (random_.bernoulli(sensor_.dropout_probability)) continue;
        if (!taken_over && geometry.normal_dot_ray.at<float>(v, u) < sensor_.grazing_cos && random_.bernoulli(0.8))
          continue;
        if (profile_.bright_dropout_probability > 0.0 && geometry.lambert.at<float>(v, u) > 0.8 &&
            random_.bernoulli(profile_.bright_dropout_probability))
          continue;
        if (!taken_over && inStereoShadow(geometry, u, v)) continue;
        const double neighbour = edgeNeighbourDepth(matched, u, v);
        if (!std::isnan(neighbour) && random_.bernoulli(sensor_.flying_pixel_probability))
          depth += random_.uniform(0.1, 0.9) * (neighbour - depth);
        const double sigma = sensor_.axialSigma(depth, camera_.fx_px);
        depth += sigma * (white_share * random_.normal() + correlated_share * correlated.at<float>(v, u));
        depth = sensor_.quantisedDepth(depth, camera_.fx_px);
        const double millimetres = std::round(depth * 1000.0);
        if (millimetres > 0.0 && millimetres < 65535.0)
          depth_mm.at<unsigned short>(v, u) = static_cast<unsigned short>(millimetres);
      }
    return misregistered(depth_mm);
  }

  std::vector<BrickTruth> groundTruth(const SyntheticFrame& frame) const
  {
    std::vector<BrickTruth> truths;
    for (int i = 0; i < static_cast<int>(scene_.bricks.size()); ++i)
    {
      BrickTruth truth;
      truth.instance_id = i + 1;
      truth.type = scene_.bricks[i].type.name;
      truth.dimensions_m = scene_.bricks[i].type.dimensions_m();
      truth.camera_T_brick = caster_.cameraTBricks()[i];
      truths.push_back(truth);
    }
    // Visible pixels of every face of every brick, in one pass: the top's,
    // and the face up of a brick on a side or an end.
    std::vector<std::array<int, kCuboidFaceLabels>> face_pixels(truths.size(), std::array<int, kCuboidFaceLabels>{});
    for (int v = 0; v < frame.instance_labels.rows; ++v)
      for (int u = 0; u < frame.instance_labels.cols; ++u)
      {
        const int label = frame.instance_labels.at<unsigned short>(v, u);
        const int face = frame.face_labels.at<unsigned char>(v, u);
        if (label > 0 && face < kCuboidFaceLabels) ++face_pixels[label - 1][face];
      }
    const std::vector<int> touching = touchingNeighbourCounts(scene_);
    for (int i = 0; i < static_cast<int>(truths.size()); ++i)
    {
      BrickTruth& truth = truths[i];
      truth.visible_top_pixels = face_pixels[i][static_cast<int>(CuboidFace::kTop)];
      const double area_px = unoccludedTopFaceArea(truth);
      truth.visible_fraction = area_px > 0.0 ? std::min(1.0, truth.visible_top_pixels / area_px) : 0.0;
      truth.top_face = topFaceVisibility(scene_, caster_, camera_, i);
      truth.top_face_complete = truth.top_face.complete();
      truth.touching_neighbours = touching[i];
      if (restingWithFaceUp(truth.top_face.up_face) != Resting::kUpright)
        truth.resting_face =
            restingFaceTruth(i, truth.top_face.up_face, face_pixels[i][static_cast<int>(truth.top_face.up_face)]);
    }
    return truths;
  }

  /// The face up of brick i, lying on a side or standing on an end, as the
  /// top of the type restingAs() makes of it; `visible_px` of it are seen.
  RestingFaceTruth restingFaceTruth(int i, CuboidFace face, int visible_px) const
  {
    const BrickType as_top = restingAs(scene_.bricks[i].type, restingWithFaceUp(face));
    RestingFaceTruth resting;
    resting.type = as_top.name;
    resting.face = face;
    resting.dimensions_m = as_top.dimensions_m();
    resting.camera_T_face = caster_.cameraTBricks()[i] * brickTFace(scene_.bricks[i].type, face);
    resting.view = faceVisibility(scene_, caster_, camera_, i, face);
    BrickTruth as_truth;
    as_truth.dimensions_m = resting.dimensions_m;
    as_truth.camera_T_brick = resting.camera_T_face;
    const double area_px = unoccludedTopFaceArea(as_truth);
    resting.visible_fraction = area_px > 0.0 ? std::min(1.0, visible_px / area_px) : 0.0;
    return resting;
  }

  /// Pixels the top face would cover if nothing hid it and the image had no
  /// border: the area of its projected quadrilateral (0 when seen from below).
  double unoccludedTopFaceArea(const BrickTruth& truth) const
  {
    const auto corners = topFaceCornersInCamera(truth);
    const Eigen::Vector3d normal = truth.camera_T_brick.linear().col(2);
    if (normal.dot(truth.camera_T_brick.translation()) >= 0.0) return 0.0;  // facing away
    Eigen::Vector2d pixels[4];
    for (int k = 0; k < 4; ++k)
    {
      if (corners[k].z() <= 1e-3) return 0.0;
      pixels[k] = camera_.project(corners[k]);
    }
    double twice_area = 0.0;
    for (int k = 0; k < 4; ++k)
    {
      const Eigen::Vector2d& a = pixels[k];
      const Eigen::Vector2d& b = pixels[(k + 1) % 4];
      twice_area += a.x() * b.y() - b.x() * a.y();
    }
    return 0.5 * std::abs(twice_area);
  }

  const PinholeCamera& camera_;
  const SensorModel& sensor_;
  const Scene& scene_;
  RayCaster caster_;
  LightingProfile profile_;
  FastRandom random_;
  Eigen::Vector3d toward_light_;
  std::vector<std::optional<BoxPrint>> prints_;  // per brick: printed cardboard, or plain colour
  std::vector<Eigen::Isometry3d> brick_T_camera_;
};
}  // namespace

SyntheticRig::SyntheticRig(const PinholeCamera& camera, const SensorModel& sensor) : camera_(camera), sensor_(sensor)
{
  camera_.validate();
  sensor_.validate();
}

SyntheticFrame SyntheticRig::render(const Scene& scene, std::uint64_t seed) const
{
  return Renderer(camera_, sensor_, scene, seed).render();
}
}  // namespace sim
}  // namespace brick_pose
