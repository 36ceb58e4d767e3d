#include "treesketch/viewer/point_colors.h"

#include <gtest/gtest.h>

#include <cmath>

#include "treesketch/gen/random.h"
#include "treesketch/render/color_map.h"

namespace treesketch::viewer {
namespace {

using geom::Vec3;
using render::viridis;

TEST(PointColors, DistanceToCircleKnownValues) {
  Circle3 c{Vec3(1, 2, 3), Vec3(0, 1, 0), 2.0};
  EXPECT_NEAR(distanceToCircle(Vec3(3, 2, 3), c), 0.0, 1e-12);                   // on the curve
  EXPECT_NEAR(distanceToCircle(Vec3(1, 2, 3), c), 2.0, 1e-12);                   // the centre
  EXPECT_NEAR(distanceToCircle(Vec3(1, 5, 3), c), std::sqrt(9.0 + 4.0), 1e-12);  // on the axis
  EXPECT_NEAR(distanceToCircle(Vec3(6, 2, 3), c), 3.0, 1e-12);                   // outside in the plane
  EXPECT_NEAR(distanceToCircle(Vec3(3, 3, 3), c), 1.0, 1e-12);                   // above the curve
}

TEST(PointColors, CircleDistanceColorsUseTheNearestCircle) {
  geom::PointCloud cloud;
  cloud.positions = {Vec3(1, 0, 0), Vec3(0, 10, 1), Vec3(50, 50, 50), Vec3(0.5, 0, 0)};
  std::vector<Circle3> circles = {{Vec3(0, 0, 0), Vec3(0, 1, 0), 1.0}, {Vec3(0, 10, 0), Vec3(0, 1, 0), 1.0}};
  auto colors = circleDistanceColors(cloud, circles, 1.0);
  EXPECT_EQ(colors[0], viridis(0.0));
  EXPECT_EQ(colors[1], viridis(0.0));
  EXPECT_EQ(colors[2], viridis(1.0));
  EXPECT_EQ(colors[3], viridis(0.5));
  auto none = circleDistanceColors(cloud, {}, 1.0);
  EXPECT_EQ(none[0], viridis(1.0));
  EXPECT_EQ(plainColors(cloud, Rgb{1, 2, 3}).size(), 4u);
}

}  // namespace
}  // namespace treesketch::viewer

namespace treesketch::viewer {
namespace {

// The grid gives exactly circleDistanceColors' colours, call after call (its scratch is reset).
TEST(DistanceColorGrid, SameColoursAsTheDirectComputation) {
  gen::Rng rng(17);
  geom::PointCloud cloud;
  for (int i = 0; i < 20000; ++i)
    cloud.positions.emplace_back(rng.uniform(-1, 1), rng.uniform(0, 4), rng.uniform(-1, 1));
  std::vector<Circle3> circles = {{geom::Vec3(0, 1, 0), geom::Vec3(0, 1, 0), 0.2},
                                  {geom::Vec3(0.3, 2.5, 0.1), geom::Vec3(0.6, 0.8, 0).normalized(), 0.1},
                                  {geom::Vec3(5, 9, 5), geom::Vec3(0, 0, 1), 0.3}};  // outside the cloud
  DistanceColorGrid grid;
  grid.build(cloud, 0.15);
  ASSERT_TRUE(grid.builtFor(cloud, 0.15));
  EXPECT_FALSE(grid.builtFor(cloud, 0.2));
  std::vector<Rgb> fast;
  for (int pass = 0; pass < 2; ++pass) {
    grid.colors(circles, fast);
    std::vector<Rgb> direct = circleDistanceColors(cloud, circles, 0.15);
    ASSERT_EQ(fast.size(), direct.size());
    std::size_t differ = 0, near = 0;
    for (std::size_t i = 0; i < fast.size(); ++i) {
      differ += !(fast[i] == direct[i]);
      near += !(direct[i] == render::viridis(1.0));
    }
    EXPECT_EQ(differ, 0u) << "pass " << pass;
    EXPECT_GT(near, 100u);  // the check sees points near the circles, not only far ones
    circles.pop_back();
  }
  grid.colors({}, fast);
  EXPECT_EQ(fast, std::vector<Rgb>(cloud.size(), render::viridis(1.0)));
}

}  // namespace
}  // namespace treesketch::viewer
