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
  /// Per branch: the vertices of each of its rings (the sides of its polygonal cross-sections).
  std::vector<int> branchRingVertices;
};

/// Builds the tube mesh of `skeleton` (world frame and metres of the skeleton). Ring vertex j of a
/// section is centre + radius * (cos(2*pi*j/n) u + sin(2*pi*j/n) v), u, v orthonormal in the
/// section's plane. Faces are counter-clockwise seen from outside. Caps are fans over the ring
/// vertices (no centre vertex), so every vertex lies exactly at `radius` from its section's axis
/// and no triangle has zero area. An empty skeleton gives an empty mesh. Throws OptionsError when
/// the skeleton is malformed (see findSkeletonProblem) or a segment count is below 3.
BranchMesh buildBranchMesh(const Skeleton& skeleton, const BranchMeshOptions& options = {});

/// Share of a circle's area covered by the regular polygon of `sides` vertices inscribed in it:
/// n/(2*pi)*sin(2*pi/n) (0.41 for 3 sides, 0.64 for 4, 0.83 for 6, 0.90 for 8, 1 in the limit).
/// Throws OptionsError for fewer than 3 sides.
double inscribedPolygonShare(int sides);

/// The wood the tube mesh of `skeleton` holds (the skeleton's units cubed): per branch, its
/// frustums (branchWoodVolume) scaled by inscribedPolygonShare of its ring vertex count, summed
/// (tubes overlapping at joints counted twice, as woodVolume does). This is what a scan of the mesh
/// can see: a ring of n vertices is a polygon inscribed in its section's circle. Exact for a
/// straight branch (a stack of regular-polygon frusta); where consecutive rings tilt against each
/// other the mesh's own volume differs by the tilt's second order. Throws OptionsError when `mesh`
/// has no ring count for some branch of `skeleton` (it was not built from it).
double branchMeshVolume(const Skeleton& skeleton, const BranchMesh& mesh);

}  // namespace treesketch::gen
