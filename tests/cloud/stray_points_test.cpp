// Stray points: far points and isolated points set aside at a distance derived from the cloud's
// own spacing; the tree (and a second large piece, or a twig behind a small gap) kept.
#include "treesketch/cloud/stray_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "treesketch/util/error.h"

namespace treesketch::cloud {
namespace {

/// The surface of a vertical cylinder (radius r, height h) sampled every `step`, around (cx, cy).
geom::PointCloud cylinderSurface(double r, double h, double step, double cx = 0, double cy = 0) {
  geom::PointCloud c;
  const int around = static_cast<int>(std::ceil(2 * std::numbers::pi * r / step));
  for (double z = 0; z <= h; z += step)
    for (int k = 0; k < around; ++k) {
      const double a = 2 * std::numbers::pi * k / around;
      c.positions.emplace_back(cx + r * std::cos(a), cy + r * std::sin(a), z);
    }
  return c;
}

TEST(StrayPoints, ACleanSurfaceLosesNoPoint) {
  const geom::PointCloud c = cylinderSurface(0.2, 3.0, 0.01);
  const StrayPoints s = findStrayPoints(c);
  EXPECT_TRUE(s.empty()) << strayPointsLine(s);
  EXPECT_GT(s.spacing, 0.005);
  EXPECT_LT(s.spacing, 0.03);  // the sampling step, measured from occupancy
  EXPECT_EQ(s.components, 1u);
}

TEST(StrayPoints, FarPointsAreSetAsideWhateverTheirDistance) {
  geom::PointCloud c = cylinderSurface(0.2, 3.0, 0.01);
  const std::size_t n = c.size();
  for (double d : {5.0, 20.0, 1e3, 1e6, 1e12}) c.positions.emplace_back(d, 0.5 * d, 1.0);
  c.positions.emplace_back(0, 0, -50.0);
  const StrayPoints s = findStrayPoints(c);
  ASSERT_EQ(s.count(), 6u) << strayPointsLine(s);
  for (std::size_t k = 0; k < s.count(); ++k) EXPECT_EQ(s.setAside[k], n + k);
  EXPECT_EQ(s.far + s.isolated, 6u);
  const geom::PointCloud kept = keptPoints(c, s);
  EXPECT_EQ(kept.size(), n);
  EXPECT_LT(kept.bounds().diagonal(), 3.1);
}

TEST(StrayPoints, AFarClusterIsFarAndALonePointNearTheTreeIsIsolated) {
  geom::PointCloud c = cylinderSurface(0.2, 3.0, 0.01);
  const std::size_t n = c.size();
  for (int k = 0; k < 20; ++k) c.positions.emplace_back(30.0 + 0.005 * k, 0, 1.0);  // a bird, 30 m out
  c.positions.emplace_back(0.6, 0, 1.0);                                            // 0.4 m off the stem
  EXPECT_EQ(findStrayPoints(c).count(), 20u);                                       // the radius rule is off by default
  StrayPointOptions radiusRule;
  radiusRule.minComponentPoints = 3;
  const StrayPoints s = findStrayPoints(c, radiusRule);
  ASSERT_EQ(s.count(), 21u) << strayPointsLine(s);
  EXPECT_EQ(s.far, 20u);
  EXPECT_EQ(s.isolated, 1u);
  EXPECT_EQ(s.setAside.back(), n + 20);
  EXPECT_EQ(s.reasons.back(), StrayReason::Isolated);
}

TEST(StrayPoints, ASecondStemAndATwigPastAGapAreKept) {
  geom::PointCloud c = cylinderSurface(0.2, 3.0, 0.01);
  c.append(cylinderSurface(0.1, 2.0, 0.01, 4.0, 0.0));  // a second stem 4 m away: its own bulk
  // a small twig 0.5 m off the stem (beyond the linking distance, within the near distance)
  for (int k = 0; k < 30; ++k) c.positions.emplace_back(0.7 + 0.01 * k, 0, 2.0);
  const StrayPoints s = findStrayPoints(c);
  EXPECT_TRUE(s.empty()) << strayPointsLine(s);
  EXPECT_GE(s.components, 2u);
}

TEST(StrayPoints, TheRulesScaleWithTheCloudsUnits) {
  geom::PointCloud metres = cylinderSurface(0.2, 3.0, 0.01);
  metres.positions.emplace_back(20.0, 0, 1.0);
  geom::PointCloud mm = metres;
  for (auto& p : mm.positions) p *= 1000.0;
  const StrayPoints a = findStrayPoints(metres), b = findStrayPoints(mm);
  EXPECT_EQ(a.setAside, b.setAside);
  EXPECT_NEAR(b.linkDistance, 1000.0 * a.linkDistance, 1e-6 * b.linkDistance);
}

TEST(StrayPoints, DegenerateCloudsAndOptions) {
  geom::PointCloud equal;
  equal.positions.assign(100, geom::Vec3(1, 2, 3));
  EXPECT_TRUE(findStrayPoints(equal).empty());
  EXPECT_TRUE(findStrayPoints(geom::PointCloud{}).empty());
  geom::PointCloud c = cylinderSurface(0.2, 3.0, 0.01);
  c.positions.emplace_back(20.0, 0, 1.0);
  StrayPointOptions off;
  off.enabled = false;
  EXPECT_TRUE(findStrayPoints(c, off).empty());
  StrayPointOptions bad;
  bad.linkSpacings = 0;
  EXPECT_THROW(findStrayPoints(c, bad), OptionsError);
  bad = {};
  bad.coreQuantile = 0.5;
  EXPECT_THROW(findStrayPoints(c, bad), OptionsError);
  bad = {};
  bad.minComponentPoints = 0;
  EXPECT_THROW(findStrayPoints(c, bad), OptionsError);
}

TEST(StrayPoints, ScatteredReturnsAreNotTakenForStrays) {
  // Points scattered at random in a box (no surface): the spacing measured as a surface's is too
  // short, and the rules would set aside much of the cloud; they set aside nothing instead.
  geom::PointCloud c;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 10);
  for (int k = 0; k < 2000; ++k) c.positions.emplace_back(u(rng), u(rng), u(rng));
  StrayPointOptions o;
  o.linkSpacings = 0.5;
  const StrayPoints s = findStrayPoints(c, o);
  EXPECT_TRUE(s.empty());
  EXPECT_TRUE(s.tooSparse);
}

TEST(StrayPoints, SelectPointsKeepsTheAttributes) {
  geom::PointCloud c;
  for (int k = 0; k < 5; ++k) {
    c.positions.emplace_back(k, 0, 0);
    c.intensity.push_back(static_cast<float>(10 * k));
    c.classification.push_back(static_cast<std::uint8_t>(k));
  }
  c.up = geom::UpAxis::Z;
  const geom::PointCloud s = selectPoints(c, {1, 3});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.positions[1].x(), 3.0);
  EXPECT_EQ(s.intensity[0], 10.0f);
  EXPECT_EQ(s.classification[1], 3);
  EXPECT_TRUE(s.station.empty());
  EXPECT_EQ(s.up, geom::UpAxis::Z);
}

