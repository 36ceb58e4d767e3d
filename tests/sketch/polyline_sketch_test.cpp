#include "treesketch/sketch/polyline_sketch.h"

#include <gtest/gtest.h>

#include <cmath>

#include "treesketch/util/error.h"

namespace treesketch::sketch {
namespace {

using geom::Vec2;
using geom::Vec3;

/// Trunk: straight up 0..10 (vertices every 2). Branch 1 leaves trunk vertex 3 (height 6)
/// towards +x and up; branch 2 leaves branch 1's vertex 1.
std::vector<BranchPolyline> tree() {
  BranchPolyline trunk;
  for (int i = 0; i <= 5; ++i) trunk.points.emplace_back(0, 2.0 * i, 0);
  BranchPolyline b1;
  b1.parent = 0;
  b1.parentVertex = 3;
  b1.points = {Vec3(0, 6, 0), Vec3(2, 7, 0), Vec3(4, 8, 0)};
  BranchPolyline b2;
  b2.parent = 1;
  b2.parentVertex = 1;
  b2.points = {Vec3(2, 7, 0), Vec3(2, 9, 0.5)};
  return {trunk, b1, b2};
}

geom::Camera camera(bool ortho) {
  geom::BBox box;
  box.add(Vec3(-1, 0, -1));
  box.add(Vec3(5, 10, 1));
  return geom::presetCamera(geom::PresetView::Front, box, geom::UpAxis::Y, {0, 0, 800, 800}, ortho);
}

double distanceToPolyline(const Vec3& p, const std::vector<Vec3>& pts) {
  double best = 1e300;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    Vec3 d = pts[i] - pts[i - 1];
    double t = std::clamp((p - pts[i - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (pts[i - 1] + t * d - p).norm());
  }
  return best;
}

/// Distance between the node's view line and the polyline: per segment, the squared distance of
/// its points to the line is a quadratic in the segment parameter; minimize it on [0, 1].
double lineToPolyline(const NodeGeometry& g, const std::vector<Vec3>& pts) {
  auto perp = [&](const Vec3& v) { return Vec3(v - g.lineDir * g.lineDir.dot(v)); };
  double best = 1e300;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    Vec3 a = perp(pts[i - 1] - g.linePoint), b = perp(pts[i] - pts[i - 1]);
    double t = b.squaredNorm() > 0 ? std::clamp(-a.dot(b) / b.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * b).norm());
  }
  return best;
}

TEST(PolylineSketch, ExactProjectionsLieOnTheBranches) {
  PolylineSketchOptions o;
  o.nodeSpacing = 1.0;
  std::vector<BranchPolyline> br = tree();
  Sketch sk = sketchFromPolylines(br, camera(false), o);
  ASSERT_NO_THROW(sk.validate());
  // Trunk 10 → root + 10 nodes; branch 1 length 2·√5 ≈ 4.47 → 4; branch 2 length √4.25 ≈ 2.06 → 2.
  EXPECT_EQ(sk.size(), 17u);
  NodeId root = sk.root();
  EXPECT_NEAR((camera(false).unproject(sk.node(root).screen, camera(false).project(Vec3(0, 0, 0)).z()) - Vec3(0, 0, 0)).norm(),
              0.0, 1e-6);
  for (NodeId id : sk.ids()) {
    double d = 1e300;
    for (const auto& b : br) d = std::min(d, lineToPolyline(sk.geometry(id), b.points));
    EXPECT_LT(d, 1e-6) << "node " << id;
  }
  // Hierarchy: a chain on the trunk, and branch 1's first node hangs under the trunk node nearest
  // to height 6 (arc lengths 0, 0.5, 1.5, ..., 9.5: the nodes at 5.5 and 6.5 tie; the first wins).
  std::vector<NodeId> order = sk.topologicalOrder();
  EXPECT_EQ(order.front(), root);
  int branching = 0;
  for (NodeId id : sk.ids()) branching += sk.node(id).children.size() > 1;
  EXPECT_EQ(branching, 2);
}

TEST(PolylineSketch, NoisyScreenPositionsReprojectWithinTheNoise) {
  PolylineSketchOptions o;
  o.nodeCount = 30;
  o.pixelNoise = 2.0;
  o.seed = 42;
  std::vector<BranchPolyline> br = tree();
  geom::Camera cam = camera(true);
  Sketch sk = sketchFromPolylines(br, cam, o);
  Sketch exact = sketchFromPolylines(br, cam, [&] { auto e = o; e.pixelNoise = 0; return e; }());
  ASSERT_EQ(sk.ids(), exact.ids());
  // World size of a pixel (orthographic: constant).
  double pixel = (cam.unproject(Vec2(0, 1), 0.5) - cam.unproject(Vec2(0, 0), 0.5)).norm();
  double sumSq = 0;
  for (NodeId id : sk.ids()) {
    Vec2 offset = sk.node(id).screen - exact.node(id).screen;
    sumSq += offset.squaredNorm();
    EXPECT_LT(offset.norm(), 5 * 2.0 * std::sqrt(2.0));  // 5 sigma
    double d = 1e300;
    for (const auto& b : br) d = std::min(d, lineToPolyline(sk.geometry(id), b.points));
    EXPECT_LT(d, 5 * 2.0 * std::sqrt(2.0) * pixel) << "node " << id;
  }
  double rms = std::sqrt(sumSq / (2.0 * sk.size()));
  EXPECT_GT(rms, 1.0);  // the noise is there, about 2 px per axis
  EXPECT_LT(rms, 3.0);
  // Same seed, same sketch; another seed, another sketch.
  Sketch again = sketchFromPolylines(br, cam, o);
  for (NodeId id : sk.ids()) EXPECT_EQ(sk.node(id).screen, again.node(id).screen);
  o.seed = 43;
  Sketch other = sketchFromPolylines(br, cam, o);
  EXPECT_NE(sk.node(sk.root()).screen, other.node(other.root()).screen);
}

TEST(PolylineSketch, PointNodesFollowTangents) {
  PolylineSketchOptions o;
  o.nodeSpacing = 1.0;
  SamplingParams p;
  p.lineEpsilon = 0.7;
  o.params = p;
  std::vector<BranchPolyline> br = tree();
  Sketch sk = pointNodesFromPolylines(br, o);
  ASSERT_NO_THROW(sk.validate());
  EXPECT_EQ(sk.size(), 17u);
  EXPECT_TRUE(sk.cameras().empty());
  EXPECT_EQ(sk.node(sk.root()).point, Vec3(0, 0, 0));
  for (NodeId id : sk.ids()) {
    const Node& n = sk.node(id);
    EXPECT_FALSE(n.isScreenNode());
    EXPECT_EQ(n.params.lineEpsilon, 0.7);
    double d = 1e300;
    for (const auto& b : br) d = std::min(d, distanceToPolyline(n.point, b.points));
    EXPECT_LT(d, 1e-12);
    EXPECT_NEAR(n.normal.norm(), 1.0, 1e-12);
  }
  // Trunk nodes point up; branch 1's nodes along (2,1,0).
  NodeId second = sk.node(sk.root()).children.front();
  EXPECT_NEAR((sk.node(second).normal - Vec3(0, 1, 0)).norm(), 0.0, 1e-12);
  for (NodeId id : sk.ids())
    if (sk.node(id).point.x() > 0.1 && sk.node(id).point.x() < 3.9 && std::abs(sk.node(id).point.z()) < 1e-12)
      EXPECT_NEAR((sk.node(id).normal - Vec3(2, 1, 0).normalized()).norm(), 0.0, 1e-12) << id;
}

TEST(PolylineSketch, RejectsBadInput) {
  PolylineSketchOptions o;
  geom::Camera cam = camera(false);
  EXPECT_THROW(sketchFromPolylines({}, cam, o), OptionsError);
  auto br = tree();
  br[1].parent = -1;  // two trunks
  EXPECT_THROW(sketchFromPolylines(br, cam, o), OptionsError);
  br = tree();
  br[1].parent = 2;  // 1 -> 2 -> 1
  EXPECT_THROW(sketchFromPolylines(br, cam, o), OptionsError);
  br = tree();
  br[2].parent = 7;
  EXPECT_THROW(pointNodesFromPolylines(br, o), OptionsError);
  br = tree();
  br[1].parentVertex = 6;
  EXPECT_THROW(sketchFromPolylines(br, cam, o), OptionsError);
  br = tree();
  br[0].points = {Vec3(0, 0, 0), Vec3(0, 0, 0)};  // zero-length trunk
  EXPECT_THROW(sketchFromPolylines(br, cam, o), OptionsError);
  br = tree();
  br[2].points[1].x() = NAN;
  EXPECT_THROW(sketchFromPolylines(br, cam, o), OptionsError);
  br = tree();
  br[2].points.clear();
  EXPECT_THROW(sketchFromPolylines(br, cam, o), OptionsError);
  PolylineSketchOptions bad = o;
  bad.nodeCount = 0;
  EXPECT_THROW(sketchFromPolylines(tree(), cam, bad), OptionsError);
  bad = o;
  bad.pixelNoise = -1;
  EXPECT_THROW(sketchFromPolylines(tree(), cam, bad), OptionsError);
  bad = o;
  bad.params.sliceHalfThickness = 0;
  EXPECT_THROW(pointNodesFromPolylines(tree(), bad), OptionsError);
  geom::Camera behind = cam;
  behind.view = geom::lookAt(Vec3(0, 5, -50), Vec3(0, 5, -100), Vec3(0, 1, 0));
  EXPECT_THROW(sketchFromPolylines(tree(), behind, o), OptionsError);
}

TEST(PolylineSketch, ZeroLengthBranchPassesItsChildrenUp) {
  auto br = tree();
  br[1].points = {Vec3(0, 6, 0)};  // a branch of one vertex
  br[2].parentVertex = 0;
  PolylineSketchOptions o;
  o.nodeSpacing = 1.0;
  Sketch sk = pointNodesFromPolylines(br, o);
  ASSERT_NO_THROW(sk.validate());
  EXPECT_EQ(sk.size(), 11u + 2u);
}

}  // namespace
}  // namespace treesketch::sketch
