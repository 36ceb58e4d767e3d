#include "treesketch/sketch/sketch.h"

#include <gtest/gtest.h>

#include <cmath>

#include "treesketch/util/error.h"

namespace treesketch::sketch {
namespace {

using geom::Vec2;
using geom::Vec3;

geom::BBox trunkBox() {
  geom::BBox box;
  box.add(Vec3(-0.5, 0, -0.5));
  box.add(Vec3(0.5, 10, 0.5));
  return box;
}

geom::Camera frontCamera(bool ortho, geom::Viewport vp = {0, 0, 800, 600}) {
  return geom::presetCamera(geom::PresetView::Front, trunkBox(), geom::UpAxis::Y, vp, ortho);
}

Vec2 screenOf(const geom::Camera& cam, const Vec3& p) { return cam.project(p).head<2>(); }

double distanceToLine(const Vec3& p, const NodeGeometry& g) {
  Vec3 r = p - g.linePoint;
  return (r - g.lineDir * g.lineDir.dot(r)).norm();
}

double degrees(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(std::abs(a.normalized().dot(b.normalized())), 0.0, 1.0)) * 180.0 / M_PI;
}

TEST(SketchGeometry, RootAtEyeHeightHasHorizontalSlice) {
  Sketch sk;
  geom::Camera cam = frontCamera(false);
  int c = sk.addCamera(cam);
  // The front camera looks at the box centre (height 5): a node there has a horizontal ray.
  NodeId root = sk.addScreenNode(kNoNode, c, screenOf(cam, Vec3(0, 5, 0)));
  NodeGeometry g = sk.geometry(root);
  EXPECT_TRUE(g.hasLine);
  EXPECT_NEAR((g.planeNormal - Vec3(0, 1, 0)).norm(), 0.0, 1e-6);  // oriented up
  EXPECT_NEAR(g.planeNormal.norm(), 1.0, 1e-12);
}

TEST(SketchGeometry, RootAtTrunkBaseIsNearlyHorizontalAndContainsItsRay) {
  Sketch sk;
  geom::Camera cam = frontCamera(false);
  NodeId root = sk.addScreenNode(kNoNode, sk.addCamera(cam), screenOf(cam, Vec3(0, 0.5, 0)));
  NodeGeometry g = sk.geometry(root);
  // Perspective: the plane contains the (downward) view ray, so it tilts by the ray's elevation.
  double elevation = std::asin(std::abs(g.lineDir.y())) * 180.0 / M_PI;
  EXPECT_GT(elevation, 1.0);
  EXPECT_NEAR(degrees(g.planeNormal, Vec3(0, 1, 0)), elevation, 1e-6);
  EXPECT_LT(elevation, 20.0);
  EXPECT_GT(g.planeNormal.y(), 0.0);
  EXPECT_NEAR(g.planeNormal.dot(g.lineDir), 0.0, 1e-12);
}

TEST(SketchGeometry, LinePassesThroughUnprojectedPointsAndTheDrawnPoint) {
  Sketch sk;
  geom::Camera cam = frontCamera(false);
  Vec3 target(0.2, 3.0, 0.1);
  Vec2 s = screenOf(cam, target);
  NodeId root = sk.addScreenNode(kNoNode, sk.addCamera(cam), s);
  NodeGeometry g = sk.geometry(root);
  Vec3 nearP = cam.unproject(s, 0.0), farP = cam.unproject(s, 1.0);
  EXPECT_NEAR((g.linePoint - nearP).norm(), 0.0, 1e-12);
  EXPECT_NEAR(distanceToLine(farP, g), 0.0, 1e-6);
  EXPECT_NEAR(distanceToLine(target, g), 0.0, 1e-6);
  EXPECT_NEAR(g.lineDir.norm(), 1.0, 1e-12);
  EXPECT_GT(g.lineDir.dot(farP - nearP), 0.0);
  EXPECT_EQ(g.planePoint, g.linePoint);
}

TEST(SketchGeometry, ChildDrawnStraightUpGetsVerticalNormal) {
  Sketch sk;
  geom::Camera cam = frontCamera(false);
  int c = sk.addCamera(cam);
  NodeId root = sk.addScreenNode(kNoNode, c, screenOf(cam, Vec3(0, 1, 0)));
  NodeId child = sk.addScreenNode(root, c, screenOf(cam, Vec3(0, 4, 0)));
  NodeGeometry g = sk.geometry(child);
  EXPECT_LT(degrees(g.planeNormal, Vec3(0, 1, 0)), 10.0);
  EXPECT_GT(g.planeNormal.y(), 0.0);  // from the parent towards the child
  EXPECT_NEAR(g.planeNormal.dot(g.lineDir), 0.0, 1e-12);
  // A child drawn to the right: the normal follows the stroke.
  NodeId right = sk.addScreenNode(child, c, screenOf(cam, Vec3(3, 4, 0)));
  EXPECT_LT(degrees(sk.geometry(right).planeNormal, Vec3(1, 0, 0)), 10.0);
  EXPECT_GT(sk.geometry(right).planeNormal.x(), 0.0);
}

TEST(SketchGeometry, OrthographicCameraUsesTheStroke) {
  Sketch sk;
  geom::Camera cam = frontCamera(true);
  int c = sk.addCamera(cam);
  NodeId root = sk.addScreenNode(kNoNode, c, screenOf(cam, Vec3(0, 1, 0)));
  // All rays are parallel: (A × A_parent) vanishes for the child, the stroke rule applies.
  NodeId child = sk.addScreenNode(root, c, screenOf(cam, Vec3(1, 2, 0)));  // 45° up-right
  NodeGeometry pg = sk.geometry(root), g = sk.geometry(child);
  EXPECT_NEAR(pg.lineDir.cross(g.lineDir).norm(), 0.0, 1e-12);
  EXPECT_NEAR(g.planeNormal.dot(g.lineDir), 0.0, 1e-9);
  EXPECT_NEAR((g.planeNormal - Vec3(1, 1, 0).normalized()).norm(), 0.0, 1e-6);
  EXPECT_NEAR((pg.planeNormal - Vec3(0, 1, 0)).norm(), 0.0, 1e-9);
}

TEST(SketchGeometry, OrthographicTopViewRootUsesScreenUp) {
  Sketch sk;
  geom::Camera cam = geom::presetCamera(geom::PresetView::Top, trunkBox(), geom::UpAxis::Y, {0, 0, 600, 600}, true);
  NodeId root = sk.addScreenNode(kNoNode, sk.addCamera(cam), Vec2(300, 300));
  NodeGeometry g = sk.geometry(root);
  EXPECT_NEAR(std::abs(g.lineDir.y()), 1.0, 1e-9);
  EXPECT_NEAR((g.planeNormal - cam.up()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(g.planeNormal.dot(g.lineDir), 0.0, 1e-12);
}

TEST(SketchGeometry, MixedViewsGiveFiniteNormals) {
  Sketch sk;
  geom::Camera front = frontCamera(false);
  geom::Camera side = geom::presetCamera(geom::PresetView::Side, trunkBox(), geom::UpAxis::Y, {0, 0, 800, 600}, false);
  int cf = sk.addCamera(front), cs = sk.addCamera(side);
  EXPECT_NE(cf, cs);
  EXPECT_EQ(sk.addCamera(front), cf);  // de-duplicated
  NodeId root = sk.addScreenNode(kNoNode, cf, screenOf(front, Vec3(0, 1, 0)));
  NodeId child = sk.addScreenNode(root, cs, screenOf(side, Vec3(0, 4, 0.5)));
  NodeGeometry g = sk.geometry(child);
  EXPECT_TRUE(g.planeNormal.allFinite());
  EXPECT_NEAR(g.planeNormal.norm(), 1.0, 1e-12);
  EXPECT_NEAR(g.planeNormal.dot(g.lineDir), 0.0, 1e-9);
  EXPECT_LT(degrees(g.lineDir, Vec3(1, 0, 0)), 15.0);  // drawn from the side
}

TEST(SketchGeometry, ParallelRaysFromTwoOrthographicViewsUseTheStroke) {
  Sketch sk;
  geom::Camera a = frontCamera(true, {0, 0, 800, 600});
  geom::Camera b = frontCamera(true, {0, 0, 400, 300});  // same direction, another camera
  int ca = sk.addCamera(a), cb = sk.addCamera(b);
  ASSERT_NE(ca, cb);
  NodeId root = sk.addScreenNode(kNoNode, ca, screenOf(a, Vec3(0, 1, 0)));
  NodeId child = sk.addScreenNode(root, cb, screenOf(b, Vec3(-2, 1, 0)));  // to the left
  NodeGeometry g = sk.geometry(child);
  EXPECT_NEAR((g.planeNormal - Vec3(-1, 0, 0)).norm(), 0.0, 1e-6);
}

TEST(SketchGeometry, PointNodesAndChildrenOfPointNodes) {
  Sketch sk;
  geom::Camera cam = frontCamera(true);
  int c = sk.addCamera(cam);
  NodeId root = sk.addPointNode(kNoNode, Vec3(0, 1, 0), Vec3(0, 2, 0));
  NodeGeometry rg = sk.geometry(root);
  EXPECT_FALSE(rg.hasLine);
  EXPECT_EQ(rg.planePoint, Vec3(0, 1, 0));
  EXPECT_NEAR((rg.planeNormal - Vec3(0, 1, 0)).norm(), 0.0, 1e-15);
  NodeId child = sk.addScreenNode(root, c, screenOf(cam, Vec3(0, 3, 0)));
  EXPECT_NEAR((sk.geometry(child).planeNormal - Vec3(0, 1, 0)).norm(), 0.0, 1e-6);
  // Drawn on top of its parent: the parent's normal is kept.
  NodeId same = sk.addScreenNode(child, c, sk.node(child).screen);
  EXPECT_NEAR((sk.geometry(same).planeNormal - Vec3(0, 1, 0)).norm(), 0.0, 1e-6);
}

TEST(SketchGeometry, LongChainsAndStacksStayCheap) {
  Sketch sk;
  geom::Camera cam = frontCamera(true);
  int c = sk.addCamera(cam);
  NodeId prev = sk.addScreenNode(kNoNode, c, Vec2(400, 500));
  NodeId first = sk.addScreenNode(prev, c, Vec2(400, 400));
  prev = first;
  for (int i = 0; i < 20000; ++i) prev = sk.addScreenNode(prev, c, Vec2(400, 400));  // all on one pixel
  NodeGeometry g = sk.geometry(prev);
  EXPECT_NEAR((g.planeNormal - sk.geometry(first).planeNormal).norm(), 0.0, 1e-12);
  EXPECT_NEAR(g.planeNormal.y(), 1.0, 1e-9);
  EXPECT_NO_THROW(sk.validate());
  EXPECT_EQ(sk.topologicalOrder().size(), sk.size());
}

// A small tree: 0 -> 1 -> {2 -> 4, 3}
Sketch smallTree() {
  Sketch sk;
  int c = sk.addCamera(frontCamera(false));
  NodeId n0 = sk.addScreenNode(kNoNode, c, Vec2(400, 500));
  NodeId n1 = sk.addScreenNode(n0, c, Vec2(400, 400));
  NodeId n2 = sk.addScreenNode(n1, c, Vec2(350, 300));
  sk.addScreenNode(n1, c, Vec2(450, 300));
  sk.addScreenNode(n2, c, Vec2(330, 200));
  return sk;
}

TEST(SketchTree, AddAndTraverse) {
  Sketch sk = smallTree();
  EXPECT_EQ(sk.size(), 5u);
  EXPECT_EQ(sk.root(), 0);
  EXPECT_EQ(sk.node(1).children, (std::vector<NodeId>{2, 3}));
  EXPECT_EQ(sk.topologicalOrder(), (std::vector<NodeId>{0, 1, 2, 4, 3}));
  EXPECT_EQ(sk.ids(), (std::vector<NodeId>{0, 1, 2, 3, 4}));
  EXPECT_NO_THROW(sk.validate());
  EXPECT_THROW(sk.addScreenNode(kNoNode, 0, Vec2(1, 1)), OptionsError);   // second root
  EXPECT_THROW(sk.addScreenNode(99, 0, Vec2(1, 1)), OptionsError);        // unknown parent
  EXPECT_THROW(sk.addScreenNode(0, 5, Vec2(1, 1)), OptionsError);         // unknown camera
  EXPECT_THROW(sk.addScreenNode(0, 0, Vec2(NAN, 1)), OptionsError);
  EXPECT_THROW(sk.addPointNode(0, Vec3(0, 0, 0), Vec3::Zero()), OptionsError);
  SamplingParams bad;
  bad.lineEpsilon = 0;
  EXPECT_THROW(sk.addScreenNode(0, 0, Vec2(1, 1), bad), OptionsError);
  EXPECT_THROW(sk.node(42), OptionsError);
  EXPECT_EQ(sk.size(), 5u);
}

TEST(SketchTree, RemoveReattachesChildrenInPlace) {
  Sketch sk = smallTree();
  sk.removeNode(1, false);
  EXPECT_FALSE(sk.contains(1));
  EXPECT_EQ(sk.node(0).children, (std::vector<NodeId>{2, 3}));
  EXPECT_EQ(sk.node(2).parent, 0);
  EXPECT_EQ(sk.node(3).parent, 0);
  EXPECT_NO_THROW(sk.validate());
  EXPECT_THROW(sk.removeNode(1, false), OptionsError);
}

TEST(SketchTree, RemoveWithSubtree) {
  Sketch sk = smallTree();
  sk.removeNode(2, true);
  EXPECT_EQ(sk.ids(), (std::vector<NodeId>{0, 1, 3}));
  EXPECT_EQ(sk.node(1).children, (std::vector<NodeId>{3}));
  EXPECT_NO_THROW(sk.validate());
  sk.removeNode(0, true);
  EXPECT_TRUE(sk.empty());
  EXPECT_EQ(sk.root(), kNoNode);
  EXPECT_NO_THROW(sk.validate());
}

TEST(SketchTree, RemoveRootPromotesFirstChild) {
  Sketch sk = smallTree();
  sk.removeNode(0, false);
  EXPECT_EQ(sk.root(), 1);
  sk.removeNode(1, false);  // children 2 and 3: 2 becomes the root and adopts 3
  EXPECT_EQ(sk.root(), 2);
  EXPECT_EQ(sk.node(2).children, (std::vector<NodeId>{4, 3}));
  EXPECT_EQ(sk.node(3).parent, 2);
  EXPECT_NO_THROW(sk.validate());
  // New nodes never reuse an id.
  EXPECT_EQ(sk.addScreenNode(2, 0, Vec2(1, 1)), 5);
}

TEST(SketchTree, SetParentRejectsCycles) {
  Sketch sk = smallTree();
  EXPECT_THROW(sk.setParent(1, 4), OptionsError);  // 4 is under 1
  EXPECT_THROW(sk.setParent(2, 2), OptionsError);
  EXPECT_THROW(sk.setParent(0, 3), OptionsError);  // the root under its descendant
  EXPECT_THROW(sk.setParent(3, kNoNode), OptionsError);  // a second root
  EXPECT_THROW(sk.setParent(3, 77), OptionsError);
  EXPECT_NO_THROW(sk.validate());
  sk.setParent(3, 4);
  EXPECT_EQ(sk.node(1).children, (std::vector<NodeId>{2}));
  EXPECT_EQ(sk.node(4).children, (std::vector<NodeId>{3}));
  EXPECT_NO_THROW(sk.validate());
}

TEST(SketchTree, MoveAndParams) {
  Sketch sk = smallTree();
  sk.moveNode(3, Vec2(10, 20));
  EXPECT_EQ(sk.node(3).screen, Vec2(10, 20));
  EXPECT_THROW(sk.movePointNode(3, Vec3(0, 0, 0), Vec3(0, 1, 0)), OptionsError);
  SamplingParams p;
  p.lineEpsilon = 2.5;
  p.enabled = false;
  sk.setParams(3, p);
  EXPECT_EQ(sk.node(3).params, p);
  p.sliceHalfThickness = -1;
  EXPECT_THROW(sk.setParams(3, p), OptionsError);
  NodeId pn = sk.addPointNode(3, Vec3(1, 2, 3), Vec3(0, 0, 1));
  EXPECT_THROW(sk.moveNode(pn, Vec2(0, 0)), OptionsError);
  sk.movePointNode(pn, Vec3(4, 5, 6), Vec3(1, 0, 0));
  EXPECT_EQ(sk.node(pn).point, Vec3(4, 5, 6));
}

void expectInvalid(const Sketch& sk, const std::string& needle) {
  try {
    sk.validate();
    ADD_FAILURE() << "validate() accepted a sketch that should fail with '" << needle << "'";
  } catch (const OptionsError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

Node rawScreen(NodeId id, NodeId parent, int camera = 0) {
  Node n;
  n.id = id;
  n.parent = parent;
  n.camera = camera;
  n.screen = Vec2(100, 100 + id);
  return n;
}

TEST(SketchValidate, RejectsBrokenStructures) {
  geom::Camera cam = frontCamera(false);
  {
    Sketch sk;
    sk.insertRawCamera(cam);
    sk.insertRaw(rawScreen(0, kNoNode));
    sk.insertRaw(rawScreen(7, kNoNode));
    expectInvalid(sk, "node 7: a second root");
  }
  {
    Sketch sk;
    sk.insertRawCamera(cam);
    sk.insertRaw(rawScreen(0, kNoNode));
    sk.insertRaw(rawScreen(3, 12));
    expectInvalid(sk, "node 3: parent 12 does not exist");
  }
  {
    Sketch sk;
    sk.insertRawCamera(cam);
    sk.insertRaw(rawScreen(0, kNoNode));
    sk.insertRaw(rawScreen(1, 2));
    sk.insertRaw(rawScreen(2, 1));
    expectInvalid(sk, "node 1: its parents form a cycle");
  }
  {
    Sketch sk;
    sk.insertRawCamera(cam);
    sk.insertRaw(rawScreen(0, kNoNode));
    sk.insertRaw(rawScreen(4, 0, 3));
    expectInvalid(sk, "node 4: camera 3 does not exist");
  }
  {
    Sketch sk;
    sk.insertRawCamera(cam);
    Node n = rawScreen(0, kNoNode);
    n.screen.x() = NAN;
    sk.insertRaw(n);
    expectInvalid(sk, "node 0: screen position is not finite");
  }
  {
    Sketch sk;
    Node n;
    n.id = 5;
    n.point = Vec3(1, 2, 3);
    sk.insertRaw(n);
    expectInvalid(sk, "node 5: normal is zero");
  }
  {
    Sketch sk;
    sk.insertRawCamera(cam);
    Node n = rawScreen(2, kNoNode);
    n.params.sliceHalfThickness = 0;
    sk.insertRaw(n);
    expectInvalid(sk, "node 2: sliceHalfThickness must be > 0");
  }
  {
    Sketch sk;
    geom::Camera bad = cam;
    bad.viewport.width = 0;
    sk.insertRawCamera(bad);
    sk.insertRaw(rawScreen(0, kNoNode));
    expectInvalid(sk, "camera 0");
  }
  {
    Sketch sk;
    sk.insertRawCamera(cam);
    sk.insertRaw(rawScreen(0, kNoNode));
    EXPECT_THROW(sk.insertRaw(rawScreen(0, kNoNode)), OptionsError);  // duplicate id
    EXPECT_NO_THROW(sk.validate());
  }
}

TEST(SketchValidate, InsertRawBuildsChildrenInAnyOrder) {
  Sketch sk;
  sk.insertRawCamera(frontCamera(false));
  sk.insertRaw(rawScreen(5, 2));  // child before its parent
  sk.insertRaw(rawScreen(2, kNoNode));
  sk.insertRaw(rawScreen(9, 2));
  EXPECT_EQ(sk.node(2).children, (std::vector<NodeId>{5, 9}));
  EXPECT_NO_THROW(sk.validate());
  EXPECT_EQ(sk.addScreenNode(9, 0, Vec2(3, 3)), 10);
}

TEST(SketchCamera, AddCameraRejectsDegenerate) {
  Sketch sk;
  geom::Camera bad = frontCamera(false);
  bad.projection = geom::Mat4::Zero();
  EXPECT_THROW(sk.addCamera(bad), OptionsError);
  EXPECT_TRUE(sk.cameras().empty());
}

TEST(SketchKeptCircle, DroppedWhenTheNodesInputsChangeAndOnlyThen) {
  Sketch sk;
  NodeId r = sk.addPointNode(kNoNode, Vec3(0, 1, 0), Vec3(0, 1, 0));
  NodeId a = sk.addPointNode(r, Vec3(0, 2, 0), Vec3(0, 1, 0));
  NodeId b = sk.addPointNode(a, Vec3(0, 3, 0), Vec3(0, 1, 0));
  const KeptCircle c{Vec3(0.01, 2, 0), 0.2};
  for (NodeId id : {r, a, b}) sk.setKeptCircle(id, c);
  EXPECT_EQ(sk.keptCircleCount(), 3u);
  // Same params, same point: nothing changes, the circles stay.
  sk.setParams(a, sk.node(a).params);
  sk.movePointNode(a, sk.node(a).point, sk.node(a).normal);
  EXPECT_TRUE(sk.node(a).kept.has_value());
  // New sampling sizes, a move, a new normal: that node's circle goes, the others stay.
  SamplingParams p = sk.node(a).params;
  p.lineEpsilon *= 2;
  sk.setParams(a, p);
  EXPECT_FALSE(sk.node(a).kept.has_value());
  sk.movePointNode(b, Vec3(0, 3.1, 0), Vec3(0, 1, 0));
  EXPECT_FALSE(sk.node(b).kept.has_value());
  sk.setKeptCircle(b, c);
  sk.movePointNode(b, Vec3(0, 3.1, 0), Vec3(0.1, 1, 0));
  EXPECT_FALSE(sk.node(b).kept.has_value());
  EXPECT_TRUE(sk.node(r).kept.has_value());
  // Re-parenting does not touch a point node's plane: its circle stays.
  sk.setKeptCircle(b, c);
  sk.removeNode(a, false);
  EXPECT_EQ(sk.node(b).parent, r);
  EXPECT_TRUE(sk.node(b).kept.has_value());
  EXPECT_EQ(sk.clearKeptCircles(), 2u);
  EXPECT_EQ(sk.keptCircleCount(), 0u);
  sk.setKeptCircle(r, c);
  sk.setKeptCircle(r, std::nullopt);
  EXPECT_FALSE(sk.node(r).kept.has_value());
}

TEST(SketchKeptCircle, BadCirclesAndScreenNodesAreRefused) {
  Sketch sk;
  int cam = sk.addCamera(frontCamera(false));
  NodeId s = sk.addScreenNode(kNoNode, cam, Vec2(400, 500));
  NodeId p = sk.addPointNode(s, Vec3(0, 2, 0), Vec3(0, 1, 0));
  EXPECT_THROW(sk.setKeptCircle(s, KeptCircle{Vec3(0, 1, 0), 0.2}), OptionsError);
  EXPECT_THROW(sk.setKeptCircle(p, KeptCircle{Vec3(0, 1, 0), 0.0}), OptionsError);
  EXPECT_THROW(sk.setKeptCircle(p, KeptCircle{Vec3(0, 1, 0), -1.0}), OptionsError);
  EXPECT_THROW(sk.setKeptCircle(p, KeptCircle{Vec3(0, NAN, 0), 1.0}), OptionsError);
  EXPECT_THROW(sk.setKeptCircle(p, KeptCircle{Vec3(0, 1, 0), INFINITY}), OptionsError);
  EXPECT_THROW(sk.setKeptCircle(99, KeptCircle{Vec3(0, 1, 0), 1.0}), OptionsError);
  EXPECT_EQ(sk.keptCircleCount(), 0u);
  // validate() catches one put in by a reader.
  Node raw = sk.node(s);
  raw.id = 7;
  raw.parent = p;
  raw.kept = KeptCircle{Vec3(0, 1, 0), 1.0};
  sk.insertRaw(raw);
  EXPECT_THROW(sk.validate(), OptionsError);
}

}  // namespace
}  // namespace treesketch::sketch
