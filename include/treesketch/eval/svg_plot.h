// Small, dependency-free SVG charts for the evaluation report: grouped bars (thesis figures 5.12
// and 5.13: one group per tree, one bar per series) and lines (figure 5.14: RMS vs node count).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace treesketch::eval {

struct BarChart {
  std::string title;
  std::string yLabel;
  std::vector<std::string> groups;            ///< x-axis categories (e.g. trees)
  std::vector<std::string> series;            ///< one bar per series in each group
  std::vector<std::vector<double>> values;    ///< values[series][group]; NaN = no bar
};

struct LineChart {
  std::string title;
  std::string xLabel;
  std::string yLabel;
  std::vector<std::string> series;
  std::vector<std::vector<double>> xs;  ///< xs[series][k]
  std::vector<std::vector<double>> ys;  ///< ys[series][k]
};

/// SVG text of the chart (800 × 450 px), axes from 0 to a rounded maximum, with a legend.
std::string renderSvg(const BarChart& chart);
std::string renderSvg(const LineChart& chart);
/// Writes `svg` atomically to `path` (OutputError on failure).
void writeSvg(const std::filesystem::path& path, const std::string& svg);

}  // namespace treesketch::eval
