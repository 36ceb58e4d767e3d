// Internal: smooth branch axes. A skeleton node's position is the centroid of its level-set
// piece; where a branch is sampled sparsely or from one side, that centroid lies on the scanned
// surface, not on the axis, and consecutive nodes alternate sides: the tube zigzags (a "lumpy
// corkscrew" on a sparse trunk, staircase limbs in a crown). A fitted circle's centre is an axis
// estimate; a centroid is a poor one. Each branch's axis is therefore re-estimated by a local,
// weighted, robust line fit of the node positions against arc length (LOESS of degree 1): fitted
// nodes weigh most, the branch keeps its course and its bends longer than the window, and a
// single node off the line (a fork's centroid pulled towards its side branch) is down-weighted.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/skeleton_sketch.h"

namespace treesketch::skeleton::detail {

/// Branches as node chains: each starts at the root or at a child whose branch order differs
/// from its parent's, and follows the child of the same order. Nodes are parent-first.
std::vector<std::vector<std::int32_t>> branchChains(const std::vector<SkeletonNode>& nodes);

/// New positions for `nodes` (parent-first): each chain's positions smoothed as above.
/// `fitted[i]` says whether node i's position is an accepted circle centre. A side branch's first
/// node is anchored at its (smoothed) parent, which it does not move. Returns one position per
/// node; with rules.halfWindowNodes == 0 the positions are returned unchanged. A fitted node
/// does not move (it weighs in its neighbours' fits); a node moves at most
/// rules.maxShiftRadii × radii[i], so a thin twig keeps its course.
std::vector<geom::Vec3> smoothAxes(const std::vector<SkeletonNode>& nodes, const std::vector<char>& fitted,
                                   const std::vector<double>& radii, const AxisRules& rules);

}  // namespace treesketch::skeleton::detail
