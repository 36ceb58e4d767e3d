// Test data for the fit, sweep and recon tests: noisy points on cylinders with known axes and
// radii, plus uniform outliers. Header-only; fixed seeds give fixed clouds.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"

namespace treesketch::test {

struct CylinderSpec {
  geom::Vec3 base = geom::Vec3::Zero();
  geom::Vec3 axis = geom::Vec3::UnitY();  ///< unit
  double radius = 0.3;
  double length = 2.0;
  int points = 5000;
  double noise = 0.003;                 ///< Gaussian radial noise σ, world units
  double arcStart = 0.0, arcSpan = 2 * M_PI;  ///< the visible part of the surface (radians)
};

/// Appends noisy surface points of `c` to `cloud`.
inline void addCylinder(geom::PointCloud& cloud, const CylinderSpec& c, std::mt19937_64& rng) {
  geom::Vec3 a = c.axis.normalized();
  geom::Vec3 e1 = geom::anyPerpendicular(a), e2 = a.cross(e1);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, c.noise);
  for (int i = 0; i < c.points; ++i) {
    double t = u01(rng) * c.length;
    double th = c.arcStart + u01(rng) * c.arcSpan;
    double r = c.radius + noise(rng);
    cloud.positions.push_back(c.base + t * a + r * (std::cos(th) * e1 + std::sin(th) * e2));
  }
}

/// Appends `n` points uniform in the box [lo, hi].
inline void addOutliers(geom::PointCloud& cloud, int n, const geom::Vec3& lo, const geom::Vec3& hi,
                        std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int i = 0; i < n; ++i)
    cloud.positions.push_back(lo + geom::Vec3(u01(rng), u01(rng), u01(rng)).cwiseProduct(hi - lo));
}

/// 2D circle points with noise plus a fraction of outliers uniform in the circle's 4r × 4r box.
inline std::vector<geom::Vec2> noisyCircle(const geom::Vec2& centre, double radius, int inliers, int outliers,
                                           double noise, double arcStart, double arcSpan, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> nd(0.0, noise);
  std::vector<geom::Vec2> pts;
  for (int i = 0; i < inliers; ++i) {
    double th = arcStart + u01(rng) * arcSpan;
    double r = radius + nd(rng);
    pts.emplace_back(centre + r * geom::Vec2(std::cos(th), std::sin(th)));
  }
  for (int i = 0; i < outliers; ++i)
    pts.emplace_back(centre + radius * geom::Vec2(4 * u01(rng) - 2, 4 * u01(rng) - 2));
  std::shuffle(pts.begin(), pts.end(), rng);
  return pts;
}

}  // namespace treesketch::test
