// Sweeps a skeleton into a triangle mesh: each branch a tube of rings (one ring per section, in
// the plane normal to the section's axis, frames parallel-transported so rings do not twist),
// the tip closed by a flat cap, roots capped at their base. Tubes are not joined: a child starts
// on its parent's axis, inside the parent, so tubes interpenetrate at joints (like the
// third-party test trees in shared/data/trees).
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/gen/skeleton.h"
#include "treesketch/geom/tri_mesh.h"

namespace treesketch::gen {

struct BranchMeshOptions {
  /// Vertices per ring for branches of each level (index = level; the last entry is used for
  /// deeper levels). Each >= 3. Default: 12 for the trunk down to 6 for twigs.
  std::vector<int> segmentsPerLevel{12, 8, 6, 6};
};

struct BranchMesh {
  geom::TriMesh mesh;
  /// Per vertex: the branch id and the section index it belongs to (every vertex lies on a ring).
  std::vector<std::int32_t> vertexBranch;
  std::vector<std::int32_t> vertexSection;
  /// Per branch: its first triangle index and triangle count in `mesh` (contiguous).
  std::vector<std::uint32_t> branchFirstTriangle;
  std::vector<std::uint32_t> branchTriangleCount;
};

/// Builds the tube mesh of `skeleton` (world frame and metres of the skeleton). Ring vertex j of a
/// section is centre + radius * (cos(2*pi*j/n) u + sin(2*pi*j/n) v), u, v orthonormal in the
/// section's plane. Faces are counter-clockwise seen from outside. Caps are fans over the ring
/// vertices (no centre vertex), so every vertex lies exactly at `radius` from its section's axis
/// and no triangle has zero area. An empty skeleton gives an empty mesh. Throws OptionsError when
/// the skeleton is malformed (see findSkeletonProblem) or a segment count is below 3.
BranchMesh buildBranchMesh(const Skeleton& skeleton, const BranchMeshOptions& options = {});

}  // namespace treesketch::gen
