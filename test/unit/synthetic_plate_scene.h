#pragma once
// Test helper for the front-end unit tests: ray-casts one rectangular plate
// at a known pose in front of a flat grey background, sampling every pixel at
// its centre, so that the truth (corners, centre, dimensions) is exact.

#include <array>
#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/frame/frame_builder.h"

namespace brick_pose
{
namespace test
{
struct PlateScene
{
  PinholeCamera camera;
  /// Plate pose: centre of the face and rotation brick -> camera.
  Eigen::Vector3d centre_m{0.0, 0.0, 1.0};
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double length_m = 0.6;
  double width_m = 0.2;
  cv::Vec3b plate_rgb{30, 170, 50};
  bool draw_plate = true;
  /// Rectangular notch cut from the plate, in brick-frame x/y (metres).
  bool has_notch = false;
  Eigen::Vector2d notch_min_m{0.0, 0.0};
  Eigen::Vector2d notch_max_m{0.0, 0.0};
  /// Background: fronto-parallel plane this far behind the plate centre.
  double background_offset_m = 0.3;
  cv::Vec3b background_rgb{128, 128, 128};
  double depth_noise_m = 0.0;
  unsigned seed = 1;

  /// Brick frame facing the camera: z toward the camera, x turned by yaw in
  /// the image, then tilted about the brick x axis.
  static Eigen::Matrix3d facingCamera(double yaw_rad, double tilt_rad = 0.0)
  {
    const Eigen::Matrix3d flip = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
    return flip * Eigen::AngleAxisd(-yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
           Eigen::AngleAxisd(tilt_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
  }

  Eigen::Vector3d pointOnFace(double x_m, double y_m) const { return centre_m + rotation * Eigen::Vector3d(x_m, y_m, 0.0); }

  /// Truth corners of the full face (brick-frame (+-L/2, +-W/2)).
  std::array<Eigen::Vector3d, 4> cornersM() const
  {
    const double a = 0.5 * length_m, b = 0.5 * width_m;
    return {pointOnFace(a, b), pointOnFace(a, -b), pointOnFace(-a, -b), pointOnFace(-a, b)};
  }

  bool insidePlate(const Eigen::Vector3d& local) const
  {
    if (std::abs(local.x()) > 0.5 * length_m || std::abs(local.y()) > 0.5 * width_m) return false;
    if (has_notch && local.x() >= notch_min_m.x() && local.x() <= notch_max_m.x() && local.y() >= notch_min_m.y() &&
        local.y() <= notch_max_m.y())
      return false;
    return true;
  }

  /// Renders colour (RGB) and depth (metres, CV_32FC1).
  void render(cv::Mat& rgb, cv::Mat& depth_m) const
  {
    rgb.create(camera.height_px, camera.width_px, CV_8UC3);
    depth_m.create(camera.height_px, camera.width_px, CV_32FC1);
    std::mt19937 generator(seed);
    std::normal_distribution<double> noise(0.0, depth_noise_m > 0.0 ? depth_noise_m : 1.0);
    const Eigen::Vector3d normal = rotation.col(2);
    const double background_z = centre_m.z() + background_offset_m;
    for (int v = 0; v < camera.height_px; ++v)
      for (int u = 0; u < camera.width_px; ++u)
      {
        const Eigen::Vector3d ray = camera.ray(u, v);
        double z = background_z;
        cv::Vec3b colour = background_rgb;
        const double denominator = normal.dot(ray);
        if (draw_plate && std::abs(denominator) > 1e-9)
        {
          const Eigen::Vector3d hit = (normal.dot(centre_m) / denominator) * ray;
          if (hit.z() > 0.0 && hit.z() < background_z && insidePlate(rotation.transpose() * (hit - centre_m)))
          {
            z = hit.z();
            colour = plate_rgb;
          }
        }
        if (depth_noise_m > 0.0) z += noise(generator);
        rgb.at<cv::Vec3b>(v, u) = colour;
        depth_m.at<float>(v, u) = static_cast<float>(z);
      }
  }

  RgbdFrame frame() const
  {
    cv::Mat rgb, depth;
    render(rgb, depth);
    FrameHeader header;
    header.stamp_ns = 1000;
    header.frame_id = "camera_color_optical_frame";
    return makeRgbdFrame(rgb, depth, camera, header);
  }

  /// A 640x480 camera with its principal point at the image centre.
  static PinholeCamera vgaCamera(double focal_px = 600.0)
  {
    PinholeCamera camera;
    camera.width_px = 640;
    camera.height_px = 480;
    camera.fx_px = focal_px;
    camera.fy_px = focal_px;
    camera.cx_px = 319.5;
    camera.cy_px = 239.5;
    return camera;
  }
};
}  // namespace test
}  // namespace brick_pose
