// A cloud for the desktop tool's tests: a trunk with two branches, their surfaces sampled at
// random (fixed seed), enough for an automatic skeleton of a few nodes.
#pragma once

#include <cmath>

#include "treesketch/gen/random.h"
#include "treesketch/geom/point_cloud.h"

namespace treesketch::test {

inline geom::PointCloud forkedTree() {
  using geom::Vec3;
  gen::Rng rng(21);
  geom::PointCloud cloud;
  auto limb = [&](Vec3 a, Vec3 b, double r, int n) {
    Vec3 d = (b - a).normalized(), u = geom::anyPerpendicular(d), v = d.cross(u);
    for (int i = 0; i < n; ++i) {
      double t = rng.uniform(0, 1), ang = rng.uniform(0, 2 * M_PI);
      cloud.positions.push_back(a + t * (b - a) + r * (std::cos(ang) * u + std::sin(ang) * v));
    }
  };
  limb(Vec3(0, 0, 0), Vec3(0, 3, 0), 0.15, 12000);
  limb(Vec3(0, 2, 0), Vec3(1.2, 3.5, 0), 0.06, 4000);
  limb(Vec3(0, 2.4, 0), Vec3(-1.0, 3.6, 0.3), 0.05, 4000);
  return cloud;
}

}  // namespace treesketch::test
