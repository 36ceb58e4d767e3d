#include "treesketch/viewer/point_colors.h"

#include <gtest/gtest.h>

#include <cmath>

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
