#pragma once
// Test helper: plates of known sizes lying touching on one plane (a row of
// bricks, a pallet layer), ray-cast at every pixel centre in front of a
// background plane, with the seams between them drawn as a real sensor
// shows them: nothing at all, a shallow groove in depth, and/or a dark line
// in colour.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/frame/frame_builder.h"

namespace brick_pose
{
namespace test
{
struct TouchingPlatesScene
{
  struct Plate
  {
    /// Rectangle on the layer's plane, layer-frame x/y (metres).
    Eigen::Vector2d min_m;
    Eigen::Vector2d max_m;
    cv::Vec3b rgb{30, 170, 50};
  };

  PinholeCamera camera;
  /// Layer frame: origin and rotation layer -> camera; z toward the camera.
  Eigen::Vector3d origin_m{0.0, 0.0, 1.4};
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  std::vector<Plate> plates;
  /// Seams: a groove this deep (m) and wide (m, each side of the seam line),
  /// and a line this much darker (grey levels) and wide (m).
  double groove_depth_m = 0.0;
  double groove_half_width_m = 0.004;
  double line_darkening = 0.0;
  double line_half_width_m = 0.001;
  double background_offset_m = 0.25;
  cv::Vec3b background_rgb{110, 105, 100};
  double depth_noise_m = 0.0015;
  /// Grey-level noise added to every colour channel of the plates (one
  /// draw per pixel, as a sensor's luminance noise).
  double colour_noise = 0.0;
  /// As a camera draws them: the seam and rim lines are shading, which
  /// scales what the plate reflects (their darkening, in mean grey levels,
  /// is shared among the channels in proportion to the plate's colour: on a
  /// red plate mostly the red); otherwise every channel loses as much.
  bool lines_are_shading = false;
  /// colour_noise drawn for each channel on its own (every photosite has
  /// its own noise), rather than once for all three.
  bool noise_per_channel = false;
  /// D4xx stereo fattens a foreground over its steps: this far (m, on the
  /// layer's plane) beyond the plates' outer edges the depth is still the
  /// layer's while the colour is the background's.
  double fattening_m = 0.0;
  /// The plates' outer rim (a rounded edge) this much darker over
  /// line_half_width_m, as their seams are.
  double rim_darkening = 0.0;
  /// The stereo shadow beyond a step: over this band (m) past the fattened
  /// fringe, this share of the background's pixels has no depth.
  double dropout_band_m = 0.0;
  double dropout_share = 0.0;
  unsigned seed = 3;

