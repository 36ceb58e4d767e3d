// Multi-scale covariance features: a line of points is linear, a flat patch planar, core points
// stand for every point, and bad options or tiny clouds are refused.
#include "treesketch/classify/features.h"

#include <gtest/gtest.h>

#include <random>

#include "treesketch/util/error.h"

namespace treesketch::classify {
namespace {

geom::PointCloud lineAndPlane(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  geom::PointCloud c;
  for (int i = 0; i < 2000; ++i) c.positions.emplace_back(0.0, 4.0 * u(rng), 0.002 * u(rng));  // a vertical stick
  for (int i = 0; i < 2000; ++i) c.positions.emplace_back(2.0 + u(rng), 2.0, 2.0 + u(rng));    // a flat square
  return c;
}

int column(const FeatureTable& t, const std::string& name) {
  for (int k = 0; k < t.count; ++k)
    if (t.names[k] == name) return k;
  ADD_FAILURE() << "no feature " << name;
  return 0;
}

TEST(Features, StickIsLinearAndVerticalSquareIsPlanarAndFlat) {
  const geom::PointCloud c = lineAndPlane(3);
  FeatureOptions o;
  o.coreSpacings = 0;  // every point a core: the answer per point
  const FeatureTable t = computeFeatures(c, geom::UpAxis::Y, o);
  ASSERT_EQ(t.points(), c.size());
  const int lin = column(t, "linearity_k16"), pla = column(t, "planarity_k16"), ax = column(t, "axis_up_k16"),
            nup = column(t, "normal_up_k16");
  double stickLin = 0, stickAxis = 0, squarePla = 0, squareNormal = 0;
  for (std::size_t i = 0; i < 2000; ++i) stickLin += t.row(i)[lin], stickAxis += t.row(i)[ax];
  for (std::size_t i = 2000; i < 4000; ++i) squarePla += t.row(i)[pla], squareNormal += t.row(i)[nup];
  EXPECT_GT(stickLin / 2000, 0.9);
  EXPECT_GT(stickAxis / 2000, 0.95);
  EXPECT_GT(squarePla / 2000, 0.4);      // random points on a square: l2 near l1, l3 near 0
  EXPECT_GT(squareNormal / 2000, 0.95);  // the square lies flat: its normal is up
  // Height: the stick's top is the highest point; the square sits at half the height.
  EXPECT_NEAR(t.treeHeight, 4.0, 0.01);
  EXPECT_NEAR(t.row(2500)[column(t, "height")], 0.5, 0.01);
  for (std::size_t i = 0; i < t.points(); ++i)
    for (int k = 0; k < t.neighbourCount; ++k) ASSERT_LT(t.neighbours[i * t.neighbourCount + k], t.points());
}

TEST(Features, CorePointsStandForEveryPoint) {
  const geom::PointCloud c = lineAndPlane(5);
  const FeatureTable t = computeFeatures(c, geom::UpAxis::Y);
  ASSERT_EQ(t.coreOf.size(), c.size());
  EXPECT_LT(t.points(), c.size());  // thinned
  std::size_t total = 0;
  for (auto s : t.coreSize) total += s;
  EXPECT_EQ(total, c.size());
  for (auto k : t.coreOf) ASSERT_LT(k, t.points());
  EXPECT_GT(t.spacing, 0.0);
}

TEST(Features, ASpacingFinerThanTheFloorIsRaisedToIt) {
  // The stick and square sampled 40 times more densely than the floor: the features work at the
  // floor (a fraction of the 4 m height), on far fewer cores; without the floor, at the spacing.
  const geom::PointCloud c = lineAndPlane(7);
  FeatureOptions o;
  o.minSpacingHeightFraction = 0.01;
  const FeatureTable floored = computeFeatures(c, geom::UpAxis::Y, o);
  EXPECT_NEAR(floored.spacing, 0.01 * floored.treeHeight, 1e-3 * floored.treeHeight);
  EXPECT_LT(floored.measuredSpacing, 0.5 * floored.spacing);
  o.minSpacingHeightFraction = 0;
  const FeatureTable measured = computeFeatures(c, geom::UpAxis::Y, o);
  EXPECT_EQ(measured.spacing, measured.measuredSpacing);
  EXPECT_EQ(measured.measuredSpacing, floored.measuredSpacing);
  EXPECT_LT(2 * floored.points(), measured.points());
  // The stick is still linear and vertical at the coarser spacing.
  const int lin = column(floored, "linearity_k16"), ax = column(floored, "axis_up_k16");
  EXPECT_GT(floored.row(floored.coreOf[100])[lin], 0.9);
  EXPECT_GT(floored.row(floored.coreOf[100])[ax], 0.95);
}

TEST(Features, BadOptionsAndTinyCloudsAreRefused) {
  geom::PointCloud c = lineAndPlane(1);
  FeatureOptions o;
  o.scales = {16, 8};
  EXPECT_THROW(computeFeatures(c, geom::UpAxis::Y, o), OptionsError);
  o.scales = {};
  EXPECT_THROW(computeFeatures(c, geom::UpAxis::Y, o), OptionsError);
  o = {};
  o.coreSpacings = -1;
  EXPECT_THROW(computeFeatures(c, geom::UpAxis::Y, o), OptionsError);
  o = {};
  o.minSpacingHeightFraction = 1.0;
  EXPECT_THROW(computeFeatures(c, geom::UpAxis::Y, o), OptionsError);
  c.positions.resize(20);
  EXPECT_THROW(computeFeatures(c, geom::UpAxis::Y), DegenerateInputError);
}

}  // namespace
}  // namespace treesketch::classify
