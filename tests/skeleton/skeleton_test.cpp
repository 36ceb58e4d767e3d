#include "treesketch/skeleton/skeleton.h"

#include <gtest/gtest.h>

#include <numbers>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <random>
#include <string>

#include "synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/scan/tls_scan.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/error.h"

using namespace treesketch;
using geom::Vec3;

namespace {

/// Distance of node positions to the true axes, as a fraction of the nearest cylinder's radius.
double worstRelativeOffset(const std::vector<test::Cyl>& cyls, const std::vector<skeleton::SkeletonNode>& nodes,
                           bool forks) {
  double worst = 0;
  for (const auto& n : nodes) {
    if ((n.children.size() >= 2) != forks) continue;
    double best = 1e300, radius = 1;
    for (const auto& c : cyls) {
      const double d = test::distanceToSegment(n.position, c.a, c.b);
      if (d < best) {
        best = d;
        radius = c.radius;
      }
    }
    worst = std::max(worst, best / radius);
  }
  return worst;
}

/// Scattered small square "leaves" (planar patches of points, random orientation) around the
/// tips of the given cylinders.
geom::PointCloud leafClutter(const std::vector<test::Cyl>& cyls, int leavesPerTip, double spread, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  geom::PointCloud leaves;
  for (const auto& c : cyls) {
    for (int l = 0; l < leavesPerTip; ++l) {
      const Vec3 centre = c.b + spread * Vec3(uni(rng), uni(rng), uni(rng));
      const Vec3 normal = Vec3(uni(rng), uni(rng), uni(rng)).normalized();
      const Vec3 u = geom::anyPerpendicular(normal), v = normal.cross(u);
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) leaves.positions.push_back(centre + 0.015 * (i - 2.5) * u + 0.015 * (j - 2.5) * v);
    }
  }
  return leaves;
}

/// A thin stem (0 to 2 along y) carrying one flat square leaf, 0.8 wide and 0.8 long, by its base
/// edge at its top, like the ez-tree leaves.
std::vector<test::Cyl> stemOfTheBlade() { return {{Vec3(0, 0, 0), Vec3(0, 2, 0), 0.03, -1}}; }
/// `density` divides the sample spacing (0.02).
geom::PointCloud stemWithBlade(int density = 1) {
  const double step = 0.02 / density;
  auto cloud = test::sampleCylinders(stemOfTheBlade(), step, 0.001, 3);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> jitter(-0.2 * step, 0.2 * step);
  for (int i = 0; i <= 40 * density; ++i)
    for (int j = 0; j < 40 * density; ++j)
      cloud.positions.push_back(Vec3(-0.4 + step * i + jitter(rng), 2.0 + step * j + jitter(rng), 0.0));
  return cloud;
}
}  // namespace

TEST(Skeleton, EmptyAndTinyClouds) {
  const auto empty = skeleton::extractSkeleton(geom::PointCloud{});
  EXPECT_TRUE(empty.nodes.empty());
  geom::PointCloud one;
  one.positions = {Vec3(1, 2, 3)};
  const auto s = skeleton::extractSkeleton(one);
  ASSERT_EQ(s.nodes.size(), 1u);
  EXPECT_TRUE(s.nodes[0].position.isApprox(Vec3(1, 2, 3)));
}

TEST(Skeleton, RejectsBadOptions) {
  geom::PointCloud cloud;
  cloud.positions = {Vec3(0, 0, 0), Vec3(0, 1, 0)};
  skeleton::SkeletonOptions o;
  o.binWidthVoxels = 0;
  EXPECT_THROW(skeleton::extractSkeleton(cloud, o), OptionsError);
  o = {};
  o.radiusMedianWindow = 0;
  EXPECT_THROW(skeleton::extractSkeleton(cloud, o), OptionsError);
  o = {};
  o.leafPlaneMaxAngleDeg = 120;
  EXPECT_THROW(skeleton::extractSkeleton(cloud, o), OptionsError);
}

TEST(Skeleton, YTreeHasOneForkTwoEndsAndNodesOnTheAxes) {
  const auto cyls = test::yTree();
  const auto cloud = test::sampleCylinders(cyls, 0.02, 0.003, 7);
  const auto s = skeleton::extractSkeleton(cloud);
  EXPECT_EQ(skeleton::countBranchPoints(s.nodes), 1u);
  EXPECT_EQ(skeleton::countEnds(s.nodes), 2u);
  EXPECT_LT(worstRelativeOffset(cyls, s.nodes, false), 0.35);
  EXPECT_LT(worstRelativeOffset(cyls, s.nodes, true), 2.0);  // forks sit where level sets split
  // Root at the base, parents first, unit directions, radii of the right size.
  EXPECT_LT(s.nodes[0].position.y(), 0.1);
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    EXPECT_LT(s.nodes[i].parent, static_cast<std::int32_t>(i));
    EXPECT_NEAR(s.nodes[i].direction.norm(), 1.0, 1e-9);
    EXPECT_GT(s.nodes[i].radius, 0.03);
    EXPECT_LT(s.nodes[i].radius, 0.25);
  }
  // The two branches get order 1 for one of them.
  int side = 0;
  for (const auto& n : s.nodes) side += n.branchOrder == 1 && n.children.empty();
  EXPECT_EQ(side, 1);
  // Plain data of every stage.
  EXPECT_EQ(s.levels.distance.size(), s.graph.size());
  EXPECT_GT(s.rawNodes.size(), s.nodes.size());
}