  /// Layer frame facing the camera (z toward it), turned by `yaw_rad` in the
  /// image and tilted by `tilt_rad` about its x axis.
  static Eigen::Matrix3d facingCamera(double yaw_rad, double tilt_rad)
  {
    const Eigen::Matrix3d flip = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
    return flip * Eigen::AngleAxisd(-yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
           Eigen::AngleAxisd(tilt_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
  }

  /// n plates of length x width side by side along the layer's y axis,
  /// centred on the origin.
  static std::vector<Plate> row(int count, double length_m, double width_m, cv::Vec3b rgb = {30, 170, 50})
  {
    std::vector<Plate> plates;
    for (int k = 0; k < count; ++k)
    {
      const double y0 = (k - 0.5 * count) * width_m;
      plates.push_back({{-0.5 * length_m, y0}, {0.5 * length_m, y0 + width_m}, rgb});
    }
    return plates;
  }

  Eigen::Vector3d toCamera(double x_m, double y_m) const { return origin_m + rotation * Eigen::Vector3d(x_m, y_m, 0.0); }

  /// Plate corners in the camera frame (layer (min.x, max.y) first).
  std::array<Eigen::Vector3d, 4> cornersM(const Plate& plate) const
  {
    return {toCamera(plate.min_m.x(), plate.max_m.y()), toCamera(plate.max_m.x(), plate.max_m.y()),
            toCamera(plate.max_m.x(), plate.min_m.y()), toCamera(plate.min_m.x(), plate.min_m.y())};
  }

  /// Distance (m) from a layer point to the nearest plate (0 on one).
  double distanceToPlates(const Eigen::Vector2d& p) const
  {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Plate& plate : plates)
    {
      const double dx = std::max({plate.min_m.x() - p.x(), 0.0, p.x() - plate.max_m.x()});
      const double dy = std::max({plate.min_m.y() - p.y(), 0.0, p.y() - plate.max_m.y()});
      nearest = std::min(nearest, std::hypot(dx, dy));
    }
    return nearest;
  }

  /// Whether a point of `plate` lies within `width_m` of an edge of it that
  /// no other plate touches (the outer rim of the layer).
  bool onRim(const Eigen::Vector2d& p, const Plate& plate, double width_m) const
  {
    const double beyond_m = width_m + 0.002;
    const std::array<std::pair<double, Eigen::Vector2d>, 4> edges{{{p.x() - plate.min_m.x(), {-1.0, 0.0}},
                                                                    {plate.max_m.x() - p.x(), {1.0, 0.0}},
                                                                    {p.y() - plate.min_m.y(), {0.0, -1.0}},
                                                                    {plate.max_m.y() - p.y(), {0.0, 1.0}}}};
    for (const auto& [distance_m, outward] : edges)
      if (distance_m < width_m && distanceToPlates(p + (distance_m + beyond_m) * outward) > 0.0) return true;
    return false;
  }

  /// Distance (m) from a layer point inside `plate` to the nearest edge it
  /// shares with another plate; infinity when none is near.
  double distanceToSeam(const Eigen::Vector2d& p, int plate_index) const
  {
    const Plate& plate = plates[static_cast<std::size_t>(plate_index)];
    double nearest = std::numeric_limits<double>::infinity();
    const double touch_m = 0.0005;
    for (std::size_t k = 0; k < plates.size(); ++k)
    {
      if (static_cast<int>(k) == plate_index) continue;
      const Plate& other = plates[k];
      const bool overlap_y = p.y() >= other.min_m.y() - touch_m && p.y() <= other.max_m.y() + touch_m;
      const bool overlap_x = p.x() >= other.min_m.x() - touch_m && p.x() <= other.max_m.x() + touch_m;
      if (overlap_y && std::abs(plate.max_m.x() - other.min_m.x()) < touch_m) nearest = std::min(nearest, plate.max_m.x() - p.x());
      if (overlap_y && std::abs(plate.min_m.x() - other.max_m.x()) < touch_m) nearest = std::min(nearest, p.x() - plate.min_m.x());
      if (overlap_x && std::abs(plate.max_m.y() - other.min_m.y()) < touch_m) nearest = std::min(nearest, plate.max_m.y() - p.y());
      if (overlap_x && std::abs(plate.min_m.y() - other.max_m.y()) < touch_m) nearest = std::min(nearest, p.y() - plate.min_m.y());
    }
    return nearest;
  }

  RgbdFrame frame() const
  {
    cv::Mat rgb(camera.height_px, camera.width_px, CV_8UC3), depth(camera.height_px, camera.width_px, CV_32FC1);
    std::mt19937 generator(seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    const Eigen::Vector3d normal = rotation.col(2);
    const double background_z = origin_m.z() + background_offset_m;
    for (int v = 0; v < camera.height_px; ++v)
      for (int u = 0; u < camera.width_px; ++u)
      {
        const Eigen::Vector3d ray = camera.ray(u, v);
        double z = background_z;
        cv::Vec3b colour = background_rgb;
        const Eigen::Vector3d hit = (normal.dot(origin_m) / normal.dot(ray)) * ray;
        const Eigen::Vector3d local = rotation.transpose() * (hit - origin_m);
        for (std::size_t k = 0; k < plates.size(); ++k)
        {
          const Plate& plate = plates[k];
          if (local.x() < plate.min_m.x() || local.x() > plate.max_m.x() || local.y() < plate.min_m.y() ||
              local.y() > plate.max_m.y() || hit.z() >= background_z)
            continue;
          z = hit.z();
          colour = plate.rgb;
          const double seam_m = distanceToSeam(local.head<2>(), static_cast<int>(k));
          if (seam_m < groove_half_width_m)
            z += groove_depth_m * (1.0 - seam_m / groove_half_width_m) / std::max(1e-6, -normal.z());
          double darkening = seam_m < line_half_width_m ? line_darkening : 0.0;
          if (rim_darkening > 0.0 && onRim(local.head<2>(), plate, line_half_width_m))
            darkening = std::max(darkening, rim_darkening);
          const double mean_level = (plate.rgb[0] + plate.rgb[1] + plate.rgb[2]) / 3.0;
          const double kept = lines_are_shading && mean_level > 0.0 ? 1.0 - darkening / mean_level : 1.0;
          if (lines_are_shading) darkening = 0.0;
          if (colour_noise > 0.0 && !noise_per_channel) darkening -= colour_noise * noise(generator);
          for (int c = 0; c < 3; ++c)
          {
            const double own_noise = noise_per_channel ? colour_noise * noise(generator) : 0.0;
            colour[c] = cv::saturate_cast<std::uint8_t>(kept * colour[c] - darkening + own_noise);
          }
          break;
        }
        const double outside_m = z == background_z && hit.z() < background_z ? distanceToPlates(local.head<2>()) : -1.0;
        if (outside_m >= 0.0 && fattening_m > 0.0 && outside_m <= fattening_m) z = hit.z();
        depth.at<float>(v, u) = static_cast<float>(z + depth_noise_m * noise(generator));
        // Drawn only where the band is, so that scenes without one keep their noise.
        if (z == background_z && outside_m >= 0.0 && outside_m <= fattening_m + dropout_band_m && dropout_band_m > 0.0 &&
            std::uniform_real_distribution<double>(0.0, 1.0)(generator) < dropout_share)
          depth.at<float>(v, u) = std::numeric_limits<float>::quiet_NaN();
        rgb.at<cv::Vec3b>(v, u) = colour;
      }
    FrameHeader header;
    header.stamp_ns = 1000;
    header.frame_id = "camera_color_optical_frame";
    return makeRgbdFrame(rgb, depth, camera, header);
  }
};
}  // namespace test
}  // namespace brick_pose
