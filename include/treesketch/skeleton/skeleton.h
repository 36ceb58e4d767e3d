// Branching skeleton of a tree from its point cloud alone (Verroust & Lazarus 1999; Xu et al.
// 2007): a voxel neighbourhood graph, geodesic distance from the root (the lowest region along the
// up axis) by Dijkstra, level sets of that distance cut into connected pieces whose centroids are
// the skeleton nodes, parents by the shortest-path tree; then spurs are dropped, near-collinear
// nodes merged, and foliage pruned by local shape. Every stage is returned as plain data.
//
// Why level sets rather than, say, Laplacian contraction or a space colonisation: they are linear
// in the cloud size after downsampling (1M points in well under a second), give the hierarchy
// (parents) for free, and follow a scanned surface's rings on thick stems. Known limits: branches
// that touch merge their level sets (one node between them until they separate); a fork's node
// sits where the level set splits, i.e. a little past the true junction on the child's side;
// centroids of one-sided (occluded) rings are biased towards the visible side (the circle fits
// that follow correct this). Foliage is the weak point: on leaf-on scans (the ez-tree test trees
// are 5-11 % wood) the default cross-section rule (minTubularFraction) keeps leaves out but drops
// most limbs with them (forward RMS ~5-10 % of the diagonal); leafOnSkeletonOptions() follows the
// crown out to the twigs (forward 0.4-1.2 %) but its level sets then run through the leaf
// clusters, whose centroids lie about half a leaf off the twigs; taking leaf points near their
// leaf's base (leafEntryPositions, leafConvergenceWeight) brings the backward error from ~2 % to
// 1.3-1.4 % (mean 1.35 %).
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"
#include "treesketch/skeleton/voxel_graph.h"
#include "treesketch/util/progress.h"

namespace treesketch::skeleton {

struct SkeletonOptions {
  geom::UpAxis up = geom::UpAxis::Y;
  VoxelGraphOptions graph;
  /// Width of one level set of the geodesic distance, in voxels (Verroust & Lazarus: a few times
  /// the point spacing).
  double binWidthVoxels = 2.0;
  /// Root region: voxels of the tree (the connected set, bridges included, with the most points)
  /// within this height of its lowest one, in voxels.
  double rootHeightVoxels = 1.5;
  /// Join pieces of a level set that touch the same piece below and above (arcs of one ring split
  /// by sparse sampling or a junction) instead of making them separate nodes.
  bool mergeSplitRings = true;
  /// End nodes with fewer points than this fraction of their parent's are dropped (the partial
  /// last level set at a branch tip, whose centroid is off the axis). Leaf-off, the tip's circle
  /// fit puts that node back on the axis, and dropping it only shortens the branch. Measured on
  /// the four ez-tree trees scanned without leaves (mean over sphere / TLS, backward / forward
  /// RMS % of the diagonal, with the long-limb rule below): 0.5 gave 0.103 / 0.172, 0.25 0.103 /
  /// 0.164, 0.1 0.103 / 0.160 and 0 0.103 / 0.159. 0.1 still drops the slivers. Leaf-on, the
  /// partial tips are leaf ends, so leafOnSkeletonOptions keeps 0.5 (0 gave 1.337 / 0.836
  /// against 1.316 / 0.859).
  double minEndSupportFraction = 0.1;

  /// Spurs: a side sub-tree whose longest path from its fork is shorter than the largest of
  /// `spurLengthRadii` × the fork's radius and `spurLengthBins` level sets is dropped.
  double spurLengthRadii = 3.0;
  double spurLengthBins = 3.0;
  /// Foliage: a side sub-tree whose nodes' mean linearity (VoxelGraph::linearity, support-weighted)
  /// is below this is dropped as leaves (0 keeps everything). Leaves are planar or scattered.
  double minBranchLinearity = 0.0;
  /// Foliage by cross-section: a level-set piece is tubular when it is thin (mean distance to its
  /// axis ≤ thinRadiusVoxels voxels) or a ring (coefficient of variation of those distances ≤
  /// maxRingVariation; a noisy ring is ~0.1-0.3, a cluster of leaves a blob, ~0.5+). A side
  /// sub-tree whose tubular share (by support) is below minTubularFraction is dropped...
  double thinRadiusVoxels = 0.5;
  double maxRingVariation = 0.4;
  double minTubularFraction = 0.6;
  /// ...unless it is at least longBranchBins level sets long: then a tubular share of
  /// minTubularFractionLong is enough (the smaller of the two applies). Leaf clusters are compact:
  /// the spurs they grow are a few leaf lengths long. A real limb that is scanned sparsely or
  /// from one side is long, but at the voxel scale it is neither thin nor a ring. On real
  /// leaf-off scans the single 0.6 rule dropped limbs with tubular shares of 0.33-0.58:
  ///   - AdTree tree7: most of its limbs (8 tips, 11.9 m of branches); with this rule 36 tips and
  ///     46.2 m, every main limb (a flat 0.3 gives 45 tips, 51.3 m);
  ///   - aRchi tree 2: a whole limb (78.8 m, now 94.6 m);
  ///   - rTwig: 1.5 m of twigs (24.4 m, now 25.8 m; its QSM has 31.4 m).
  /// On the ez-tree trees without leaves the rule's forward RMS is 0.163 % (0.6 alone: 0.172 %, with
  /// the end rule above; a flat 0.3: 0.160 %), and the backward is 0.103 % in all three. The
  /// compact-cluster threshold stays at 0.6: a flat 0.3 let the leaf-clutter test grow 6 forks
  /// instead of at most 4. On the leafy ez-tree scans run with these (leaf-off) settings, sphere /
  /// TLS: backward 1.59 / 1.86 %, forward 5.0 / 4.8 % (the single 0.6 rule: 1.44 / 1.66 %, 8.5 /
  /// 10.1 %; leafOnSkeletonOptions, the settings for such scans: 1.24 / 1.40 %, 0.52 / 1.20 %).
  double longBranchBins = 10.0;
  double minTubularFractionLong = 0.3;