TEST(Skeleton, ThreeLevelTree) {
  const auto cyls = test::threeLevelTree();
  const auto cloud = test::sampleCylinders(cyls, 0.02, 0.003, 11);
  const auto s = skeleton::extractSkeleton(cloud);
  EXPECT_EQ(skeleton::countBranchPoints(s.nodes), 4u);
  EXPECT_EQ(skeleton::countEnds(s.nodes), 5u);
  EXPECT_LT(worstRelativeOffset(cyls, s.nodes, false), 0.35);
  EXPECT_LT(worstRelativeOffset(cyls, s.nodes, true), 2.0);  // forks sit where level sets split
  int maxOrder = 0;
  for (const auto& n : s.nodes) maxOrder = std::max(maxOrder, n.branchOrder);
  EXPECT_EQ(maxOrder, 2);
}

TEST(Skeleton, OcclusionGapIsBridged) {
  const auto cyls = test::yTree();
  auto cloud = test::sampleCylinders(cyls, 0.02, 0.003, 5);
  // Remove a 0.12-long stretch of the left branch (around its middle).
  const Vec3 a = cyls[1].a, b = cyls[1].b, axis = (b - a).normalized();
  const Vec3 mid = 0.5 * (a + b);
  geom::PointCloud cut;
  for (const auto& p : cloud.positions)
    if (!(std::abs((p - mid).dot(axis)) < 0.06 && test::distanceToSegment(p, a, b) < 0.2)) cut.positions.push_back(p);
  ASSERT_LT(cut.size(), cloud.size());
  const auto s = skeleton::extractSkeleton(cut);
  EXPECT_GE(s.graph.bridges.size(), 1u);
  EXPECT_EQ(skeleton::countBranchPoints(s.nodes), 1u);
  EXPECT_EQ(skeleton::countEnds(s.nodes), 2u);
  // The left branch's tip is reached.
  double nearest = 1e300;
  for (const auto& n : s.nodes) nearest = std::min(nearest, (n.position - b).norm());
  EXPECT_LT(nearest, 0.3);
  // Without bridging the cut-off part is lost.
  skeleton::SkeletonOptions o;
  o.graph.maxGapVoxels = 0;
  const auto unbridged = skeleton::extractSkeleton(cut, o);
  nearest = 1e300;
  for (const auto& n : unbridged.nodes) nearest = std::min(nearest, (n.position - b).norm());
  EXPECT_GT(nearest, 0.5);
}

TEST(Skeleton, LeafClutterDoesNotGrowBranches) {
  const auto cyls = test::yTree();
  auto cloud = test::sampleCylinders(cyls, 0.02, 0.003, 7);
  const std::vector<test::Cyl> tips = {cyls[1], cyls[2]};
  cloud.append(leafClutter(tips, 40, 0.35, 9));
  // The foliage guards (the leaf-on settings' bridging cone, here on the leaf-off voxels) keep
  // leaves from growing branches...
  skeleton::SkeletonOptions guarded;
  guarded.graph.maxGapVoxels = 8;
  guarded.graph.coneAngleDeg = 45;
  guarded.graph.minBridgeLinearity = 0.4;
  guarded.twigOutBins = 0;  // as leafOnSkeletonOptions: a short piece standing out is a leaf as often
  guarded.splitMergedForks = false;  // as leafOnSkeletonOptions: leaf clusters are not limbs
  const auto s = skeleton::extractSkeleton(cloud, guarded);
  // ...which the leaf-off defaults do not have (a leaf-off scan has no leaves): the clutter grows
  // forks. Known limit: with this dense clutter (80 leaves within 0.35 of two tips) leaf spurs
  // survive the guards too (the true tree has 1 fork and 2 ends; measured 8 forks and 10 ends
  // guarded, 14 and 23 without); the guards take at least 40 % of them.
  const auto unfiltered = skeleton::extractSkeleton(cloud);
  const std::size_t forks = skeleton::countBranchPoints(s.nodes), ends = skeleton::countEnds(s.nodes);
  EXPECT_GE(skeleton::countBranchPoints(unfiltered.nodes), forks + 3);
  EXPECT_LE(10 * forks, 6 * skeleton::countBranchPoints(unfiltered.nodes));
  EXPECT_LE(10 * ends, 6 * skeleton::countEnds(unfiltered.nodes));
}

// A tree scanned sparsely from one side only (a single station, as real scans often are): the
// level sets of a branch are noisy half rings, and every side branch and twig is still reached.
TEST(Skeleton, OneSidedLimbsAreKept) {
  const auto cyls = test::threeLevelTree();
  const auto full = test::sampleCylinders(cyls, 0.04, 0.01, 13);
  geom::PointCloud half;
  for (const auto& p : full.positions) {
    // The nearest axis decides the side: keep the half of each surface that faces -z.
    std::size_t k = 0;
    for (std::size_t j = 1; j < cyls.size(); ++j)
      if (test::distanceToSegment(p, cyls[j].a, cyls[j].b) < test::distanceToSegment(p, cyls[k].a, cyls[k].b)) k = j;
    const Vec3 axis = (cyls[k].b - cyls[k].a).normalized();
    const Vec3 off = (p - cyls[k].a) - axis * axis.dot(p - cyls[k].a);
    if (off.z() < 0) half.positions.push_back(p);
  }
  auto tipsReached = [&](const std::vector<skeleton::SkeletonNode>& nodes) {
    int reached = 0;
    for (int c : {2, 3, 4, 5}) {  // the side branches and twigs
      double nearest = 1e300;
      for (const auto& n : nodes) nearest = std::min(nearest, (n.position - cyls[c].b).norm());
      reached += nearest < 0.3;
    }
    return reached;
  };
  const auto s = skeleton::extractSkeleton(half);
  EXPECT_EQ(tipsReached(s.nodes), 4);
  EXPECT_LE(skeleton::countEnds(s.nodes), 7u);  // the true tree has 5
  EXPECT_EQ(tipsReached(skeleton::extractSkeleton(half, skeleton::leafOnSkeletonOptions()).nodes), 4);
}

