#pragma once
// What is printed and stuck on a plain cardboard box, as a colour at a point
// of its surface: fibre texture, the flap seam, tape, labels with text and a
// barcode. Thin features are box-filtered over the pixel's footprint, so a
// 2 mm seam seen from 2 m is a faint line, not a dotted one.

#include <vector>

#include <Eigen/Core>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/sim/scene.h"

namespace brick_pose
{
namespace sim
{
class BoxPrint
{
public:
  BoxPrint(const BrickType& type, const SurfaceMarkings& markings);

  /// Colour (0..255 per channel, before lighting) of `face` at `point_brick`
  /// (brick frame) for a box whose plain colour there is `base_rgb`;
  /// `footprint_m` is the size of one pixel on the surface.
  Eigen::Vector3d colourAt(const Eigen::Vector3d& base_rgb, CuboidFace face, const Eigen::Vector3d& point_brick,
                           double footprint_m) const;

private:
  struct Span
  {
    double low;
    double high;
  };
  struct Label
  {
    Span x;                    // extent on the top face, brick frame
    Span y;
    bool text_along_x = true;  // orientation of text lines and bars
    std::vector<Span> text_rows;  // across the label, as fractions 0..1 of its short side
    Span barcode_rows;            // fraction of the short side the barcode fills
    std::vector<Span> bars;       // along the label, as fractions 0..1 of its long side
  };

  Eigen::Vector3d topColour(const Eigen::Vector3d& base_rgb, double x, double y, double footprint_m) const;
  Eigen::Vector3d printedColour(CuboidFace face, double a, double b) const;
  double fibre(double a, double b) const;

  SurfaceMarkings markings_;
  double half_length_m_;
  double half_width_m_;
  std::vector<Label> labels_;
  std::vector<Eigen::Vector3d> palette_;  // printed packaging's colours
};
}  // namespace sim
}  // namespace brick_pose
