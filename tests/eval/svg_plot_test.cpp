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

}  // namespace
}  // namespace treesketch::eval
