#include "skeleton/axis_smoothing.h"

#include <gtest/gtest.h>

namespace treesketch::skeleton {
namespace {

using geom::Vec3;

/// A vertical chain of `n` nodes, one unit apart, node k offset by offsets(k) in x.
template <typename Offset>
std::vector<SkeletonNode> chain(int n, Offset offset) {
  std::vector<SkeletonNode> nodes(n);
  for (int k = 0; k < n; ++k) {
    nodes[k].parent = k - 1;
    if (k + 1 < n) nodes[k].children = {k + 1};
    nodes[k].position = Vec3(offset(k), k, 0);
  }
  return nodes;
}

TEST(AxisSmoothing, AZigzagOfCentroidsOnAThickBranchBecomesStraight) {
  // Centroids of a sparse trunk (radius 1) alternate sides of the axis x = 0 by 0.6.
  const auto nodes = chain(12, [](int k) { return k % 2 ? 0.6 : -0.6; });
  const std::vector<char> fitted(nodes.size(), 0);
  const std::vector<double> radii(nodes.size(), 1.0);
  const auto p = detail::smoothAxes(nodes, fitted, radii, AxisRules{});
  for (int k = 2; k < 10; ++k) EXPECT_LT(std::abs(p[k].x()), 0.25) << "node " << k;
  for (int k = 0; k < 12; ++k) EXPECT_NEAR(p[k].y(), k, 0.3) << "node " << k;
}

TEST(AxisSmoothing, FittedNodesStayAndNoNodeMovesMoreThanItsRadius) {
  const auto nodes = chain(12, [](int k) { return k % 2 ? 0.6 : -0.6; });
  std::vector<char> fitted(nodes.size(), 0);
  fitted[5] = 1;
  std::vector<double> radii(nodes.size(), 1.0);
  radii[8] = 0.05;  // a twig: its centroid is within 0.05 of its axis
  radii[3] = 0.3;   // a branch: within 0.3
  const auto p = detail::smoothAxes(nodes, fitted, radii, AxisRules{});
  EXPECT_EQ(p[5], nodes[5].position);
  EXPECT_LE((p[8] - nodes[8].position).norm(), 0.05 + 1e-9);
  EXPECT_GT((p[3] - nodes[3].position).norm(), 0.25);  // towards the axis, as far as its radius allows
  EXPECT_LE((p[3] - nodes[3].position).norm(), 0.3 + 1e-9);
  for (int k = 0; k < 12; ++k) EXPECT_LE((p[k] - nodes[k].position).norm(), radii[k] + 1e-9) << "node " << k;
}

TEST(AxisSmoothing, ABendLongerThanTheWindowIsKept) {
  // A bend of curvature radius 10 (ten branch radii) sampled every unit: the axis follows it
  // within a fifth of the branch radius (a chord across the nine-node window would miss by 1).
  std::vector<SkeletonNode> nodes = chain(16, [](int) { return 0.0; });
  for (int k = 0; k < 16; ++k) {
    const double a = k / 10.0;
    nodes[k].position = Vec3(10 - 10 * std::cos(a), 10 * std::sin(a), 0);
  }
  const std::vector<char> fitted(nodes.size(), 0);
  const std::vector<double> radii(nodes.size(), 1.0);
  const auto p = detail::smoothAxes(nodes, fitted, radii, AxisRules{});
  for (int k = 0; k < 16; ++k) {
    const double onCircle = (p[k] - Vec3(10, 0, 0)).norm();
    EXPECT_NEAR(onCircle, 10.0, 0.2) << "node " << k;
  }
}

TEST(AxisSmoothing, ASideBranchStartsAtItsParent) {
  // Trunk 0..5 up x = 0; a side branch 6..9 from node 3 along +x, order 1.
  std::vector<SkeletonNode> nodes = chain(6, [](int) { return 0.0; });
  for (int k = 0; k < 4; ++k) {
    SkeletonNode n;
    n.parent = k == 0 ? 3 : 6 + k - 1;
    n.branchOrder = 1;
    n.position = Vec3(k + 1, 3 + (k % 2 ? 0.4 : -0.4), 0);
    nodes.push_back(n);
  }
  nodes[3].children.push_back(6);
  for (int k = 6; k < 9; ++k) nodes[k].children = {k + 1};
  const std::vector<char> fitted(nodes.size(), 0);
  const std::vector<double> radii(nodes.size(), 1.0);
  const auto p = detail::smoothAxes(nodes, fitted, radii, AxisRules{});
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(p[k].x(), 0.0, 1e-9);
  for (int k = 6; k < 9; ++k) EXPECT_LT(std::abs(p[k].y() - 3), 0.3) << "node " << k;
  AxisRules off;
  off.halfWindowNodes = 0;
  const auto same = detail::smoothAxes(nodes, fitted, radii, off);
  for (std::size_t k = 0; k < nodes.size(); ++k) EXPECT_EQ(same[k], nodes[k].position);
}

}  // namespace
}  // namespace treesketch::skeleton
