// Internal: helpers on node lists (parents before children), shared by the level-set nodes and
// their simplification.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/types.h"
#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton::detail {

/// `v` normalized, or `fallback` when `v` is (nearly) zero.
geom::Vec3 safeNormalized(const geom::Vec3& v, const geom::Vec3& fallback);

/// Children lists rebuilt from parents (increasing indices).
void linkChildren(std::vector<SkeletonNode>& nodes);

/// Longest path (world length) from each node down its subtree; nodes must be parent-first.
std::vector<double> subtreeReach(const std::vector<SkeletonNode>& nodes);
/// Total length of the segments below each node (its sub-tree's branch length, world units):
/// what the node carries.
std::vector<double> subtreeLength(const std::vector<SkeletonNode>& nodes);

/// The child continuing node i's branch: the largest `reach` (a per-node length below it: the
/// longest path, or the total length carried) plus its segment (ties: lowest index); -1 for none.
std::int32_t mainChild(const std::vector<SkeletonNode>& nodes, const std::vector<double>& reach, std::size_t i);

/// The nodes on the tracked stem (SkeletonNode::stem) made one chain, the stem's branch (order 0
/// where the stem starts at the root). A stem node whose parent is off the stem (the geodesic path
/// reached it through a branch at a whorl, so the stem's chain left the stem and came back) is
/// re-attached to the stem node below it, the one with the largest geodesic distance smaller than
/// its own; a stem node's stem child then continues its branch, and the other children start
/// branches of their own. Returns whether any node was re-attached. Nodes must be parent-first.
bool chainTrackedStem(std::vector<SkeletonNode>& nodes);

}  // namespace treesketch::skeleton::detail
