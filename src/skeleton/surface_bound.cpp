#include "skeleton/surface_bound.h"


#include <algorithm>
#include <cmath>
#include <limits>

#include "skeleton/axis_smoothing.h"
#include "skeleton/nearest_tube.h"
#include "skeleton/range_noise.h"
#include "treesketch/compare/model_fit.h"
#include "treesketch/skeleton/skeleton_export.h"
#include "treesketch/skeleton/skeleton_sketch.h"

namespace treesketch::skeleton::detail {
namespace {

using geom::Vec3;

/// A tube is at most the median of its points' distances to its axis. A round surface's points,
/// with the scanner's noise symmetric about it, have their median on it, whatever the noise and
/// wherever the axis sits within about a radius (the distances to an off-centre axis swing as much
/// above the radius as below it). A branch of a few flat sides has its perimeter's median within a
/// few percent of the radius of the circle with its area (a square's 1 % under it, a triangle's 3 %
/// over), where its lower quartile lies 9 % (square) to 15 % (triangle) under it. The bound was
/// the lower quartile plus two noises: on the synthetic trees, whose branches have 3-7 flat sides,
/// the sphere scans' wood came out 12.8-13.5 % short on average (tuning half), 9.9-10.0 % with the
/// median and the convex section's quartile below (docs/notes/radii_and_volume.md). A shell of
/// noise about a twig or a leaf cluster still has its median well inside the circle fitted round it.
constexpr double kBoundQuantile = 0.5;
/// The bound's allowance for the median's own sampling error, in standard errors (1.2533 σ/√n for
/// n points spread by the noise σ): a tube of the right radius is thinned by chance at about one
/// node in 700.
constexpr double kMedianErrors = 3.0;
constexpr double kMedianStandardError = 1.2533;  // a normal sample's median: σ/√n times this
/// A tube's points reach this many of its radii farther out than the scan's noise and a voxel: a
/// flat-sided branch modelled at the radius with its area has its corners up to 0.56 of that radius
/// outside it (a triangle's; a square's 0.25), and the median needs its whole perimeter.
constexpr double kCornerRadii = 0.6;
/// A convex section's lower quartile over the radius with its area, at least: a triangle's 0.85 (a
/// square's 0.91, a circle's 1). Points whose lower quartile (less the noise's share) is lower are
/// not one convex section about the tube's axis: an axis beside its branch (a circle fitted round
/// a twig from the wrong centre, whose points' median is the offset), several stems in one tube, a
/// joint's inside. On the 4-station scans of the tuning bush the median alone gave +61 % of its
/// wood, with this +40 % (before: +37 %).
constexpr double kConvexQuartile = 0.85;
/// A normal distribution's lower quartile, in standard deviations below its mean.
constexpr double kNoiseQuartile = 0.674;
/// The quantile an inferred radius is raised to (less kRaiseMarginNoise noises).
constexpr double kRaiseQuantile = 0.25;
/// An inferred radius (no circle of its own) whose points lie outside it is raised to their lower
/// quartile less this many noises. Points about a line with Gaussian noise σ in the plane across it
/// (a twig thinner than the noise) have their distances' lower quartile at 0.76σ (Rayleigh), so a
/// margin of one noise raises no tube on noise alone; a surface of radius r sampled all round has
/// it at r − 0.67σ, and seen from one side with the axis at the points' centroid lower still, so
/// the raise never passes the wood the points show. Where the scanner's range noise is known and
/// the points' median is over kResolvableNoises of it, the points resolve the section, and the raise
/// goes to the radius their median shows under that noise (radiusUnderNoise): the quartile less a
/// noise left the inferred twigs of real scans a median 1.5–3.4 of their radii inside their points
/// (docs/notes/radii_and_volume.md, "Inferred radii read through the noise").
constexpr double kRaiseMarginNoise = 1.0;
/// The circles' noise is the lower quartile of their spreads: a well-sampled branch's circle shows
/// the scanner's noise, a circle around a leaf cluster or a twig's blob of points a wider spread
/// (of the median and the lower quartile, chosen on the tuning clouds: the quartile left
/// adtree_tree7 with 1.0 % of its points inside instead of 1.2 %, the others within 0.1 point).
constexpr double kFitNoiseQuantile = 0.25;
/// The stem's noise is measured over windows of this many nodes along it.
constexpr std::size_t kStemWindow = 3;
/// A node judged on fewer points than this keeps its radius.
constexpr std::size_t kMinPoints = 12;
/// A node of the tracked stem reads its quantiles from its own points when it has this many (else
/// with its neighbours', nearest first, up to the window): the stem's few long segments span the
/// tree's taper and its forks, and pooled with the limb above a fork its lower nodes were thinned
/// to the limb (a sphere scan's ash trunk, 1.7 → 1.36 and 1.5 → 0.89 units, the tree's wood 19 %
/// short). Its radii are measured by whole slabs' circles, so it needs the window least.
constexpr std::size_t kOwnStemPoints = 4 * kMinPoints;
/// Points measured at most: every k-th point of a larger cloud (deterministic), enough for the
/// quantiles of a few thousand tubes and bounded work on any cloud.
constexpr std::size_t kMaxPoints = 400000;

double quantile(std::vector<double>& v, double q) {
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

/// Per node: its points' distances to the axis of their nearest tube, the points at most `band`
/// plus `bandRadii` of the tube's radius outside it.
std::vector<std::vector<double>> distancesPerNode(const std::vector<SkeletonNode>& model,
                                                  const geom::PointCloud& cloud, double band, double bandRadii = 0.0) {
  const geom::CylinderModel pieces = cylinderModelFromSkeleton(model);
  std::vector<std::int32_t> nodeOf;  // piece -> node (pieces are the non-root nodes in order)
  for (std::size_t i = 0; i < model.size(); ++i)
    if (model[i].parent >= 0) nodeOf.push_back(static_cast<std::int32_t>(i));
  std::vector<std::vector<double>> perNode(model.size());
  if (pieces.empty()) return perNode;
  const compare::CylinderModelIndex index(pieces);
  for (const NearestTube& n : nearestTubes(index, cloud, kMaxPoints)) {
    const Vec3& p = cloud.positions[n.point];
    const geom::ModelCylinder& c = pieces.cylinders[static_cast<std::size_t>(n.piece)];
    const Vec3 axis = c.end - c.start;
    const double len2 = axis.squaredNorm();
    if (!(len2 > 0)) continue;
    const double t = std::clamp((p - c.start).dot(axis) / len2, 0.0, 1.0);
    if (!(n.distance <= band + bandRadii * (c.startRadius + t * (c.endRadius - c.startRadius)))) continue;
    const std::int32_t own = nodeOf[static_cast<std::size_t>(n.piece)];
    const std::int32_t parent = model[own].parent;
    // The lower half of a piece is its parent node's ring, unless the piece starts a branch.
    const bool startsBranch = model[own].branchOrder != model[parent].branchOrder;
    perNode[static_cast<std::size_t>((t >= 0.5 || startsBranch) ? own : parent)].push_back(
        (p - (c.start + t * axis)).norm());
  }
  return perNode;
}

}  // namespace

namespace {

/// 1.4826 × the median absolute residual of the fit's test points about its circle (a robust σ),
/// or NaN when it has too few.
double fitNoise(const fit::NodeResult& f, const geom::PointCloud& cloud, std::vector<double>& residuals) {
  constexpr std::size_t kMinTestPoints = 12;
  constexpr double kMadToSigma = 1.4826;  // a normal distribution's σ over its median absolute deviation
  if (f.testIndices.size() < kMinTestPoints || !(f.radius > 0)) return std::nan("");
  residuals.clear();
  for (const std::uint32_t id : f.testIndices) {
    if (id >= cloud.size()) continue;
    Vec3 d = cloud.positions[id] - f.centre;
    d -= d.dot(f.normal) * f.normal;
    residuals.push_back(std::abs(d.norm() - f.radius));
  }
  if (residuals.size() < kMinTestPoints) return std::nan("");
  return kMadToSigma * quantile(residuals, 0.5);
}

}  // namespace

std::vector<double> surfaceSpreads(const std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double noise,
                                   double voxel, int window) {
  constexpr double kMadToSigma = 1.4826;
  std::vector<double> spread(model.size(), std::nan(""));
  if (model.size() < 2 || cloud.empty() || !(noise > 0) || !(voxel > 0)) return spread;
  const std::vector<std::vector<double>> perNode = distancesPerNode(model, cloud, noise + voxel);
  const int half = std::max(0, window / 2);
  std::vector<double> pooled;
  for (const auto& chain : branchChains(model)) {
    const int m = static_cast<int>(chain.size());
    for (int k = 0; k < m; ++k) {
      pooled.clear();
      for (int j = std::max(0, k - half); j <= std::min(m - 1, k + half); ++j)
        pooled.insert(pooled.end(), perNode[chain[j]].begin(), perNode[chain[j]].end());
      if (pooled.size() < kMinPoints) continue;
      const double med = quantile(pooled, 0.5);
      for (double& d : pooled) d = std::abs(d - med);
      spread[chain[k]] = kMadToSigma * quantile(pooled, 0.5);
    }
  }
  return spread;
}

double spreadNoise(const std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double standIn, double voxel,
                   int window) {
  std::vector<double> spreads;
  for (double s : surfaceSpreads(model, cloud, standIn, voxel, window))
    if (std::isfinite(s) && s > 0) spreads.push_back(s);
  if (spreads.size() < 3) return -1.0;
  return quantile(spreads, kFitNoiseQuantile);
}

double fitSpread(const fit::NodeResult& f, const geom::PointCloud& cloud) {
  std::vector<double> residuals;
  return fitNoise(f, cloud, residuals);
}

double measuredNoise(const std::vector<fit::NodeResult>& fits, const std::vector<char>& accepted,
                     const geom::PointCloud& cloud, double fallback) {
  std::vector<double> perFit, residuals;
  for (std::size_t i = 0; i < fits.size() && i < accepted.size(); ++i) {
    if (!accepted[i]) continue;
    const double sigma = fitNoise(fits[i], cloud, residuals);
    if (std::isfinite(sigma)) perFit.push_back(sigma);
  }
  if (perFit.size() < 3) return fallback;
  return quantile(perFit, kFitNoiseQuantile);
}

double stemNoise(const std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double voxel) {
  constexpr double kMadToSigma = 1.4826;
  constexpr std::size_t kMinStemPoints = 30;
  if (model.size() < 2 || cloud.empty() || !(voxel > 0)) return -1.0;
  std::size_t stemNodes = 0;
  for (const SkeletonNode& n : model) stemNodes += n.stem ? 1 : 0;
  if (stemNodes < 3) return -1.0;
  // Points up to two voxels outside a tube are its (a stem's noise is well under that).
  const std::vector<std::vector<double>> perNode = distancesPerNode(model, cloud, 2 * voxel);
  std::vector<double> perWindow, pooled, spread;
  for (const auto& chain : branchChains(model)) {
    for (std::size_t k = 0; k < chain.size(); k += kStemWindow) {
      pooled.clear();
      for (std::size_t j = k; j < std::min(chain.size(), k + kStemWindow); ++j)
        if (model[chain[j]].stem) pooled.insert(pooled.end(), perNode[chain[j]].begin(), perNode[chain[j]].end());
      if (pooled.size() < kMinStemPoints) continue;
      const double centre = quantile(pooled, 0.5);
      spread.clear();
      for (const double rho : pooled) spread.push_back(std::abs(rho - centre));
      perWindow.push_back(kMadToSigma * quantile(spread, 0.5));
    }
  }
  if (perWindow.size() < 3) return -1.0;
  return quantile(perWindow, 0.5);
}

SurfaceBoundStats boundRadiiBySurface(std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double noise,
                                      double voxel, int window, const std::vector<double>& ownResidual,
                                      double rangeNoise, double maxFlatFraction) {
  SurfaceBoundStats stats;
  if (model.size() < 2 || cloud.empty() || !(noise > 0) || !(voxel > 0)) return stats;
  const std::vector<std::vector<double>> perNode = distancesPerNode(model, cloud, noise + voxel, kCornerRadii);
  // Each node is judged on the points of the nodes around it along its branch (a window of
  // `window` nodes; a stem node on its own points when it has enough, kOwnStemPoints): a sparse
  // scan puts a few points on each node, a window enough for a quantile, and one odd node does not
  // decide alone. A branch's first node is capped by its parent's radius (chains are parent-first,
  // so that radius is final). An inferred radius the points show too thin is raised, never above
  // the node before it along the branch (or its parent).
  const int half = std::max(0, window / 2);
  std::vector<double> pooled;
  for (const auto& chain : branchChains(model)) {
    const int m = static_cast<int>(chain.size());
    std::vector<double> bound(chain.size(), -1.0);  // < 0: too few points
    std::vector<double> raise(chain.size(), -1.0);  // < 0: no raise (a measured radius, or too few points)
    for (int k = 0; k < m; ++k) {
      pooled.assign(perNode[chain[k]].begin(), perNode[chain[k]].end());
      const std::size_t enough = model[chain[k]].stem ? kOwnStemPoints : std::numeric_limits<std::size_t>::max();
      for (int step = 1; step <= half && pooled.size() < enough; ++step)
        for (const int j : {k - step, k + step})
          if (j >= 0 && j < m) pooled.insert(pooled.end(), perNode[chain[j]].begin(), perNode[chain[j]].end());
      if (pooled.size() < kMinPoints) continue;
      // A radius with a circle of its own (a residual) or on the tracked stem is measured: never raised.
      const double own = chain[k] < static_cast<std::int32_t>(ownResidual.size()) ? ownResidual[chain[k]] : 0.0;
      // The allowance for the median's sampling error keeps a measured radius from being thinned by
      // chance; an inferred one is the pipe model's guess, and its points say more than it does.
      const bool inferred = !(own > 0) && !model[chain[k]].stem;
      const double median = quantile(pooled, kBoundQuantile);
      bound[k] = radiusUnderNoise(median, rangeNoise);
      if (!inferred)
        bound[k] += kMedianErrors * kMedianStandardError * noise / std::sqrt(static_cast<double>(pooled.size()));
      // One convex section (round, or of three or more flat sides) about the axis has its lower
      // quartile, less the noise's share, at 0.85 of its area's radius or more.
      const double low = quantile(pooled, kRaiseQuantile);
      bound[k] = std::min(bound[k], (low + kNoiseQuartile * noise) / kConvexQuartile);
      if (inferred) {
        raise[k] = low - kRaiseMarginNoise * noise;
        const bool leafPiece = model[chain[k]].flatFraction > maxFlatFraction;
        if (rangeNoise > 0 && median >= kResolvableNoises * rangeNoise && !leafPiece)
          raise[k] = std::max(raise[k], radiusUnderNoise(median, rangeNoise));
      }
      ++stats.nodesWithEvidence;
    }
    const std::int32_t parent = model[chain.front()].parent;
    for (int k = 0; k < m; ++k) {
      SkeletonNode& node = model[chain[k]];
      double r = node.radius;
      if (k == 0 && parent >= 0) r = std::min(r, model[parent].radius);
      if (bound[k] >= 0) r = std::min(r, bound[k]);
      if (raise[k] > r) {
        const double cap = k > 0 ? model[chain[k - 1]].radius : parent >= 0 ? model[parent].radius : raise[k];
        r = std::max(r, std::min(raise[k], cap));
      }
      if (r < node.radius) ++stats.nodesThinned;
      if (r > node.radius) ++stats.nodesThickened;
      node.radius = r;
    }
  }
  return stats;
}

}  // namespace treesketch::skeleton::detail
