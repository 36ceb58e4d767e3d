// The depth choice of screen-node fits: a view ray that crosses a thin branch in front
// of a thicker one takes the front branch (what the person sees) or the one continuing the
// parent, never the best-supported circle silently.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fit/synthetic_cylinder.h"
#include "treesketch/fit/node_fit.h"

namespace treesketch::fit {
namespace {

using geom::Vec3;

/// Two branches along X, lined up in depth for a camera looking down -Z: a thin one (radius
/// 0.08) at z = 0 and a thicker, denser one (radius 0.15) at z = -1.
struct TwoBranches {
  geom::PointCloud cloud;
  TwoBranches() {
    std::mt19937_64 rng(11);
    test::addCylinder(cloud, {Vec3(-1, 0, 0), Vec3::UnitX(), 0.08, 3.0, 6000, 0.002}, rng);
    test::addCylinder(cloud, {Vec3(-1, 0, -1), Vec3::UnitX(), 0.15, 3.0, 20000, 0.002}, rng);
  }
};

/// The screen node's line: through (0.5, 0, 5) down -Z; its plane contains it, normal along X.
sketch::NodeGeometry rayThroughBoth() {
  sketch::NodeGeometry g;
  g.hasLine = true;
  g.linePoint = Vec3(0.5, 0, 5);
  g.lineDir = Vec3(0, 0, -1);
  g.planePoint = g.linePoint;
  g.planeNormal = Vec3::UnitX();
  return g;
}

sketch::SamplingParams params() {
  sketch::SamplingParams p;
  p.sliceHalfThickness = 0.02;
  p.lineEpsilon = 0.25;
  p.lineEpsilonStep = 0.25;
  return p;
}

TEST(DepthChoice, ThesisFitTakesTheBestSupportedCircleBehind) {
  TwoBranches t;
  CloudIndex index(t.cloud);
  NodeResult r = fitNode(index, rayThroughBoth(), params());
  ASSERT_EQ(r.status, NodeStatus::Fitted);
  EXPECT_NEAR(r.centre.z(), -1.0, 0.05);  // the failure the depth choice is for
  EXPECT_TRUE(std::isnan(r.depth));
}

TEST(DepthChoice, WithoutAParentTheFrontSurfaceIsTaken) {
  TwoBranches t;
  CloudIndex index(t.cloud);
  NodeFitOptions o;
  o.chooseDepth = true;
  NodeResult r = fitNode(index, rayThroughBoth(), params(), o);
  ASSERT_EQ(r.status, NodeStatus::Fitted);
  EXPECT_NEAR(r.centre.z(), 0.0, 0.03);
  EXPECT_NEAR(r.radius, 0.08, 0.01);
  EXPECT_NEAR(r.depth, 5.0, 0.03);  // along the ray from its near point
  EXPECT_EQ(r.depthHypotheses, 2);
  EXPECT_FALSE(r.depthJump);
  EXPECT_FALSE(r.warning.empty());  // two surfaces had a circle: said
}

TEST(DepthChoice, TheParentsDepthWinsAndItsRadiusBoundsTheCircle) {
  TwoBranches t;
  CloudIndex index(t.cloud);
  NodeFitOptions o;
  o.chooseDepth = true;
  FitPrior behind{Vec3(0.3, 0, -1.0), 0.15};
  NodeResult r = fitNode(index, rayThroughBoth(), params(), o, &behind);
  ASSERT_EQ(r.status, NodeStatus::Fitted);
  EXPECT_NEAR(r.centre.z(), -1.0, 0.05);
  EXPECT_FALSE(r.depthJump);
  // A thin parent behind: the thick circle there is refused (more than twice the parent), and
  // the front one lies farther from the parent's depth than the branch can have gone: no jump,
  // the node is skipped and says why.
  FitPrior thinBehind{Vec3(0.3, 0, -1.0), 0.04};
  r = fitNode(index, rayThroughBoth(), params(), o, &thinBehind);
  EXPECT_EQ(r.status, NodeStatus::Skipped);
  EXPECT_NE(r.reason.find("parent's depth"), std::string::npos) << r.reason;
  // A parent far to the side, between the two depths: the nearer circle (front) is taken, and
  // flagged as a jump (0.45 from the parent's depth, more than 3 of its radii).
  FitPrior between{Vec3(-1.0, 0, -0.45), 0.05};
  r = fitNode(index, rayThroughBoth(), params(), o, &between);
  ASSERT_EQ(r.status, NodeStatus::Fitted) << r.reason;
  EXPECT_NEAR(r.centre.z(), 0.0, 0.03);
  EXPECT_TRUE(r.depthJump);
  EXPECT_NE(r.warning.find("parent"), std::string::npos);
}

}  // namespace
}  // namespace treesketch::fit