TEST(Skeleton, Deterministic) {
  const auto cloud = test::sampleCylinders(test::threeLevelTree(), 0.02, 0.003, 2);
  const auto s1 = skeleton::extractSkeleton(cloud);
  const auto s2 = skeleton::extractSkeleton(cloud);
  ASSERT_EQ(s1.nodes.size(), s2.nodes.size());
  for (std::size_t i = 0; i < s1.nodes.size(); ++i) {
    EXPECT_EQ(s1.nodes[i].parent, s2.nodes[i].parent);
    EXPECT_EQ(s1.nodes[i].position, s2.nodes[i].position);
    EXPECT_EQ(s1.nodes[i].radius, s2.nodes[i].radius);
  }
}

TEST(Skeleton, LeafOnSettingsKeepTheRestOfTheBase) {
  skeleton::SkeletonOptions base;
  base.up = geom::UpAxis::Z;
  base.spurLengthRadii = 7.0;
  const auto o = skeleton::leafOnSkeletonOptions(base);
  EXPECT_EQ(o.up, geom::UpAxis::Z);
  EXPECT_EQ(o.spurLengthRadii, 7.0);
  EXPECT_LT(o.graph.autoSpacingFactor, base.graph.autoSpacingFactor);
  EXPECT_LT(o.binWidthVoxels, base.binWidthVoxels);
  // The foliage guards are on leaf-on only; the occlusion gaps bridged are the same.
  EXPECT_EQ(o.graph.maxGapVoxels, base.graph.maxGapVoxels);
  EXPECT_LT(o.graph.coneAngleDeg, base.graph.coneAngleDeg);
  EXPECT_GT(o.graph.minBridgeLinearity, base.graph.minBridgeLinearity);
}

TEST(Skeleton, LeafEntryPositionsPutLeafNodesAtTheLeafBase) {
  // A thin stem carrying one flat square leaf by its base edge. The level sets cross the blade in arcs around its base,
  // so their centroids run out along the blade's midline; with leaf-entry positions the blade counts at its base.
  const std::vector<test::Cyl> stem = stemOfTheBlade();
  const auto cloud = stemWithBlade();
  auto farthest = [&](const skeleton::Skeleton& s) {
    double worst = 0;
    for (const auto& n : s.rawNodes) worst = std::max(worst, test::distanceToSegment(n.position, stem[0].a, stem[0].b));
    return worst;
  };
  auto o = skeleton::leafOnSkeletonOptions();
  ASSERT_TRUE(o.leafEntryPositions);
  // A fixed voxel (1.5 spacings): the automatic one from this mixed sampling splits the stem's rings.
  o.graph.voxelSize = 0.03;
  o.leafEntryPositions = false;
  const auto plain = skeleton::extractSkeleton(cloud, o);
  EXPECT_GT(farthest(plain), 0.4);
  o.leafEntryPositions = true;
  const auto entry = skeleton::extractSkeleton(cloud, o);
  EXPECT_LT(farthest(entry), 0.15);
  // Only the centroids move: the graph keeps the voxels' own positions and the same level sets.
  EXPECT_EQ(entry.graph.positions, plain.graph.positions);
  EXPECT_EQ(entry.levels.level, plain.levels.level);
}

TEST(Skeleton, LeafPlaneConvergencePullsLeafNodesTowardsAnUnseenTwig) {
  // A stem whose last part, a twig, is not in the scan (hidden by its leaves, as on the ez-tree
  // crowns); five square blades hang from the twig, each tilted 40 degrees out from it in a plane
  // that holds the twig's line (one quad of a crossed leaf), all on one side. The level sets cut
  // the blades, so entry positions alone leave the nodes out on the blades; the blades' planes
  // meet on the twig, which is where plane convergence pulls them.
  const std::vector<test::Cyl> stem = {{Vec3(0, 0, 0), Vec3(0, 2, 0), 0.03, -1}};
  auto cloud = test::sampleCylinders(stem, 0.02, 0.001, 3);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> jitter(-0.003, 0.003);
  const double kPi = 3.14159265358979323846, tilt = 40 * kPi / 180, width = 0.6;
  for (int leaf = 0; leaf < 5; ++leaf) {
    const double azimuth = (-60 + 30 * leaf) * kPi / 180;
    const Vec3 radial(std::cos(azimuth), 0, std::sin(azimuth));
    const Vec3 base(0, 2.0 + 0.2 * leaf, 0);
    const Vec3 spine = std::cos(tilt) * Vec3::UnitY() + std::sin(tilt) * radial;
    const Vec3 across = -std::sin(tilt) * Vec3::UnitY() + std::cos(tilt) * radial;
    for (int i = 0; i <= 30; ++i)
      for (int j = 0; j <= 30; ++j) {
        const Vec3 p = base + (width * i / 30) * spine + (width * (j / 30.0 - 0.5)) * across;
        cloud.positions.push_back(p + Vec3(jitter(rng), jitter(rng), jitter(rng)));
      }
  }
  auto meanOffAxis = [&](const skeleton::Skeleton& s) {
    double sum = 0;
    int count = 0;
    for (const auto& n : s.rawNodes)
      if (n.position.y() > 2.1) {
        sum += std::hypot(n.position.x(), n.position.z());
        ++count;
      }
    EXPECT_GT(count, 5);
    return sum / std::max(count, 1);
  };
  auto o = skeleton::leafOnSkeletonOptions();
  o.graph.voxelSize = 0.03;
  ASSERT_GT(o.leafConvergenceWeight, 0);
  const auto converged = skeleton::extractSkeleton(cloud, o);
  o.leafConvergenceWeight = 0;
  const auto entryOnly = skeleton::extractSkeleton(cloud, o);
  EXPECT_LT(meanOffAxis(converged), 0.75 * meanOffAxis(entryOnly))
      << meanOffAxis(converged) << " vs " << meanOffAxis(entryOnly);
  // The graph and the level sets are the same; only the centroids moved.
  EXPECT_EQ(converged.graph.positions, entryOnly.graph.positions);
  EXPECT_EQ(converged.levels.level, entryOnly.levels.level);
  // Out-of-range settings are refused.
  o.leafConvergenceWeight = 1.5;
  EXPECT_THROW(skeleton::extractSkeleton(cloud, o), OptionsError);
  o.leafConvergenceWeight = 0.5;
  o.leafConvergenceRadiusVoxels = -1;
  EXPECT_THROW(skeleton::extractSkeleton(cloud, o), OptionsError);
  o.leafConvergenceRadiusVoxels = 0;  // automatic
  o.leafConvergenceAutoScale = 0;
  EXPECT_THROW(skeleton::extractSkeleton(cloud, o), OptionsError);
}

