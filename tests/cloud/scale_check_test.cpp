// A cloud too large for a tree in metres, or too far from its origin for its spacing, is named
// with the fix; a tree in metres, even in UTM coordinates, is not.
#include "treesketch/cloud/scale_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace treesketch::cloud {
namespace {

geom::PointCloud trunk(double scale, const geom::Vec3& offset) {
  geom::PointCloud c;
  const double step = 0.01;
  for (double z = 0; z <= 5.0; z += step)
    for (int k = 0; k < 120; ++k) {
      const double a = 2 * std::numbers::pi * k / 120;
      c.positions.push_back(offset + scale * geom::Vec3(0.2 * std::cos(a), 0.2 * std::sin(a), z));
    }
  return c;
}

ScaleCheck check(const geom::PointCloud& c, double unit = 1.0) { return checkScale(c, findStrayPoints(c), unit); }

TEST(ScaleCheck, ATreeInMetresIsQuietEvenInUtmCoordinates) {
  EXPECT_TRUE(check(trunk(1, geom::Vec3::Zero())).warnings.empty());
  const ScaleCheck utm = check(trunk(1, geom::Vec3(512345.0, 5412345.0, 250.0)));
  EXPECT_TRUE(utm.warnings.empty()) << utm.warnings.front();
  EXPECT_LT(utm.doubleStep, 1e-9);
  EXPECT_GT(utm.floatStep, 0.1);  // what a float export would keep there
}

TEST(ScaleCheck, ACloudInMillimetresIsNamedWithTheFix) {
  const geom::PointCloud mm = trunk(1000, geom::Vec3::Zero());
  const ScaleCheck c = check(mm);
  EXPECT_TRUE(c.implausibleSize);
  EXPECT_NEAR(c.extentMetres, 5000, 1);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("--units-metres"), std::string::npos);
  EXPECT_NE(c.warnings[0].find("0.001"), std::string::npos);
  EXPECT_TRUE(check(mm, 0.001).warnings.empty());  // said so: quiet
}

TEST(ScaleCheck, CoordinatesThatLostTheirSpacingAreNamed) {
  const ScaleCheck c = check(trunk(1, geom::Vec3(1e15, 0, 0)));
  EXPECT_TRUE(c.precisionLost);
  EXPECT_EQ(c.doubleStep, 0.125);
  ASSERT_FALSE(c.warnings.empty());
  EXPECT_NE(c.warnings.back().find("recentre"), std::string::npos);
  EXPECT_TRUE(checkScale(geom::PointCloud{}, StrayPoints{}).warnings.empty());
}

// Coordinates past 1e10 with their spacing intact (doubles step by 0.12 mm at 1e12) are named too:
// the automatic model was the same up to 1e10 from the origin, and drifted at 1e11 and 1e12.
TEST(ScaleCheck, CoordinatesPastTheTestedRangeAreNamed) {
  const ScaleCheck tested = check(trunk(1, geom::Vec3(9e9, 0, 0)));
  EXPECT_FALSE(tested.beyondTestedOffset);
  EXPECT_TRUE(tested.warnings.empty());
  const ScaleCheck far = check(trunk(1, geom::Vec3(1e12, 0, 0)));
  EXPECT_FALSE(far.precisionLost);
  EXPECT_TRUE(far.beyondTestedOffset);
  ASSERT_EQ(far.warnings.size(), 1u);
  EXPECT_NE(far.warnings[0].find("recentre"), std::string::npos);
  EXPECT_FALSE(check(trunk(1, geom::Vec3(1e15, 0, 0))).beyondTestedOffset);  // the spacing warning says it
}

}  // namespace
}  // namespace treesketch::cloud