TEST(StrayPoints, MarkedNoiseIsTheFilesClassesSevenAndEighteen) {
  geom::PointCloud c = cylinderSurface(0.2, 1.0, 0.05);
  c.classification.assign(c.size(), 1);
  const std::vector<std::uint32_t> marked{0, 3, 17, static_cast<std::uint32_t>(c.size() - 1)};
  for (std::size_t k = 0; k < marked.size(); ++k)
    c.classification[marked[k]] = k % 2 ? kHighNoiseClass : kLowNoiseClass;
  c.classification[5] = 2;   // ground: not noise
  c.classification[6] = 17;  // bridge deck, beside 18: not noise
  c.classification[7] = 8;   // "model key-point" (LAS 1.0-1.3), beside 7: not noise
  EXPECT_EQ(findMarkedNoise(c), marked);
  MarkedNoiseOptions keep;
  keep.enabled = false;
  EXPECT_TRUE(findMarkedNoise(c, keep).empty());
  c.classification.clear();  // a cloud without classes marks nothing
  EXPECT_TRUE(findMarkedNoise(c).empty());
  EXPECT_TRUE(findMarkedNoise(geom::PointCloud{}).empty());
}

TEST(StrayPoints, RepeatedPointsAreTheLaterCopiesOfAPosition) {
  geom::PointCloud c = cylinderSurface(0.2, 1.0, 0.05);
  const std::size_t n = c.size();
  c.positions.push_back(c.positions[3]);      // n: a copy of 3
  c.positions.push_back(c.positions[0]);      // n + 1: a copy of 0
  c.positions.push_back(c.positions[3]);      // n + 2: a second copy of 3
  c.positions.emplace_back(c.positions[5].x() + 1e-9, c.positions[5].y(), c.positions[5].z());  // near, not equal
  c.positions.emplace_back(0.0, 5.0, 0.0);   // n + 4
  c.positions.emplace_back(-0.0, 5.0, 0.0);  // n + 5: the same position
  const auto repeated = findRepeatedPoints(c);
  EXPECT_EQ(repeated, (std::vector<std::uint32_t>{static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n + 1),
                                                  static_cast<std::uint32_t>(n + 2), static_cast<std::uint32_t>(n + 5)}));
  EXPECT_TRUE(findRepeatedPoints(cylinderSurface(0.2, 1.0, 0.05)).empty());
  EXPECT_TRUE(findRepeatedPoints(geom::PointCloud{}).empty());
  StrayPoints s;
  addSetAside(s, repeated, StrayReason::Repeated);
  EXPECT_EQ(s.repeated, 4u);
  EXPECT_NE(strayPointsLine(s).find("4 repeating an earlier point's position"), std::string::npos) << strayPointsLine(s);
}

TEST(StrayPoints, AddedPointsMergeInOrderAndCountUnderTheirReason) {
  geom::PointCloud c = cylinderSurface(0.2, 3.0, 0.01);
  c.positions.emplace_back(100.0, 0.0, 1.0);  // far
  StrayPoints s = findStrayPoints(c);
  ASSERT_EQ(s.far, 1u);
  const auto far = s.setAside.front();
  addSetAside(s, {2, 9, far}, StrayReason::MarkedNoise);  // the far point keeps its reason
  addSetAside(s, {0, 5}, StrayReason::Ground);
  EXPECT_EQ(s.markedNoise, 2u);
  EXPECT_EQ(s.ground, 2u);
  EXPECT_EQ(s.far, 1u);
  ASSERT_EQ(s.count(), 5u);
  EXPECT_EQ(s.setAside, (std::vector<std::uint32_t>{0, 2, 5, 9, far}));
  EXPECT_EQ(s.reasons, (std::vector<StrayReason>{StrayReason::Ground, StrayReason::MarkedNoise, StrayReason::Ground,
                                                 StrayReason::MarkedNoise, StrayReason::Far}));
  const std::string line = strayPointsLine(s);
  EXPECT_NE(line.find("5 points set aside (2 marked as noise by the file, 2 on the ground, 1 far"), std::string::npos)
      << line;
  EXPECT_EQ(keptPoints(c, s).size(), c.size() - 5);
}

}  // namespace
}  // namespace treesketch::cloud