TEST(Skeleton, LevelSetCentroidPositionsMoveCentroidsAndRadiiButNotTheShapeTest) {
  // Centroid positions pulled towards the stem's axis, alternately to 0.2 and 0.8 of the way out:
  // the pieces' radii halve, but the ring test stays on the scanned shape — over the pulled
  // positions (distances to the axis varying by ±60 %) every piece would read as foliage.
  const std::vector<test::Cyl> stem = {{Vec3(0, 0, 0), Vec3(0, 2, 0), 0.1, -1}};
  const auto cloud = test::sampleCylinders(stem, 0.02, 0.001, 4);
  skeleton::SkeletonOptions o;
  o.graph.voxelSize = 0.04;
  o.trackStem = false;  // the tracked stem would give its pieces its own axis and radius
  const auto graph = skeleton::buildVoxelGraph(cloud, o.graph);
  auto levels = skeleton::computeGeodesicLevels(graph, o);
  const auto own = skeleton::levelSetNodes(graph, levels, o);
  std::vector<Vec3> pulled(graph.size());
  for (std::size_t k = 0; k < graph.size(); ++k) {
    const Vec3& p = graph.positions[k];
    const double f = k % 2 ? 0.8 : 0.2;
    pulled[k] = Vec3(f * p.x(), p.y(), f * p.z());
  }
  const auto moved = skeleton::levelSetNodes(graph, levels, o, &pulled);
  ASSERT_EQ(own.size(), moved.size());
  ASSERT_GT(own.size(), 10u);
  int compared = 0;
  for (std::size_t i = 0; i < own.size(); ++i) {
    if (own[i].position.y() < 0.3 || own[i].position.y() > 1.7) continue;  // away from the ends
    ++compared;
    EXPECT_NEAR(moved[i].radius, 0.5 * own[i].radius, 0.15 * own[i].radius) << i;
    EXPECT_LT(std::hypot(moved[i].position.x(), moved[i].position.z()), 0.3 * own[i].radius) << i;
    EXPECT_NEAR(moved[i].ringVariation, own[i].ringVariation, 0.05) << i;
  }
  EXPECT_GT(compared, 5);
  // One centroid position per voxel or an error.
  pulled.pop_back();
  EXPECT_THROW(skeleton::levelSetNodes(graph, levels, o, &pulled), OptionsError);
}

TEST(Skeleton, LeafOnNodesKnowHowFlatTheirPieceIs) {
  // The leaf-plane test's verdict per piece: the blade's nodes are leaf pieces, the stem's are not;
  // without the test (leaf-off settings) every node reads 0.
  // Also on a scan three times denser (~20 points per voxel) with the test on all points and thinned
  // to the default 8 per voxel: the verdicts hold.
  auto o = skeleton::leafOnSkeletonOptions();
  o.graph.voxelSize = 0.03;
  ASSERT_EQ(o.leafPlaneMaxPointsPerVoxel, 8);
  for (const int perVoxel : {0, 8})
    for (const int density : {1, 3}) {
      const auto cloud = stemWithBlade(density);
      o.leafPlaneMaxPointsPerVoxel = perVoxel;
      const auto leafOn = skeleton::extractSkeleton(cloud, o);
      double stemSum = 0, bladeSum = 0;
      int stemCount = 0, bladeCount = 0;
      for (const auto& n : leafOn.rawNodes) {
        EXPECT_GE(n.flatFraction, 0.0f);
        EXPECT_LE(n.flatFraction, 1.0f);
        if (n.distance > 0.3 && n.distance < 1.6) {
          stemSum += n.flatFraction;
          ++stemCount;
        } else if (n.distance > 2.2) {
          bladeSum += n.flatFraction;
          ++bladeCount;
        }
      }
      ASSERT_GT(stemCount, 5);
      ASSERT_GT(bladeCount, 5);
      EXPECT_LT(stemSum / stemCount, 0.3) << perVoxel;
      EXPECT_GT(bladeSum / bladeCount, 0.7) << perVoxel;
      std::printf("density %d, points per voxel %d: mean flat fraction stem %.2f, blade %.2f\n", density, perVoxel,
                  stemSum / stemCount, bladeSum / bladeCount);
    }
  const auto cloud = stemWithBlade();
  o.leafPlaneMaxPointsPerVoxel = -1;
  EXPECT_THROW(skeleton::extractSkeleton(cloud, o), OptionsError);
  o.leafPlaneMaxPointsPerVoxel = 8;
  o.leafEntryPositions = false;
  for (const auto& n : skeleton::extractSkeleton(cloud, o).rawNodes) EXPECT_EQ(n.flatFraction, 0.0f);
}

