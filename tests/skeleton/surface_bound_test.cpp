#include "skeleton/surface_bound.h"

#include <gtest/gtest.h>

#include "synthetic_tree.h"

using namespace treesketch;
using geom::Vec3;

namespace {

/// A trunk along y (0 to 2) and a side branch from its middle, as model nodes every 0.1.
std::vector<skeleton::SkeletonNode> trunkAndBranch(double trunkRadius, double branchRadius) {
  std::vector<skeleton::SkeletonNode> nodes;
  for (int k = 0; k <= 20; ++k) {
    skeleton::SkeletonNode n;
    n.position = Vec3(0, 0.1 * k, 0);
    n.radius = trunkRadius;
    n.parent = k - 1;
    n.branchOrder = 0;
    nodes.push_back(n);
  }
  for (int k = 1; k <= 10; ++k) {
    skeleton::SkeletonNode n;
    n.position = Vec3(0.1 * k, 1.0, 0);
    n.radius = branchRadius;
    n.parent = k == 1 ? 10 : static_cast<std::int32_t>(nodes.size()) - 1;
    n.branchOrder = 1;
    nodes.push_back(n);
  }
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].parent >= 0) nodes[nodes[i].parent].children.push_back(static_cast<std::int32_t>(i));
  return nodes;
}

const std::vector<test::Cyl> kTree = {{Vec3(0, 0, 0), Vec3(0, 2, 0), 0.10, -1}, {Vec3(0, 1, 0), Vec3(1, 1, 0), 0.02, 0}};
constexpr double kNoise = 0.002;

}  // namespace

TEST(SurfaceBound, TubesOnTheirPointsKeepTheirRadii) {
  // The model is the truth: its points lie on its surface with the noise, and no radius moves.
  const geom::PointCloud cloud = test::sampleCylinders(kTree, 0.01, kNoise, 3);
  auto model = trunkAndBranch(0.10, 0.02);
  const auto stats = skeleton::detail::boundRadiiBySurface(model, cloud, kNoise, 0.02, 5);
  EXPECT_GT(stats.nodesWithEvidence, 25u);
  EXPECT_EQ(stats.nodesThinned, 0u);
  for (std::size_t i = 0; i < model.size(); ++i) EXPECT_DOUBLE_EQ(model[i].radius, i <= 20 ? 0.10 : 0.02) << i;
}

TEST(SurfaceBound, ABranchThreeTimesTooThickComesBackToItsPoints) {
  // The side branch's tube is three times the wood its points show (a fit to a shell of noise);
  // the trunk is right. The branch comes back to within the margin of its surface, the trunk stays.
  const geom::PointCloud cloud = test::sampleCylinders(kTree, 0.01, kNoise, 4);
  auto model = trunkAndBranch(0.10, 0.06);
  const auto stats = skeleton::detail::boundRadiiBySurface(model, cloud, kNoise, 0.02, 5);
  EXPECT_GE(stats.nodesThinned, 8u);
  for (std::size_t i = 0; i <= 20; ++i) EXPECT_DOUBLE_EQ(model[i].radius, 0.10) << i;
  for (std::size_t i = 22; i < model.size(); ++i) {
    EXPECT_LT(model[i].radius, 0.02 + 4 * kNoise + 1e-9) << i;
    EXPECT_GT(model[i].radius, 0.02 - 2 * kNoise) << i;
  }
}

TEST(SurfaceBound, ABranchStartsNoThickerThanItsParent) {
  const geom::PointCloud cloud;  // no points: only the fork's cap acts
  auto model = trunkAndBranch(0.05, 0.08);
  skeleton::detail::boundRadiiBySurface(model, test::sampleCylinders(kTree, 0.5, 0, 1), kNoise, 0.02, 5);
  EXPECT_DOUBLE_EQ(model[21].radius, 0.05);
}

TEST(SurfaceBound, TheNoiseIsTheMedianResidualOfTheAcceptedFits) {
  std::vector<fit::NodeResult> fits(5);
  const double rms[] = {0.001, 0.003, 0.1, 0.002, 0.004};
  for (int i = 0; i < 5; ++i) fits[i].rms = rms[i];
  EXPECT_DOUBLE_EQ(skeleton::detail::measuredNoise(fits, {1, 1, 0, 1, 1}, -1), 0.003);
  EXPECT_DOUBLE_EQ(skeleton::detail::measuredNoise(fits, {1, 0, 0, 0, 1}, -1), -1);  // too few fits
}
