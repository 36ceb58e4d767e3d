// The correction tools on synthetic clouds with a known answer: a trunk with a branch
// in front and a second branch right behind it in the front view.
#include "treesketch/edit/correction_tools.h"

#include <gtest/gtest.h>

#include <random>

#include "../fit/synthetic_cylinder.h"
#include "treesketch/geom/camera.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/sketch/auto_sketch.h"
#include "treesketch/util/error.h"

namespace treesketch::edit {
namespace {

using geom::Vec2;
using geom::Vec3;

constexpr double kTrunkR = 0.2, kBranchR = 0.08;
const Vec3 kFork(0, 2, 0);
const Vec3 kBranchDir = Vec3(1, 0.5, 0).normalized();
/// The second branch: the same shape, 1.2 units behind the first in the front view (-z).
const Vec3 kBehind(0, 0, -1.2);

/// Trunk (Y axis, y in [0, 4]) + a branch from the fork + the same branch 1.2 behind (on its own
/// post, so it is a separate limb in 3D that overlaps the first on screen).
geom::PointCloud scene(std::uint64_t seed = 3) {
  std::mt19937_64 rng(seed);
  geom::PointCloud c;
  test::addCylinder(c, {Vec3(0, 0, 0), Vec3::UnitY(), kTrunkR, 4.0, 20000, 0.003}, rng);
  test::addCylinder(c, {kFork, kBranchDir, kBranchR, 1.6, 6000, 0.002}, rng);
  test::addCylinder(c, {kFork + kBehind, kBranchDir, kBranchR, 1.6, 6000, 0.002}, rng);
  test::addCylinder(c, {Vec3(0, 0, 0) + kBehind, Vec3::UnitY(), 0.1, 2.0, 4000, 0.002}, rng);
  return c;
}

geom::Camera front(const geom::PointCloud& c) {
  return geom::presetCamera(geom::PresetView::Front, c.bounds(), geom::UpAxis::Y, geom::Viewport{0, 0, 1280, 800},
                            false);
}

/// A trunk sketch of point nodes y = 0.25 .. 2.0 (kept circles: the trunk is known).
sketch::Sketch trunkSketch(const geom::PointCloud& c, double top = 2.0) {
  sketch::Sketch sk;
  sk.defaults = sketch::defaultSamplingFor(c.bounds());
  sketch::NodeId parent = sketch::kNoNode;
  for (double y = 0.25; y <= top + 1e-9; y += 0.25) {
    parent = sk.addPointNode(parent, Vec3(0, y, 0), Vec3::UnitY());
    sk.setKeptCircle(parent, sketch::KeptCircle{Vec3(0, y, 0), kTrunkR});
  }
  return sk;
}

std::vector<Vec2> strokeAlong(const geom::Camera& cam, const Vec3& a, const Vec3& b, int n = 12) {
  std::vector<Vec2> s;
  for (int i = 0; i <= n; ++i) s.push_back(cam.project(a + (b - a) * (double(i) / n)).head<2>());
  return s;
}

TEST(DrawLimb, FollowsTheFrontBranchNotTheOneBehindIt) {
  const geom::PointCloud cloud = scene();
  const geom::Camera cam = front(cloud);
  sketch::Sketch sk = trunkSketch(cloud);
  recon::Reconstruction rec(cloud);
  rec.update(sk);
  ViewPicker picker(cloud, cam);
  const auto stroke = strokeAlong(cam, kFork, kFork + 1.5 * kBranchDir);
  StrokeResult r = drawLimb(sk, picker, cloud, stroke, nodeAnchors(sk, &rec));
  ASSERT_GE(r.added.size(), 3u);
  EXPECT_EQ(sk.node(r.added.front()).parent, r.attachedTo);
  // Attached to the trunk node at the fork (y = 2).
  EXPECT_NEAR(sk.node(r.attachedTo).point.y(), 2.0, 0.26);
  for (sketch::NodeId id : r.added) {
    const Vec3 p = sk.node(id).point;
    EXPECT_NEAR(p.z(), 0.0, 0.15) << "node " << id << " took the depth of the branch behind";
    EXPECT_GT(std::abs(sk.node(id).normal.normalized().dot(kBranchDir)), 0.9);
  }
  rec.update(sk);
  int fitted = 0;
  for (sketch::NodeId id : r.added) {
    const fit::NodeResult* f = rec.result(id);
    ASSERT_NE(f, nullptr);
    if (f->status != fit::NodeStatus::Fitted) continue;
    ++fitted;
    EXPECT_NEAR(f->radius, kBranchR, 0.03);
    EXPECT_NEAR(f->centre.z(), 0.0, 0.1);
  }
  EXPECT_GE(fitted, int(r.added.size()) - 1);
}

TEST(DrawLimb, StartingOnTheBranchBehindFollowsThatOne) {
  // Continuity: a stroke started on a node of the branch behind keeps its depth, and says so.
  const geom::PointCloud cloud = scene();
  const geom::Camera cam = front(cloud);
  sketch::Sketch sk = trunkSketch(cloud);
  const Vec3 start = kFork + kBehind + 0.3 * kBranchDir;
  sketch::NodeId behindNode = sk.addPointNode(sk.root(), start, kBranchDir);
  sk.setKeptCircle(behindNode, sketch::KeptCircle{start, kBranchR});
  ViewPicker picker(cloud, cam);
  std::map<sketch::NodeId, NodeAnchor> anchors = nodeAnchors(sk, nullptr);
  StrokeResult r = drawLimb(sk, picker, cloud, strokeAlong(cam, start, kFork + kBehind + 1.5 * kBranchDir), anchors);
  EXPECT_EQ(r.attachedTo, behindNode);
  for (sketch::NodeId id : r.added) EXPECT_NEAR(sk.node(id).point.z(), kBehind.z(), 0.15);
  EXPECT_GT(r.behindFront, 0);  // the chosen surface was not the front-most: counted
}

// With the front branch's points classed leaf (the picker skips them by index), the same stroke
// can only follow the branch behind it.
TEST(DrawLimb, PointsThePickerSkipsAreNotCandidates) {
  const geom::PointCloud cloud = scene();
  const geom::Camera cam = front(cloud);
  sketch::Sketch sk = trunkSketch(cloud);
  std::vector<std::uint8_t> leaf(cloud.size(), 0);
  std::fill(leaf.begin() + 20000, leaf.begin() + 26000, 1);  // the front branch (scene(): second cylinder)
  ViewPicker picker(cloud, cam, 4.0, [&](std::size_t i, const Vec3& p) { return !isWoodPoint(sk, leaf, i, p); });
  const Vec3 start = kFork + 0.3 * kBranchDir;
  StrokeResult r =
      drawLimb(sk, picker, cloud, strokeAlong(cam, start, kFork + 1.5 * kBranchDir), nodeAnchors(sk, nullptr));
  ASSERT_FALSE(r.added.empty());
  for (sketch::NodeId id : r.added) EXPECT_NEAR(sk.node(id).point.z(), kBehind.z(), 0.15);
}

// woodOnly with a classification: leaf points go, a wood lasso brings them back, a not-wood lasso
// drawn after it wins.
TEST(Lasso, WoodLassoCorrectsTheClassification) {
  const geom::PointCloud cloud = scene();
  const geom::Camera cam = front(cloud);
  sketch::Sketch sk = trunkSketch(cloud);
  std::vector<std::uint8_t> leaf(cloud.size(), 0);
  std::fill(leaf.begin() + 20000, leaf.begin() + 26000, 1);
  EXPECT_EQ(woodOnly(cloud, sk, leaf).size(), cloud.size() - 6000);
  EXPECT_THROW(woodOnly(cloud, sk, std::vector<std::uint8_t>(5, 0)), OptionsError);
  const Vec2 s = cam.project(kFork + 0.8 * kBranchDir).head<2>();
  const std::vector<Vec2> poly = {s + Vec2(-40, -40), s + Vec2(40, -40), s + Vec2(40, 40), s + Vec2(-40, 40)};
  const std::size_t marked = lassoWood(sk, cloud, cam, poly);
  EXPECT_GT(marked, 500u);
  EXPECT_EQ(sk.woodLassoCount(), 1u);
  const std::size_t back = woodOnly(cloud, sk, leaf).size();
  EXPECT_GT(back, cloud.size() - 6000);  // the front branch's points inside the lasso are wood again
  EXPECT_LE(back, cloud.size());
  const std::size_t leafInside = back - (cloud.size() - 6000), leafOutside = 6000 - leafInside;
  EXPECT_EQ(lassoNotWood(sk, cloud, cam, poly), marked);
  // Every point inside is out now, and the leaf points outside stay out.
  EXPECT_EQ(woodOnly(cloud, sk, leaf).size(), cloud.size() - marked - leafOutside);
  // A sketch that replaces another keeps both kinds, in order.
  sketch::Sketch other;
  copyNotWood(sk, other);
  ASSERT_EQ(other.notWood().size(), 2u);
  EXPECT_TRUE(other.notWood()[0].wood);
  EXPECT_FALSE(other.notWood()[1].wood);
}

TEST(DrawLimb, RejectsStrokesWithNothingToFollow) {
  const geom::PointCloud cloud = scene();
  const geom::Camera cam = front(cloud);
  sketch::Sketch sk = trunkSketch(cloud);
  ViewPicker picker(cloud, cam);
  EXPECT_THROW(drawLimb(sk, picker, cloud, {Vec2(5, 5)}, {}), OptionsError);
  EXPECT_THROW(drawLimb(sk, picker, cloud, {Vec2(2, 2), Vec2(10, 3)}, {}), OptionsError);  // empty corner
  EXPECT_THROW(drawLimb(sk, picker, cloud, {Vec2(2, 2), Vec2(NAN, 3)}, {}), OptionsError);
}

TEST(Lasso, NotWoodPointsLeaveTheFitsAndComeBackWhenRemoved) {
  const geom::PointCloud cloud = scene();
  const geom::Camera cam = front(cloud);
  sketch::Sketch sk = trunkSketch(cloud);
  const Vec3 p = kFork + 0.8 * kBranchDir;
  sketch::SamplingParams params = sk.defaults;
  params.maxGrowthSteps = 0;  // no growth: the node sees only the points around it
  sketch::NodeId n = sk.addPointNode(sk.root(), p, kBranchDir, params);
  recon::Reconstruction rec(cloud);
  rec.update(sk);
  ASSERT_EQ(rec.result(n)->status, fit::NodeStatus::Fitted);
  // A lasso around the branch's middle in the front view: marks both branches there.
  const Vec2 s = cam.project(p).head<2>();
  const std::vector<Vec2> poly = {s + Vec2(-40, -40), s + Vec2(40, -40), s + Vec2(40, 40), s + Vec2(-40, 40)};
  const std::size_t marked = lassoNotWood(sk, cloud, cam, poly);
  EXPECT_GT(marked, 500u);
  EXPECT_LT(marked, cloud.size() / 4);
  EXPECT_TRUE(sk.isNotWood(p));
  EXPECT_FALSE(sk.isNotWood(Vec3(0, 0.5, 0)));
  rec.update(sk);
  EXPECT_NE(rec.result(n)->status, fit::NodeStatus::Fitted) << "fitted on points the lasso marked";
  EXPECT_EQ(rec.index().excludedCount(), marked);
  EXPECT_EQ(woodOnly(cloud, sk).size(), cloud.size() - marked);
  sk.clearNotWood();
  rec.update(sk);
  EXPECT_EQ(rec.result(n)->status, fit::NodeStatus::Fitted);
  EXPECT_EQ(rec.index().excludedCount(), 0u);
}

TEST(AutomaticBelow, AddsTheTreeAboveANodeWithoutRepeatingIt) {
  const geom::PointCloud cloud = scene();
  sketch::Sketch sk = trunkSketch(cloud, 1.0);
  const std::size_t before = sk.size();
  sketch::NodeId top = sk.topologicalOrder().back();
  AutoHereOptions o;
  o.regionRadius = 10.0;
  AutoHereResult r = automaticBelow(sk, cloud, top, nodeAnchors(sk, nullptr), o);
  EXPECT_GT(r.added.size(), 3u);
  EXPECT_EQ(sk.size(), before + r.added.size());
  EXPECT_GT(r.regionPoints, 10000u);
  EXPECT_NO_THROW(sk.validate());
  for (sketch::NodeId id : r.added) {
    const sketch::Node& n = sk.node(id);
    const Vec3 c = n.kept ? n.kept->centre : n.point;
    EXPECT_GT(c.y(), 0.9) << "node " << id << " lies below the node it was run from";
  }
  // The region's own base repeats the node it grows from: dropped, and the rest hangs below it.
  EXPECT_EQ(sk.node(r.added.front()).parent, top);
  EXPECT_THROW(automaticBelow(sk, cloud, 999, {}, o), OptionsError);
}

TEST(AutomaticInRegion, RejectsARegionWithTooFewPoints) {
  const geom::PointCloud cloud = scene();
  const geom::Camera cam = front(cloud);
  sketch::Sketch sk = trunkSketch(cloud);
  EXPECT_THROW(automaticInRegion(sk, cloud, cam, {Vec2(1, 1), Vec2(5, 1), Vec2(3, 4)}, {}, {}), OptionsError);
  EXPECT_THROW(automaticInRegion(sk, cloud, cam, {Vec2(1, 1), Vec2(5, 1)}, {}, {}), OptionsError);
}

}  // namespace
}  // namespace treesketch::edit
