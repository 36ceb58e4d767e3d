// The skeleton pipeline: voxel graph (voxel_graph.cpp), geodesic level sets and their nodes
// (level_sets.cpp), leaf-entry positions for leaf-on scans (leaf_planes.cpp), pruning and
// simplification (simplify.cpp). Here: running them, validating the options, the leaf-on preset.
#include "treesketch/skeleton/skeleton.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "skeleton/checks.h"
#include "skeleton/leaf_planes.h"
#include "skeleton/node_tree.h"
#include "treesketch/util/error.h"

namespace treesketch::skeleton {

namespace detail {

void checkOptions(const SkeletonOptions& o) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw OptionsError(std::string("skeleton: ") + name + " must be > 0");
  };
  auto nonNegative = [](double v, const char* name) {
    if (!(v >= 0) || !std::isfinite(v)) throw OptionsError(std::string("skeleton: ") + name + " must be >= 0");
  };
  positive(o.binWidthVoxels, "binWidthVoxels");
  nonNegative(o.rootHeightVoxels, "rootHeightVoxels");
  // 0 would let a one-voxel piece have radius 0, which no circle can keep (measured: 8 of 9 real clouds refused).
  positive(o.minRadiusVoxels, "minRadiusVoxels");
  nonNegative(o.spurLengthRadii, "spurLengthRadii");
  nonNegative(o.spurLengthBins, "spurLengthBins");
  nonNegative(o.twigOutBins, "twigOutBins");
  nonNegative(o.minEndSupportFraction, "minEndSupportFraction");
  nonNegative(o.forkZoneRadii, "forkZoneRadii");
  nonNegative(o.collinearToleranceRadii, "collinearToleranceRadii");
  nonNegative(o.collinearToleranceVoxels, "collinearToleranceVoxels");
  positive(o.maxSegmentRadii, "maxSegmentRadii");
  positive(o.maxSegmentBins, "maxSegmentBins");
  if (o.radiusMedianWindow < 1) throw OptionsError("skeleton: radiusMedianWindow must be >= 1");
  positive(o.leafPlaneRadiusVoxels, "leafPlaneRadiusVoxels");
  positive(o.leafPlaneBandVoxels, "leafPlaneBandVoxels");
  if (o.leafPlaneHypotheses < 1) throw OptionsError("skeleton: leafPlaneHypotheses must be >= 1");
  nonNegative(o.leafPlaneMinInliers, "leafPlaneMinInliers");
  nonNegative(o.leafPlaneMinSpread, "leafPlaneMinSpread");
  if (!(o.leafPlaneMaxAngleDeg >= 0 && o.leafPlaneMaxAngleDeg <= 90))
    throw OptionsError("skeleton: leafPlaneMaxAngleDeg must be in [0, 90]");
  nonNegative(o.leafPatchMaxOffsetVoxels, "leafPatchMaxOffsetVoxels");
  if (o.leafPlaneMaxPointsPerVoxel < 0) throw OptionsError("skeleton: leafPlaneMaxPointsPerVoxel must be >= 0");
  if (!(o.leafConvergenceWeight >= 0 && o.leafConvergenceWeight <= 1))
    throw OptionsError("skeleton: leafConvergenceWeight must be in [0, 1]");
  nonNegative(o.leafConvergenceRadiusVoxels, "leafConvergenceRadiusVoxels");
  positive(o.leafConvergenceAutoScale, "leafConvergenceAutoScale");
  positive(o.leafConvergenceMinRadiusVoxels, "leafConvergenceMinRadiusVoxels");
  if (!(o.leafConvergenceMaxRadiusVoxels >= o.leafConvergenceMinRadiusVoxels) ||
      !std::isfinite(o.leafConvergenceMaxRadiusVoxels))
    throw OptionsError("skeleton: leafConvergenceMaxRadiusVoxels must be >= leafConvergenceMinRadiusVoxels");
  nonNegative(o.leafConvergenceFreeShare, "leafConvergenceFreeShare");
}

}  // namespace detail

