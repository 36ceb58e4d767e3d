// Stems at breast height: a plot's stems found and its points shared out by tree; a tree forked
// below breast height, a limb crossing the slice and a limb resting on the ground are one tree.
#include "treesketch/cloud/stems.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "treesketch/cloud/ground.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/util/error.h"

namespace treesketch::cloud {
namespace {

using geom::Vec3;

/// The surface of a cylinder of radius r from `a` to `b`, rings every `step` along it.
void addTube(geom::PointCloud& c, const Vec3& a, const Vec3& b, double r, double step) {
  const Vec3 axis = (b - a).normalized();
  const Vec3 u = axis.unitOrthogonal(), v = axis.cross(u);
  const int around = static_cast<int>(std::ceil(2 * std::numbers::pi * r / step));
  const double length = (b - a).norm();
  for (double t = 0; t <= length; t += step)
    for (int k = 0; k < around; ++k) {
      const double angle = 2 * std::numbers::pi * k / around;
      c.positions.push_back(a + t * axis + r * (std::cos(angle) * u + std::sin(angle) * v));
    }
}

/// A crown: points scattered in a ball round `centre`.
void addCrown(geom::PointCloud& c, const Vec3& centre, double radius, std::size_t n, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, radius / 2);
  for (std::size_t k = 0; k < n; ++k) c.positions.push_back(centre + Vec3(g(rng), g(rng), g(rng)));
}

/// Level ground over [-half, half]², with a slope along x, every `step`.
void addGround(geom::PointCloud& c, double half, double slope, double step) {
  for (double x = -half; x <= half; x += step)
    for (double y = -half; y <= half; y += step) c.positions.emplace_back(x, y, slope * x);
}

struct Plot {
  geom::PointCloud cloud;
  std::vector<Vec3> feet;
  std::vector<std::pair<std::size_t, std::size_t>> stemPoints;  // [from, to) of each stem's tube
};

/// Three trees 4 m apart (stems 30, 24 and 16 cm across, 8 m tall, a crown each) on ground sloping
/// by `slope`.
Plot threeTrees(double slope, bool ground) {
  Plot p;
  std::mt19937 rng(3);
  const std::vector<std::pair<Vec3, double>> trees = {{{-4, 0, 0}, 0.15}, {{0, 1, 0}, 0.12}, {{4, -1, 0}, 0.08}};
  for (const auto& [foot, r] : trees) {
    const Vec3 base(foot.x(), foot.y(), slope * foot.x());
    const std::size_t from = p.cloud.size();
    addTube(p.cloud, base, base + Vec3(0, 0, 8), r, 0.01);
    p.stemPoints.emplace_back(from, p.cloud.size());
    addCrown(p.cloud, base + Vec3(0, 0, 7), 1.0, 3000, rng);
    p.feet.push_back(base);
  }
  if (ground) addGround(p.cloud, 7.0, slope, 0.04);
  return p;
}

std::vector<std::uint32_t> groundOf(const geom::PointCloud& c) {
  return findGround(c, geom::UpAxis::Z, 0.0).points;
}

TEST(Stems, APlotsStemsAreFoundWithTheirDiametersOnLevelAndSlopingGround) {
  for (const bool ground : {true, false})
    for (const double slope : {0.0, 0.25}) {
      const Plot p = threeTrees(slope, ground);
      const std::vector<std::uint32_t> g = ground ? groundOf(p.cloud) : std::vector<std::uint32_t>{};
      if (ground) EXPECT_GT(g.size(), 10000u);
      const Stems s = findStems(p.cloud, geom::UpAxis::Z, g, 0.0);
      ASSERT_EQ(s.stems.size(), 3u) << "ground " << ground << " slope " << slope;
      EXPECT_EQ(s.trees, 3u);
      EXPECT_EQ(s.terrainFromGround, ground);
      const double diameters[] = {0.30, 0.24, 0.16};
      for (std::size_t k = 0; k < 3; ++k) {  // largest first, as the trees were made
        EXPECT_NEAR(s.stems[k].diameter, diameters[k], 0.01) << k;
        EXPECT_NEAR(s.stems[k].centre.x(), p.feet[k].x(), 0.02) << k;
        EXPECT_NEAR(s.stems[k].centre.y(), p.feet[k].y(), 0.02) << k;
        EXPECT_NEAR(s.stems[k].centre.z(), p.feet[k].z() + 1.3, 0.1) << k;  // 1.3 m above its own foot
        EXPECT_EQ(s.stems[k].tree, static_cast<std::int32_t>(k));
      }
    }
}

TEST(Stems, EachStemsPointsGoToItsTreeAndTheGroundToNone) {
  const Plot p = threeTrees(0.1, true);
  const std::vector<std::uint32_t> g = groundOf(p.cloud);
  const Stems s = findStems(p.cloud, geom::UpAxis::Z, g, 0.0);
  ASSERT_EQ(s.trees, 3u);
  const std::vector<std::int32_t> label = splitByTree(p.cloud, geom::UpAxis::Z, s, g);
  ASSERT_EQ(label.size(), p.cloud.size());
  std::vector<char> isGround(p.cloud.size(), 0);
  for (std::uint32_t i : g) isGround[i] = 1;
  for (std::size_t k = 0; k < 3; ++k) {  // every point of a stem but its foot's ring taken for ground
    std::size_t right = 0, footInGround = 0;
    for (std::size_t i = p.stemPoints[k].first; i < p.stemPoints[k].second; ++i) {
      right += label[i] == s.stems[k].tree;
      footInGround += isGround[i];
    }
    EXPECT_EQ(right + footInGround, p.stemPoints[k].second - p.stemPoints[k].first) << "stem " << k;
    EXPECT_LT(footInGround, (p.stemPoints[k].second - p.stemPoints[k].first) / 50) << "stem " << k;
  }
  for (std::uint32_t i : g) EXPECT_EQ(label[i], -1);
}

TEST(Stems, ATreeForkedBelowBreastHeightIsOneTreeOfTwoStems) {
  geom::PointCloud c;
  addTube(c, Vec3(0, 0, 0), Vec3(0, 0, 0.9), 0.2, 0.01);
  addTube(c, Vec3(0, -0.08, 0.9), Vec3(-1.5, -0.08, 8), 0.1, 0.01);
  addTube(c, Vec3(0, 0.08, 0.9), Vec3(1.5, 0.08, 8), 0.1, 0.01);
  addGround(c, 5.0, 0.0, 0.04);
  const std::vector<std::uint32_t> g = groundOf(c);
  const Stems s = findStems(c, geom::UpAxis::Z, g, 0.0);
  EXPECT_EQ(s.stems.size(), 2u);
  EXPECT_EQ(s.trees, 1u);
}

TEST(Stems, ALimbCrossingTheSliceOrRestingOnTheGroundIsNoStem) {
  geom::PointCloud c;
  addTube(c, Vec3(0, 0, 0), Vec3(0, 0, 8), 0.15, 0.01);
  addTube(c, Vec3(0.15, 0, 1.3), Vec3(3, 0, 1.3), 0.06, 0.01);        // level limb at breast height
  addTube(c, Vec3(0, 0.15, 3.0), Vec3(0, 2.5, 0.05), 0.05, 0.01);     // a limb sweeping down to the ground
  addGround(c, 5.0, 0.0, 0.04);
  const Stems s = findStems(c, geom::UpAxis::Z, groundOf(c), 0.0);
  ASSERT_EQ(s.trees, 1u);
  EXPECT_NEAR(s.stems.front().diameter, 0.30, 0.01);
  EXPECT_NEAR(s.stems.front().centre.x(), 0.0, 0.02);
}

TEST(Stems, NoStemInACrownAloneOrAThinCloud) {
  std::mt19937 rng(5);
  geom::PointCloud c;
  addCrown(c, Vec3(0, 0, 5), 2.0, 20000, rng);
  EXPECT_TRUE(findStems(c, geom::UpAxis::Z, {}, 0.0).stems.empty());
  geom::PointCloud few;
  few.positions = {Vec3(0, 0, 0), Vec3(0, 0, 1.3)};
  EXPECT_TRUE(findStems(few, geom::UpAxis::Z, {}, 0.0).stems.empty());
  const Stems none;
  EXPECT_EQ(splitByTree(c, geom::UpAxis::Z, none, {}), std::vector<std::int32_t>(c.size(), -1));
}

TEST(Stems, EitherUpAxisAndOtherUnits) {
  Plot p = threeTrees(0.0, true);
  // Y up, in decimetres.
  geom::PointCloud y;
  for (const Vec3& q : p.cloud.positions) y.positions.emplace_back(10 * q.x(), 10 * q.z(), -10 * q.y());
  StemOptions o;
  o.unitMetres = 0.1;
  const Stems s = findStems(y, geom::UpAxis::Y, findGround(y, geom::UpAxis::Y, 0.0).points, 0.0, o);
  ASSERT_EQ(s.stems.size(), 3u);
  EXPECT_NEAR(s.stems[0].diameter, 0.30, 0.01);  // metres
  EXPECT_NEAR(s.stems[0].centre.y(), 13.0, 1.0);  // 1.3 m up, in decimetres
}

TEST(Stems, BadOptionsAreRefused) {
  const Plot p = threeTrees(0.0, false);
  for (auto set : {+[](StemOptions& o) { o.unitMetres = 0; }, +[](StemOptions& o) { o.breastHeight = -1; },
                   +[](StemOptions& o) { o.maxDiameter = 0.01; }, +[](StemOptions& o) { o.minOnCircleShare = 2; },
                   +[](StemOptions& o) { o.checkOffset = 0.01; }, +[](StemOptions& o) { o.linkSpacings = NAN; }}) {
    StemOptions o;
    set(o);
    EXPECT_THROW(findStems(p.cloud, geom::UpAxis::Z, {}, 0.0, o), OptionsError);
  }
}

}  // namespace
}  // namespace treesketch::cloud
