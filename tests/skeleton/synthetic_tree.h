// Test trees made of noisy cylinder surfaces with known axes and radii (Y up), for the skeleton
// tests. Points inside another cylinder (a child's base inside its parent) are dropped, as a scan
// would not see them.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"
#include "treesketch/skeleton/skeleton.h"

namespace treesketch::test {

struct Cyl {
  geom::Vec3 a, b;  ///< axis ends (base, tip)
  double radius;
  int parent;  ///< index of the parent cylinder (-1 for the trunk)
};

/// Distance from p to segment [a, b].
inline double distanceToSegment(const geom::Vec3& p, const geom::Vec3& a, const geom::Vec3& b) {
  const geom::Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

/// Distance from p to the nearest true axis.
inline double distanceToAxes(const std::vector<Cyl>& cyls, const geom::Vec3& p) {
  double best = 1e300;
  for (const auto& c : cyls) best = std::min(best, distanceToSegment(p, c.a, c.b));
  return best;
}

/// Samples the surfaces at `spacing` (points per area ~ 1/spacing^2) with Gaussian noise `noise`.
/// The cloud declares `up` (the trees below are Y-up), so a PLY written from it says so and the
/// CLI needs no --up (io/up_axis.h).
inline geom::PointCloud sampleCylinders(const std::vector<Cyl>& cyls, double spacing, double noise, unsigned seed,
                                        geom::UpAxis up = geom::UpAxis::Y) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  geom::PointCloud cloud;
  cloud.up = up;
  for (std::size_t k = 0; k < cyls.size(); ++k) {
    const auto& c = cyls[k];
    const geom::Vec3 axis = (c.b - c.a).normalized();
    const geom::Vec3 u = geom::anyPerpendicular(axis);
    const geom::Vec3 v = axis.cross(u);
    const double length = (c.b - c.a).norm();
    const auto count = static_cast<std::size_t>(2 * M_PI * c.radius * length / (spacing * spacing));
    for (std::size_t i = 0; i < count; ++i) {
      const double t = uni(rng) * length, phi = uni(rng) * 2 * M_PI;
      const double r = c.radius + noise * gauss(rng);
      const geom::Vec3 p = c.a + t * axis + r * (std::cos(phi) * u + std::sin(phi) * v);
      bool inside = false;
      for (std::size_t j = 0; j < cyls.size() && !inside; ++j)
        if (j != k && distanceToSegment(p, cyls[j].a, cyls[j].b) < 0.98 * cyls[j].radius) inside = true;
      if (!inside) cloud.positions.push_back(p);
    }
  }
  return cloud;
}

/// One upright branch as model nodes: `count` nodes every `spacing` along y from the origin, each of
/// radius `radius`, parent before child.
inline std::vector<skeleton::SkeletonNode> uprightChain(int count, double spacing, double radius) {
  std::vector<skeleton::SkeletonNode> nodes(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    skeleton::SkeletonNode& n = nodes[static_cast<std::size_t>(k)];
    n.position = geom::Vec3(0, spacing * k, 0);
    n.radius = radius;
    n.parent = k - 1;
    if (k > 0) nodes[static_cast<std::size_t>(k - 1)].children.push_back(k);
  }
  return nodes;
}

/// A Y: trunk and two branches from its top.
inline std::vector<Cyl> yTree() {
  using geom::Vec3;
  return {{Vec3(0, 0, 0), Vec3(0, 3, 0), 0.15, -1},
          {Vec3(0, 3, 0), Vec3(-1.2, 5.0, 0.1), 0.10, 0},
          {Vec3(0, 3, 0), Vec3(1.1, 5.2, -0.3), 0.09, 0}};
}

/// Three levels: a trunk continuing to the top with two side branches, each carrying one twig.
/// Forks: 4 (two on the trunk, one on each branch); ends: 5.
inline std::vector<Cyl> threeLevelTree() {
  using geom::Vec3;
  return {{Vec3(0, 0, 0), Vec3(0, 2.5, 0), 0.16, -1},           // 0 trunk, lower
          {Vec3(0, 2.5, 0), Vec3(0.05, 5.5, 0), 0.12, 0},       // 1 trunk, upper
          {Vec3(0, 2.5, 0), Vec3(1.6, 4.0, 0.2), 0.08, 0},      // 2 branch A
          {Vec3(0.05, 4.0, 0), Vec3(-1.5, 5.4, -0.3), 0.07, 1}, // 3 branch B
          {Vec3(0.8, 3.25, 0.1), Vec3(1.0, 4.5, 0.9), 0.05, 2}, // 4 twig on A
          {Vec3(-0.75, 4.7, -0.15), Vec3(-0.9, 5.9, -1.0), 0.045, 3}};  // 5 twig on B
}

}  // namespace treesketch::test
