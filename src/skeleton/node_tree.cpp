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

namespace {

// The stem node below stem node `s`: of the stem nodes before it (parent-first, so none of them
// is below it in the tree), the one with the largest geodesic distance smaller than its own; -1
// for none.
std::int32_t stemNodeBelow(const std::vector<SkeletonNode>& nodes, const std::vector<std::int32_t>& stem,
                           std::size_t k) {
  const SkeletonNode& s = nodes[stem[k]];
  std::int32_t best = -1;
  for (std::size_t j = 0; j < k; ++j) {
    const SkeletonNode& t = nodes[stem[j]];
    if (t.distance < s.distance && (best < 0 || t.distance > nodes[best].distance)) best = stem[j];
  }
  return best;
}

}  // namespace

bool chainTrackedStem(std::vector<SkeletonNode>& nodes) {
  std::vector<std::int32_t> stem;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].stem) stem.push_back(static_cast<std::int32_t>(i));
  // Whether each node continued its parent's branch, before any re-attachment.
  std::vector<char> continued(nodes.size(), 0);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    continued[i] = nodes[i].parent >= 0 && nodes[i].branchOrder == nodes[nodes[i].parent].branchOrder;
  bool changed = false;
  for (std::size_t k = 1; k < stem.size(); ++k) {
    SkeletonNode& s = nodes[stem[k]];
    if (s.parent >= 0 && nodes[s.parent].stem) continue;
    const std::int32_t below = stemNodeBelow(nodes, stem, k);
    if (below < 0) continue;
    s.parent = below;
    changed = true;
  }
  if (!changed) return false;
  linkChildren(nodes);
  // Orders, parent-first: a stem node's first stem child continues its branch, its other children
  // start their own; elsewhere each child keeps whether it continued its parent's branch.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    SkeletonNode& n = nodes[i];
    if (n.parent < 0) {
      n.branchOrder = 0;
      continue;
    }
    const SkeletonNode& p = nodes[n.parent];
    std::int32_t stemChild = -1;
    if (p.stem)
      for (std::int32_t c : p.children)
        if (nodes[c].stem) {
          stemChild = c;
          break;
        }
    const bool main = stemChild >= 0 ? stemChild == static_cast<std::int32_t>(i) : continued[i] != 0;
    n.branchOrder = p.branchOrder + (main ? 0 : 1);
  }
  return true;
}

}  // namespace treesketch::skeleton::detail
