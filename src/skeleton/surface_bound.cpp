#include "skeleton/surface_bound.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "skeleton/axis_smoothing.h"
#include "treesketch/compare/model_fit.h"
#include "treesketch/skeleton/skeleton_export.h"

namespace treesketch::skeleton::detail {
namespace {

using geom::Vec3;

/// The share of a tube's points allowed deeper than the margin inside it. Good wood has some:
/// rough bark, a slightly off-centre axis, a fork's neighbouring tube, and in the synthetic test
/// meshes (open tubes, a branch starting on its parent's axis) the insides of joints seen through
/// a tube's open end, up to a tenth of a trunk's points. A shell of noise or a leaf cluster puts
/// far more there. Of 0.1, 0.25 and 0.5, chosen on the tuning data: 0.1 thinned the built-in
/// demo tree's trunk from 24.5 to 18.3 cm (true: 25.6 cm) and the synthetic sphere scans' volume by
/// 15-25 %; 0.5 changed nothing on the tuning clouds (docs/notes/radii_and_volume.md).
constexpr double kInsideQuantile = 0.25;
/// The margin, in noise. A surface scanned with Gaussian noise σ has its lower quartile at
/// r − 0.67σ, so any margin above that keeps a true radius; bark is rougher than a circle and a
/// branch's axis is only known to about the noise. Of 1.5, 2 and 3 (with the noise of
/// stemNoise / measuredNoise), chosen on the tuning clouds: 2 (3 left adtree_tree7 with 1.3 % of
/// its points inside and 1.33× TreeQSM's volume; 1.5 took 2-3 more points of volume off the
/// synthetic trees' sphere scans, docs/notes/radii_and_volume.md).
constexpr double kMarginNoise = 2.0;
/// An inferred radius (no circle of its own) whose points lie outside it is raised to their lower
/// quartile less this many noises. Points about a line with Gaussian noise σ in the plane across it
/// (a twig thinner than the noise) have their distances' lower quartile at 0.76σ (Rayleigh), so a
/// margin of one noise raises no tube on noise alone; a surface of radius r sampled all round has
/// it at r − 0.67σ, and seen from one side with the axis at the points' centroid lower still, so
/// the raise never passes the wood the points show.
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
/// Points measured at most: every k-th point of a larger cloud (deterministic), enough for the
/// quantiles of a few thousand tubes and bounded work on any cloud.
constexpr std::size_t kMaxPoints = 400000;

double quantile(std::vector<double>& v, double q) {
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

/// Per node: its points' distances to the axis of their nearest tube.
std::vector<std::vector<double>> distancesPerNode(const std::vector<SkeletonNode>& model,
                                                  const geom::PointCloud& cloud, double band) {
  const geom::CylinderModel pieces = cylinderModelFromSkeleton(model);
  std::vector<std::int32_t> nodeOf;  // piece -> node (pieces are the non-root nodes in order)
  for (std::size_t i = 0; i < model.size(); ++i)
    if (model[i].parent >= 0) nodeOf.push_back(static_cast<std::int32_t>(i));
  std::vector<std::vector<double>> perNode(model.size());
  if (pieces.empty()) return perNode;
  const compare::CylinderModelIndex index(pieces);
  const std::size_t stride = std::max<std::size_t>(1, (cloud.size() + kMaxPoints - 1) / kMaxPoints);
  const std::size_t count = (cloud.size() + stride - 1) / stride;
  std::vector<std::int32_t> node(count, -1);
  std::vector<double> rho(count, 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k < r.end(); ++k) {
      const Vec3& p = cloud.positions[k * stride];
      std::int64_t piece = -1;
      const double d = index.signedDistance(p, &piece);
      if (piece < 0 || !(d <= band)) continue;
      const geom::ModelCylinder& c = pieces.cylinders[static_cast<std::size_t>(piece)];
      const Vec3 axis = c.end - c.start;
      const double len2 = axis.squaredNorm();
      if (!(len2 > 0)) continue;
      const double t = std::clamp((p - c.start).dot(axis) / len2, 0.0, 1.0);
      const std::int32_t own = nodeOf[static_cast<std::size_t>(piece)];
      const std::int32_t parent = model[own].parent;
      // The lower half of a piece is its parent node's ring, unless the piece starts a branch.
      const bool startsBranch = model[own].branchOrder != model[parent].branchOrder;
      node[k] = (t >= 0.5 || startsBranch) ? own : parent;
      rho[k] = (p - (c.start + t * axis)).norm();
    }
  });
  for (std::size_t k = 0; k < count; ++k)
    if (node[k] >= 0) perNode[static_cast<std::size_t>(node[k])].push_back(rho[k]);
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
                                      double voxel, int window, const std::vector<double>& ownResidual) {
  SurfaceBoundStats stats;
  if (model.size() < 2 || cloud.empty() || !(noise > 0) || !(voxel > 0)) return stats;
  const std::vector<std::vector<double>> perNode = distancesPerNode(model, cloud, noise + voxel);
  const double margin = kMarginNoise * noise;
  // Each node is judged on the points of the nodes around it along its branch (a window of
  // `window` nodes): a sparse scan puts a few points on each node, a window enough for a quantile,
  // and one odd node does not decide alone. A branch's first node is capped by its parent's radius
  // (chains are parent-first, so that radius is final). An inferred radius the points show too
  // thin is raised, never above the node before it along the branch (or its parent).
  const int half = std::max(0, window / 2);
  std::vector<double> pooled;
  for (const auto& chain : branchChains(model)) {
    const int m = static_cast<int>(chain.size());
    std::vector<double> bound(chain.size(), -1.0);  // < 0: too few points
    std::vector<double> raise(chain.size(), -1.0);  // < 0: no raise (a measured radius, or too few points)
    for (int k = 0; k < m; ++k) {
      pooled.clear();
      for (int j = std::max(0, k - half); j <= std::min(m - 1, k + half); ++j)
        pooled.insert(pooled.end(), perNode[chain[j]].begin(), perNode[chain[j]].end());
      if (pooled.size() < kMinPoints) continue;
      // A branch whose own circle fit left a larger residual than the scan's noise is not round
      // (or rough): its points spread that much about its surface.
      const double own = chain[k] < static_cast<std::int32_t>(ownResidual.size()) ? ownResidual[chain[k]] : 0.0;
      const double low = quantile(pooled, kInsideQuantile);
      bound[k] = low + std::max(margin, kMarginNoise * own);
      if (!(own > 0) && !model[chain[k]].stem) raise[k] = low - kRaiseMarginNoise * noise;
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
