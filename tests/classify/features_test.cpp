// Multi-scale covariance features: a line of points is linear, a flat patch planar, core points
// stand for every point, and bad options or tiny clouds are refused.
#include "treesketch/classify/features.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// Points repeated at the same position are no neighbours of each other: the cloud written twice
// measures the spacing it measures once (it measured 0 and fell back to 1e-6).
TEST(Features, RepeatedPointsDoNotShrinkTheMeasuredSpacing) {
  const geom::PointCloud once = lineAndPlane(9);
  geom::PointCloud twice = once;
  twice.positions.insert(twice.positions.end(), once.positions.begin(), once.positions.end());
  FeatureOptions o;
  o.minSpacingHeightFraction = 0;
  const FeatureTable a = computeFeatures(once, geom::UpAxis::Y, o);
  const FeatureTable b = computeFeatures(twice, geom::UpAxis::Y, o);
  EXPECT_NEAR(b.measuredSpacing, a.measuredSpacing, 0.01 * a.measuredSpacing);
}

/// A limb's bark (a cylinder of radius 0.15 m, 2 m long) and, beside it, a cluster of small flat
/// leaves (3 cm squares) at random orientations, both sampled about 1 cm apart.
geom::PointCloud barkAndLeaves(unsigned seed, std::size_t& barkPoints) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  geom::PointCloud c;
  for (int i = 0; i < 20000; ++i) {
    const double a = 2 * M_PI * u(rng);
    c.positions.emplace_back(0.15 * std::cos(a), 2.0 * u(rng), 0.15 * std::sin(a));
  }
  barkPoints = c.size();
  std::normal_distribution<double> g(0.0, 1.0);
  for (int leaf = 0; leaf < 400; ++leaf) {
    const geom::Vec3 centre(2.0 + 0.25 * g(rng), 1.0 + 0.25 * g(rng), 0.25 * g(rng));
    const geom::Vec3 n = geom::Vec3(g(rng), g(rng), g(rng)).normalized();
    const geom::Vec3 a = n.unitOrthogonal(), b = n.cross(a);
    for (int k = 0; k < 25; ++k) c.positions.push_back(centre + 0.03 * (u(rng) - 0.5) * a + 0.03 * (u(rng) - 0.5) * b);
  }
  return c;
}

TEST(Features, BarkNormalsFanAboutOneAxisLeafNormalsScatter) {
  // At 32 points the bark patch is about as planar as a leaf; its normals turn about the limb's axis
  // only (fan), while a leaf cluster's turn every way (scatter).
  std::size_t bark = 0;
  const geom::PointCloud c = barkAndLeaves(11, bark);
  FeatureOptions o;
  o.coreSpacings = 0;
  o.minSpacingHeightFraction = 0;
  const FeatureTable t = computeFeatures(c, geom::UpAxis::Y, o);
  const int fan = column(t, "normal_fan_k32"), scatter = column(t, "normal_scatter_k32"),
            spread = column(t, "normal_spread_k32");
  double barkFan = 0, barkScatter = 0, barkSpread = 0, leafFan = 0, leafScatter = 0;
  for (std::size_t i = 0; i < bark; ++i)
    barkFan += t.row(i)[fan], barkScatter += t.row(i)[scatter], barkSpread += t.row(i)[spread];
  for (std::size_t i = bark; i < c.size(); ++i) leafFan += t.row(i)[fan], leafScatter += t.row(i)[scatter];
  barkFan /= bark, barkScatter /= bark, barkSpread /= bark;
  leafFan /= c.size() - bark, leafScatter /= c.size() - bark;
  EXPECT_GT(barkSpread, 0.01);          // the bark's normals do turn over the patch
  EXPECT_GT(barkFan, 3 * barkScatter);  // ... about one axis
  EXPECT_GT(leafScatter, 3 * barkScatter);
  EXPECT_GT(barkFan / std::max(barkSpread, 1e-9), leafFan / std::max(leafScatter + leafFan, 1e-9));
  // Switched off, the columns are gone.
  o.normalFeatures = false;
  const FeatureTable without = computeFeatures(c, geom::UpAxis::Y, o);
  EXPECT_EQ(without.count, t.count - 9);  // 3 per fine scale after the first (16, 32), 3 for coarse 24
  for (const auto& name : without.names) EXPECT_EQ(name.find("normal_fan"), std::string::npos);
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
