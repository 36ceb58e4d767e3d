#include "treesketch/recon/reconstruction.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "fit/synthetic_cylinder.h"
#include "treesketch/util/error.h"

namespace treesketch::recon {
namespace {

using geom::Vec2;
using geom::Vec3;

// A vertical trunk (axis x = 0.5, z = 0, radius 0.25, y 0..3) with a branch leaning in x from
// (0.5, 2, 0), plus 30 % outliers.
geom::PointCloud treeCloud() {
  std::mt19937_64 rng(21);
  geom::PointCloud cloud;
  test::CylinderSpec trunk;
  trunk.base = Vec3(0.5, 0, 0);
  trunk.radius = 0.25;
  trunk.length = 3.0;
  trunk.points = 12000;
  test::addCylinder(cloud, trunk, rng);
  test::addOutliers(cloud, 5000, Vec3(-1, 0, -1), Vec3(2, 3.5, 1), rng);
  return cloud;
}

sketch::SamplingParams params() {
  sketch::SamplingParams p;
  p.sliceHalfThickness = 0.05;
  p.lineEpsilon = 0.4;
  p.lineEpsilonStep = 0.25;
  return p;
}

// Four point nodes up the trunk.
sketch::Sketch trunkSketch() {
  sketch::Sketch s;
  sketch::NodeId prev = sketch::kNoNode;
  for (int i = 0; i < 4; ++i) prev = s.addPointNode(prev, Vec3(0.52, 0.5 + 0.6 * i, 0.03), Vec3::UnitY(), params());
  return s;
}

ReconstructionOptions serial() {
  ReconstructionOptions o;
  o.parallel = false;
  return o;
}

TEST(Reconstruction, TrunkChainFitsEveryNode) {
  geom::PointCloud cloud = treeCloud();
  sketch::Sketch s = trunkSketch();
  Reconstruction rec(cloud);
  auto changed = rec.update(s);
  EXPECT_EQ(changed.size(), 4u);
  EXPECT_EQ(rec.fitCount(), 4u);
  for (auto id : s.ids()) {
    const fit::NodeResult* r = rec.result(id);
    ASSERT_NE(r, nullptr);
    ASSERT_EQ(r->status, fit::NodeStatus::Fitted) << r->reason;
    EXPECT_LT((r->centre - Vec3(0.5, s.node(id).point.y(), 0)).norm(), 0.02 * 0.25);
    EXPECT_LT(std::abs(r->radius - 0.25), 0.02 * 0.25);
  }
  // 4 rings of 16 + 2 cap centres; 3 bands + 2 caps.
  EXPECT_EQ(rec.mesh().vertices.size(), 4u * 16 + 2);
  EXPECT_EQ(rec.mesh().triangles.size(), 3u * 32 + 2 * 16);
  EXPECT_EQ(rec.sweeper().segmentKeys().size(), 3u);
  EXPECT_GE(rec.lastUpdateMs(), 0.0);
  EXPECT_EQ(rec.result(99), nullptr);
}

TEST(Reconstruction, FittingAloneSweepsNothingAndTheNextUpdateSweepsOnce) {
  geom::PointCloud cloud = treeCloud();
  sketch::Sketch s = trunkSketch();
  Reconstruction rec(cloud);
  EXPECT_EQ(rec.fit(s).size(), 4u);
  EXPECT_TRUE(rec.mesh().empty());  // fitted, not swept
  for (auto id : s.ids()) EXPECT_EQ(rec.result(id)->status, fit::NodeStatus::Fitted);
  EXPECT_TRUE(rec.update(s).empty());  // nothing to re-fit ...
  EXPECT_EQ(rec.fitCount(), 4u);
  const ReconstructionResult once = reconstruct(cloud, s);
  EXPECT_EQ(rec.mesh().vertices, once.mesh.vertices);  // ... and the tubes are what one pass makes
  EXPECT_EQ(rec.mesh().triangles.size(), once.mesh.triangles.size());
}

TEST(Reconstruction, EditsRefitOnlyTheTouchedNodes) {
  geom::PointCloud cloud = treeCloud();
  sketch::Sketch s = trunkSketch();
  Reconstruction rec(cloud, serial());
  rec.update(s);
  ASSERT_EQ(rec.fitCount(), 4u);
  EXPECT_TRUE(rec.update(s).empty());  // no change: no fit
  EXPECT_EQ(rec.fitCount(), 4u);

  auto ids = s.ids();
  sketch::SamplingParams p = params();
  p.sliceHalfThickness = 0.08;
  s.setParams(ids[1], p);  // params change
  EXPECT_EQ(rec.update(s), std::vector<sketch::NodeId>{ids[1]});
  EXPECT_EQ(rec.fitCount(), 5u);
  std::size_t bandsBefore = rec.sweeper().segmentBuilds();

  s.movePointNode(ids[2], Vec3(0.48, 1.8, -0.02), Vec3::UnitY());  // move
  EXPECT_EQ(rec.update(s), std::vector<sketch::NodeId>{ids[2]});
  EXPECT_EQ(rec.fitCount(), 6u);
  EXPECT_EQ(rec.sweeper().segmentBuilds(), bandsBefore + 2);  // its two bands only
  EXPECT_NEAR(rec.result(ids[2])->centre.y(), 1.8, 1e-9);

  s.removeNode(ids[1], false);  // delete: children re-attached, nothing to fit
  EXPECT_TRUE(rec.update(s).empty());
  EXPECT_EQ(rec.fitCount(), 6u);
  EXPECT_EQ(rec.result(ids[1]), nullptr);
  EXPECT_EQ(rec.sweeper().segmentKeys().size(), 2u);

  // The incremental state equals a fresh one-shot reconstruction.
  ReconstructionResult fresh = reconstruct(cloud, s, serial());
  for (auto id : s.ids()) {
    EXPECT_EQ(fresh.results.at(id).centre, rec.result(id)->centre);
    EXPECT_EQ(fresh.results.at(id).radius, rec.result(id)->radius);
  }
  EXPECT_EQ(fresh.mesh.triangles, rec.mesh().triangles);
  EXPECT_EQ(fresh.mesh.vertices, rec.mesh().vertices);
}

TEST(Reconstruction, KeptCirclesAreUsedAsGivenAndRefitWhenDropped) {
  geom::PointCloud cloud = treeCloud();
  sketch::Sketch s = trunkSketch();
  // Node 1 keeps a circle that is not the trunk's (off the plane in y: it is projected onto it).
  s.setKeptCircle(1, sketch::KeptCircle{Vec3(0.6, 1.3, 0.1), 0.4});
  // Node 2 keeps one but is disabled: it stays disabled.
  sketch::SamplingParams off = params();
  off.enabled = false;
  s.setParams(2, off);
  s.setKeptCircle(2, sketch::KeptCircle{Vec3(0.5, 1.7, 0), 0.25});
  Reconstruction rec(cloud, serial());
  rec.update(s);
  const fit::NodeResult* kept = rec.result(1);
  ASSERT_NE(kept, nullptr);
  EXPECT_EQ(kept->status, fit::NodeStatus::Fitted);
  EXPECT_TRUE(kept->kept);
  EXPECT_EQ(kept->radius, 0.4);
  EXPECT_NEAR((kept->centre - Vec3(0.6, 1.1, 0.1)).norm(), 0.0, 1e-12);  // node 1's plane is y = 1.1
  EXPECT_TRUE(kept->inlierIndices.empty());
  EXPECT_EQ(rec.result(2)->status, fit::NodeStatus::Disabled);
  EXPECT_FALSE(rec.result(2)->kept);
  EXPECT_FALSE(rec.result(0)->kept);
  EXPECT_EQ(rec.result(0)->status, fit::NodeStatus::Fitted);
  EXPECT_GT(rec.result(0)->inlierIndices.size(), 0u);
  // Same circle again: nothing to do. A new circle or none: that node alone is redone.
  EXPECT_TRUE(rec.update(s).empty());
  s.setKeptCircle(1, sketch::KeptCircle{Vec3(0.6, 1.1, 0.1), 0.3});
  EXPECT_EQ(rec.update(s), (std::vector<sketch::NodeId>{1}));
  EXPECT_EQ(rec.result(1)->radius, 0.3);
  s.setKeptCircle(1, std::nullopt);
  EXPECT_EQ(rec.update(s), (std::vector<sketch::NodeId>{1}));
  EXPECT_FALSE(rec.result(1)->kept);
  ASSERT_EQ(rec.result(1)->status, fit::NodeStatus::Fitted);
  EXPECT_NEAR(rec.result(1)->radius, 0.25, 0.02);  // now measured: the trunk's radius
}

TEST(Reconstruction, MovingAScreenNodeRefitsItsChildren) {
  geom::PointCloud cloud = treeCloud();
  geom::BBox box = cloud.bounds();
  geom::Camera cam = geom::presetCamera(geom::PresetView::Front, box, geom::UpAxis::Y, {0, 0, 800, 800}, false);
  sketch::Sketch s;
  int c = s.addCamera(cam);
  auto screenOf = [&](const Vec3& p) { return Vec2(cam.project(p).head<2>()); };
  auto a = s.addScreenNode(sketch::kNoNode, c, screenOf(Vec3(0.5, 0.5, 0)), params());
  auto b = s.addScreenNode(a, c, screenOf(Vec3(0.5, 1.3, 0)), params());
  auto d = s.addScreenNode(b, c, screenOf(Vec3(0.5, 2.1, 0)), params());
  auto e = s.addScreenNode(d, c, screenOf(Vec3(0.5, 2.8, 0)), params());
  Reconstruction rec(cloud, serial());
  rec.update(s);
  for (auto id : {a, b, d, e}) {
    ASSERT_EQ(rec.result(id)->status, fit::NodeStatus::Fitted) << rec.result(id)->reason;
    EXPECT_NEAR(rec.result(id)->radius, 0.25, 0.02 * 0.25);
    EXPECT_NEAR(rec.result(id)->centre.z(), 0.0, 0.02 * 0.25);  // the data give the depth
  }
  // Moving b changes b's line and its child d's plane (N uses the parent's ray); e is untouched.
  s.moveNode(b, screenOf(Vec3(0.52, 1.35, 0)));
  auto changed = rec.update(s);
  std::sort(changed.begin(), changed.end());
  EXPECT_EQ(changed, (std::vector<sketch::NodeId>{b, d}));
  EXPECT_EQ(rec.fitCount(), 6u);
}

TEST(Reconstruction, SkippedAndDisabledNodesAreBridged) {
  geom::PointCloud cloud = treeCloud();
  sketch::Sketch s;
  auto n0 = s.addPointNode(sketch::kNoNode, Vec3(0.5, 0.5, 0), Vec3::UnitY(), params());
  auto n1 = s.addPointNode(n0, Vec3(0.5, 10.0, 0), Vec3::UnitY(), params());  // above the cloud
  sketch::SamplingParams off = params();
  off.enabled = false;
  auto n2 = s.addPointNode(n1, Vec3(0.5, 1.5, 0), Vec3::UnitY(), off);
  auto n3 = s.addPointNode(n2, Vec3(0.5, 2.5, 0), Vec3::UnitY(), params());
  Reconstruction rec(cloud);
  rec.update(s);
  EXPECT_EQ(rec.result(n1)->status, fit::NodeStatus::Skipped);
  EXPECT_FALSE(rec.result(n1)->reason.empty());
  EXPECT_EQ(rec.result(n2)->status, fit::NodeStatus::Disabled);
  std::vector<sweep::SegmentKey> expected = {{n0, n3}};
  EXPECT_EQ(rec.sweeper().segmentKeys(), expected);
  EXPECT_EQ(rec.mesh().triangles.size(), 32u + 2 * 16);
}

TEST(Reconstruction, DeterministicAndOrderIndependent) {
  geom::PointCloud cloud = treeCloud();
  sketch::Sketch s = trunkSketch();
  ReconstructionOptions par;
  par.seed = 7;
  ReconstructionOptions ser = par;
  ser.parallel = false;
  ReconstructionResult a = reconstruct(cloud, s, par), b = reconstruct(cloud, s, ser);
  for (auto id : s.ids()) {
    EXPECT_EQ(a.results.at(id).centre, b.results.at(id).centre);
    EXPECT_EQ(a.results.at(id).inlierIndices, b.results.at(id).inlierIndices);
  }
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.order, s.topologicalOrder());
}

// A parallel re-fit of every node (in whatever order TBB schedules the nodes) gives the same
// results and mesh as a serial one.
TEST(Reconstruction, ParallelRefitMatchesSerial) {
  geom::PointCloud cloud = treeCloud();
  sketch::Sketch s = trunkSketch();
  ReconstructionOptions par;
  par.seed = 3;
  ReconstructionOptions ser = par;
  ser.parallel = false;
  Reconstruction a(cloud, par), b(cloud, ser);
  a.update(s);
  b.update(s);
  for (int round = 0; round < 3; ++round) {
    for (auto id : s.ids()) {
      sketch::SamplingParams p = s.node(id).params;
      p.sliceHalfThickness = 0.042 + 0.005 * ((int(id) + round) % 3);
      s.setParams(id, p);
    }
    auto ca = a.update(s), cb = b.update(s);
    ASSERT_EQ(ca.size(), s.ids().size());
    EXPECT_EQ(ca, cb);
    for (auto id : s.ids()) {
      ASSERT_EQ(a.result(id)->status, fit::NodeStatus::Fitted) << a.result(id)->reason;
      EXPECT_EQ(a.result(id)->centre, b.result(id)->centre);
      EXPECT_EQ(a.result(id)->radius, b.result(id)->radius);
      EXPECT_EQ(a.result(id)->testIndices, b.result(id)->testIndices);
      EXPECT_EQ(a.result(id)->inlierIndices, b.result(id)->inlierIndices);
    }
    EXPECT_EQ(a.mesh().vertices, b.mesh().vertices);
  }
}

TEST(Reconstruction, EmptyAndInvalidInput) {
  geom::PointCloud cloud = treeCloud();
  sketch::Sketch empty;
  ReconstructionResult r = reconstruct(cloud, empty);
  EXPECT_TRUE(r.results.empty());
  EXPECT_TRUE(r.mesh.empty());

  sketch::Sketch bad;
  sketch::Node orphan;
  orphan.id = 3;
  orphan.parent = 7;  // does not exist
  orphan.normal = Vec3::UnitY();
  bad.insertRaw(orphan);
  Reconstruction rec(cloud);
  EXPECT_THROW(rec.update(bad), OptionsError);

  geom::PointCloud none;
  sketch::Sketch s = trunkSketch();
  ReconstructionResult nothing = reconstruct(none, s);
  for (const auto& [id, res] : nothing.results) EXPECT_EQ(res.status, fit::NodeStatus::Skipped);
  EXPECT_TRUE(nothing.mesh.empty());
}

// The points a classification calls leaf are left out of the fits (every node is fitted again),
// and a wood lasso brings them back.
TEST(Reconstruction, LeafPointsAreLeftOutUntilAWoodLassoHoldsThem) {
  const geom::PointCloud cloud = treeCloud();
  sketch::Sketch s = trunkSketch();
  Reconstruction rec(cloud, serial());
  rec.update(s);
  auto onTrunk = [&](sketch::NodeId id) {
    const fit::NodeResult* r = rec.result(id);
    return r && r->status == fit::NodeStatus::Fitted && std::abs(r->radius - 0.25) < 0.02 * 0.25 &&
           (r->centre - Vec3(0.5, s.node(id).point.y(), 0)).norm() < 0.02 * 0.25;
  };
  auto countOnTrunk = [&] {
    int n = 0;
    for (auto id : s.ids()) n += onTrunk(id);
    return n;
  };
  ASSERT_EQ(countOnTrunk(), 4);
  // The trunk's points (the first 12,000) are called leaf: no node finds the trunk.
  std::vector<std::uint8_t> leaf(cloud.size(), 0);
  std::fill(leaf.begin(), leaf.begin() + 12000, 1);
  rec.setLeafPoints(leaf);
  EXPECT_EQ(rec.update(s).size(), 4u);
  EXPECT_EQ(countOnTrunk(), 0);
  // A wood lasso over the whole front view: every point is wood again.
  const int cam = s.addCamera(geom::presetCamera(geom::PresetView::Front, cloud.bounds(), geom::UpAxis::Y,
                                                 geom::Viewport{0, 0, 100, 100}, false));
  s.addWoodLasso(cam, {Vec2(-1, -1), Vec2(101, -1), Vec2(101, 101), Vec2(-1, 101)});
  EXPECT_EQ(rec.update(s).size(), 4u);
  EXPECT_EQ(countOnTrunk(), 4);
  // A not-wood lasso drawn after it over the same view wins.
  s.addNotWoodLasso(cam, {Vec2(-1, -1), Vec2(101, -1), Vec2(101, 101), Vec2(-1, 101)});
  rec.update(s);
  EXPECT_EQ(countOnTrunk(), 0);
  EXPECT_THROW(rec.setLeafPoints(std::vector<std::uint8_t>(3, 0)), OptionsError);
}

}  // namespace
}  // namespace treesketch::recon