TEST(Skeleton, LeafPiecesAreNotFitted) {
  // The automatic sketch skips the circle fit of nodes that are mostly leaf (their slice holds
  // blades, not a branch) and fits the others; 1 fits every node; out of range is refused.
  const auto cloud = stemWithBlade();
  auto o = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOn);
  o.skeleton.graph.voxelSize = 0.03;
  ASSERT_LT(o.maxFitFlatFraction, 1.0);
  const auto r = skeleton::autoSkeletonSketch(cloud, o);
  int skipped = 0, tried = 0;
  for (std::size_t i = 0; i < r.model.size(); ++i) {
    const bool leaf = r.skeleton.nodes[i].flatFraction > o.maxFitFlatFraction;
    const bool skippedAsLeaf = r.fits[i].reason.find("leaf") != std::string::npos;
    EXPECT_EQ(leaf, skippedAsLeaf) << "node " << i;
    if (leaf) {
      EXPECT_EQ(r.fits[i].status, fit::NodeStatus::Skipped);
      EXPECT_FALSE(r.fitAccepted[i]);
    }
    skipped += leaf;
    tried += !leaf;
  }
  EXPECT_GT(skipped, 0);
  EXPECT_GT(tried, 0);
  o.maxFitFlatFraction = 1.0;
  for (const auto& f : skeleton::autoSkeletonSketch(cloud, o).fits) EXPECT_EQ(f.reason.find("leaf"), std::string::npos);
  o.maxFitFlatFraction = 1.5;
  EXPECT_THROW(skeleton::autoSkeletonSketch(cloud, o), OptionsError);
}

// The thesis's sphere pattern aims every ray at the tree's centre: the trunk's base gets a few
// points, farther apart than the voxel size, so the grid leaves it as single voxels. Sparse links
// (each voxel joined to its nearest voxels in other pieces) keep it attached, and the root is found
// at the base instead of at the dense part's lowest voxel.
TEST(Skeleton, SparseTrunkBaseKeepsTheRootAtTheBase) {
  const std::vector<test::Cyl> trunk = {{Vec3(0, 0, 0), Vec3(0, 2, 0), 0.06, -1}};
  const auto dense = test::sampleCylinders(trunk, 0.008, 0.001, 3);
  geom::PointCloud cloud;
  std::size_t lower = 0;
  for (const auto& p : dense.positions) {
    if (p.y() >= 1.0) {
      cloud.positions.push_back(p);
    } else if (lower++ % 40 == 0) {  // ~40x sparser below y = 1
      cloud.positions.push_back(p);
    }
  }
  skeleton::SkeletonOptions o;
  o.graph.voxelSize = 0.02;
  const auto linked = skeleton::extractSkeleton(cloud, o);
  ASSERT_FALSE(linked.nodes.empty());
  EXPECT_GT(linked.graph.sparseLinks, 0u);
  EXPECT_LT(linked.nodes[0].position.y(), 0.15);
  o.graph.sparseLinkNeighbours = 0;
  const auto gridOnly = skeleton::extractSkeleton(cloud, o);
  ASSERT_FALSE(gridOnly.nodes.empty());
  EXPECT_EQ(gridOnly.graph.sparseLinks, 0u);
  EXPECT_GT(gridOnly.nodes[0].position.y(), 0.5);
}

// The root node sits at the trunk's foot (the lowest point of the root region), not at the
// centroid of the first level set half a bin above it.
TEST(Skeleton, TheRootIsAtTheTrunksFoot) {
  const std::vector<test::Cyl> trunk = {{Vec3(0, 0, 0), Vec3(0, 2, 0), 0.06, -1}};
  const auto cloud = test::sampleCylinders(trunk, 0.008, 0.001, 5);
  double lowest = 1e9;
  for (const auto& p : cloud.positions) lowest = std::min(lowest, p.y());
  skeleton::SkeletonOptions o;
  o.graph.voxelSize = 0.02;
  const auto s = skeleton::extractSkeleton(cloud, o);
  ASSERT_FALSE(s.nodes.empty());
  EXPECT_NEAR(s.nodes[0].position.y(), lowest, 1e-9);
  EXPECT_LT(std::hypot(s.nodes[0].position.x(), s.nodes[0].position.z()), 0.06);
  ASSERT_GE(s.nodes.size(), 2u);
  EXPECT_GT(s.nodes[1].position.y(), s.nodes[0].position.y() + o.graph.voxelSize);
}

