// Internal: radii bounded by the points around each tube. A scanner sees the surface of the wood,
// so the points a tube explains lie on its surface, not inside it: where many of them lie deeper
// than the scan's noise inside, the tube is thicker than the wood (a circle fitted to a shell of
// noise or leaves, or a radius the pipe model inferred for a branch the points show thinner).
// Each tube's radius is therefore bounded by the median of its points' distances to its axis (a
// round surface's points have their median on it whatever the noise, a flat-sided one's within a
// few percent of the radius with its area); the noise, measured on the cloud itself (the residuals
// of the circles fitted to it), never a figure in metres that assumes a scanner, sets which points
// are a tube's and how far an inferred radius is raised.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/fit/node_fit.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton::detail {

/// The scan's noise (cloud units), a robust standard deviation of the points about the accepted
/// circles (fits[i] with accepted[i] != 0): per fit with at least 12 test points, 1.4826 × the
/// median of |distance to the centre in the node's plane − radius| over all its test points
/// (inliers or not: the inliers' own RMS is truncated by the RANSAC band, and a scan with 25 mm
/// of range noise measured 13 mm by it), and the lower quartile over the fits (the cleanest
/// circles: a leaf cluster's or a twig's blob spreads wider). `fallback` when fewer than three
/// fits qualify.
double measuredNoise(const std::vector<fit::NodeResult>& fits, const std::vector<char>& accepted,
                     const geom::PointCloud& cloud, double fallback);

/// 1.4826 × the median of |distance to the centre in the fit's plane − radius| over all the fit's
/// test points (a robust σ of the points about the circle), NaN with fewer than 12.
double fitSpread(const fit::NodeResult& f, const geom::PointCloud& cloud);

/// Per node of `model`: the robust spread (1.4826 × median absolute deviation) of its points'
/// distances to the axis, the points of the `window` nodes around it along its branch pooled (as
/// boundRadiiBySurface assigns them); NaN with fewer than 12 points.
std::vector<double> surfaceSpreads(const std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double noise,
                                   double voxel, int window);

/// The scan's noise read from the tubes' own points (cloud units), for a cloud where neither
/// circles nor a tracked stem measure it (a sparse airborne scan: limbs as lines of points): the
/// lower quartile of the nodes' spreads (surfaceSpreads, `standIn` the noise they assume), the
/// same reading as the circles' (measuredNoise): the cleanest surfaces show the scanner's noise,
/// a limb with a twig or a neighbour beside it a wider spread. -1 when fewer than three nodes have
/// a spread.
double spreadNoise(const std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double standIn, double voxel,
                   int window);

/// The scan's noise measured on the stem (cloud units): the points of the tracked stem's tubes
/// (model nodes with `stem`), in windows of three nodes, their distances to the axis' robust
/// spread (1.4826 × the median absolute deviation from their median); the median over the
/// windows. A stem is large and well sampled, and round: the spread of its points about its
/// surface is the scanner's noise (and the bark's roughness), where a leafy crown's circles hold
/// leaves about them. -1 when fewer than three windows have 30 points (no tracked stem).
double stemNoise(const std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double voxel);

/// What the bound did.
struct SurfaceBoundStats {
  std::size_t nodesWithEvidence = 0;  ///< nodes with enough points to be judged
  std::size_t nodesThinned = 0;       ///< nodes whose radius the bound lowered
  std::size_t nodesThickened = 0;     ///< inferred radii the points raised
};

/// Fits the radii of `model` (parent-first nodes) to the points about the tubes. Each point goes
/// to the node of its nearest tube (points farther than `noise` plus `voxel` plus 0.6 of the tube's
/// radius outside it are left out: a flat-sided branch's corners); a node is judged on the points
/// of the `window` nodes around it along its branch: its radius is at most their distances to the
/// axis' median (plus three of the median's standard errors under `noise`), and at most their lower
/// quartile plus 0.674 `noise` over 0.85 (a convex section's quartile: deeper points are several
/// stems in one tube). A node without a measured radius (no residual of its own in `ownResidual`,
/// not on the tracked stem) whose points' lower quartile lies more than one `noise` outside it is
/// raised to that, never above the node before it along its branch. A branch's first node is also
/// capped by its parent's radius. With `rangeNoise` (the scanner's, range_noise.h) the median is read
/// as the radius that shows it under that noise (radiusUnderNoise): a twig thinner than the noise
/// has its points' median at 0.68 of the noise whatever its radius; and where that median is over
/// kResolvableNoises noises, an inferred radius is raised to the radius it shows (same cap), unless
/// its piece's flat share (SkeletonNode::flatFraction) is over `maxFlatFraction`: points on leaves
/// show where the foliage is, not the wood's surface.
SurfaceBoundStats boundRadiiBySurface(std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double noise,
                                      double voxel, int window, const std::vector<double>& ownResidual = {},
                                      double rangeNoise = 0.0, double maxFlatFraction = 1.0);

}  // namespace treesketch::skeleton::detail
