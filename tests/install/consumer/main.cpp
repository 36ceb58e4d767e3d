// Uses the installed library end to end: a mesh against a copy shifted by 0.25 must be 0.25 away
// (the Hausdorff comparison runs the Embree closest-point search, so every link dependency is
// exercised). Prints the distance; exits 1 when it is wrong.
#include <cmath>
#include <cstdio>

#include "treesketch/compare/hausdorff.h"
#include "treesketch/geom/tri_mesh.h"

namespace {

treesketch::geom::TriMesh square(double z) {
  treesketch::geom::TriMesh m;
  m.vertices = {{0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

}  // namespace

int main() {
  treesketch::compare::CompareOptions o;
  o.sampling.count = 100;
  const auto both = treesketch::compare::compareBoth(square(0.0), square(0.25), o);
  std::printf("consumer: Hausdorff distance %.6f (expected 0.25)\n", both.hausdorff);
  return std::abs(both.hausdorff - 0.25) < 1e-9 ? 0 : 1;
}
