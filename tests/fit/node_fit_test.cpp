#include "treesketch/fit/node_fit.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "fit/synthetic_cylinder.h"
#include "treesketch/util/error.h"

namespace treesketch::fit {
namespace {

using geom::Vec3;

// A vertical trunk (axis x = 1, z = -0.5, radius 0.3) with 30 % outliers around it.
struct Trunk {
  geom::PointCloud cloud;
  Vec3 axisPoint = Vec3(1.0, 0.0, -0.5);
  double radius = 0.3;
  Trunk() {
    std::mt19937_64 rng(5);
    test::CylinderSpec c;
    c.base = axisPoint;
    c.radius = radius;
    c.length = 3.0;
    c.points = 14000;
    test::addCylinder(cloud, c, rng);
    test::addOutliers(cloud, 6000, Vec3(0, 0, -1.5), Vec3(2, 3, 0.5), rng);
  }
};

sketch::NodeGeometry pointNode(const Vec3& p, const Vec3& n) {
  sketch::NodeGeometry g;
  g.hasLine = false;
  g.planePoint = p;
  g.planeNormal = n.normalized();
  return g;
}

// A screen-like node: the view ray runs along z through (x, y), the plane is horizontal.
sketch::NodeGeometry lineNode(double x, double y) {
  sketch::NodeGeometry g;
  g.hasLine = true;
  g.linePoint = Vec3(x, y, 5.0);
  g.lineDir = Vec3(0, 0, -1);
  g.planePoint = g.linePoint;
  g.planeNormal = Vec3::UnitY();
  return g;
}

TEST(FitNode, PointNodeOnATrunk) {
  Trunk t;
  CloudIndex index(t.cloud);
  sketch::SamplingParams p;
  p.sliceHalfThickness = 0.05;
  p.lineEpsilon = 0.5;
  NodeResult r = fitNode(index, pointNode(t.axisPoint + Vec3(0.05, 1.5, 0.02), Vec3::UnitY()), p);
  ASSERT_EQ(r.status, NodeStatus::Fitted) << r.reason;
  Vec3 expected = t.axisPoint + Vec3(0, 1.5, 0);
  EXPECT_LT((r.centre - expected).norm(), 0.02 * t.radius);
  EXPECT_LT(std::abs(r.radius - t.radius), 0.02 * t.radius);
  EXPECT_EQ(r.growthSteps, 0);
  EXPECT_FALSE(r.sliceComputed);  // lazy: the first fit succeeded
  // Lists in the index's storage order: compare them as sets.
  auto sorted = [](std::vector<std::uint32_t> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  const auto test = sorted(r.testIndices), inliers = sorted(r.inlierIndices);
  EXPECT_TRUE(std::includes(test.begin(), test.end(), inliers.begin(), inliers.end()));
  EXPECT_GT(r.inlierIndices.size(), 100u);
  EXPECT_GT(r.iterations, 0);
  EXPECT_TRUE(r.reason.empty());
  // The GUI's highlight: the slice contains the test points.
  auto slice = sorted(nodeSlice(index, pointNode(t.axisPoint + Vec3(0.05, 1.5, 0.02), Vec3::UnitY()), p));
  EXPECT_TRUE(std::includes(slice.begin(), slice.end(), test.begin(), test.end()));
  EXPECT_GT(slice.size(), r.testIndices.size());
}

TEST(FitNode, LineNodeAndTiltedPlane) {
  Trunk t;
  CloudIndex index(t.cloud);
  sketch::SamplingParams p;
  p.lineEpsilon = 0.4;
  NodeResult r = fitNode(index, lineNode(1.05, 2.0), p);
  ASSERT_EQ(r.status, NodeStatus::Fitted) << r.reason;
  EXPECT_LT((r.centre - Vec3(1.0, 2.0, -0.5)).norm(), 0.02 * t.radius);
  EXPECT_LT(std::abs(r.radius - t.radius), 0.02 * t.radius);
  // A slightly tilted plane (10°) cuts an ellipse whose minor radius is the trunk's.
  sketch::NodeGeometry g = lineNode(1.0, 2.0);
  g.planeNormal = Vec3(0, std::cos(0.17), std::sin(0.17));
  g.lineDir = g.planeNormal.cross(Vec3::UnitX()).normalized();
  r = fitNode(index, g, p);
  ASSERT_EQ(r.status, NodeStatus::Fitted) << r.reason;
  EXPECT_NEAR(r.radius, t.radius, 0.05 * t.radius);
}

TEST(FitNode, LineEpsilonGrowsUntilTheBranchIsFound) {
  Trunk t;
  CloudIndex index(t.cloud);
  sketch::SamplingParams p;
  p.lineEpsilon = 0.1;      // the line passes 0.55 from the axis: no trunk point within 0.1...
  p.lineEpsilonStep = 0.2;  // ...so it grows 0.1 → 0.3 → 0.5 → 0.7
  NodeResult r = fitNode(index, lineNode(1.55, 1.0), p);
  ASSERT_EQ(r.status, NodeStatus::Fitted) << r.reason;
  EXPECT_GT(r.growthSteps, 0);
  EXPECT_NEAR(r.lineEpsilon, 0.1 + 0.2 * r.growthSteps, 1e-12);
  EXPECT_TRUE(r.sliceComputed);  // computed once, at the first failure
  EXPECT_LT((r.centre - Vec3(1.0, 1.0, -0.5)).norm(), 0.02 * t.radius);
  EXPECT_LT(std::abs(r.radius - t.radius), 0.02 * t.radius);
}

TEST(FitNode, NodeInEmptySpaceIsSkippedWithAReason) {
  Trunk t;
  CloudIndex index(t.cloud);
  sketch::SamplingParams p;
  p.lineEpsilon = 0.2;
  p.lineEpsilonStep = 0.5;
  NodeResult r = fitNode(index, lineNode(1.0, 10.0), p);  // above the cloud
  EXPECT_EQ(r.status, NodeStatus::Skipped);
  EXPECT_NE(r.reason.find("no points"), std::string::npos) << r.reason;
  EXPECT_TRUE(r.sliceComputed);
  EXPECT_TRUE(r.sliceIndices.empty());
  EXPECT_EQ(r.growthSteps, 0);  // testPts == nearPts (both empty) after the first try

  // A slice of pure scattered outliers (no circle with 10 % support): growth runs until the test
  // region holds the whole slice, then the node is skipped.
  geom::PointCloud noise;
  std::mt19937_64 rng(3);
  test::addOutliers(noise, 3000, Vec3(0, 0, 0), Vec3(4, 1, 4), rng);
  CloudIndex ni(noise);
  p.sliceHalfThickness = 0.5;
  r = fitNode(ni, lineNode(2.0, 0.5), p);
  EXPECT_EQ(r.status, NodeStatus::Skipped);
  EXPECT_NE(r.reason.find("no circle"), std::string::npos) << r.reason;
  EXPECT_GT(r.growthSteps, 0);
  EXPECT_EQ(r.testIndices.size(), r.sliceIndices.size());
}

TEST(FitNode, PerNodeGrowthCap) {
  Trunk t;
  CloudIndex index(t.cloud);
  sketch::SamplingParams p;
  p.lineEpsilon = 0.1;      // as LineEpsilonGrowsUntilTheBranchIsFound: needs a few steps...
  p.lineEpsilonStep = 0.2;
  p.maxGrowthSteps = 1;     // ...but may take only one
  NodeResult r = fitNode(index, lineNode(1.55, 1.0), p);
  EXPECT_EQ(r.status, NodeStatus::Skipped);
  EXPECT_EQ(r.growthSteps, 1);
  EXPECT_NE(r.reason.find("growth cap reached"), std::string::npos) << r.reason;
  p.maxGrowthSteps = -1;    // unlimited again: it fits
  EXPECT_EQ(fitNode(index, lineNode(1.55, 1.0), p).status, NodeStatus::Fitted);
}

TEST(FitNode, ScreenNodesWithoutGrowthKeepToTheirFirstTestRegion) {
  Trunk t;
  CloudIndex index(t.cloud);
  sketch::SamplingParams p;
  p.lineEpsilon = 0.1;  // the line passes 0.55 from the axis: the trunk is found only after growing
  p.lineEpsilonStep = 0.2;
  NodeFitOptions o;
  o.growScreenNodes = false;
  NodeResult r = fitNode(index, lineNode(1.55, 1.0), p, o);
  EXPECT_EQ(r.status, NodeStatus::Skipped);
  EXPECT_EQ(r.growthSteps, 0);
  EXPECT_FALSE(r.reason.empty());
  // A line through the trunk with a region wide enough for the trunk still fits in it.
  sketch::SamplingParams wide = p;
  wide.lineEpsilon = 0.4;
  r = fitNode(index, lineNode(1.05, 1.0), wide, o);
  EXPECT_EQ(r.status, NodeStatus::Fitted) << r.reason;
  EXPECT_EQ(r.growthSteps, 0);
  // Point nodes still grow (their own cap decides).
  sketch::SamplingParams pp = p;
  pp.lineEpsilon = 0.05;
  r = fitNode(index, pointNode(Vec3(1.0, 1.0, -0.05), Vec3::UnitY()), pp, o);
  EXPECT_EQ(r.status, NodeStatus::Fitted) << r.reason;
  EXPECT_GT(r.growthSteps, 0);
}

TEST(FitNode, DisabledNodesAreNotFitted) {
  Trunk t;
  CloudIndex index(t.cloud);
  sketch::SamplingParams p;
  p.enabled = false;
  NodeResult r = fitNode(index, lineNode(1.0, 1.0), p);
  EXPECT_EQ(r.status, NodeStatus::Disabled);
  EXPECT_TRUE(r.testIndices.empty());
  EXPECT_EQ(r.iterations, 0);
}

TEST(FitNode, BruteForceAndKeepSliceAgreeWithTheIndex) {
  Trunk t;
  CloudIndex index(t.cloud);
  sketch::SamplingParams p;
  NodeFitOptions fast, brute, keep;
  brute.bruteForce = true;
  keep.keepSlice = true;
  auto g = lineNode(1.1, 0.7);
  NodeResult a = fitNode(index, g, p, fast), b = fitNode(index, g, p, brute), c = fitNode(index, g, p, keep);
  ASSERT_EQ(a.status, NodeStatus::Fitted);
  EXPECT_EQ(a.testIndices, b.testIndices);
  EXPECT_EQ(a.inlierIndices, b.inlierIndices);
  EXPECT_EQ(a.centre, b.centre);
  EXPECT_EQ(a.radius, c.radius);
  EXPECT_TRUE(b.sliceComputed);
  EXPECT_TRUE(c.sliceComputed);
  EXPECT_EQ(b.sliceIndices, c.sliceIndices);
  EXPECT_EQ(c.sliceIndices, nodeSlice(index, g, p));
}

TEST(FitNode, SanityRuleRejectsCirclesCentredOutsideTheTestRegion) {
  // A wide trunk (r = 1): a line 0.9 from the axis with lineEpsilon 0.3 sees only an arc of the
  // near surface whose centre is 0.9 away: the node must not claim that circle.
  geom::PointCloud cloud;
  std::mt19937_64 rng(8);
  test::CylinderSpec c;
  c.radius = 1.0;
  c.points = 20000;
  c.noise = 0.002;
  test::addCylinder(cloud, c, rng);
  CloudIndex index(cloud);
  sketch::SamplingParams p;
  p.lineEpsilon = 0.3;
  p.lineEpsilonStep = 0.3;
  NodeResult r = fitNode(index, lineNode(0.9, 1.0), p);
  ASSERT_EQ(r.status, NodeStatus::Fitted) << r.reason;
  EXPECT_GT(r.growthSteps, 0);  // not at 0.3 ...
  EXPECT_LE(std::abs(r.centre.x() - 0.9), r.lineEpsilon + 1e-9);  // ... only once the centre is in range
  EXPECT_NEAR(r.radius, 1.0, 0.02);
}

TEST(FitNode, InvalidInputsThrow) {
  Trunk t;
  CloudIndex index(t.cloud);
  sketch::SamplingParams p;
  p.sliceHalfThickness = 0;
  EXPECT_THROW(fitNode(index, lineNode(1, 1), p), OptionsError);
  p = {};
  p.lineEpsilonStep = -1;
  EXPECT_THROW(fitNode(index, lineNode(1, 1), p), OptionsError);
  p = {};
  p.lineEpsilon = std::numeric_limits<double>::infinity();
  EXPECT_THROW(fitNode(index, lineNode(1, 1), p), OptionsError);
  p = {};
  auto g = lineNode(1, 1);
  g.lineDir = Vec3::Zero();
  EXPECT_THROW(fitNode(index, g, p), OptionsError);
  EXPECT_THROW(fitNode(index, pointNode(Vec3(1, 1, 1), Vec3::Zero()), p), OptionsError);
}

}  // namespace
}  // namespace treesketch::fit
