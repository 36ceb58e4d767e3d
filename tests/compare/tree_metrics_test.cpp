// Tree metrics on analytic models: a cone split into frustums gives its volume, DBH and taper; a
// stem with branches gives its branch counts per order; a scanned cone's slice gives its DBH.
#include "treesketch/compare/tree_metrics.h"

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <numbers>
#include <random>

#include "treesketch/util/error.h"

namespace treesketch::compare {
namespace {

using geom::CylinderModel;
using geom::ModelCylinder;
using geom::Vec3;

using test::modelPiece;

constexpr double kR0 = 0.2, kH = 10.0;  // cone: base radius 0.2 m, height 10 m, along z from z0

/// The cone as `n` frustums (exact: a cone is piecewise linear in radius), base at z0.
CylinderModel cone(int n, double z0 = 5.0) {
  CylinderModel m;
  for (int i = 0; i < n; ++i) {
    const double a = kH * i / n, b = kH * (i + 1) / n;
    m.cylinders.push_back(modelPiece({1, 2, z0 + a}, {1, 2, z0 + b}, kR0 * (1 - a / kH), kR0 * (1 - b / kH), i - 1));
  }
  return m;
}

TEST(TreeMetrics, ConeGivesVolumeDbhTaperHeight) {
  const TreeMetrics m = treeMetrics(cone(20), geom::UpAxis::Z);
  EXPECT_NEAR(m.figures.volume, std::numbers::pi * kR0 * kR0 * kH / 3, 1e-9);
  EXPECT_NEAR(m.stemVolume, m.figures.volume, 1e-12);
  EXPECT_EQ(m.branchVolume, 0);
  EXPECT_NEAR(m.height, kH, 1e-9);
  EXPECT_NEAR(m.figures.trunkDiameter, 2 * kR0 * (1 - 1.3 / kH), 1e-9);
  ASSERT_EQ(m.taper.size(), 11u);  // 0, 1, ... 10 m (the tip, diameter 0)
  for (const auto& t : m.taper) EXPECT_NEAR(t.diameter, 2 * kR0 * (1 - t.height / kH), 1e-9) << t.height;
  EXPECT_EQ(m.branches, 0u);
  ASSERT_EQ(m.orders.size(), 1u);
  EXPECT_EQ(m.orders[0].branches, 1u);
  EXPECT_NEAR(m.orders[0].length, kH, 1e-9);
  // Crown: the base disc is the widest: area π r0² (the 4-point disc outline gives a square of
  // diagonal 2 r0: area 2 r0²).
  EXPECT_NEAR(m.crownArea, 2 * kR0 * kR0, 1e-9);
  EXPECT_NEAR(m.crownSpread, 2 * kR0, 1e-9);
}

TEST(TreeMetrics, UnitsScaleEveryFigure) {
  TreeMetricsOptions o;
  o.unitMetres = 0.1;  // the model is in decimetres: the cone is 1 m tall
  const TreeMetrics m = treeMetrics(cone(20), geom::UpAxis::Z, o);
  EXPECT_NEAR(m.height, 1.0, 1e-9);
  EXPECT_NEAR(m.figures.volume, std::numbers::pi * kR0 * kR0 * kH / 3 * 1e-3, 1e-12);
  EXPECT_TRUE(std::isnan(m.figures.trunkDiameter));  // 1.3 m is above the 1 m tree
  EXPECT_EQ(m.taper.size(), 2u);                     // 0 m and the tip at 1 m
}

TEST(TreeMetrics, BranchOrdersDerivedFromTheLinks) {
  // Stem of 3 pieces; two branches off piece 0 and 1; a sub-branch off the first branch.
  CylinderModel m;
  m.cylinders.push_back(modelPiece({0, 0, 0}, {0, 0, 1}, 0.2, 0.18, -1));    // 0 stem
  m.cylinders.push_back(modelPiece({0, 0, 1}, {0, 0, 2}, 0.18, 0.15, 0));    // 1 stem
  m.cylinders.push_back(modelPiece({0, 0, 2}, {0, 0, 3}, 0.15, 0.1, 1));     // 2 stem
  m.cylinders.push_back(modelPiece({0, 0, 1}, {1, 0, 1.5}, 0.05, 0.04, 0));  // 3 branch A
  m.cylinders.push_back(modelPiece({1, 0, 1.5}, {2, 0, 2}, 0.04, 0.03, 3));  // 4 branch A
  m.cylinders.push_back(modelPiece({0, 0, 2}, {0, 1, 2.5}, 0.05, 0.04, 1));  // 5 branch B
  m.cylinders.push_back(modelPiece({1, 0, 1.5}, {1, 1, 2}, 0.02, 0.01, 3));  // 6 sub-branch of A
  const geom::BranchStructure b = geom::branchStructure(m, geom::UpAxis::Z);
  EXPECT_EQ(b.order, (std::vector<std::int32_t>{0, 0, 0, 1, 1, 1, 2}));
  EXPECT_EQ(b.extension[0], 1);
  EXPECT_EQ(b.extension[3], 4);
  EXPECT_EQ(b.branches(), 4u);
  const TreeMetrics t = treeMetrics(m, geom::UpAxis::Z);
  ASSERT_EQ(t.orders.size(), 3u);
  EXPECT_EQ(t.orders[0].branches, 1u);
  EXPECT_EQ(t.orders[1].branches, 2u);
  EXPECT_EQ(t.orders[2].branches, 1u);
  EXPECT_EQ(t.branches, 3u);
  EXPECT_NEAR(t.stemLength, 3.0, 1e-12);
  EXPECT_NEAR(t.orders[1].length, 2 * std::sqrt(1.25) + std::sqrt(1.25), 1e-12);
  EXPECT_NEAR(t.stemVolume + t.branchVolume, t.figures.volume, 1e-12);
}

TEST(TreeMetrics, GivenOrdersWin) {
  CylinderModel m;
  m.cylinders.push_back(modelPiece({0, 0, 0}, {0, 0, 1}, 0.2, 0.2, -1, 0));
  m.cylinders.push_back(modelPiece({0, 0, 1}, {0, 0, 2}, 0.05, 0.05, 0, 0));  // thin, but the stem by its order
  m.cylinders.push_back(modelPiece({0, 0, 1}, {1, 0, 1}, 0.1, 0.1, 0, 1));
  const geom::BranchStructure b = geom::branchStructure(m, geom::UpAxis::Z);
  EXPECT_EQ(b.extension[0], 1);
  EXPECT_EQ(b.order, (std::vector<std::int32_t>{0, 0, 1}));
}

TEST(TreeMetrics, CycleAndBadParentThrow) {
  CylinderModel m;
  m.cylinders.push_back(modelPiece({0, 0, 0}, {0, 0, 1}, 0.1, 0.1, 1));
  m.cylinders.push_back(modelPiece({0, 0, 1}, {0, 0, 2}, 0.1, 0.1, 0));
  EXPECT_THROW(geom::branchStructure(m, geom::UpAxis::Z), OptionsError);
  m.cylinders[0].parent = 7;
  EXPECT_THROW(treeMetrics(m, geom::UpAxis::Z), OptionsError);
}

TEST(TreeMetrics, EmptyModelAndBadOptions) {
  const TreeMetrics m = treeMetrics({}, geom::UpAxis::Z);
  EXPECT_TRUE(std::isnan(m.height));
  EXPECT_EQ(m.figures.volume, 0);
  EXPECT_TRUE(m.taper.empty());
  TreeMetricsOptions o;
  o.unitMetres = 0;
  EXPECT_THROW(treeMetrics(cone(4), geom::UpAxis::Z, o), OptionsError);
  o = {};
  o.taperStep = 0;
  EXPECT_THROW(treeMetrics(cone(4), geom::UpAxis::Z, o), OptionsError);
}

/// Points on the cone's side (one third of it hidden, as a single scan sees a stem), noise σ.
geom::PointCloud scannedCone(double sigma, double z0, geom::UpAxis up) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> h(0, kH), a(0, 1.5 * std::numbers::pi);
  std::normal_distribution<double> noise(0, sigma);
  geom::PointCloud c;
  for (int i = 0; i < 60000; ++i) {
    const double z = h(rng), t = a(rng), r = kR0 * (1 - z / kH) + noise(rng);
    const Vec3 p(1 + r * std::cos(t), 2 + r * std::sin(t), z0 + z);
    c.positions.push_back(up == geom::UpAxis::Z ? p : Vec3(p.x(), p.z(), p.y()));
  }
  c.positions.push_back(up == geom::UpAxis::Z ? Vec3(1, 2, z0) : Vec3(1, z0, 2));  // the ground at the base
  return c;
}

TEST(TreeMetrics, CloudSliceGivesDbh) {
  const geom::PointCloud cloud = scannedCone(0.003, 5.0, geom::UpAxis::Z);
  const TreeMetrics m = treeMetrics(cone(20), geom::UpAxis::Z, {}, &cloud);
  ASSERT_TRUE(m.cloudDbh.ok) << m.cloudDbh.reason;
  EXPECT_NEAR(m.cloudDbh.diameter, 2 * kR0 * (1 - 1.3 / kH), 0.004);
  EXPECT_GT(m.cloudDbh.slicePoints, 100u);
  EXPECT_GT(m.cloudDbh.inliers, m.cloudDbh.slicePoints * 8 / 10);
  EXPECT_LT(m.cloudDbh.rms, 0.006);
  EXPECT_NEAR(m.cloudHeight, kH, 0.01);
  EXPECT_NEAR(m.cloudCrownDiameter, 2 * kR0, 0.02);
}

TEST(TreeMetrics, CloudSliceYUp) {
  const geom::PointCloud cloud = scannedCone(0.003, -3.0, geom::UpAxis::Y);
  CylinderModel model = cone(20, -3.0);
  for (auto& c : model.cylinders) {
    c.start = Vec3(c.start.x(), c.start.z(), c.start.y());
    c.end = Vec3(c.end.x(), c.end.z(), c.end.y());
  }
  const TreeMetrics m = treeMetrics(model, geom::UpAxis::Y, {}, &cloud);
  ASSERT_TRUE(m.cloudDbh.ok) << m.cloudDbh.reason;
  EXPECT_NEAR(m.cloudDbh.diameter, m.figures.trunkDiameter, 0.004);
}

TEST(TreeMetrics, CloudWithoutStemSaysWhy) {
  geom::PointCloud cloud;
  for (int i = 0; i < 10; ++i) cloud.positions.emplace_back(i, 0, 0);  // all on the ground
  const TreeMetrics m = treeMetrics(cone(4), geom::UpAxis::Z, {}, &cloud);
  EXPECT_FALSE(m.cloudDbh.ok);
  EXPECT_FALSE(m.cloudDbh.reason.empty());
  const nlohmann::json j = toJson(m);
  EXPECT_TRUE(j["cloud"]["dbh"]["diameterM"].is_null());
  EXPECT_NE(metricsTable(m).find("DBH (cloud slice)"), std::string::npos);
}

TEST(ConvexHull, SquareAndDegenerate) {
  double a = 0, s = 0;
  convexHullFigures({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}}, &a, &s);
  EXPECT_NEAR(a, 1, 1e-12);
  EXPECT_NEAR(s, std::sqrt(2.0), 1e-12);
  convexHullFigures({{0, 0}, {2, 0}, {1, 0}}, &a, &s);
  EXPECT_EQ(a, 0);
  EXPECT_NEAR(s, 2, 1e-12);
  convexHullFigures({}, &a, &s);
  EXPECT_EQ(a, 0);
}

// A crown far from the origin (projected coordinates, or a cloud moved 1e9): the same area and
// spread as at the origin. The area's cross products of raw coordinates (1e18 at 1e9) rounded by
// 128 and gave 64 m² for a 7 m² crown.
TEST(ConvexHull, FarFromTheOriginTheSameFigures) {
  std::vector<geom::Vec2> crown;
  for (int k = 0; k < 40; ++k) crown.push_back({1.5 * std::cos(0.157 * k), 1.2 * std::sin(0.157 * k)});
  double a0 = 0, s0 = 0;
  convexHullFigures(crown, &a0, &s0);
  ASSERT_GT(a0, 5);
  for (double far : {5e5, 1e6, 1e9, 1e12}) {
    std::vector<geom::Vec2> moved = crown;
    for (auto& p : moved) p += geom::Vec2(far, -far);
    double a = 0, s = 0;
    convexHullFigures(moved, &a, &s);
    EXPECT_NEAR(a, a0, 1e-3 * a0) << far;
    EXPECT_NEAR(s, s0, 1e-3 * s0) << far;
  }
}

}  // namespace
}  // namespace treesketch::compare
