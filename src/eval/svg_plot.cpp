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
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
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

/// An axis: linear from 0 to a nice maximum, or logarithmic over whole decades.
struct Axis {
  bool log = false;
  double lo = 0, hi = 1;  ///< linear: values; log: log10 of the values

  /// Fraction of the axis length at value v (NaN when v cannot be drawn).
  double at(double v) const {
    if (!std::isfinite(v)) return NAN;
    if (log) return v > 0 ? (std::log10(v) - lo) / (hi - lo) : NAN;
    return v / hi;
  }
  std::vector<double> ticks() const {
    std::vector<double> t;
    if (log)
      for (int e = static_cast<int>(lo); e <= static_cast<int>(hi); ++e) t.push_back(std::pow(10.0, e));
    else
      for (int i = 0; i <= 5; ++i) t.push_back(hi * i / 5.0);
    return t;
  }
};

Axis makeAxis(const std::vector<std::vector<double>>& values, bool log) {
  Axis a;
  a.log = log;
  double vmax = 0, lmin = INFINITY, lmax = -INFINITY;
  for (const auto& row : values)
    for (double v : row) {
      if (!std::isfinite(v)) continue;
      vmax = std::max(vmax, v);
      if (v > 0) {
        lmin = std::min(lmin, std::log10(v));
        lmax = std::max(lmax, std::log10(v));
      }
    }
  if (!log) {
    a.hi = niceMax(vmax);
    return a;
  }
  if (!std::isfinite(lmin)) lmin = lmax = 0;
  a.lo = std::floor(lmin);
  a.hi = std::max(std::ceil(lmax), a.lo + 1);
  return a;
}

void header(std::ostringstream& s, const std::string& title, const std::string& yLabel, const Axis& y) {
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s << "<text x=\"" << kWidth / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << esc(title)
    << "</text>\n";
  double plotH = kHeight - kTop - kBottom;
  for (double v : y.ticks()) {
    double yy = kTop + plotH * (1.0 - y.at(v));
    s << "<line x1=\"" << kLeft << "\" x2=\"" << kWidth - kRight << "\" y1=\"" << yy << "\" y2=\"" << yy
      << "\" stroke=\"#ddd\"/>\n";
    s << "<text x=\"" << kLeft - 6 << "\" y=\"" << yy + 4 << "\" text-anchor=\"end\">" << fmt(v) << "</text>\n";
  }
  s << "<text transform=\"translate(18," << kTop + plotH / 2 << ") rotate(-90)\" text-anchor=\"middle\">" << esc(yLabel)
    << "</text>\n";
  s << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft << "\" y1=\"" << kTop << "\" y2=\"" << kTop + plotH
    << "\" stroke=\"black\"/>\n";
  s << "<line x1=\"" << kLeft << "\" x2=\"" << kWidth - kRight << "\" y1=\"" << kTop + plotH << "\" y2=\""
    << kTop + plotH << "\" stroke=\"black\"/>\n";
}

void legend(std::ostringstream& s, const std::vector<std::string>& series,
            const std::vector<SeriesStyle>& styles = {}) {
  for (std::size_t i = 0; i < series.size(); ++i) {
    double y = kTop + 10 + 20.0 * i;
    SeriesStyle st = i < styles.size() ? styles[i] : SeriesStyle{};
    const char* colour = kColors[(st.colour >= 0 ? st.colour : static_cast<int>(i)) % 8];
    double x = kWidth - kRight + 15;
    if (st.dashed)
      s << "<line x1=\"" << x - 2 << "\" x2=\"" << x + 14 << "\" y1=\"" << y - 3 << "\" y2=\"" << y - 3
        << "\" stroke=\"" << colour << "\" stroke-width=\"2\" stroke-dasharray=\"4,3\"/>\n";
    else if (st.hollow)
      s << "<circle cx=\"" << x + 6 << "\" cy=\"" << y - 3 << "\" r=\"4\" fill=\"none\" stroke=\"" << colour
        << "\"/>\n";
    else
      s << "<rect x=\"" << x << "\" y=\"" << y - 9 << "\" width=\"12\" height=\"12\" fill=\"" << colour << "\"/>\n";
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
  Axis yAxis;
  yAxis.hi = yMax;
  std::ostringstream s;
  header(s, c.title, c.yLabel, yAxis);
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
  Axis xAxis = makeAxis(c.xs, c.logX), yAxis = makeAxis(c.ys, c.logY);
  std::ostringstream s;
  header(s, c.title, c.yLabel, yAxis);
  double plotW = kWidth - kLeft - kRight, plotH = kHeight - kTop - kBottom;
  for (double v : xAxis.ticks()) {
    double x = kLeft + plotW * xAxis.at(v);
    s << "<text x=\"" << x << "\" y=\"" << kTop + plotH + 16 << "\" text-anchor=\"middle\">" << fmt(v) << "</text>\n";
  }
  s << "<text x=\"" << kLeft + plotW / 2 << "\" y=\"" << kTop + plotH + 36 << "\" text-anchor=\"middle\">"
    << esc(c.xLabel) << "</text>\n";
  for (std::size_t k = 0; k < c.series.size() && k < c.xs.size() && k < c.ys.size(); ++k) {
    SeriesStyle st = k < c.styles.size() ? c.styles[k] : SeriesStyle{};
    const char* colour = kColors[(st.colour >= 0 ? st.colour : static_cast<int>(k)) % 8];
    std::ostringstream pts;
    for (std::size_t i = 0; i < c.xs[k].size() && i < c.ys[k].size(); ++i) {
      double fx = xAxis.at(c.xs[k][i]), fy = yAxis.at(c.ys[k][i]);
      if (!std::isfinite(fx) || !std::isfinite(fy)) continue;
      double x = kLeft + plotW * fx, y = kTop + plotH * (1.0 - fy);
      pts << x << "," << y << " ";
      if (st.hollow)
        s << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"3\" fill=\"none\" stroke=\"" << colour << "\"/>\n";
      else
        s << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"3\" fill=\"" << colour << "\"/>\n";
    }
    if (st.line)
      s << "<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" << colour << "\""
        << (st.dashed ? " stroke-dasharray=\"6,4\"" : "") << " points=\"" << pts.str() << "\"/>\n";
  }
  legend(s, c.series, c.styles);
  s << "</svg>\n";
  return s.str();
}

void writeSvg(const std::filesystem::path& path, const std::string& svg) {
  writeFileAtomically(
      path, [&](std::ostream& out) { out << svg; }, false);
}

}  // namespace treesketch::eval
