// Internal: leaf-entry positions for the level-set centroids of leaf-on scans (see
// SkeletonOptions::leafEntryPositions): the leaf-plane test, the entry of each flat patch, and the
// convergence of leaf planes towards their twig.
#pragma once

#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton::detail {

/// Position of each voxel for the level-set centroids: a flat voxel at the first voxel of its flat
/// patch on its shortest path from the root (where the path entered the leaf: its base), moved
/// towards the meeting point of the leaf planes around it (leafConvergenceWeight); other voxels at
/// their own position. `flat` receives the plane test's verdict per voxel.
std::vector<geom::Vec3> leafEntryPositions(const geom::PointCloud& cloud, const VoxelGraph& graph,
                                           const GeodesicLevels& levels, const SkeletonOptions& options,
                                           std::vector<char>& flat);

/// Sets each node's flatFraction: the share of its piece's voxels that `flat` marks.
void setFlatFractions(const GeodesicLevels& levels, const std::vector<char>& flat, std::vector<SkeletonNode>& nodes);

}  // namespace treesketch::skeleton::detail
