// Forks moved down to where the branches meet (private to the skeleton module).
//
// A level set cuts two limbs of a narrow fork (a V, two stems from one trunk) as one connected
// piece for as long as their surfaces lie within a voxel or two of each other: the graph joins
// them. Each such piece became one node, its centroid between the two limbs, off the wood, and
// the fork was put where the pieces finally separate, well above the real junction (the three
// real leaf-off scans lost 2–5 cm of fit on every V; rtwig's two stems ran as one tube between them).
// Seen from above the fork, though, each limb is a line: its first level-set nodes. Going down
// from the fork, every piece whose voxels fall to the limbs' lines in separate groups, while
// those lines are still more than the two radii apart (the tubes do not overlap), is split into
// one node per limb. The fork ends up at the highest piece where the limbs' tubes overlap.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/types.h"
#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton::detail {

/// Splits the pieces below each fork of `nodes` (level-set nodes from pieceNodes: parents first,
/// ordered by level; positions are the centroids of `at` over each piece) as above. Updates
/// `lv.vertexNode`, `count` (voxels per node) and `nodes`, whose order stays by level. `tube`
/// (per voxel, may be empty): the tracked stem's tube, whose pieces are never split.
void splitMergedForks(const VoxelGraph& g, GeodesicLevels& lv, const std::vector<geom::Vec3>& at,
                      const std::vector<char>& tube, const SkeletonOptions& options, std::vector<SkeletonNode>& nodes,
                      std::vector<std::uint32_t>& count);

}  // namespace treesketch::skeleton::detail
