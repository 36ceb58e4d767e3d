#include "skeleton/completion.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"
#include "treesketch/gen/random.h"

#include "treesketch/skeleton/skeleton_export.h"

using namespace treesketch;
using geom::Vec3;

namespace {

/// A chain of nodes along y, parent-first, each with the given radius and direction +y.
std::vector<skeleton::SkeletonNode> chain(const std::vector<Vec3>& at, double radius) {
  std::vector<skeleton::SkeletonNode> nodes(at.size());
  for (std::size_t i = 0; i < at.size(); ++i) {
    nodes[i].position = at[i];
    nodes[i].radius = radius;
    nodes[i].direction = Vec3::UnitY();
    nodes[i].parent = static_cast<std::int32_t>(i) - 1;
    if (i > 0) nodes[i - 1].children.push_back(static_cast<std::int32_t>(i));
  }
  return nodes;
}

struct Limb {
  std::vector<skeleton::SkeletonNode> nodes = chain({Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 2, 0), Vec3(0, 3, 0)}, 0.1);
  geom::CylinderModel pieces = skeleton::cylinderModelFromSkeleton(nodes);
  compare::CylinderModelIndex index{pieces};
};

}  // namespace

TEST(Completion, ATwigIsReRootedAtItsFootAndGraftedOnTheNearestNode) {
  Limb limb;
  // The part's skeleton ran from its far end (its lowest point) back to the limb: its root is the
  // twig's tip, its last node the foot beside the limb at y = 2.
  auto twig = chain({Vec3(0.6, 1.6, 0), Vec3(0.4, 1.8, 0), Vec3(0.13, 2.0, 0)}, 0.5);
  std::vector<skeleton::SkeletonNode> nodes = limb.nodes;
  ASSERT_TRUE(skeleton::detail::graftPart(nodes, twig, limb.nodes, limb.pieces, limb.index, 0.2));
  ASSERT_EQ(nodes.size(), 7u);
  EXPECT_EQ(nodes[4].position, twig[2].position);  // the foot first
  EXPECT_EQ(nodes[4].parent, 2);                   // on the limb's node at y = 2
  EXPECT_EQ(nodes[5].parent, 4);
  EXPECT_EQ(nodes[6].parent, 5);
  EXPECT_EQ(nodes[6].position, twig[0].position);  // the old root is the tip
  EXPECT_EQ(nodes[2].children, (std::vector<std::int32_t>{3, 4}));
  for (std::size_t i = 4; i < 7; ++i) {
    EXPECT_TRUE(nodes[i].grafted) << i;
    EXPECT_LE(nodes[i].radius, 0.1) << i;  // no thicker than the node it grows from
    EXPECT_EQ(nodes[i].branchOrder, 1) << i;
  }
  EXPECT_EQ(nodes[5].direction, -Vec3::UnitY());  // reversed: it now points away from the foot
}

TEST(Completion, APartAlongTheLimbsSideIsNotGrafted) {
  Limb limb;
  // 5 cm outside a 0.1 m limb along its length: the limb's own far side, not a twig.
  const auto side = chain({Vec3(0.15, 0.5, 0), Vec3(0.16, 1.5, 0), Vec3(0.15, 2.5, 0)}, 0.02);
  std::vector<skeleton::SkeletonNode> nodes = limb.nodes;
  EXPECT_FALSE(skeleton::detail::graftPart(nodes, side, limb.nodes, limb.pieces, limb.index, 0.2));
  // Farther than maxGap from the model at its nearest: a neighbour or noise.
  const auto far = chain({Vec3(0.5, 1.0, 0), Vec3(0.9, 1.2, 0)}, 0.02);
  EXPECT_FALSE(skeleton::detail::graftPart(nodes, far, limb.nodes, limb.pieces, limb.index, 0.2));
  // One node beside the limb's side: its surface too.
  const auto one = chain({Vec3(0.15, 1.0, 0)}, 0.02);
  EXPECT_FALSE(skeleton::detail::graftPart(nodes, one, limb.nodes, limb.pieces, limb.index, 0.2));
  // No node at all.
  EXPECT_FALSE(skeleton::detail::graftPart(nodes, {}, limb.nodes, limb.pieces, limb.index, 0.2));
  EXPECT_EQ(nodes.size(), limb.nodes.size());
}