// A branch bent down below the foot (a bush's stem arching to the ground, a conifer's lowest
// branch) holds the tree's lowest points; the root stays at the stem's foot, not at that tip.
TEST(Skeleton, ABranchBentBelowTheFootIsNoRoot) {
  // A bush: a short foot, seven stems leaning out from it (no vertical stem to find) and a thin
  // eighth arching out and down to 10 cm below the foot.
  std::vector<test::Cyl> bush = {{Vec3(0, 0, 0), Vec3(0, 0.04, 0), 0.12, -1}};
  for (int k = 0; k < 7; ++k) {
    const double a = 2 * std::numbers::pi * k / 7;
    bush.push_back({Vec3(0, 0.04, 0), Vec3(1.1 * std::cos(a), 3.0, 1.1 * std::sin(a)), 0.05, 0});
  }
  bush.push_back({Vec3(0, 0.04, 0), Vec3(0.9, 0.45, 0.15), 0.012, 0});
  bush.push_back({Vec3(0.9, 0.45, 0.15), Vec3(1.8, -0.1, 0.3), 0.012, 8});
  const auto cloud = test::sampleCylinders(bush, 0.008, 0.001, 7);
  skeleton::SkeletonOptions o;
  o.graph.voxelSize = 0.02;
  const auto s = skeleton::extractSkeleton(cloud, o);
  ASSERT_FALSE(s.nodes.empty());
  EXPECT_LT(std::hypot(s.nodes[0].position.x(), s.nodes[0].position.z()), 0.15) << s.nodes[0].position.transpose();
  EXPECT_LT(std::abs(s.nodes[0].position.y()), 0.1) << s.nodes[0].position.transpose();
  // The bent branch is still modelled, down to its tip.
  double lowest = 1e9;
  for (const auto& n : s.nodes) lowest = std::min(lowest, n.position.y());
  EXPECT_LT(lowest, -0.05);
}

// At a fork the stem goes on into the child carrying the most wood, not the one with the longest
// path: here a long bare limb (1.2) and a bushier continuation (three limbs of 0.8 from a short
// piece: shorter path, more wood). The bushy child keeps branch order 0.
TEST(Skeleton, TheStemContinuesIntoTheChildCarryingTheMostWood) {
  std::vector<skeleton::SkeletonNode> raw;
  auto add = [&](int parent, Vec3 p) {
    skeleton::SkeletonNode n;
    n.parent = parent;
    n.position = p;
    n.radius = 0.01;
    n.support = 100;
    n.level = parent < 0 ? 0 : raw[parent].level + 1;
    raw.push_back(n);
    return static_cast<int>(raw.size()) - 1;
  };
  int cur = add(-1, Vec3(0, 0, 0));
  for (int k = 1; k <= 5; ++k) cur = add(cur, Vec3(0, 0.1 * k, 0));
  const int fork = cur;
  int limb = fork;
  for (int k = 1; k <= 12; ++k) limb = add(limb, Vec3(0.1 * k, 0.5 + 0.05 * k, 0));
  int stem = add(fork, Vec3(0, 0.6, 0));
  stem = add(stem, Vec3(0, 0.7, 0));
  for (double dx : {-0.1, 0.0, 0.1}) {
    int b = stem;
    for (int k = 1; k <= 8; ++k) b = add(b, Vec3(dx * k / 8.0 - 0.02 * k, 0.7 + 0.1 * k, 0.03 * dx * k));
  }
  for (std::size_t i = 0; i < raw.size(); ++i)
    if (raw[i].parent >= 0) raw[raw[i].parent].children.push_back(static_cast<std::int32_t>(i));
  const auto nodes = skeleton::simplifySkeleton(raw, 0.02, 0.05, skeleton::SkeletonOptions{});
  ASSERT_GE(skeleton::countBranchPoints(nodes), 2u);
  // The order-0 chain reaches the bushy top (y > 1.2), and the bare limb's tip (x = 1.2) is order 1.
  double topOfStem = 0;
  for (const auto& n : nodes)
    if (n.branchOrder == 0) topOfStem = std::max(topOfStem, n.position.y());
  EXPECT_GT(topOfStem, 1.2);
  for (const auto& n : nodes)
    if (n.position.x() > 1.1) EXPECT_EQ(n.branchOrder, 1);
}

TEST(Skeleton, ASideBranchJoinsItsParentWhereItsAxisMeetsIt) {
  // A trunk with a side branch leaving it at 35 degrees from the vertical at y = 2. The level sets
  // separate the branch from the trunk only well above the junction, where the two no longer
  // touch; linked there, the branch's first segment runs sideways (a "shelf"). Re-anchored, it
  // starts near the true junction and follows the branch's direction.
  const Vec3 junction(0, 2, 0);
  const Vec3 dir = Vec3(std::sin(35 * M_PI / 180), std::cos(35 * M_PI / 180), 0);
  const std::vector<test::Cyl> cyls = {{Vec3(0, 0, 0), Vec3(0, 5, 0), 0.15, -1},
                                       {junction, junction + 2.5 * dir, 0.1, 0}};
  const auto cloud = test::sampleCylinders(cyls, 0.02, 0.002, 11);
  const auto s = skeleton::extractSkeleton(cloud);
  ASSERT_EQ(skeleton::countEnds(s.nodes), 2u);
  // The side branch: the chain from the tip whose end lies off the trunk, down to its fork.
  std::int32_t tip = -1;
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    if (s.nodes[i].children.empty() && s.nodes[i].position.x() > 0.5) tip = static_cast<std::int32_t>(i);
  ASSERT_GE(tip, 0);
  std::int32_t first = tip;
  while (s.nodes[s.nodes[first].parent].children.size() < 2) first = s.nodes[first].parent;
  const Vec3 fork = s.nodes[s.nodes[first].parent].position;
  EXPECT_LT(std::abs(fork.y() - junction.y()), 0.45) << "fork at y = " << fork.y();
  const Vec3 firstSegment = (s.nodes[first].position - fork).normalized();
  EXPECT_GT(firstSegment.dot(dir), std::cos(20 * M_PI / 180)) << "first segment " << firstSegment.transpose();
}

