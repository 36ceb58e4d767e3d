// Branching skeleton of a tree from its point cloud alone (Verroust & Lazarus 1999; Xu et al.
// 2007): a voxel neighbourhood graph, geodesic distance from the root (the lowest region along the
// up axis) by Dijkstra, level sets of that distance cut into connected pieces whose centroids are
// the skeleton nodes, parents by the shortest-path tree; then spurs are dropped, foliage pruned by
// the pieces' cross-sections, forks straightened and chains simplified. Every stage is returned as
// plain data. The stages live one a file: voxel_graph.cpp, level_sets.cpp, leaf_planes.cpp (the
// leaf-on centroid positions), simplify.cpp; skeleton.cpp runs them.
//
// Why level sets rather than, say, Laplacian contraction or a space colonisation: they are linear
// in the cloud size after downsampling (1M points in well under a second), give the hierarchy
// (parents) for free, and follow a scanned surface's rings on thick stems. Known limits: branches
// that touch merge their level sets (one node between them until they separate; below a fork the
// pieces are cut along the limbs' lines down to where their tubes overlap, fork_split.h, but two
// limbs that merely cross stay merged); a fork's node sits where the level set splits, i.e. a
// little past the true junction on the child's side; centroids of one-sided (occluded) rings are
// biased towards the visible side (the circle fits that follow correct this). Foliage is the weak
// point: on leaf-on scans the default cross-section rule drops most limbs together with the
// leaves, while leafOnSkeletonOptions() follows the crown out to the twigs at the price of nodes
// half a leaf off them (leaf-entry positions cut that by a
// third).
// The measurements behind every default: docs/notes/skeleton_options.md.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"
#include "treesketch/skeleton/voxel_graph.h"
#include "treesketch/util/progress.h"

namespace treesketch::skeleton {

/// Every tunable of the skeleton after the graph (VoxelGraphOptions: the graph's). Lengths are in
/// voxels (VoxelGraph::voxelSize) or level sets (binWidthVoxels) so that they follow the cloud's
/// scale; defaults are for leaf-off scans (leafOnSkeletonOptions() for trees in leaf).
struct SkeletonOptions {
  geom::UpAxis up = geom::UpAxis::Y;  ///< the tree's up axis; the root is its lowest region along it
  VoxelGraphOptions graph;

  // ---- level sets (level_sets.cpp) ----
  /// Width of one level set of the geodesic distance, voxels: a few point spacings (Verroust & Lazarus).
  double binWidthVoxels = 2.0;
  /// Root region: the tree's voxels within this height of its lowest one, voxels (the stem's base).
  double rootHeightVoxels = 1.5;
  /// Smallest node radius, voxels: a piece one voxel across has no measurable spread about its axis.
  double minRadiusVoxels = 0.25;
  /// Track the stem from its base by circle fits and make each level set's voxels in its tube one
  /// piece (stem_tracking.h): on a sparsely scanned trunk a level set's ring breaks into arcs,
  /// and each arc went on as a thin chain up the trunk's surface beside a one-sided trunk node.
  bool trackStem = true;
  /// Cut the pieces below a fork that hold both its limbs into one piece per limb, down to where
  /// the limbs' tubes overlap (fork_split.h): a level set joins two limbs whose surfaces are a
  /// voxel or two apart, so a narrow fork's node sat between them and too high.
  bool splitMergedForks = true;

  // ---- pruning (simplify.cpp) ----
  /// Spurs: a side sub-tree whose longest path from its fork is shorter than the largest of
  /// spurLengthRadii × the fork's radius and spurLengthBins level sets is dropped (surface bumps).
  double spurLengthRadii = 3.0;
  double spurLengthBins = 3.0;
  /// ...unless it stands out of the parent's surface (its nodes' largest distance from the
  /// parent's axis, less the parent's radius) by at least this many level sets: a short twig,
  /// where a bump or a strip of bark lies on the surface. 0 = off. In a sparse scan three level
  /// sets are 0.4 m and more, and twigs that the stations saw were dropped as spurs: 1 lowered
  /// the forward error of every condition (tls-base 0.356 → 0.322 %) and raised the real scans'
  /// share of points within ±2 cm by 1.5–2.6 points, backward within ±0.006; 0.5 raised the
  /// spurious tips at 73k rays to 2.5 per limb, 1.5–2 gained half as much
  /// (docs/notes/skeleton_options.md, "twigOutBins").
  double twigOutBins = 1.0;
  /// End nodes with less support (points) than this fraction of their parent's are dropped: the
  /// partial last level set of a tip, off the axis; 0.1 drops the slivers, and shortens branches least.
  double minEndSupportFraction = 0.1;