namespace {

/// The root node moved down to the lowest point of the root region (the Dijkstra sources): a
/// level set's centroid sits half a bin above its bottom, and the tube would leave the trunk's
/// foot uncovered; the foot is where a user expects the trunk to end.
void rootToBase(Skeleton& s, const geom::PointCloud& cloud) {
  if (s.nodes.empty() || s.levels.rootVertices.empty()) return;
  std::vector<char> inRoot(s.graph.size(), 0);
  for (std::uint32_t v : s.levels.rootVertices) inRoot[v] = 1;
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (inRoot[s.graph.pointVoxel[i]]) lowest = std::min(lowest, geom::height(cloud.positions[i], s.up));
  SkeletonNode& root = s.nodes.front();
  const double drop = geom::height(root.position, s.up) - lowest;
  if (std::isfinite(drop) && drop > 0) root.position -= drop * geom::upVector(s.up);
}

/// Each end node moved along its direction to the farthest voxel of its level-set piece and of
/// the pieces dropped below it (partial tips, short spurs): a centroid sits half a level set
/// before the branch's last points, and the tube stopped short of the wood at every tip.
void tipsToEnds(Skeleton& s) {
  const std::size_t rawCount = s.rawNodes.size();
  if (s.nodes.empty() || rawCount == 0) return;
  std::vector<std::int32_t> endOf(rawCount, -1);
  // Raw nodes on the way to a kept node are that node's, not dropped: only a raw subtree with no
  // kept node in it hangs below an end (a raw stem that went on above a kept tip, with the kept
  // stem reanchored beside it, gave that tip the whole stem's reach: a straight tube 11 m out of
  // a spruce's crown).
  std::vector<char> leadsToKept(rawCount, 0);
  for (const auto& n : s.nodes)
    if (n.raw >= 0) leadsToKept[n.raw] = 1;
  for (std::size_t i = rawCount; i-- > 0;) {  // raw nodes are parent-first
    const std::int32_t p = s.rawNodes[i].parent;
    if (leadsToKept[i] && p >= 0) leadsToKept[p] = 1;
  }
  for (std::size_t k = 0; k < s.nodes.size(); ++k) {
    const auto& n = s.nodes[k];
    if (n.parent >= 0 && n.children.empty() && n.raw >= 0) endOf[n.raw] = static_cast<std::int32_t>(k);
  }
  for (std::size_t i = 0; i < rawCount; ++i) {
    const std::int32_t p = s.rawNodes[i].parent;
    if (endOf[i] < 0 && p >= 0 && !leadsToKept[i]) endOf[i] = endOf[p];
  }
  std::vector<double> reach(s.nodes.size(), 0.0);
  for (std::size_t v = 0; v < s.graph.size(); ++v) {
    const std::int32_t r = s.levels.vertexNode[v];
    if (r < 0 || endOf[r] < 0) continue;
    const SkeletonNode& end = s.nodes[endOf[r]];
    reach[endOf[r]] = std::max(reach[endOf[r]], (s.graph.positions[v] - end.position).dot(end.direction));
  }
  for (std::size_t k = 0; k < s.nodes.size(); ++k) s.nodes[k].position += reach[k] * s.nodes[k].direction;
}

}  // namespace

std::size_t countBranchPoints(const std::vector<SkeletonNode>& nodes) {
  return static_cast<std::size_t>(
      std::count_if(nodes.begin(), nodes.end(), [](const SkeletonNode& n) { return n.children.size() >= 2; }));
}

std::size_t countEnds(const std::vector<SkeletonNode>& nodes) {
  return static_cast<std::size_t>(
      std::count_if(nodes.begin(), nodes.end(), [](const SkeletonNode& n) { return n.children.empty(); }));
}

Skeleton extractSkeleton(const geom::PointCloud& cloud, const SkeletonOptions& options, const ProgressFn& progress) {
  detail::checkOptions(options);
  Skeleton s;
  s.up = options.up;
  if (progress) progress(0, 4);
  s.graph = buildVoxelGraph(cloud, options.graph);
  if (progress) progress(1, 4);
  s.levels = computeGeodesicLevels(s.graph, options);
  if (progress) progress(2, 4);
  if (options.leafEntryPositions && s.graph.size() > 0) {
    // Only the level-set nodes see the entry positions; the graph, distances and levels stay.
    std::vector<char> flat;
    const std::vector<geom::Vec3> positions = detail::leafEntryPositions(cloud, s.graph, s.levels, options, flat);
    s.rawNodes = levelSetNodes(s.graph, s.levels, options, &positions);
    detail::setFlatFractions(s.levels, flat, s.rawNodes);
  } else {
    s.rawNodes = levelSetNodes(s.graph, s.levels, options);
  }
  if (progress) progress(3, 4);
  s.nodes = simplifySkeleton(s.rawNodes, s.graph.voxelSize, s.levels.binWidth, options);
  // A stem found beside the root region cuts the level sets at its tube (level_sets.cpp), so a
  // stem piece's parent may be a limb's piece of its own level: the stem's chain went out along
  // the limb and back. Chained, the stem is one branch. (For every tracked stem: a leaf-on aspen's
  // backward error +0.26 points, its crown's pieces re-ordered.)
  if (s.levels.stemBesideRoot) detail::chainTrackedStem(s.nodes);
  rootToBase(s, cloud);
  tipsToEnds(s);
  if (progress) progress(4, 4);
  return s;
}

SkeletonOptions leafOnSkeletonOptions(SkeletonOptions base) {
  base.graph.autoSpacingFactor = 1.5;
  base.binWidthVoxels = 1.0;
  // The occlusion gaps bridged are the leaf-off ones (20 voxels): in leaf a limb or the stem under
  // the crown is hidden by leaves and sampled more sparsely still, and the cone and linearity below
  // keep the long bridges on limb-shaped pieces. With 8, the thesis's sphere scans left the lower
  // stem unjoined (rooted on a branch tip up to 23 % of the diagonal off the base) and parts of the
  // crown out (forward error 1.6–2.6 %, 0.9–1.2 % with 20; docs/notes/leaf_on_skeleton.md).
  base.graph.coneAngleDeg = 45.0;
  base.graph.minBridgeLinearity = 0.4;
  base.minEndSupportFraction = 0.5;  // partial tips in a crown are leaf ends (see the option)
  base.twigOutBins = 0;              // a short piece standing out of a twig is a leaf as often
  // Leaf clusters at the twigs are as long as limbs to the split, and a fork moved down made
  // their spurs long enough to be kept (the leaf-clutter test: 5 forks and 7 ends, not 4 and 5).
  base.splitMergedForks = false;
  base.leafEntryPositions = true;
  return base;
}

}  // namespace treesketch::skeleton
