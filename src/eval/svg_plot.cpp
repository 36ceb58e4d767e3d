#include "treesketch/eval/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::eval {

namespace {

constexpr double kWidth = 800, kHeight = 450;
constexpr double kLeft = 70, kRight = 170, kTop = 40, kBottom = 90;
const char* kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"};

std::string esc(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

/// A "nice" axis maximum >= v (1, 2, 2.5, 5 × 10^k).
double niceMax(double v) {
  if (!(v > 0) || !std::isfinite(v)) return 1.0;
  double p = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * p >= v * 1.0000001) return m * p;
  return 10 * p;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

void header(std::ostringstream& s, const std::string& title, const std::string& yLabel, double yMax) {
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s << "<text x=\"" << kWidth / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << esc(title)
    << "</text>\n";
  double plotH = kHeight - kTop - kBottom;
  for (int i = 0; i <= 5; ++i) {
    double v = yMax * i / 5.0;
    double y = kTop + plotH * (1.0 - i / 5.0);
    s << "<line x1=\"" << kLeft << "\" x2=\"" << kWidth - kRight << "\" y1=\"" << y << "\" y2=\"" << y
      << "\" stroke=\"#ddd\"/>\n";
    s << "<text x=\"" << kLeft - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">" << fmt(v) << "</text>\n";
  }
  s << "<text transform=\"translate(18," << kTop + plotH / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
    << esc(yLabel) << "</text>\n";
  s << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft << "\" y1=\"" << kTop << "\" y2=\"" << kTop + plotH
    << "\" stroke=\"black\"/>\n";
  s << "<line x1=\"" << kLeft << "\" x2=\"" << kWidth - kRight << "\" y1=\"" << kTop + plotH << "\" y2=\""
    << kTop + plotH << "\" stroke=\"black\"/>\n";
}

void legend(std::ostringstream& s, const std::vector<std::string>& series) {
  for (std::size_t i = 0; i < series.size(); ++i) {
    double y = kTop + 10 + 20.0 * i;
    s << "<rect x=\"" << kWidth - kRight + 15 << "\" y=\"" << y - 9 << "\" width=\"12\" height=\"12\" fill=\""
      << kColors[i % 8] << "\"/>\n";
    s << "<text x=\"" << kWidth - kRight + 32 << "\" y=\"" << y + 1 << "\">" << esc(series[i]) << "</text>\n";
  }
}

}  // namespace

std::string renderSvg(const BarChart& c) {
  double vmax = 0;
  for (const auto& row : c.values)
    for (double v : row)
      if (std::isfinite(v)) vmax = std::max(vmax, v);
  double yMax = niceMax(vmax);
  std::ostringstream s;
  header(s, c.title, c.yLabel, yMax);
  double plotW = kWidth - kLeft - kRight, plotH = kHeight - kTop - kBottom;
  std::size_t ng = std::max<std::size_t>(c.groups.size(), 1), ns = std::max<std::size_t>(c.series.size(), 1);
  double groupW = plotW / ng, barW = groupW * 0.8 / ns;
  for (std::size_t g = 0; g < c.groups.size(); ++g) {
    double gx = kLeft + g * groupW + groupW * 0.1;
    for (std::size_t k = 0; k < c.series.size() && k < c.values.size(); ++k) {
      if (g >= c.values[k].size() || !std::isfinite(c.values[k][g])) continue;
      double h = plotH * c.values[k][g] / yMax;
      s << "<rect x=\"" << gx + k * barW << "\" y=\"" << kTop + plotH - h << "\" width=\"" << barW * 0.95
        << "\" height=\"" << h << "\" fill=\"" << kColors[k % 8] << "\"><title>" << esc(c.series[k]) << ", "
        << esc(c.groups[g]) << ": " << fmt(c.values[k][g]) << "</title></rect>\n";
    }
    double cx = kLeft + (g + 0.5) * groupW;
    s << "<text transform=\"translate(" << cx << "," << kTop + plotH + 14 << ") rotate(20)\">" << esc(c.groups[g])
      << "</text>\n";
  }
  legend(s, c.series);
  s << "</svg>\n";
  return s.str();
}

std::string renderSvg(const LineChart& c) {
  double ymax = 0, xmax = 0;
  for (const auto& row : c.ys)
    for (double v : row)
      if (std::isfinite(v)) ymax = std::max(ymax, v);
  for (const auto& row : c.xs)
    for (double v : row)
      if (std::isfinite(v)) xmax = std::max(xmax, v);
  double yMax = niceMax(ymax), xMax = niceMax(xmax);
  std::ostringstream s;
  header(s, c.title, c.yLabel, yMax);
  double plotW = kWidth - kLeft - kRight, plotH = kHeight - kTop - kBottom;
  for (int i = 0; i <= 5; ++i) {
    double x = kLeft + plotW * i / 5.0;
    s << "<text x=\"" << x << "\" y=\"" << kTop + plotH + 16 << "\" text-anchor=\"middle\">" << fmt(xMax * i / 5.0)
      << "</text>\n";
  }
  s << "<text x=\"" << kLeft + plotW / 2 << "\" y=\"" << kTop + plotH + 36 << "\" text-anchor=\"middle\">"
    << esc(c.xLabel) << "</text>\n";
  for (std::size_t k = 0; k < c.series.size() && k < c.xs.size() && k < c.ys.size(); ++k) {
    std::ostringstream pts;
    for (std::size_t i = 0; i < c.xs[k].size() && i < c.ys[k].size(); ++i) {
      if (!std::isfinite(c.xs[k][i]) || !std::isfinite(c.ys[k][i])) continue;
      double x = kLeft + plotW * c.xs[k][i] / xMax, y = kTop + plotH * (1.0 - c.ys[k][i] / yMax);
      pts << x << "," << y << " ";
      s << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"3\" fill=\"" << kColors[k % 8] << "\"/>\n";
    }
    s << "<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" << kColors[k % 8] << "\" points=\"" << pts.str()
      << "\"/>\n";
  }
  legend(s, c.series);
  s << "</svg>\n";
  return s.str();
}

void writeSvg(const std::filesystem::path& path, const std::string& svg) {
  writeFileAtomically(path, [&](std::ostream& out) { out << svg; }, false);
}

}  // namespace treesketch::eval
