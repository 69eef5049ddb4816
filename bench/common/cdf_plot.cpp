#include "common/cdf_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <opencv2/imgproc.hpp>
#include <pcl/io/png_io.h>

#include "common/report_format.h"

namespace brick_pose
{
namespace bench
{
namespace
{
constexpr int kFractionTicks = 5;
constexpr int kPanelWidth = 540, kPanelHeight = 380, kLeftMargin = 80, kTopMargin = 80, kGap = 110;

struct PanelFrame
{
  cv::Rect area;  ///< Plotting area inside the image (axes drawn around it).
  /// Logarithmic x axis from 10^first_decade to 10^last_decade.
  int first_decade = -2;
  int last_decade = 1;
};

cv::Point toPixel(const PanelFrame& panel, double x, double y)
{
  const double decades = panel.last_decade - panel.first_decade;
  const double position =
      (std::log10(std::max(x, std::pow(10.0, panel.first_decade))) - panel.first_decade) / decades;
  const double clamped = std::min(std::max(position, 0.0), 1.0);
  return {panel.area.x + static_cast<int>(std::lround(clamped * panel.area.width)),
          panel.area.y + panel.area.height - static_cast<int>(std::lround(y * panel.area.height))};
}

void drawText(cv::Mat& image, const std::string& text, cv::Point origin, double scale = 0.45)
{
  cv::putText(image, text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

std::string decadeLabel(int exponent)
{
  return exponent < 0 ? formatted(("%." + std::to_string(-exponent) + "f").c_str(), std::pow(10.0, exponent))
                      : formatted("%.0f", std::pow(10.0, exponent));
}

void drawAxes(cv::Mat& image, const PanelFrame& panel, const CdfPanel& spec)
{
  const cv::Scalar major_grid(215, 215, 215), minor_grid(240, 240, 240), black(0, 0, 0);
  for (int exponent = panel.first_decade; exponent <= panel.last_decade; ++exponent)
  {
    for (int multiple = 2; multiple <= 9 && exponent < panel.last_decade; ++multiple)
    {
      const cv::Point minor = toPixel(panel, multiple * std::pow(10.0, exponent), 0.0);
      cv::line(image, minor, {minor.x, panel.area.y}, minor_grid, 1);
    }
    const cv::Point tick = toPixel(panel, std::pow(10.0, exponent), 0.0);
    cv::line(image, tick, {tick.x, panel.area.y}, major_grid, 1);
    cv::line(image, tick, {tick.x, tick.y + 5}, black, 1);
    drawText(image, decadeLabel(exponent), {tick.x - 12, tick.y + 20});
  }
  for (int k = 0; k <= kFractionTicks; ++k)
  {
    const double fraction = static_cast<double>(k) / kFractionTicks;
    const cv::Point tick = {panel.area.x, toPixel(panel, 1.0, fraction).y};
    cv::line(image, tick, {panel.area.x + panel.area.width, tick.y}, major_grid, 1);
    cv::line(image, tick, {tick.x - 5, tick.y}, black, 1);
    drawText(image, formatted("%.1f", fraction), {tick.x - 35, tick.y + 5});
  }
  cv::rectangle(image, panel.area, black, 1);
  drawText(image, spec.title, {panel.area.x, panel.area.y - 35}, 0.6);
  drawText(image, "fraction of bricks with error <= x", {panel.area.x - 40, panel.area.y - 10});
  drawText(image, spec.x_label, {panel.area.x + panel.area.width / 2 - 90, panel.area.y + panel.area.height + 42});
}

/// Step curve of the empirical CDF; values outside the axis are clamped to its ends.
void drawCdf(cv::Mat& image, const PanelFrame& panel, std::vector<double> values, const cv::Scalar& rgb)
{
  if (values.empty()) return;
  std::sort(values.begin(), values.end());
  cv::Point previous = toPixel(panel, 0.0, 0.0);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const double below = static_cast<double>(i) / values.size();
    const double at = static_cast<double>(i + 1) / values.size();
    const cv::Point riser_bottom = toPixel(panel, values[i], below);
    cv::line(image, previous, riser_bottom, rgb, 2, cv::LINE_AA);
    previous = toPixel(panel, values[i], at);
    cv::line(image, riser_bottom, previous, rgb, 2, cv::LINE_AA);
  }
}

/// One legend row under the panels, so that no curve is hidden.
void drawLegend(cv::Mat& image, const CdfPlot& plot, int y_px)
{
  int x_px = 80;
  for (const CdfCurve& curve : plot.curves)
  {
    cv::line(image, {x_px, y_px - 5}, {x_px + 30, y_px - 5}, curve.rgb, 3, cv::LINE_AA);
    drawText(image, curve.label, {x_px + 38, y_px}, 0.5);
    x_px += plot.legend_spacing_px;
  }
}

/// Decades that hold every value of every series (at least one decade).
std::pair<int, int> axisDecades(const std::vector<std::vector<double>>& series)
{
  double smallest = std::numeric_limits<double>::max(), largest = 0.0;
  for (const auto& values : series)
    for (const double value : values)
      if (value > 0.0)
      {
        smallest = std::min(smallest, value);
        largest = std::max(largest, value);
      }
  if (!(largest > 0.0)) return {-2, 1};
  const int first = static_cast<int>(std::floor(std::log10(smallest)));
  const int last = static_cast<int>(std::ceil(std::log10(largest)));
  return {first, std::max(first + 1, last)};
}
}  // namespace

cv::Mat renderCdfPlot(const CdfPlot& plot)
{
  const int panel_count = static_cast<int>(plot.panels.size());
  cv::Mat image(kTopMargin + kPanelHeight + 130,
                kLeftMargin + panel_count * kPanelWidth + std::max(0, panel_count - 1) * kGap + 50, CV_8UC3,
                cv::Scalar(255, 255, 255));
  std::vector<std::size_t> order = plot.draw_order;
  if (order.empty())
    for (std::size_t c = 0; c < plot.curves.size(); ++c) order.push_back(c);
  for (int p = 0; p < panel_count; ++p)
  {
    const CdfPanel& spec = plot.panels[static_cast<std::size_t>(p)];
    PanelFrame panel;
    panel.area = cv::Rect(kLeftMargin + p * (kPanelWidth + kGap), kTopMargin, kPanelWidth, kPanelHeight);
    std::tie(panel.first_decade, panel.last_decade) = axisDecades(spec.series);
    drawAxes(image, panel, spec);
    for (const std::size_t c : order)
      if (c < spec.series.size() && c < plot.curves.size()) drawCdf(image, panel, spec.series[c], plot.curves[c].rgb);
  }
  drawLegend(image, plot, kTopMargin + kPanelHeight + 85);
  if (!plot.footnote.empty()) drawText(image, plot.footnote, {kLeftMargin, kTopMargin + kPanelHeight + 115}, 0.45);
  return image;
}

void writeCdfPlot(const std::string& path, const CdfPlot& plot)
{
  const cv::Mat image = renderCdfPlot(plot);
  // pcl_io's PNG writer (already linked by the core) takes RGB rows, which is
  // the channel order the colours are given in.
  pcl::io::saveRgbPNGFile(path, image.ptr<unsigned char>(0), image.cols, image.rows);
}
}  // namespace bench
}  // namespace brick_pose