  /// Forks: the fork node and the raw nodes within forkZoneRadii × radius + one level set below
  /// it are moved onto the line of the parent chain below that zone (their level sets include the
  /// children's bases, which pull the centroids sideways).
  double forkZoneRadii = 3.5;

  /// Simplification of each chain between forks and ends (Douglas–Peucker): a node is dropped
  /// when it lies closer than max(collinearToleranceRadii × radius, collinearToleranceVoxels ×
  /// voxel) to the line through its kept neighbours...
  double collinearToleranceRadii = 0.5;
  double collinearToleranceVoxels = 0.5;
  /// ...and kept nodes are at most max(maxSegmentRadii × radius, maxSegmentBins level sets) apart.
  double maxSegmentRadii = 6.0;
  double maxSegmentBins = 4.0;
  /// Radius smoothing of raw nodes along a chain before simplification: running median over this
  /// many nodes (odd; 1 = none).
  int radiusMedianWindow = 5;

  /// Leaf-entry positions (for leaf-on scans; off by default). A leaf hangs from its twig by one
  /// edge, so the centroid of a level set through a leaf cluster lies half a leaf off the twig, in
  /// no particular direction (measured on the ez-tree test trees: node centres 1-3 % of the
  /// diagonal from any wood, offsets isotropic). With this rule a voxel on a flat patch (a leaf)
  /// counts at the position where the shortest path from the root entered that patch — the leaf's
  /// base, on the twig — when level-set centroids are taken; the graph, its distances and the level
  /// sets are unchanged (the leaves still connect the crown). A voxel is flat when a plane (RANSAC,
  /// inlier band 0.15 voxel) through its centroid holds at least leafPlaneMinInliers of the points
  /// within leafPlaneRadiusVoxels and their in-plane spread (second principal axis) is at least
  /// leafPlaneMinSpread × that radius; the path stays on one patch while successive voxels are flat
  /// and their planes differ by less than leafPlaneMaxAngleDeg (and lie within half a voxel of
  /// each other's plane). Measured with `treesketch evaluate` on the four ez-tree trees scanned
  /// with leaves (backward / forward RMS % of the diagonal, leafOnSkeletonOptions): sphere 1.945 /
  /// 0.475 -> 1.681 / 0.424, TLS 2.112 / 1.251 -> 1.890 / 1.204 (mean 2.03 / 0.86 -> 1.79 / 0.81),
  /// for ~1-2 s more per 160k-point scan (one RANSAC plane per voxel). With exact leaf bases (from
  /// the leaf meshes, diagnosis only) the same pipeline gives 0.66 / 0.61: finding the patches and
  /// their entry points is the limit, not the rule. Why not on by default: a stem or limb is
  /// locally flat at this radius too (leaf-off scans with it on: 0.144 / 0.180 -> 0.237 / 0.293).
  bool leafEntryPositions = false;
  double leafPlaneRadiusVoxels = 3.0;
  double leafPlaneMinInliers = 0.3;
  double leafPlaneMinSpread = 0.1;
  double leafPlaneMaxAngleDeg = 45.0;
  /// The plane test looks at no more than this many points per voxel (an even stride through each
  /// fuller voxel's points, in scan order; 0 = all): the cost per voxel stays bounded on dense
  /// scans. The leafy 1 M-point benchmark scan holds ~24 points per voxel; there the leaf-on
  /// skeleton took 1.1-1.35 s with all of them and 0.77 s with 8. On the leaf-on test trees
  /// (mean backward / forward RMS %): all 1.334 / 0.836, 16 the same (no voxel holds more),
  /// 12 1.332 / 0.849, 8 1.313 / 0.849, 6 1.326 / 0.840, 4 1.329 / 0.855 — within the spread that
  /// any change of the RANSAC samples gives.
  int leafPlaneMaxPointsPerVoxel = 8;
  /// Plane convergence (part of the leaf-entry rule; 0 = entry positions alone). The leaves of a
  /// twig radiate from it: every leaf plane passes through its base on the twig, and one quad of
  /// each crossed (double-billboard) leaf holds the twig's whole line, so leaf planes meet near
  /// the twig. Each flat voxel's position is moved from its entry position by this fraction of
  /// the way to the least-squares point nearest to the planes of the flat voxels within
  /// leafConvergenceRadiusVoxels of that entry position (directions the planes leave free — along
  /// a twig, or within a lone blade — are not moved along; the move is at most that radius).
  /// Measured with `treesketch evaluate` on the ez-tree trees scanned with leaves (mean over the
  /// four trees × sphere/TLS, backward / forward RMS % of the diagonal): entry positions alone
  /// 1.79 / 0.81; radius 14 voxels, weight 0.5 1.52 / 0.80, weight 1 1.42 / 0.82; the automatic
  /// radius (below), weight 1: 1.37 / 0.81, and 1.35 / 0.82 with the free-direction threshold at
  /// 2 % instead of 5 % of the plane count (skeleton.cpp, kFreeDirection). Also measured (same
  /// trees, weight 1): fixed radius 10 / 20 voxels 1.47 / 0.79, 1.45 / 0.88; planes around the
  /// voxel's own position instead of its entry position (weight 0.5) 1.60 / 0.90. Weight 1 needs levelSetNodes' tubular
  /// test on the voxels' own positions: on the moved positions the pine's needle-covered lower
  /// limbs read as foliage and were pruned (1.43 / 1.27).
  double leafConvergenceWeight = 1.0;
  /// 0 = automatic: leafConvergenceAutoScale × the 90th percentile of the flat voxels' distances to
  /// their entry positions (about a leaf's length), clamped to [6, 20] voxels — on the test trees
  /// 17-19 voxels for the bush's large leaves, 7-8 for the pine's needles. Measured (weight 1):
  /// fixed 14 voxels 1.42 / 0.82, automatic with scale 1.1 1.37 / 0.81, scale 1.4 1.35 / 0.87.
  /// Why 20 at most: the dense 1 M-point benchmark scan asks for 80 (its leaves span many fine
  /// voxels); at 30 its fits took 0.75 s instead of 0.49 s (more, larger nodes) and the whole run
  /// 1.86-1.92 s of the 2 s budget, at 20 1.71-1.79 s. Beyond 16 voxels the planes are thinned to
  /// one per radius/8 cell, which holds the query cost.
  double leafConvergenceRadiusVoxels = 0.0;
  double leafConvergenceAutoScale = 1.1;
};

/// Settings for scans of trees in leaf: finer voxels (1.5 point spacings instead of 2.5), level
/// sets one voxel wide instead of two, a weak cross-section rule (minTubularFraction 0.2 instead of
/// 0.6, for long sub-trees too), partial tips dropped below half their parent's support
/// (minEndSupportFraction 0.5 instead of 0.1) and leaf-entry positions (leafEntryPositions; the
/// figures below are without it), applied to `base`. In a leafy crown the level sets run through
/// the leaf clusters; finer pieces keep neighbouring twigs' clusters apart and follow them out to
/// the twigs, where the strict rule drops them together with the limbs that carry them. Measured on
/// the four ez-tree test trees scanned with leaves (backward / forward RMS % of the diagonal,
/// `treesketch evaluate`): sphere 1.65 / 8.27 -> 1.95 / 0.48, TLS 1.89 / 9.83 -> 2.11 / 1.25: far
/// more of the tree is found, at the price of tubes through leaf clusters that sit one or two leaf
/// sizes off their twigs (the backward error); with leaf-entry positions as well, sphere 1.68 /
/// 0.43 and TLS 1.90 / 1.20, and with their plane convergence (leafConvergenceWeight) sphere 1.26 /
/// 0.47, TLS 1.44 / 1.16. Why not the default: on densely sampled surfaces with random (not
/// scan-line) spacing, 1.5 spacings leave holes in the voxel graph that split rings into arcs
/// (spurious forks on the synthetic test cylinders).
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
  bool tubular = true;       ///< thin or ring-like (see SkeletonOptions::maxRingVariation)
  /// Share of the piece's voxels the leaf-plane test found flat (leaves; see
  /// SkeletonOptions::leafEntryPositions); 0 when the test did not run (leaf-off settings).
  float flatFraction = 0;
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
/// over instead of the voxels' own (the leaf-entry positions); ring variation and the tubular
/// test stay on the voxels' own positions (the scanned shape).
std::vector<SkeletonNode> levelSetNodes(const VoxelGraph& graph, GeodesicLevels& levels, const SkeletonOptions& options,
                                        const std::vector<geom::Vec3>* centroids = nullptr);
/// Pruning (spurs, foliage) and simplification of raw nodes. The result's index 0 is the root
/// and parents come before children.
std::vector<SkeletonNode> simplifySkeleton(const std::vector<SkeletonNode>& raw, double voxelSize, double binWidth,
                                           const SkeletonOptions& options);

}  // namespace treesketch::skeleton
