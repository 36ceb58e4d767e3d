// A helper shared by the scanner's patterns (sphere jitter) and the beam footprint's sub-rays.
#pragma once

#include <cmath>

#include "treesketch/geom/types.h"

namespace treesketch::scan {

/// An orthonormal basis (e1, e2) perpendicular to the unit vector d, branch-free (Duff et al.,
/// "Building an Orthonormal Basis, Revisited", JCGT 2017).
inline void orthonormalBasis(const geom::Vec3& d, geom::Vec3& e1, geom::Vec3& e2) {
  const double sign = std::copysign(1.0, d.z());
  const double a = -1.0 / (sign + d.z());
  const double b = d.x() * d.y() * a;
  e1 = geom::Vec3(1.0 + sign * d.x() * d.x() * a, sign * b, -sign * d.x());
  e2 = geom::Vec3(b, sign + d.y() * d.y() * a, -d.y());
}

}  // namespace treesketch::scan
