// Status messages that expire, optional node labels, the colour legend and the up direction
// (at the library level; the window runs apps/viewer/tests/view_options.json).
#include <gtest/gtest.h>

#include <cmath>

#include "treesketch/gen/random.h"
#include "treesketch/render/color_map.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/point_colors.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {
namespace {

using geom::Vec2;
using geom::Vec3;
using namespace std::chrono_literals;

/// A trunk of radius 0.2 and height 4 along `axis` (0 x, 1 y, 2 z).
geom::PointCloud trunk(int axis = 1, int n = 4000) {
  gen::Rng rng(11);
  geom::PointCloud cloud;
  for (int i = 0; i < n; ++i) {
    double a = rng.uniform(0, 2 * M_PI);
    Vec3 p(0.2 * std::cos(a), 0.2 * std::sin(a), 0);
    Vec3 q;
    q[axis] = rng.uniform(0, 4);
    q[(axis + 1) % 3] = p.x();
    q[(axis + 2) % 3] = p.y();
    cloud.positions.push_back(q);
  }
  return cloud;
}

TEST(StatusLine, InfosExpireErrorsStayUntilDismissedOrReplaced) {
  ViewerState s;
  s.status().info("hello");
  auto now = std::chrono::steady_clock::now();
  ASSERT_TRUE(s.status().statusLine(now));
  EXPECT_EQ(s.status().statusLine(now)->text, "hello");
  ASSERT_TRUE(s.status().expiry());
  EXPECT_FALSE(s.status().statusLine(now + 10s));  // 6 s by default
  s.status().error("broken");
  EXPECT_TRUE(s.status().statusLine(now + 1h));
  EXPECT_FALSE(s.status().expiry());
  s.status().dismiss();
  EXPECT_FALSE(s.status().statusLine(now + 1s));
  s.status().error("again");
  s.status().info("replaced");
  EXPECT_EQ(s.status().statusLine()->text, "replaced");
  EXPECT_FALSE(s.status().statusLine(now + 1h));
  // Esc dismisses too; the log keeps every message.
  s.status().error("third");
  EXPECT_TRUE(s.keyPress("escape"));
  EXPECT_FALSE(s.status().statusLine());
  EXPECT_EQ(s.status().messages().size(), 5u);
}

TEST(Labels, AutoHidesThemOnLargeSketchesAndTheKeyCycles) {
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(trunk(), geom::UpAxis::Y));
  s.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  ASSERT_TRUE(s.autoSketchUniform(12));
  EXPECT_EQ(s.view().display().labels, LabelMode::Auto);
  EXPECT_TRUE(s.scene().labelsShown());
  ASSERT_TRUE(s.autoSketchUniform(int(s.options().autoLabelMaxNodes) + 1));
  EXPECT_FALSE(s.scene().labelsShown());
  EXPECT_TRUE(s.keyPress("l"));  // auto -> on
  EXPECT_TRUE(s.scene().labelsShown());
  EXPECT_TRUE(s.keyPress("l"));  // on -> off
  EXPECT_FALSE(s.scene().labelsShown());
  EXPECT_EQ(parseLabelMode("auto"), LabelMode::Auto);
  EXPECT_THROW(parseLabelMode("maybe"), OptionsError);
}