  // ---- forks and chains (simplify.cpp) ----
  /// The fork node and the raw nodes within forkZoneRadii × radius + one level set below it are
  /// moved onto the parent chain's line (their level sets hold the children's bases too).
  double forkZoneRadii = 3.5;
  /// Douglas–Peucker along each chain between forks and ends: a node is dropped when within
  /// max(collinearToleranceRadii × radius, collinearToleranceVoxels voxels) of its kept neighbours' line...
  double collinearToleranceRadii = 0.5;
  double collinearToleranceVoxels = 0.5;
  /// ...and kept nodes are at most max(maxSegmentRadii × radius, maxSegmentBins level sets) apart
  /// (a curved branch keeps nodes where a straight tolerance would not). One level set: a thin
  /// branch keeps a node per level set. In a sparse scan a level set is several times a thin
  /// limb's radius (and so is the collinear tolerance, through the voxel), and 4 level sets drew
  /// chords up to 0.7 m long and 3 radii off their limbs (oak_medium_s1290, 4-station TLS); 1
  /// lowered the backward error on every condition of the matrix, held-out as tuning
  /// (docs/notes/skeleton_options.md), for 1.9× the nodes.
  double maxSegmentRadii = 6.0;
  double maxSegmentBins = 1.0;
  /// Running median of the raw nodes' radii along a chain, nodes (odd; 1 = none): one noisy piece
  /// does not make a bulge.
  int radiusMedianWindow = 5;