TEST(Skeleton, EachTipReachesItsBranchsLastPoints) {
  // A level set's centroid sits half a level set before the branch's last points; the end nodes
  // go on to the farthest wood of their pieces, so the tubes do not stop short at every tip.
  const auto cyls = test::yTree();
  const auto cloud = test::sampleCylinders(cyls, 0.02, 0.003, 7);
  const auto s = skeleton::extractSkeleton(cloud);
  ASSERT_EQ(skeleton::countEnds(s.nodes), 2u);
  for (const auto& n : s.nodes) {
    if (!n.children.empty()) continue;
    const test::Cyl& c = n.position.x() < 0 ? cyls[1] : cyls[2];
    const Vec3 axis = (c.b - c.a).normalized();
    // Along the branch: at most a quarter of a level set short of its end (and not past it by more).
    const double along = (n.position - c.b).dot(axis);
    EXPECT_GT(along, -0.25 * s.levels.binWidth) << n.position.transpose();
    EXPECT_LT(along, 0.5 * s.levels.binWidth) << n.position.transpose();
  }
}

TEST(Skeleton, AForkNearItsBranchsStartStaysOnItsBranch) {
  // A limb leaves the trunk sideways and forks soon after, within its fork zone's reach of the
  // trunk. Forks are put back on their branch's line below them; that line stopped nowhere, took
  // the trunk's nodes, and put the limb's fork on the trunk's axis (a tube from the trunk
  // straight to the twigs). It stops below the previous fork now.
  const Vec3 junction(0, 2, 0), forkAt(0.5, 2.05, 0);
  const std::vector<test::Cyl> cyls = {{Vec3(0, 0, 0), Vec3(0, 4, 0), 0.15, -1},
                                       {junction, forkAt, 0.12, 0},
                                       {forkAt, forkAt + Vec3(0.9, 0.2, 0.7), 0.08, 1},
                                       {forkAt, forkAt + Vec3(0.9, 0.2, -0.7), 0.08, 1}};
  const auto cloud = test::sampleCylinders(cyls, 0.02, 0.002, 5);
  const auto s = skeleton::extractSkeleton(cloud);
  ASSERT_GE(skeleton::countEnds(s.nodes), 3u);
  // The fork the two twigs' tips meet at.
  std::vector<std::int32_t> tips;
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    if (s.nodes[i].children.empty() && s.nodes[i].position.x() > 1.0) tips.push_back(static_cast<std::int32_t>(i));
  ASSERT_EQ(tips.size(), 2u);
  std::vector<std::int32_t> path;
  for (std::int32_t a = tips[0]; a >= 0; a = s.nodes[a].parent) path.push_back(a);
  std::int32_t fork = tips[1];
  while (std::find(path.begin(), path.end(), fork) == path.end()) fork = s.nodes[fork].parent;
  const Vec3 p = s.nodes[fork].position;
  std::printf("twigs' fork at %.3f %.3f %.3f\n", p.x(), p.y(), p.z());
  EXPECT_GT(p.x(), 0.35) << "the twigs' fork at " << p.transpose();
  EXPECT_LT((p - forkAt).norm(), 0.3) << "the twigs' fork at " << p.transpose();
}

TEST(Skeleton, AShortTwigStandingOutOfItsParentIsKept) {
  // A twig reaching 0.2 out of a trunk of radius 0.15: shorter than a spur measured from the
  // trunk's axis (three radii, 0.45), but two level sets out of the trunk's surface. The spur
  // rule alone dropped it with the surface bumps it is meant for.
  const std::vector<test::Cyl> cyls = {{Vec3(0, 0, 0), Vec3(0, 3, 0), 0.15, -1},
                                       {Vec3(0, 1.5, 0), Vec3(0.35, 1.6, 0), 0.03, 0}};
  const auto cloud = test::sampleCylinders(cyls, 0.015, 0.001, 3);
  skeleton::SkeletonOptions o;
  o.graph.voxelSize = 0.04;
  const auto s = skeleton::extractSkeleton(cloud, o);
  ASSERT_LT(0.35, std::max(o.spurLengthRadii * 0.15, o.spurLengthBins * s.levels.binWidth) + 0.01);
  EXPECT_EQ(skeleton::countEnds(s.nodes), 2u);
  o.twigOutBins = 0;
  EXPECT_EQ(skeleton::countEnds(skeleton::extractSkeleton(cloud, o).nodes), 1u);
}

TEST(Skeleton, ABushsStemsAreNotTrackedAsOneStem) {
  // A bush scanned by 4 stations (0.2°, 2 mm noise; the matrix's tls-noise-2mm case of this tree):
  // a circle through its several stems held 156 of 238 of a slab's voxels and covered 324° of
  // the ring, and was tracked as one stem of radius 1.44 where the stems are 0.14–0.22 thick
  // (backward RMS 0.50 % of the diagonal, against 0.13 % with no stem). The stems' near sides lay
  // well inside that circle (28 % of the voxels): a stem's cross-section is empty inside.
  const auto dir = test::sharedDataDir() / "trees";
  if (!std::filesystem::exists(dir / "bush_2_s45590.branches.obj")) GTEST_SKIP() << "no " << dir.string();
  const geom::TriMesh mesh = io::readMesh(dir / "bush_2_s45590.branches.obj");
  scan::TlsScanOptions t;
  t.stationCount = 4;
  t.stepDeg = 0.2;
  t.rangeNoise = 0.002;
  t.unitMetres = 0.1;
  t.up = geom::UpAxis::Y;
  const std::vector<geom::TriMesh> meshes{mesh};
  const geom::PointCloud cloud = scan::tlsScan(meshes, t).cloud;
  skeleton::SkeletonOptions o;
  const auto s = skeleton::extractSkeleton(cloud, o);
  double thickest = 0;
  for (const auto& n : s.rawNodes)
    if (n.stem) thickest = std::max(thickest, n.radius);
  EXPECT_LT(thickest, 0.5) << "a tracked stem of radius " << thickest;
}

