#include "treesketch/skeleton/voxel_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "synthetic_tree.h"
#include "treesketch/util/error.h"

using namespace treesketch;
using geom::Vec3;

TEST(VoxelGraph, EmptyCloudGivesEmptyGraph) {
  const auto g = skeleton::buildVoxelGraph(geom::PointCloud{});
  EXPECT_EQ(g.size(), 0u);
  EXPECT_EQ(g.edgeCount(), 0u);
}

TEST(VoxelGraph, RejectsNaNAndBadOptions) {
  geom::PointCloud cloud;
  cloud.positions = {Vec3(0, 0, 0), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0)};
  EXPECT_THROW(skeleton::buildVoxelGraph(cloud), OptionsError);
  cloud.positions.pop_back();
  skeleton::VoxelGraphOptions o;
  o.voxelSize = -1;
  EXPECT_THROW(skeleton::buildVoxelGraph(cloud, o), OptionsError);
  o = {};
  o.reach = 0;
  EXPECT_THROW(skeleton::buildVoxelGraph(cloud, o), OptionsError);
}

TEST(VoxelGraph, VoxelsEdgesAndFeatures) {
  // A dense thin line (linear) and a flat square patch (planar), far apart.
  geom::PointCloud cloud;
  for (int i = 0; i < 400; ++i) cloud.positions.emplace_back(0, 0.005 * i, 0);
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) cloud.positions.emplace_back(5 + 0.005 * i, 0, 0.005 * j);
  skeleton::VoxelGraphOptions o;
  o.voxelSize = 0.02;
  o.maxGapVoxels = 0;
  const auto g = skeleton::buildVoxelGraph(cloud, o);
  EXPECT_EQ(g.voxelSize, 0.02);
  ASSERT_GT(g.size(), 100u);
  EXPECT_EQ(g.pointVoxel.size(), cloud.size());
  std::int64_t total = 0;
  for (auto c : g.pointCount) total += c;
  EXPECT_EQ(total, static_cast<std::int64_t>(cloud.size()));
  // Two pieces: the line and the patch.
  EXPECT_EQ(*std::max_element(g.piece.begin(), g.piece.end()), 1);
  // Line voxels are linear, patch voxels planar.
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (g.positions[i].x() < 1) {
      EXPECT_GT(g.linearity[i], 0.9f);
      EXPECT_GT(std::abs(g.principal[i].y()), 0.95f);
    } else if (g.positions[i].x() > 5.06 && g.positions[i].x() < 5.14 && g.positions[i].z() > 0.06 &&
               g.positions[i].z() < 0.14) {
      EXPECT_GT(g.planarity[i], 0.5f);
      EXPECT_LT(g.scattering[i], 0.05f);
    }
  }
  // Edges are symmetric and no longer than the 26-neighbourhood allows.
  for (std::size_t v = 0; v < g.size(); ++v)
    for (auto k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
      EXPECT_LT(g.weights[k], 2 * std::sqrt(3.0) * 0.02 + 1e-9);
      const auto w = g.targets[k];
      bool back = false;
      for (auto j = g.offsets[w]; j < g.offsets[w + 1]; ++j) back |= g.targets[j] == v;
      EXPECT_TRUE(back);
    }
}

TEST(VoxelGraph, BridgesAGapAlongTheBranchButNotASidewaysOne) {
  // A vertical cylinder cut by a gap of 0.12 between y = 1 and 1.12 (6 voxels), and a blob beside
  // it at the same distance but across the axis direction of the blob (a horizontal bar pointing
  // along z, offset in x).
  std::vector<test::Cyl> cyls = {{Vec3(0, 0, 0), Vec3(0, 1, 0), 0.05, -1},
                                 {Vec3(0, 1.12, 0), Vec3(0, 2, 0), 0.05, 0},
                                 {Vec3(0.2, 0.5, -0.3), Vec3(0.2, 0.5, 0.3), 0.02, 0}};
  const auto cloud = test::sampleCylinders(cyls, 0.01, 0.001, 3);
  skeleton::VoxelGraphOptions o;
  o.voxelSize = 0.02;
  // The foliage guards (the leaf-on settings; leaf-off leaves them open).
  o.maxGapVoxels = 8;
  o.coneAngleDeg = 45;
  o.minBridgeLinearity = 0.4;
  const auto g = skeleton::buildVoxelGraph(cloud, o);
  ASSERT_EQ(*std::max_element(g.piece.begin(), g.piece.end()), 2);
  ASSERT_EQ(g.bridges.size(), 1u);
  const auto& b = g.bridges[0];
  EXPECT_NEAR(b.length, 0.12, 0.05);
  // The bridge joins the two parts of the cylinder (both near the axis, on either side of the gap).
  const double y1 = g.positions[b.from].y(), y2 = g.positions[b.to].y();
  EXPECT_LT(std::min(y1, y2), 1.03);
  EXPECT_GT(std::max(y1, y2), 1.09);
  // Without the cone test (the leaf-off defaults) the bar is attached too.
  EXPECT_EQ(skeleton::buildVoxelGraph(cloud, skeleton::VoxelGraphOptions{.voxelSize = 0.02}).bridges.size(), 2u);
}

TEST(VoxelGraph, AutomaticSizeFollowsTheCloud) {
  const auto cloud = test::sampleCylinders(test::yTree(), 0.02, 0.002, 1);
  skeleton::VoxelGraphOptions o;
  const double v = skeleton::chooseVoxelSize(cloud, o);
  EXPECT_GE(v, cloud.bounds().diagonal() * o.autoDiagonalFraction - 1e-12);
  EXPECT_LT(v, 0.2);
  o.maxVoxels = 500;
  const auto g = skeleton::buildVoxelGraph(cloud, o);
  EXPECT_LE(g.size(), 500u);
  EXPECT_GT(g.voxelSize, v);
}
