#include "treesketch/render/color_map.h"

#include <gtest/gtest.h>

#include <cmath>

namespace treesketch::render {
namespace {

int brightness(Rgb c) { return c.r + c.g + c.b; }

TEST(ColorMap, ViridisRunsDarkToBrightAndClamps) {
  EXPECT_EQ(viridis(0.0), (Rgb{68, 1, 84}));
  EXPECT_EQ(viridis(1.0), (Rgb{253, 231, 37}));
  EXPECT_EQ(viridis(-3.0), viridis(0.0));
  EXPECT_EQ(viridis(7.0), viridis(1.0));
  EXPECT_EQ(viridis(NAN), viridis(0.0));
  for (double t = 0.1; t <= 1.0; t += 0.1) EXPECT_GE(brightness(viridis(t)) + 8, brightness(viridis(t - 0.1)));
}

TEST(ColorMap, HeightColorsFollowTheUpAxis) {
  std::vector<geom::Vec3> pts = {geom::Vec3(0, 0, 5), geom::Vec3(0, 2, 0), geom::Vec3(0, 1, 10)};
  auto byY = heightColors(pts, geom::UpAxis::Y);
  ASSERT_EQ(byY.size(), 3u);
  EXPECT_EQ(byY[0], viridis(0.0));
  EXPECT_EQ(byY[1], viridis(1.0));
  EXPECT_EQ(byY[2], viridis(0.5));
  auto byZ = heightColors(pts, geom::UpAxis::Z);
  EXPECT_EQ(byZ[1], viridis(0.0));
  EXPECT_EQ(byZ[2], viridis(1.0));
  EXPECT_TRUE(heightColors({}, geom::UpAxis::Z).empty());
  auto flatCloud = heightColors({geom::Vec3(1, 2, 3), geom::Vec3(4, 5, 3)}, geom::UpAxis::Z);
  EXPECT_EQ(flatCloud[0], viridis(0.5));
}

TEST(ColorMap, DistinctColorsAndBlend) {
  EXPECT_NE(distinctColor(0), distinctColor(1));
  EXPECT_EQ(distinctColor(0), distinctColor(6));
  EXPECT_EQ(blend({0, 100, 200}, {255, 255, 255}, 0.0), (Rgb{0, 100, 200}));
  EXPECT_EQ(blend({0, 100, 200}, {255, 255, 255}, 1.0), (Rgb{255, 255, 255}));
  EXPECT_EQ(blend({0, 100, 200}, {100, 200, 0}, 0.5), (Rgb{50, 150, 100}));
  EXPECT_EQ(blend({0, 100, 200}, {100, 200, 0}, 9.0), (Rgb{100, 200, 0}));
}

}  // namespace
}  // namespace treesketch::render