TEST(Skeleton, ANarrowForksLimbsAreApartWhereTheirTubesAre) {
  // Two limbs of radius 0.1 leave a trunk 17° apart: their axes are 0.3 × h apart at h above the
  // junction, and their tubes stop overlapping at h = 0.67. A level set holds both limbs as one
  // piece while their surfaces are within a voxel or two, and that piece's node sat between the
  // limbs, off the wood, with the fork at its top. Cut along the limbs' lines, the pieces are one
  // per limb down to where the tubes overlap, and the fork is there. Sparsely sampled (a point
  // every 4 cm, voxels of 10 cm, as on a real scan's crown) the merged pieces reach highest.
  const Vec3 junction(0, 2, 0);
  const std::vector<test::Cyl> cyls = {{Vec3(0, 0, 0), junction, 0.15, -1},
                                       {junction, Vec3(-0.45, 5, 0), 0.1, 0},
                                       {junction, Vec3(0.45, 5, 0), 0.1, 0}};
  const auto cloud = test::sampleCylinders(cyls, 0.04, 0.005, 1);
  struct Fork {
    double height = -1;  // of the fork node
    double offAxes = 0;  // mean distance of the nodes between 2.6 and 3.6 high to the true axes
  };
  auto fork = [&](bool split) {
    skeleton::SkeletonOptions o;
    o.graph.voxelSize = 0.1;
    o.splitMergedForks = split;
    const auto s = skeleton::extractSkeleton(cloud, o);
    EXPECT_EQ(skeleton::countBranchPoints(s.nodes), 1u);
    Fork f;
    int n = 0;
    for (const auto& node : s.nodes) {
      if (node.children.size() >= 2) f.height = node.position.y();
      if (node.position.y() > 2.6 && node.position.y() < 3.6) {
        f.offAxes += test::distanceToAxes(cyls, node.position);
        ++n;
      }
    }
    f.offAxes /= std::max(n, 1);
    std::printf("split %d: fork at %.3f, nodes between 2.6 and 3.6 %.3f off the axes\n", split, f.height, f.offAxes);
    return f;
  };
  const Fork split = fork(true), merged = fork(false);
  const double apart = junction.y() + 0.2 / 0.3;
  EXPECT_GT(split.height, apart - 0.1);
  EXPECT_LT(split.height, apart + 0.4);
  EXPECT_LT(split.offAxes, 0.06);
  EXPECT_GT(merged.height, split.height + 0.25);
  EXPECT_GT(merged.offAxes, 1.5 * split.offAxes);
}

// The skeleton of a cloud of ../shared/data/real (z up) with `o`, and its lowest height in *foot;
// none when the file is absent.
std::optional<skeleton::Skeleton> skeletonOfRealCloud(const std::string& name, skeleton::SkeletonOptions o,
                                                      double* foot) {
  const std::filesystem::path file = test::sharedDataDir() / "real" / name;
  if (!std::filesystem::exists(file)) return std::nullopt;
  const geom::PointCloud cloud = io::readPointCloud(file);
  o.up = geom::UpAxis::Z;
  *foot = cloud.bounds().min.z();
  return skeleton::extractSkeleton(cloud, o);
}

// A piece touching two pieces of the level below grows out of the larger. voxr_Tree_t0 of
// ../shared/data/real forks 1.5 m above its foot; a 2 cm limb leaves the 4 cm stem there and leans
// on it again 0.7 m higher, and the shortest path from the root to the stem above ran through the
// limb: the stem's branch took the limb (up to 0.2 m off the stem's axis) and the stem itself
// became a side branch.
TEST(Skeleton, TheStemBranchStaysOnTheStemWhereALimbLeansOnIt) {
  double foot = 0;
  const auto s = skeletonOfRealCloud("voxr_Tree_t0.asc", skeleton::SkeletonOptions{}, &foot);
  if (!s) GTEST_SKIP() << "no voxr_Tree_t0.asc in ../shared/data/real";
  // Over the fork (1.8-2.3 m above the foot) the stem's axis stands at (0.04, 0.10).
  int seen = 0;
  for (const auto& n : s->nodes) {
    const double h = n.position.z() - foot;
    if (n.branchOrder != 0 || h < 1.8 || h > 2.3) continue;
    ++seen;
    EXPECT_LT(std::hypot(n.position.x() - 0.04, n.position.y() - 0.10), 0.08) << "at " << h << " m";
  }
  EXPECT_GE(seen, 3);
}

// A swollen base (a palm's, a root flare) twice the stem's radius: the stem cannot be followed
// from a circle that wide (each slab may narrow to 0.6 of the last), so the tracker starts again
// from a slab above it. The palm of ../shared/data/real: a slice 1.3 m above its base is a circle
// of about 0.17 m radius; before, no stem was tracked and the crown's fits gave it 0.34 m.
TEST(Skeleton, APalmsStemIsTrackedAboveItsSwollenBase) {
  double base = 0;
  const auto s = skeletonOfRealCloud("pytlidar_tree_1.las", skeleton::leafOnSkeletonOptions(), &base);
  if (!s) GTEST_SKIP() << "no pytlidar_tree_1.las in ../shared/data/real";
  int measured = 0;
  for (const auto& n : s->nodes) {
    const double h = n.position.z() - base;
    if (!n.stem || h < 1.0 || h > 4.0) continue;
    ++measured;
    EXPECT_NEAR(n.radius, 0.17, 0.05) << "at " << h << " m";
  }
  EXPECT_GE(measured, 5);
}
