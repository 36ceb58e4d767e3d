#include "skeleton/node_tree.h"

#include <algorithm>

namespace treesketch::skeleton::detail {

using geom::Vec3;

// Below this length a direction is noise (coincident centroids): the caller's fallback is used.
constexpr double kShortestDirection = 1e-12;

Vec3 safeNormalized(const Vec3& v, const Vec3& fallback) {
  const double n = v.norm();
  return n > kShortestDirection ? Vec3(v / n) : fallback;
}

void linkChildren(std::vector<SkeletonNode>& nodes) {
  for (auto& n : nodes) n.children.clear();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].parent >= 0) nodes[nodes[i].parent].children.push_back(static_cast<std::int32_t>(i));
}

std::vector<double> subtreeReach(const std::vector<SkeletonNode>& nodes) {
  std::vector<double> reach(nodes.size(), 0.0);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const auto& n = nodes[i];
    if (n.parent >= 0) {
      const double viaThis = reach[i] + (n.position - nodes[n.parent].position).norm();
      reach[n.parent] = std::max(reach[n.parent], viaThis);
    }
  }
  return reach;
}

std::vector<double> subtreeLength(const std::vector<SkeletonNode>& nodes) {
  std::vector<double> length(nodes.size(), 0.0);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const auto& n = nodes[i];
    if (n.parent >= 0) length[n.parent] += length[i] + (n.position - nodes[n.parent].position).norm();
  }
  return length;
}

std::int32_t mainChild(const std::vector<SkeletonNode>& nodes, const std::vector<double>& reach, std::size_t i) {
  std::int32_t best = -1;
  double bestLength = -1;
  for (std::int32_t c : nodes[i].children) {
    const double length = reach[c] + (nodes[c].position - nodes[i].position).norm();
    if (length > bestLength) {
      bestLength = length;
      best = c;
    }
  }
  return best;
}

}  // namespace treesketch::skeleton::detail
