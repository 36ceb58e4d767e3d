// Small, dependency-free SVG charts for the evaluation report: grouped bars (thesis figures 5.12
// and 5.13: one group per tree, one bar per series) and lines or scatter plots (figure 5.14: RMS vs
// node count; the robustness plots: RMS vs wood point count and vs range noise, log axes).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace treesketch::eval {

struct BarChart {
  std::string title;
  std::string yLabel;
  std::vector<std::string> groups;          ///< x-axis categories (e.g. trees)
  std::vector<std::string> series;          ///< one bar per series in each group
  std::vector<std::vector<double>> values;  ///< values[series][group]; NaN = no bar
};

/// How one series of a LineChart is drawn.
struct SeriesStyle {
  int colour = -1;      ///< palette index; -1 = the series' own index
  bool line = true;     ///< join the points (false: markers only, a scatter plot)
  bool dashed = false;  ///< dashed line
  bool hollow = false;  ///< hollow markers
};

struct LineChart {
  std::string title;
  std::string xLabel;
  std::string yLabel;
  std::vector<std::string> series;
  std::vector<std::vector<double>> xs;  ///< xs[series][k]
  std::vector<std::vector<double>> ys;  ///< ys[series][k]
  std::vector<SeriesStyle> styles;      ///< per series; missing = default style
  /// Logarithmic axes (decades; non-positive values are not drawn). Linear axes run from 0.
  bool logX = false;
  bool logY = false;
};

/// SVG text of the chart (800 × 450 px), linear axes from 0 to a rounded maximum (log axes: whole
/// decades around the data), with a legend.
std::string renderSvg(const BarChart& chart);
std::string renderSvg(const LineChart& chart);
/// Writes `svg` atomically to `path` (OutputError on failure).
void writeSvg(const std::filesystem::path& path, const std::string& svg);

}  // namespace treesketch::eval