TEST(Completion, AStubOfOneNodeIsATubeFromTheNodeItGrowsFrom) {
  Limb limb;
  // A short shoot 0.2 m off the limb's surface at y = 1.1 (its points one level set: one node),
  // and a twig's tip 0.15 m past the limb's end.
  const auto shoot = chain({Vec3(0.3, 1.1, 0)}, 0.5);
  const auto tip = chain({Vec3(0, 3.15, 0)}, 0.03);
  std::vector<skeleton::SkeletonNode> nodes = limb.nodes;
  ASSERT_TRUE(skeleton::detail::graftPart(nodes, shoot, limb.nodes, limb.pieces, limb.index, 0.2));
  ASSERT_TRUE(skeleton::detail::graftPart(nodes, tip, limb.nodes, limb.pieces, limb.index, 0.2));
  ASSERT_EQ(nodes.size(), 6u);
  EXPECT_EQ(nodes[4].position, shoot[0].position);
  EXPECT_EQ(nodes[4].parent, 1);  // the limb's node nearest to it, at y = 1
  EXPECT_LE(nodes[4].radius, 0.1);  // no thicker than that node
  EXPECT_EQ(nodes[5].parent, 3);  // the tip continues the limb's last node
  EXPECT_EQ(nodes[3].children, (std::vector<std::int32_t>{5}));
  for (std::size_t i = 4; i < 6; ++i) {
    EXPECT_TRUE(nodes[i].grafted) << i;
    EXPECT_EQ(nodes[i].branchOrder, 1) << i;
  }
  // The model of the grafted skeleton holds both: a tube from the limb to each.
  const geom::CylinderModel grown = skeleton::cylinderModelFromSkeleton(nodes);
  const compare::CylinderModelIndex index(grown);
  EXPECT_LT(index.signedDistance(Vec3(0.25, 1.09, 0)), 0.0);
  EXPECT_LT(index.signedDistance(Vec3(0, 3.1, 0)), 0.0);
}

TEST(Completion, AStubReachesItsTip) {
  Limb limb;
  // A shoot's points from 0.12 to 0.28 m out of the limb at y = 1 (its surface at 0.1): one level
  // set, one node at their centroid, 0.2 m out.
  geom::PointCloud points;
  for (int i = 0; i <= 4; ++i) points.positions.push_back(Vec3(0.12 + 0.04 * i, 1.0, 0.01 * (i % 2)));
  const Vec3 tip = points.positions.back();
  auto stub = chain({Vec3(0.2, 1.0, 0.005)}, 0.02);
  skeleton::detail::reachStubTip(stub, points, limb.index);
  EXPECT_EQ(stub[0].position, tip);
  // Grafted, its tube now holds the shoot's outer points too.
  std::vector<skeleton::SkeletonNode> nodes = limb.nodes;
  ASSERT_TRUE(skeleton::detail::graftPart(nodes, stub, limb.nodes, limb.pieces, limb.index, 0.2));
  const compare::CylinderModelIndex grown(skeleton::cylinderModelFromSkeleton(nodes));
  EXPECT_LT(grown.signedDistance(Vec3(0.27, 1.0, 0)), 0.02);
  // A part of two nodes is a skeleton of its own: left as it is.
  auto twig = chain({Vec3(0.2, 1.0, 0), Vec3(0.3, 1.0, 0)}, 0.02);
  const auto before = twig;
  skeleton::detail::reachStubTip(twig, points, limb.index);
  EXPECT_EQ(twig[0].position, before[0].position);
  EXPECT_EQ(twig[1].position, before[1].position);
}

TEST(Completion, UnexplainedPointsAreThoseBeyondTheMargin) {
  Limb limb;
  geom::PointCloud cloud;
  cloud.positions = {Vec3(0.1, 1, 0), Vec3(0.15, 1, 0), Vec3(0.25, 1, 0), Vec3(0, 1.5, 0.3)};
  EXPECT_EQ(skeleton::detail::unexplainedPoints(cloud, limb.index, 0.1), (std::vector<std::uint32_t>{2, 3}));
  const std::vector<std::uint32_t> among{0, 3};
  EXPECT_EQ(skeleton::detail::unexplainedPoints(cloud, limb.index, 0.1, nullptr, &among),
            (std::vector<std::uint32_t>{3}));
}

TEST(Completion, EachPieceHasItsOwnMargin) {
  // The limb's three pieces: the middle one fitted (a margin of its circle's spread, 1 cm), the
  // others with a voxel's margin (10 cm). A point 5 cm off the middle piece is a twig the level
  // sets merged into it; 5 cm off the others it is within their margin.
  Limb limb;
  geom::PointCloud cloud;
  cloud.positions = {Vec3(0.15, 0.5, 0), Vec3(0.15, 1.5, 0), Vec3(0.15, 2.5, 0), Vec3(0.105, 1.5, 0)};
  const std::vector<double> margins{0.1, 0.01, 0.1};
  EXPECT_EQ(skeleton::detail::unexplainedPoints(cloud, limb.index, 0.1, nullptr, nullptr, &margins),
            (std::vector<std::uint32_t>{1}));
  // Voxels decided at once agree.
  skeleton::VoxelGraphOptions o;
  o.voxelSize = 0.02;
  const skeleton::VoxelGraph grid = skeleton::buildVoxelGraph(cloud, o);
  EXPECT_EQ(skeleton::detail::unexplainedPoints(cloud, limb.index, 0.1, &grid, nullptr, &margins),
            (std::vector<std::uint32_t>{1}));
}

