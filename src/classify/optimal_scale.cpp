// Features at each point's own best neighbourhood size (classify/optimal_scale.h).
#include "optimal_scale.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace treesketch::classify::detail {

namespace {

struct Shape {
  geom::Vec3 ev = geom::Vec3::Constant(1.0 / 3);  ///< eigenvalues normalised to sum 1, ascending
  geom::Vec3 axis = geom::Vec3::Zero();           ///< the principal axis
  geom::Vec3 normal = geom::Vec3::Zero();         ///< the direction of least spread
  double entropy = 0;  ///< -sum e ln e of the normalised eigenvalues
};

/// The shape of a neighbourhood whose offsets from the query point sum to `sum` and `outer` over `k`.
Shape shapeOf(const geom::Vec3& sum, const geom::Mat3& outer, int k) {
  const geom::Vec3 mean = sum / k;
  const geom::Mat3 cov = outer / k - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<geom::Mat3> eig;
  eig.computeDirect(cov);
  Shape s;
  const geom::Vec3 ev = eig.eigenvalues().cwiseMax(0.0);
  s.ev = ev / std::max(ev.sum(), 1e-300);
  for (int i = 0; i < 3; ++i) s.entropy -= s.ev[i] > 1e-12 ? s.ev[i] * std::log(s.ev[i]) : 0.0;
  s.axis = eig.eigenvectors().col(2);
  s.normal = eig.eigenvectors().col(0);
  return s;
}

}  // namespace

std::vector<std::string> optimalScaleFeatureNames() {
  return {"opt_scale",      "opt_radius",  "opt_radius_growth", "opt_eigenentropy", "opt_linearity",
          "opt_planarity",  "opt_scattering", "opt_omnivariance", "opt_axis_up",   "opt_normal_up"};
}

void optimalScaleFeatures(const accel::PointIndex& index, const geom::Vec3& p, const std::vector<accel::Neighbour>& nb,
                          const std::vector<int>& candidates, double spacing, const geom::Vec3& up, float* out) {
  geom::Vec3 sum = geom::Vec3::Zero();
  geom::Mat3 outer = geom::Mat3::Zero();
  Shape best;
  best.entropy = INFINITY;
  int bestScale = 0;  // index into candidates
  double bestRadius = 0, firstRadius = 0;
  std::size_t c = 0;
  for (std::size_t j = 0; j < nb.size() && c < candidates.size(); ++j) {
    const geom::Vec3 d = index.point(nb[j].index) - p;
    sum += d;
    outer += d * d.transpose();
    const bool last = j + 1 == nb.size();
    if (static_cast<int>(j) < candidates[c] && !last) continue;
    const double r = std::sqrt(nb[j].distance2);
    if (c == 0) firstRadius = r;
    const Shape s = shapeOf(sum, outer, static_cast<int>(j + 1));
    if (s.entropy < best.entropy) best = s, bestScale = static_cast<int>(c), bestRadius = r;
    ++c;
    if (last) break;
  }
  const double e1 = std::max(best.ev[2], 1e-30), e2 = best.ev[1], e3 = best.ev[0];
  out[0] = static_cast<float>(bestScale);
  out[1] = static_cast<float>(std::log(std::max(bestRadius, 1e-12) / spacing));
  out[2] = static_cast<float>(std::log(std::max(bestRadius, 1e-12) / std::max(firstRadius, 1e-12)));
  out[3] = static_cast<float>(best.entropy);
  out[4] = static_cast<float>((e1 - e2) / e1);
  out[5] = static_cast<float>((e2 - e3) / e1);
  out[6] = static_cast<float>(e3 / e1);
  out[7] = static_cast<float>(std::cbrt(std::max(e1 * e2 * e3, 0.0)));
  out[8] = static_cast<float>(std::abs(best.axis.dot(up)));
  out[9] = static_cast<float>(std::abs(best.normal.dot(up)));
}

}  // namespace treesketch::classify::detail
