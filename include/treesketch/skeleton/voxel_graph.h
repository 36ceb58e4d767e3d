// The neighbourhood graph the skeleton is grown on: the cloud is voxel-downsampled (one vertex per
// occupied voxel, at the centroid of its points), occupied voxels that touch (26-neighbourhood, or
// a wider ring) are joined by edges weighted by their length, local shape features (PCA of each
// neighbourhood) are attached to every vertex, and pieces cut off by occlusion are bridged to the
// main piece (Xu et al. 2007: join a disconnected sub-graph if it lies within a distance and an
// angular cone of the main one). World frame, the cloud's units.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"

namespace treesketch::skeleton {

/// Tunables of the voxel graph. Lengths in voxels follow the voxel size; the measurements behind
/// the defaults: docs/notes/skeleton_options.md.
struct VoxelGraphOptions {
  /// Voxel edge length, world units; 0 = automatic: max(autoDiagonalFraction × bbox diagonal,
  /// autoSpacingFactor × point spacing), grown until at most maxVoxels voxels are occupied.
  double voxelSize = 0;
  /// Automatic size as a fraction of the bbox diagonal: 1/400 resolves the small synthetic test
  /// trees (1/250 measured a little better on the 160k-point scans).
  double autoDiagonalFraction = 1.0 / 400.0;
  /// Automatic size as a multiple of the point spacing: ≥ 2 keeps a sampled surface connected in
  /// the 26-neighbourhood.
  double autoSpacingFactor = 2.5;
  /// Most occupied voxels for the automatic size: keeps 1M-point clouds within the time budget.
  std::size_t maxVoxels = 200000;
  /// Edges join voxels whose integer coordinates differ by at most this per axis: 1, the
  /// 26-neighbourhood, is what autoSpacingFactor keeps connected (2 joins 124 neighbours).
  int reach = 1;
  /// Sparse links: every voxel is also joined to those of its this many nearest voxels (within
  /// maxGapVoxels) that lie in another grid-connected piece (0 = off). Where a scan is sparse (a
  /// trunk base or a crown seen by few rays) the grid falls apart into single voxels and these
  /// links keep it connected at the local point spacing; where it is dense, a piece's nearest
  /// voxels are its own and nothing changes. 3 measured best (2 lost a root, 6 raised the error;
  /// docs/notes/skeleton_options.md).
  int sparseLinkNeighbours = 3;
  /// Side of the cells the local shape (PCA) is measured on, voxels; a vertex takes its cell's
  /// 3×3×3 block, ~6 voxels wide: a twig's surface and some of its length.
  double shapeCellVoxels = 2.0;

  /// Occlusion gaps: a piece not connected to the main piece is bridged if its nearest voxel is
  /// within this many voxels of an already connected one (also the longest sparse link). 20 for
  /// leaf-off scans: a sparsely scanned crown or trunk base leaves gaps of 10-20 voxels (the thesis's
  /// sphere pattern at 73k rays: the root found on 7/7 tuning trees with 20, 2/7 with 8 and no
  /// sparse links); leaf-on keeps 8 (leafOnSkeletonOptions).
  double maxGapVoxels = 20.0;
  /// ...and, for gaps longer than freeGapVoxels voxels (always bridged: a missed scan line or
  /// two), the gap lies within this angle of the piece's own axis near the joint, degrees (Xu et
  /// al.). The cone and the linearity test below guard against joining leaves: leaf-off, where a
  /// piece near the tree is wood, they are open (90°, 0); leaf-on they are 45° and 0.4.
  double coneAngleDeg = 90.0;
  double freeGapVoxels = 2.5;
  /// Radius around the joint over which the piece's axis is measured, voxels: several branch
  /// widths, so that it is the branch's axis and not its surface's.
  double coneRadiusVoxels = 12.0;
  /// ...and the piece is elongated there: linearity (l1-l2)/l1 at least this (a cut-off branch is
  /// a tube; a leaf or a clump of leaves is flat or round).
  double minBridgeLinearity = 0.0;
  /// Pieces with fewer points than this are never bridged (isolated noise).
  int minBridgePoints = 3;
};

/// A bridge edge added across an occlusion gap.
struct Bridge {
  std::uint32_t from = 0;  ///< vertex on the side that was connected first
  std::uint32_t to = 0;    ///< vertex of the piece being attached
  double length = 0;       ///< world units
};

/// Undirected graph over occupied voxels, adjacency in compressed rows (both directions stored).
struct VoxelGraph {
  double voxelSize = 0;
  geom::Vec3 origin = geom::Vec3::Zero();  ///< corner of voxel (0,0,0)
  std::vector<geom::Vec3> positions;       ///< centroid of each voxel's points
  std::vector<std::int32_t> pointCount;    ///< input points in each voxel
  std::vector<std::uint32_t> pointVoxel;   ///< voxel index of each input point
  /// Local shape of each vertex's neighbourhood from the eigenvalues l1 ≥ l2 ≥ l3 of its
  /// covariance: linearity (l1-l2)/l1, planarity (l2-l3)/l1, scattering l3/l1; and the principal
  /// direction (unit). Thin branches are linear; leaves planar or scattered.
  std::vector<float> linearity, planarity, scattering;
  std::vector<geom::Vec3f> principal;
  std::vector<std::uint32_t> offsets;  ///< size = vertices + 1
  std::vector<std::uint32_t> targets;
  std::vector<float> weights;  ///< edge lengths, world units
  /// Connected piece of each vertex before bridging; pieces numbered from 0 by decreasing point
  /// count (0 = the main piece).
  std::vector<std::int32_t> piece;
  std::vector<Bridge> bridges;
  std::size_t sparseLinks = 0;  ///< edges added by VoxelGraphOptions::sparseLinkNeighbours

  std::size_t size() const { return positions.size(); }
  std::size_t edgeCount() const { return targets.size() / 2; }
};

/// Voxel size the automatic rule picks for this cloud (see VoxelGraphOptions::voxelSize), world
/// units. Returns options.voxelSize when it is > 0, and 1 for an empty or single-point cloud.
double chooseVoxelSize(const geom::PointCloud& cloud, const VoxelGraphOptions& options = {});

/// Builds the graph (voxels, features, edges, bridges). An empty cloud gives an empty graph.
/// Throws OptionsError for negative sizes or NaN/Inf coordinates.
VoxelGraph buildVoxelGraph(const geom::PointCloud& cloud, const VoxelGraphOptions& options = {});

}  // namespace treesketch::skeleton