// Voxels decided at once (by the distance at their centroid and their points' spread) give the
// points measured one by one: a cloud on, inside and around the limb at every distance, on grids
// coarser and finer than the margin.
TEST(Completion, TheGridDecidesVoxelsAsThePointsWould) {
  Limb limb;
  gen::Rng rng(5);
  geom::PointCloud cloud;
  for (int i = 0; i < 20000; ++i) {
    const double a = rng.uniform(0, 2 * M_PI), r = rng.uniform(0, 0.6);
    cloud.positions.emplace_back(r * std::cos(a), rng.uniform(-0.3, 3.3), r * std::sin(a));
  }
  const std::vector<std::uint32_t> all = skeleton::detail::unexplainedPoints(cloud, limb.index, 0.05);
  ASSERT_GT(all.size(), 1000u);
  ASSERT_LT(all.size(), cloud.size() - 1000);
  for (double voxel : {0.02, 0.05, 0.12}) {
    skeleton::VoxelGraphOptions o;
    o.voxelSize = voxel;
    const skeleton::VoxelGraph grid = skeleton::buildVoxelGraph(cloud, o);
    EXPECT_EQ(skeleton::detail::unexplainedPoints(cloud, limb.index, 0.05, &grid), all) << voxel;
    std::vector<std::uint32_t> among, expected;
    for (std::uint32_t i = 0; i < cloud.size(); i += 3) among.push_back(i);
    for (std::uint32_t i : all)
      if (i % 3 == 0) expected.push_back(i);
    EXPECT_EQ(skeleton::detail::unexplainedPoints(cloud, limb.index, 0.05, &grid, &among), expected) << voxel;
    const std::vector<double> margins{0.02, 0.08, 0.05};  // a margin per piece
    EXPECT_EQ(skeleton::detail::unexplainedPoints(cloud, limb.index, 0.05, &grid, nullptr, &margins),
              skeleton::detail::unexplainedPoints(cloud, limb.index, 0.05, nullptr, nullptr, &margins))
        << voxel;
  }
}

// The voxels' shortcuts (and the index's cells) against the plain per-point test through the
// index's search, point for point, on random models of joined pieces (forks, radius steps, open
// caps at joints: where the signed distance inside is not continuous) with a random margin per
// piece (some pieces beyond the list: the common margin), on clouds about their surfaces, inside
// them and scattered, over voxels from a fifth of the margins to twice them.
TEST(Completion, TheGridAgreesWithThePointsOnRandomModels) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const geom::CylinderModel m = test::randomJoinedModel(seed, 60);
    const compare::CylinderModelIndex index(m), searched(m, false);  // the reference: no cells
    gen::Rng rng(100 + seed);
    std::vector<double> margins(m.size() - seed);  // the last `seed` pieces: the common margin
    for (double& x : margins) x = rng.uniform(0.005, 0.04);
    geom::PointCloud cloud;
    for (int i = 0; i < 30000; ++i) {
      const geom::ModelCylinder& c = m.cylinders[static_cast<std::size_t>(rng.uniformInt(m.size()))];
      const double t = rng.uniform(0, 1);
      const geom::Vec3 axis = (c.end - c.start).normalized();
      geom::Vec3 across = rng.unitVector();
      across = (across - across.dot(axis) * axis).normalized();
      const double r = c.startRadius + t * (c.endRadius - c.startRadius);
      const double off = i % 10 == 0 ? rng.uniform(-r, 0.2) : rng.normal(0, 0.02);  // deep inside to far out
      cloud.positions.push_back(c.start + t * (c.end - c.start) + std::max(0.0, r + off) * across);
    }
    for (int i = 0; i < 3000; ++i)
      cloud.positions.emplace_back(rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2));
    const double common = 0.02;
    const std::vector<std::uint32_t> plain =
        skeleton::detail::unexplainedPoints(cloud, searched, common, nullptr, nullptr, &margins);
    ASSERT_GT(plain.size(), cloud.size() / 20) << seed;
    ASSERT_LT(plain.size(), cloud.size() - cloud.size() / 5) << seed;
    std::vector<std::uint32_t> among, expected;
    for (std::uint32_t i = 0; i < cloud.size(); ++i)
      if (i % 4 != 1) among.push_back(i);
    for (std::uint32_t i : plain)
      if (i % 4 != 1) expected.push_back(i);
    for (double voxel : {0.005, 0.015, 0.04, 0.08}) {
      skeleton::VoxelGraphOptions o;
      o.voxelSize = voxel;
      const skeleton::VoxelGraph grid = skeleton::buildVoxelGraph(cloud, o);
      EXPECT_EQ(skeleton::detail::unexplainedPoints(cloud, index, common, &grid, nullptr, &margins), plain)
          << seed << " " << voxel;
      EXPECT_EQ(skeleton::detail::unexplainedPoints(cloud, index, common, &grid, &among, &margins), expected)
          << seed << " " << voxel;
    }
  }
}
