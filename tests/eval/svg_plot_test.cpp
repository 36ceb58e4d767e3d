#include "treesketch/eval/svg_plot.h"

#include <gtest/gtest.h>

#include <cmath>

namespace treesketch::eval {
namespace {

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(SvgPlot, BarChartHasOneBarPerFiniteValue) {
  BarChart c;
  c.title = "t <&>";
  c.groups = {"a", "b", "c"};
  c.series = {"x", "y"};
  c.values = {{1, 2, 3}, {0.5, NAN, 4}};
  std::string svg = renderSvg(c);
  // 5 bars + 2 legend swatches + the background.
  EXPECT_EQ(count(svg, "<rect"), 5u + 2u + 1u);
  EXPECT_NE(svg.find("t &lt;&amp;&gt;"), std::string::npos);
  EXPECT_EQ(svg.rfind("</svg>"), svg.size() - 7);
}

TEST(SvgPlot, LineChartPlotsEveryPoint) {
  LineChart c;
  c.series = {"tree1", "tree2"};
  c.xs = {{5, 10, 20}, {5, 10}};
  c.ys = {{3, 2, 1}, {4, 3}};
  std::string svg = renderSvg(c);
  EXPECT_EQ(count(svg, "<circle"), 5u);
  EXPECT_EQ(count(svg, "<polyline"), 2u);
}

TEST(SvgPlot, LogAxesAndStyles) {
  LineChart c;
  c.series = {"a", "b"};
  c.xs = {{5000, 20000, 1e6}, {1e4, 0.0}};
  c.ys = {{0.1, 0.5, 20}, {1, 2}};
  c.styles = {SeriesStyle{0, false, false, false}, SeriesStyle{0, true, true, true}};
  c.logX = c.logY = true;
  std::string svg = renderSvg(c);
  // Markers only for "a"; "b" loses its x = 0 point on the log axis and is dashed and hollow.
  EXPECT_EQ(count(svg, "<polyline"), 1u);
  EXPECT_EQ(count(svg, "stroke-dasharray"), 2u);                  // line + legend
  EXPECT_EQ(count(svg, "fill=\"none\" stroke=\"#1f77b4\""), 1u);  // the hollow marker (legend: the dash)
  EXPECT_EQ(count(svg, "<circle"), 3u + 1u);
  // Whole decades: 1000 .. 1e6 on x, 0.1 .. 100 on y.
  EXPECT_NE(svg.find(">1e+06<"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">1000<"), std::string::npos);
  EXPECT_NE(svg.find(">0.1<"), std::string::npos);
  EXPECT_NE(svg.find(">100<"), std::string::npos);
}

}  // namespace
}  // namespace treesketch::eval
