// The stem tracker (src/skeleton/stem_tracking.h) on small synthetic trees: a stem narrow against
// the voxel, whorls of branches, and a conifer's lowest branches reaching the ground beside it.
#include "skeleton/stem_tracking.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "skeleton/synthetic_tree.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/skeleton/voxel_graph.h"

namespace treesketch {
namespace {

using geom::Vec3;
using test::Cyl;

constexpr double kVoxel = 0.05;
constexpr double kStemRadius = 0.075;  // 1.5 voxels, as a spruce's stem in its wood-only cloud
constexpr double kFoot = 0.3;          // the stem's lowest height (Y up)

// A stem with a whorl of three level branches every half metre; with `drooping`, the lowest
// whorl's two limbs on one side bend down to the ground, lower than the stem's foot.
std::vector<Cyl> conifer(bool drooping) {
  std::vector<Cyl> c{{Vec3(0, kFoot, 0), Vec3(0, 4.0, 0), kStemRadius, -1}};
  for (int w = 0; w < 7; ++w) {
    const double y = 0.8 + 0.5 * w;
    for (int k = 0; k < 3; ++k) {
      const double a = 2.0 * M_PI * (k + 0.37 * w) / 3.0;
      c.push_back({Vec3(0, y, 0), Vec3(0.8 * std::cos(a), y + 0.05, 0.8 * std::sin(a)), 0.015, 0});
    }
  }
  if (drooping) {
    c.push_back({Vec3(0, 0.6, 0), Vec3(-1.0, 0.0, 0.15), 0.02, 0});
    c.push_back({Vec3(0, 0.65, 0), Vec3(-0.9, 0.02, -0.35), 0.02, 0});
  }
  return c;
}

skeleton::VoxelGraph graphOf(const std::vector<Cyl>& tree) {
  const geom::PointCloud cloud = test::sampleCylinders(tree, 0.012, 0.002, 7);
  skeleton::VoxelGraphOptions o;
  o.voxelSize = kVoxel;
  return skeleton::buildVoxelGraph(cloud, o);
}

// The tree's lowest voxels: the Dijkstra sources (as the level sets choose them).
std::vector<std::uint32_t> lowestVoxels(const skeleton::VoxelGraph& g) {
  double lowest = 1e300;
  for (const Vec3& p : g.positions) lowest = std::min(lowest, p.y());
  std::vector<std::uint32_t> root;
  for (std::size_t v = 0; v < g.size(); ++v)
    if (g.positions[v].y() <= lowest + 1.5 * kVoxel) root.push_back(static_cast<std::uint32_t>(v));
  return root;
}

// The lowest region is two branch tips a metre beside the stem; the stem, 1.5 voxels in radius,
// is found where the tree is most continuously vertical and followed through the whorls on its
// axis. (Looked for from the lowest region only, with rings of at least two voxels, it was not.)
TEST(StemTracking, FindsANarrowStemBesideTheLowestBranches) {
  const skeleton::VoxelGraph g = graphOf(conifer(true));
  const std::vector<std::uint32_t> root = lowestVoxels(g);
  ASSERT_FALSE(root.empty());
  Vec3 rootMean = Vec3::Zero();
  for (std::uint32_t v : root) rootMean += g.positions[v];
  rootMean /= static_cast<double>(root.size());
  ASSERT_GT(std::hypot(rootMean.x(), rootMean.z()), 0.5) << "the lowest voxels should be the drooping tips";

  const std::vector<skeleton::detail::StemSample> stem = skeleton::detail::trackStem(g, root, geom::UpAxis::Y);
  ASSERT_GE(stem.size(), 3u);
  double low = 1e300, high = -1e300;
  for (const auto& s : stem) {
    if (s.centre.y() < kFoot) continue;  // the stem carried down to the tree's lowest height
    EXPECT_LT(std::hypot(s.centre.x(), s.centre.z()), 0.5 * kStemRadius) << "sample at height " << s.centre.y();
    EXPECT_NEAR(s.radius, kStemRadius, 0.5 * kStemRadius) << "sample at height " << s.centre.y();
    low = std::min(low, s.centre.y());
    high = std::max(high, s.centre.y());
  }
  EXPECT_LT(low, 1.0);   // from below the first whorl...
  EXPECT_GT(high, 3.0);  // ...up through most of them
  EXPECT_FALSE(skeleton::detail::rootOnStem(g, stem, root));
}

// With its foot among the lowest voxels, a stem under two voxels in radius is left to the level
// sets (its level sets are its cross-sections, centred on its axis).
TEST(StemTracking, LeavesANarrowStemStandingOnTheLowestVoxelsToTheLevelSets) {
  const skeleton::VoxelGraph g = graphOf(conifer(false));
  const std::vector<std::uint32_t> root = lowestVoxels(g);
  ASSERT_FALSE(root.empty());
  EXPECT_TRUE(skeleton::detail::trackStem(g, root, geom::UpAxis::Y).empty());
}

// A vertical limb standing on a crooked stem two metres up is not a stem beside the lowest voxels:
// a stem stands on the ground (without that rule this limb was taken for the tree's stem).
TEST(StemTracking, AColumnStartingHighUpIsNoStemBesideTheBase) {
  std::vector<Cyl> tree{{Vec3(-1.2, 0, 0), Vec3(-0.8, 2.0, 0), kStemRadius, -1},
                        {Vec3(-0.8, 2.0, 0), Vec3(0, 2.0, 0), kStemRadius, 0},
                        {Vec3(0, 2.0, 0), Vec3(0, 4.5, 0), kStemRadius, 1}};
  for (int w = 0; w < 4; ++w) {
    const double y = 2.4 + 0.5 * w;
    tree.push_back({Vec3(0, y, 0), Vec3(0.7 * std::cos(w), y + 0.05, 0.7 * std::sin(w)), 0.015, 2});
  }
  const skeleton::VoxelGraph g = graphOf(tree);
  const std::vector<std::uint32_t> root = lowestVoxels(g);
  ASSERT_FALSE(root.empty());
  EXPECT_TRUE(skeleton::detail::trackStem(g, root, geom::UpAxis::Y).empty());
}

// The whole skeleton: rooted at the stem's foot, not at the drooping branches' tips, and its
// stem's nodes lie on the stem's axis.
TEST(StemTracking, TheSkeletonIsRootedAtTheStemsFootBesideTheDroopingBranches) {
  const geom::PointCloud cloud = test::sampleCylinders(conifer(true), 0.012, 0.002, 7);
  skeleton::SkeletonOptions o;
  o.graph.voxelSize = kVoxel;
  const skeleton::Skeleton s = skeleton::extractSkeleton(cloud, o);
  ASSERT_FALSE(s.rawNodes.empty());
  EXPECT_TRUE(s.levels.stemBesideRoot);
  ASSERT_FALSE(s.levels.rootVertices.empty());
  for (std::uint32_t v : s.levels.rootVertices) {
    const Vec3& p = s.graph.positions[v];
    EXPECT_LT(std::hypot(p.x(), p.z()), kStemRadius + 1.5 * kVoxel) << "root voxel at height " << p.y();
  }
  ASSERT_FALSE(s.nodes.empty());
  EXPECT_LT(std::hypot(s.nodes.front().position.x(), s.nodes.front().position.z()), kStemRadius);
  int onStem = 0, off = 0;
  for (const auto& n : s.rawNodes) {
    if (!n.stem) continue;
    ++onStem;
    if (std::hypot(n.position.x(), n.position.z()) > 0.5 * kStemRadius) ++off;
  }
  EXPECT_GT(onStem, 10);
  EXPECT_EQ(off, 0);
}

// A conifer in leaf as its wood-only cloud shows it: at every whorl eight limbs rising from the
// stem, so the slabs there hold as many limb voxels beside the stem as bark voxels on it, and no
// circle holds most of a slab. The stem, found beside the drooping branches, is followed through
// the whorls on its axis (each whorl's slab seen as its first surface from the axis: the bark,
// with the limbs behind it); before, the tracker stopped at the first two whorls it met.
std::vector<Cyl> denseWhorls() {
  std::vector<Cyl> c = conifer(true);
  c.resize(1);
  for (int w = 0; w < 7; ++w) {
    const double y = 0.8 + 0.5 * w;
    for (int k = 0; k < 8; ++k) {
      const double a = 2.0 * M_PI * (k + 0.37 * w) / 8.0;
      c.push_back({Vec3(0, y, 0), Vec3(0.6 * std::cos(a), y + 0.35, 0.6 * std::sin(a)), 0.03, 0});
    }
  }
  c.push_back({Vec3(0, 0.6, 0), Vec3(-1.0, 0.0, 0.15), 0.02, 0});
  c.push_back({Vec3(0, 0.65, 0), Vec3(-0.9, 0.02, -0.35), 0.02, 0});
  return c;
}

TEST(StemTracking, FollowsAStemBesideTheBaseThroughDenseWhorls) {
  const skeleton::VoxelGraph g = graphOf(denseWhorls());
  const std::vector<std::uint32_t> root = lowestVoxels(g);
  ASSERT_FALSE(root.empty());
  bool beside = false;
  const std::vector<skeleton::detail::StemSample> stem =
      skeleton::detail::trackStem(g, root, geom::UpAxis::Y, &beside);
  ASSERT_GE(stem.size(), 3u);
  EXPECT_TRUE(beside);
  double high = -1e300;
  for (const auto& s : stem) {
    if (s.centre.y() < kFoot) continue;
    EXPECT_LT(std::hypot(s.centre.x(), s.centre.z()), 0.5 * kStemRadius) << "sample at height " << s.centre.y();
    high = std::max(high, s.centre.y());
  }
  EXPECT_GT(high, 3.0);
}

// The whole skeleton on the same conifer: up to the top whorl (where it goes on along a limb) the
// stem's branch is the tracked stem's pieces, in its tube (its radius plus a voxel). The level sets
// cut at the stem's tube leave limb pieces of a stem piece's own level; before the stem was
// chained its branch went out through such a piece at a whorl (here one, 0.1 m off the axis; on
// the spruce in leaf 0.2-0.5 m) and back.
TEST(StemTracking, TheStemIsOneBranchInItsTubeThroughDenseWhorls) {
  const geom::PointCloud cloud = test::sampleCylinders(denseWhorls(), 0.012, 0.002, 7);
  skeleton::SkeletonOptions o;
  o.graph.voxelSize = kVoxel;
  const skeleton::Skeleton s = skeleton::extractSkeleton(cloud, o);
  ASSERT_TRUE(s.levels.stemBesideRoot);
  constexpr double kTopWhorl = 0.8 + 0.5 * 6;
  double high = -1e300;
  for (const auto& n : s.nodes) {
    if (n.branchOrder != 0 || n.position.y() > kTopWhorl) continue;
    EXPECT_TRUE(n.stem) << "a limb's piece on the stem's branch at height " << n.position.y();
    EXPECT_LT(std::hypot(n.position.x(), n.position.z()), kStemRadius + kVoxel) << "stem node at height "
                                                                                << n.position.y();
    high = std::max(high, n.position.y());
  }
  EXPECT_GT(high, 3.5);
}

// The automatic model of the same conifer: its stem's nodes stay on the tracked axis, where the
// fits of the nodes at the whorls took the limbs' bases in with the stem (up to 3.5 cm off the
// axis, a node beside the top whorl) and the simplification had moved a node 10 cm out.
TEST(StemTracking, TheModelsStemStaysOnTheTrackedAxisThroughDenseWhorls) {
  const geom::PointCloud cloud = test::sampleCylinders(denseWhorls(), 0.012, 0.002, 7);
  skeleton::AutoSkeletonOptions o = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOff, geom::UpAxis::Y);
  o.skeleton.graph.voxelSize = kVoxel;
  const skeleton::AutoSkeletonResult r = skeleton::autoSkeletonSketch(cloud, o);
  ASSERT_TRUE(r.skeleton.levels.stemBesideRoot);
  constexpr double kTopWhorl = 0.8 + 0.5 * 6;
  int onStem = 0;
  for (const auto& n : r.model) {
    if (n.branchOrder != 0 || n.position.y() > kTopWhorl + 0.1) continue;
    ++onStem;
    EXPECT_LT(std::hypot(n.position.x(), n.position.z()), 0.25 * kStemRadius) << "stem node at height "
                                                                              << n.position.y();
  }
  EXPECT_GT(onStem, 10);
}

// A conifer's foot in a skirt of dead branches, some rising close beside the stem: the stem's
// branch is the tracked stem from a root on its axis up to the top whorl, and the stem is not
// followed down past the tree's lowest voxel (a slab under the tree, doubled in height, reached up
// to the skirt: samples 0.25 m under the ground, their tube round the branches on it).
std::vector<Cyl> skirtedConifer() {
  std::vector<Cyl> c = denseWhorls();
  for (int k = 0; k < 14; ++k) {
    const double a = 2.0 * M_PI * (k + 0.5) / 14.0, y = 0.35 + 0.03 * (k % 4);
    const double reach = 0.7 + 0.1 * (k % 3);
    c.push_back({Vec3(0, y, 0), Vec3(reach * std::cos(a), 0.02 + 0.04 * (k % 2), reach * std::sin(a)), 0.02, 0});
    const double b = a + 0.3;
    c.push_back({Vec3(0, y + 0.15, 0), Vec3(0.6 * std::cos(b), y + 0.05, 0.6 * std::sin(b)), 0.02, 0});
  }
  for (int k = 0; k < 6; ++k) {  // dead shoots rising close beside the stem
    const double a = 2.0 * M_PI * k / 6.0;
    c.push_back({Vec3(0, 0.32, 0), Vec3(0.2 * std::cos(a), 1.1, 0.2 * std::sin(a)), 0.015, 0});
  }
  return c;
}

TEST(StemTracking, TheStemsBranchRunsFromItsFootThroughASkirtOfDeadBranches) {
  const geom::PointCloud cloud = test::sampleCylinders(skirtedConifer(), 0.012, 0.002, 7);
  skeleton::SkeletonOptions o;
  o.graph.voxelSize = kVoxel;
  const skeleton::Skeleton s = skeleton::extractSkeleton(cloud, o);
  ASSERT_FALSE(s.levels.stemCentres.empty());
  double lowest = 1e300;
  for (const Vec3& p : s.graph.positions) lowest = std::min(lowest, p.y());
  EXPECT_GE(s.levels.stemCentres.front().y(), lowest - 1e-9) << "a stem sample under the tree";
  ASSERT_FALSE(s.nodes.empty());
  EXPECT_LT(std::hypot(s.nodes.front().position.x(), s.nodes.front().position.z()), kStemRadius);
  constexpr double kTopWhorl = 0.8 + 0.5 * 6;
  double high = -1e300;
  int off = 0;
  for (const auto& n : s.nodes) {
    if (n.branchOrder != 0 || n.position.y() > kTopWhorl) continue;
    if (std::hypot(n.position.x(), n.position.z()) > kStemRadius + kVoxel) ++off;
    high = std::max(high, n.position.y());
  }
  EXPECT_EQ(off, 0) << "nodes of the stem's branch off the stem";
  EXPECT_GT(high, 3.5);
}

}  // namespace
}  // namespace treesketch
