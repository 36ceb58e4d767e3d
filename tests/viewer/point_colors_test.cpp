#include "treesketch/viewer/point_colors.h"

#include <gtest/gtest.h>

#include <cmath>

namespace treesketch::viewer {
namespace {

using geom::Vec3;

TEST(PointColors, RampEndsAndClamping) {
  EXPECT_EQ(rampColor(0.0), (Rgb{68, 1, 84}));
  EXPECT_EQ(rampColor(1.0), (Rgb{253, 231, 37}));
  EXPECT_EQ(rampColor(-3.0), rampColor(0.0));
  EXPECT_EQ(rampColor(7.0), rampColor(1.0));
  EXPECT_EQ(rampColor(std::nan("")), rampColor(0.0));
}

TEST(PointColors, HeightColorsFollowTheUpAxis) {
  geom::PointCloud cloud;
  cloud.positions = {Vec3(0, 0, 5), Vec3(0, 10, 0), Vec3(0, 5, 10)};
  auto y = heightColors(cloud, geom::UpAxis::Y);
  ASSERT_EQ(y.size(), 3u);
  EXPECT_EQ(y[0], rampColor(0.0));
  EXPECT_EQ(y[1], rampColor(1.0));
  EXPECT_EQ(y[2], rampColor(0.5));
  auto z = heightColors(cloud, geom::UpAxis::Z);
  EXPECT_EQ(z[1], rampColor(0.0));
  EXPECT_EQ(z[2], rampColor(1.0));
  geom::PointCloud flat;
  flat.positions = {Vec3(1, 2, 3), Vec3(4, 2, 6)};
  EXPECT_EQ(heightColors(flat, geom::UpAxis::Y)[0], rampColor(0.5));
  EXPECT_TRUE(heightColors(geom::PointCloud{}, geom::UpAxis::Y).empty());
}

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
  EXPECT_EQ(colors[0], rampColor(0.0));
  EXPECT_EQ(colors[1], rampColor(0.0));
  EXPECT_EQ(colors[2], rampColor(1.0));
  EXPECT_EQ(colors[3], rampColor(0.5));
  auto none = circleDistanceColors(cloud, {}, 1.0);
  EXPECT_EQ(none[0], rampColor(1.0));
  EXPECT_EQ(plainColors(cloud, Rgb{1, 2, 3}).size(), 4u);
}

}  // namespace
}  // namespace treesketch::viewer