  // ---- leaf-entry positions, for leaf-on scans (leaf_planes.cpp) ----
  /// Level-set centroids take a leaf voxel (on a flat patch) at the entry of the root's shortest
  /// path into its patch: the leaf's base, on the twig. Off by default: a stem is locally flat too.
  bool leafEntryPositions = false;
  /// A voxel is flat when a plane through its centroid holds most points within this radius, voxels
  /// (radius 2.5 and 4 measured no better).
  double leafPlaneRadiusVoxels = 3.0;
  /// Inlier band of that plane (RANSAC), voxels: above the scans' range noise, below a twig's width.
  double leafPlaneBandVoxels = 0.15;
  /// RANSAC hypotheses per voxel: 20 saved only 30-60 ms of the 1 M-point leaf-on benchmark.
  int leafPlaneHypotheses = 40;
  /// Flat: at least this share of the points lies in the band...
  double leafPlaneMinInliers = 0.3;
  /// ...spread in the plane (second principal axis) over at least this × the radius: a blade, not a line.
  double leafPlaneMinSpread = 0.1;
  /// The path stays on one patch while successive voxels are flat, their planes within this angle,
  /// degrees...
  double leafPlaneMaxAngleDeg = 45.0;
  /// ...and each lies within this distance of the next one's plane, voxels (a step off the blade).
  double leafPatchMaxOffsetVoxels = 0.5;
  /// The plane test looks at no more than this many points per voxel (an even stride in scan
  /// order; 0 = all): bounded cost on dense scans, results within the RANSAC spread.
  int leafPlaneMaxPointsPerVoxel = 8;
  /// Plane convergence (0 = entry positions alone): a flat voxel moves this fraction of the way
  /// from its entry position to the least-squares point of the leaf planes around it (on the twig).
  double leafConvergenceWeight = 1.0;
  /// Radius of "around", voxels; 0 = automatic: leafConvergenceAutoScale × the 90th percentile
  /// of the flat voxels' distances to their entry positions (a leaf's length), clamped below.
  double leafConvergenceRadiusVoxels = 0.0;
  double leafConvergenceAutoScale = 1.1;
  /// Clamp of the automatic radius, voxels: 6 below (the smallest leaves, needles, want 7-8); 20
  /// above holds the dense 1 M-point benchmark scan (it asks for 80) within its time budget.
  double leafConvergenceMinRadiusVoxels = 6.0;
  double leafConvergenceMaxRadiusVoxels = 20.0;
  /// Directions the planes leave free (eigenvalue of their normal matrix below this × the plane
  /// count: along a twig, within a lone blade) are not moved along; 0.02 measured best.
  double leafConvergenceFreeShare = 0.02;
};

/// Settings for scans of trees in leaf, applied to `base`: finer voxels (graph.autoSpacingFactor 1.5
/// instead of 2.5), level sets one voxel wide, the foliage guards on (bridges only along a piece's
/// axis within 8 voxels), partial tips dropped below half their parent's support (in a crown they
/// are leaf ends), no short side branch kept for standing out of its parent (twigOutBins 0: leaves
/// stand out too), no pieces cut along a fork's limbs (splitMergedForks off: leaf clusters are not
/// limbs) and leaf-entry positions with plane convergence. Finer pieces keep neighbouring twigs'
/// clusters apart and follow them out to the twigs. (A cross-section rule that dropped side
/// sub-trees with few thin or ring-like pieces as foliage was removed: over the leaf-on matrix it
/// changed the RMS by under 0.01 and the tips per limb by 2-9 %; docs/notes/leaf_on_skeleton.md.)
/// Not the default: on densely, randomly sampled surfaces 1.5 spacings leave holes in the voxel
/// graph that split rings into arcs (spurious forks).
SkeletonOptions leafOnSkeletonOptions(SkeletonOptions base = {});

/// One skeleton node (raw level-set piece, or a kept node after simplification).
struct SkeletonNode {
  std::int32_t parent = -1;                    ///< index in the same list; -1 for the root
  std::vector<std::int32_t> children;          ///< indices, increasing
  geom::Vec3 position = geom::Vec3::Zero();    ///< centroid of the piece, world
  geom::Vec3 direction = geom::Vec3::UnitY();  ///< unit local branch direction (away from the root)
  double radius = 0;         ///< estimated branch radius (mean distance of the piece's voxels to the axis)
  double distance = 0;       ///< geodesic distance from the root, world units
  std::int32_t level = 0;    ///< level-set index
  std::int32_t support = 0;  ///< input points in the piece(s) the node stands for
  float linearity = 0;       ///< support-weighted mean linearity of the piece's voxels
  float ringVariation = 0;   ///< std / mean of the voxels' (own) distances to the axis (ring ~ low)
  /// Share of the piece's voxels the leaf-plane test found flat (leaves; see
  /// SkeletonOptions::leafEntryPositions); 0 when the test did not run (leaf-off settings).
  float flatFraction = 0;
  /// Grafted on by the completion of the automatic model (CompletionRules in skeleton_sketch.h): a
  /// twig's node beside the limb it was merged with, where a slice holds the limb's surface too.
  /// Not fitted: its radius follows the tree's allometry and its parent (a fit there took the
  /// limb's circle and moved the twig inside the limb).
  bool grafted = false;
  /// On the tracked stem (SkeletonOptions::trackStem): its position and radius are the stem's
  /// circle fits over slabs of the cloud, a measurement and not a piece's spread.
  bool stem = false;
  std::int32_t branchOrder = 0;  ///< 0 = trunk; +1 at every fork for the side (non-main) child
  std::int32_t raw = -1;         ///< simplified nodes: the raw node it came from
};

/// Geodesic distances over the voxel graph.
struct GeodesicLevels {
  double binWidth = 0;                      ///< world units
  std::vector<std::uint32_t> rootVertices;  ///< Dijkstra sources
  std::vector<double> distance;             ///< per vertex; +inf when unreachable
  std::vector<std::int64_t> predecessor;    ///< per vertex; -1 for sources and unreachable
  std::vector<std::int32_t> level;          ///< per vertex; -1 when unreachable
  std::vector<std::int32_t> vertexNode;     ///< raw node of each vertex; -1 when none
  /// The stem tracked by circle fits (SkeletonOptions::trackStem), base first: axis points (world
  /// frame) and radii (world units); empty when none was found.
  std::vector<geom::Vec3> stemCentres;
  std::vector<double> stemRadii;
  /// The stem was found beside the tree's lowest region (a conifer's lowest branch tips on the
  /// ground): rootVertices are then the stem's foot.
  bool stemBesideRoot = false;
};

struct Skeleton {
  geom::UpAxis up = geom::UpAxis::Y;
  VoxelGraph graph;
  GeodesicLevels levels;
  std::vector<SkeletonNode> rawNodes;  ///< one per connected piece of each level set
  std::vector<SkeletonNode> nodes;     ///< after pruning and simplification; index 0 is the root
};

/// Forks (nodes with ≥ 2 children) and ends (no children) of a node list.
std::size_t countBranchPoints(const std::vector<SkeletonNode>& nodes);
std::size_t countEnds(const std::vector<SkeletonNode>& nodes);

/// Extracts the skeleton of `cloud` (world frame, any units). Returns an empty `nodes` list for an
/// empty cloud; a single node for a cloud that fits in one level set. Throws OptionsError for
/// out-of-range options or NaN/Inf coordinates.
Skeleton extractSkeleton(const geom::PointCloud& cloud, const SkeletonOptions& options = {},
                         const ProgressFn& progress = {});

/// The stages after the graph, for callers that already have one (tests, the viewer re-running
/// with other options): Dijkstra from the root region, then level-set nodes.
GeodesicLevels computeGeodesicLevels(const VoxelGraph& graph, const SkeletonOptions& options);
/// `centroids` (optional, one per voxel): the positions the pieces' centroids and radii are taken
/// over instead of the voxels' own (the leaf-entry positions); ring variation stays on the voxels'
/// own positions (the scanned shape).
std::vector<SkeletonNode> levelSetNodes(const VoxelGraph& graph, GeodesicLevels& levels, const SkeletonOptions& options,
                                        const std::vector<geom::Vec3>* centroids = nullptr);
/// Pruning (spurs, partial tips) and simplification of raw nodes. The result's index 0 is the root
/// and parents come before children.
std::vector<SkeletonNode> simplifySkeleton(const std::vector<SkeletonNode>& raw, double voxelSize, double binWidth,
                                           const SkeletonOptions& options);

}  // namespace treesketch::skeleton
