#include "skeleton/range_noise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "skeleton/nearest_tube.h"
#include "treesketch/compare/model_fit.h"
#include "treesketch/skeleton/skeleton_export.h"

namespace treesketch::skeleton::detail {
namespace {

using geom::Vec3;

/// Radius over noise, and the median distance to the axis over noise (noisyMedianOverNoise): means
/// over five simulations of 3,000 points with 1, 4 and 8 directions of view.
constexpr std::array<double, 11> kRadius = {0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0};
constexpr std::array<double, 11> kMedian = {0.679, 0.709, 0.790, 0.920, 1.108, 1.317, 1.543, 2.029, 2.513, 3.016, 4.005};
/// A tube's median distance over its nugget, and the share of the noise the nugget shows there,
/// with the pairing tubeNoise uses (the same model simulated at 10 to 300 points per noise of length,
/// means over ratio bins; the spread between densities under 0.06): a blob's points pair with
/// neighbours moved the same way (their angle about the axis is the noise's), a limb's with
/// neighbours along the bark.
constexpr std::array<double, 9> kRatio = {1.25, 1.51, 1.75, 1.95, 2.18, 2.50, 2.84, 3.50, 4.63};
constexpr std::array<double, 9> kShare = {0.54, 0.48, 0.46, 0.46, 0.50, 0.54, 0.56, 0.61, 0.61};
constexpr double kMadToSigma = 1.4826;
constexpr std::size_t kMinPoints = 12;
/// Points read at most (every k-th of a larger cloud).
constexpr std::size_t kMaxPoints = 400000;
/// A tube's points reach this many of its radii beyond the band (a flat-sided branch's corners).
constexpr double kCornerRadii = 0.6;

template <std::size_t N>
double interpolate(const std::array<double, N>& xs, const std::array<double, N>& ys, double x) {
  if (x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
  const double t = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
  return ys[k - 1] + t * (ys[k] - ys[k - 1]);
}

double median(std::vector<double>& v) {
  const std::size_t k = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

/// A point about a tube: along its axis, round it (radians) and its distance to it.
struct TubePoint {
  double along = 0, angle = 0, rho = 0;
};

/// The tube's noise from its points (see rangeNoise), NaN with too few.
double tubeNoise(std::vector<TubePoint>& pts, double radius) {
  if (pts.size() < kMinPoints) return std::nan("");
  std::sort(pts.begin(), pts.end(), [](const TubePoint& a, const TubePoint& b) { return a.along < b.along; });
  const double arc = std::max(radius, 1e-12);
  std::vector<double> diffs, rhos;
  diffs.reserve(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t pair = i;
    auto visit = [&](std::size_t j) {
      double turn = std::abs(pts[i].angle - pts[j].angle);
      turn = std::min(turn, 2 * std::numbers::pi - turn);
      const double ds = pts[i].along - pts[j].along;
      const double d2 = ds * ds + (turn * arc) * (turn * arc);
      if (d2 < best) {
        best = d2;
        pair = j;
      }
    };
    for (std::size_t j = i + 1; j < pts.size() && (pts[j].along - pts[i].along) * (pts[j].along - pts[i].along) < best; ++j)
      visit(j);
    for (std::size_t j = i; j-- > 0 && (pts[i].along - pts[j].along) * (pts[i].along - pts[j].along) < best;) visit(j);
    if (pair != i) diffs.push_back(std::abs(pts[i].rho - pts[pair].rho));
    rhos.push_back(pts[i].rho);
  }
  const double nugget = kMadToSigma * median(diffs) / std::sqrt(2.0);
  if (!(nugget > 0)) return std::nan("");
  return nugget / interpolate(kRatio, kShare, median(rhos) / nugget);
}

}  // namespace

double noisyMedianOverNoise(double x) {
  if (x >= kRadius.back()) return x + (kMedian.back() - kRadius.back());
  return interpolate(kRadius, kMedian, std::max(0.0, x));
}

double radiusUnderNoise(double median, double noise) {
  if (!(noise > 0) || !(median > 0)) return median;
  const double m = median / noise;
  const double floor = std::min(median, kRadius[1] * noise);
  if (m <= kMedian[1]) return floor;
  if (m >= kMedian.back()) return noise * (m - (kMedian.back() - kRadius.back()));
  return std::max(floor, noise * interpolate(kMedian, kRadius, m));
}

double rangeNoise(const std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double band) {
  const geom::CylinderModel pieces = cylinderModelFromSkeleton(model);
  if (pieces.empty() || cloud.empty()) return -1.0;
  const compare::CylinderModelIndex index(pieces);
  std::vector<std::vector<TubePoint>> perPiece(pieces.size());
  for (const NearestTube& n : nearestTubes(index, cloud, kMaxPoints)) {
    const Vec3& p = cloud.positions[n.point];
    const geom::ModelCylinder& c = pieces.cylinders[static_cast<std::size_t>(n.piece)];
    Vec3 axis = c.end - c.start;
    const double len = axis.norm();
    if (!(len > 0)) continue;
    axis /= len;
    const double along = (p - c.start).dot(axis);
    if (along < 0 || along > len || !(n.distance <= band + kCornerRadii * std::max(c.startRadius, c.endRadius)))
      continue;
    const Vec3 u = axis.unitOrthogonal();
    const Vec3 v = axis.cross(u);
    const Vec3 q = p - c.start - along * axis;
    perPiece[static_cast<std::size_t>(n.piece)].push_back({along, std::atan2(q.dot(v), q.dot(u)), q.norm()});
  }
  std::vector<double> perTube(pieces.size(), std::nan(""));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pieces.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      const geom::ModelCylinder& c = pieces.cylinders[i];
      perTube[i] = tubeNoise(perPiece[i], 0.5 * (c.startRadius + c.endRadius));
    }
  });
  std::vector<double> noise;
  for (double s : perTube)
    if (std::isfinite(s) && s > 0) noise.push_back(s);
  if (noise.size() < 3) return -1.0;
  return median(noise);
}

}  // namespace treesketch::skeleton::detail
