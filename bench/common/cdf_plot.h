#pragma once
// Empirical CDF plots of error samples as a PNG: panels side by side, a
// logarithmic x axis each (errors of competing methods differ by orders of
// magnitude), one step curve per series and one legend row under the panels.

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace brick_pose
{
namespace bench
{
struct CdfCurve
{
  std::string label;
  cv::Scalar rgb;  ///< Colour in R, G, B order.
};

struct CdfPanel
{
  std::string title;
  std::string x_label;
  /// One sample vector per curve, in CdfPlot::curves order.
  std::vector<std::vector<double>> series;
};

struct CdfPlot
{
  std::vector<CdfCurve> curves;
  /// Curve indices in drawing order (the last is drawn on top); empty draws
  /// them in order.
  std::vector<std::size_t> draw_order;
  std::vector<CdfPanel> panels;
  std::string footnote;  ///< One line under the legend, may be empty.
  int legend_spacing_px = 290;
};

/// Renders `plot` (each panel's axis spans the decades of its samples).
cv::Mat renderCdfPlot(const CdfPlot& plot);

/// renderCdfPlot() written as a PNG.
void writeCdfPlot(const std::string& path, const CdfPlot& plot);
}  // namespace bench
}  // namespace brick_pose