TEST(Legend, DistanceScaleMatchesThePointColoursAndHeightFollowsTheViewUp) {
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(trunk(), geom::UpAxis::Y));
  s.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  s.view().setColorMode(ColorMode::CircleDistance);
  Legend l = colorLegend(s);
  ASSERT_EQ(l.kind, Legend::Kind::Scale);
  ASSERT_GE(l.ramp.size(), 2u);
  const double scale = s.options().distanceColorScale * s.bounds().diagonal();
  EXPECT_DOUBLE_EQ(l.range.min, 0.0);
  EXPECT_NEAR(l.range.max, scale, 1e-12);
  EXPECT_NE(l.note.find("no fitted circle"), std::string::npos) << l.note;
  // The legend's colours are those circleDistanceColors gives a point at that distance.
  Circle3 c{Vec3(0, 0, 0), Vec3(0, 1, 0), 1.0};
  geom::PointCloud probe;
  const std::size_t n = l.ramp.size();
  for (std::size_t i = 0; i < n; ++i) probe.positions.push_back(Vec3(1.0 + scale * double(i) / double(n - 1), 0, 0));
  std::vector<Rgb> colors = circleDistanceColors(probe, {c}, scale);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_NEAR(colors[i].r, l.ramp[i].r, 1) << i;
    EXPECT_NEAR(colors[i].g, l.ramp[i].g, 1) << i;
  }
  s.view().setColorMode(ColorMode::Height);
  l = colorLegend(s);
  ASSERT_EQ(l.kind, Legend::Kind::Scale);
  EXPECT_NEAR(l.range.max - l.range.min, s.bounds().extent().y(), 1e-9);
  s.setUpDirection(UpDirection::PosX);  // the ramp follows the view's up: the legend too
  l = colorLegend(s);
  EXPECT_NEAR(l.range.max - l.range.min, s.bounds().extent().x(), 1e-9);
  EXPECT_NE(l.title.find(toString(UpDirection::PosX)), std::string::npos) << l.title;
  s.view().setColorMode(ColorMode::Plain);
  EXPECT_EQ(colorLegend(s).kind, Legend::Kind::None);
}

TEST(UpDirection, TheLibraryRuleDecidesAndALyingCloudIsWarnedAbout) {
  geom::PointCloud zUp = trunk(2);
  ViewUpChoice c = chooseViewUp("", zUp, false);  // a text cloud declares nothing: Z
  EXPECT_EQ(c.axis, geom::UpAxis::Z);
  EXPECT_EQ(c.view, UpDirection::PosZ);
  EXPECT_EQ(chooseViewUp("", zUp, true).axis, geom::UpAxis::Y);  // the demo tree
  geom::PointCloud declared = zUp;
  declared.up = geom::UpAxis::Y;
  EXPECT_EQ(chooseViewUp("", declared, false).axis, geom::UpAxis::Y);
  ViewUpChoice neg = chooseViewUp("-z", zUp, false);
  EXPECT_EQ(neg.view, UpDirection::NegZ);
  EXPECT_THROW(chooseViewUp("w", zUp, false), OptionsError);

  // The same Z-up trunk opened as Y-up (the old default) lies down: warned; under +Z it stands.
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(zUp, geom::UpAxis::Y));
  s.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  EXPECT_TRUE(s.upWarningShown());
  EXPECT_NE(s.lyingDownWarning().find("lying down"), std::string::npos);
  // On two of its points (the view looks down the hollow trunk: its axis meets no points).
  s.clickAt(s.view().camera().project(zUp.positions[0]).head<2>());
  s.clickAt(s.view().camera().project(zUp.positions[1]).head<2>());
  ASSERT_EQ(s.sketch().size(), 2u);
  s.setUpDirection(UpDirection::PosZ);
  EXPECT_FALSE(s.upWarningShown());
  EXPECT_EQ(s.up(), geom::UpAxis::Z);
  EXPECT_EQ(s.sketch().size(), 2u);  // the sketch is kept
  // The front view now has +Z as screen up.
  geom::Camera cam = s.view().camera();
  Vec3 low = cam.project(Vec3(0, 0, 0)), high = cam.project(Vec3(0, 0, 4));
  EXPECT_LT(high.y(), low.y());  // window y grows downwards
  // -Z: upside down; the automatic sketches refuse with a message (they assume +Y or +Z).
  s.setUpDirection(UpDirection::NegZ);
  EXPECT_FALSE(s.autoSketchUniform());
  EXPECT_TRUE(s.status().lastMessage().error);
  EXPECT_EQ(s.sketch().size(), 2u);
  s.setUpDirection(UpDirection::PosX);
  EXPECT_TRUE(s.upWarningShown());
  s.view().dismissUpWarning();
  EXPECT_FALSE(s.upWarningShown());
}

}  // namespace
}  // namespace treesketch::viewer
