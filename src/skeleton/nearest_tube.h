// Internal: each point of a cloud with the tube of a cylinder model nearest to it, for the rules
// that read a tube's own points (the points' bound on radii, the scan's noise).
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/compare/model_fit.h"
#include "treesketch/geom/point_cloud.h"

namespace treesketch::skeleton::detail {

/// A point of the cloud (its index) and the piece of the model nearest to it, with its signed
/// distance to that piece's surface (negative inside).
struct NearestTube {
  std::uint32_t point = 0;
  std::int64_t piece = -1;
  double distance = 0;
};

/// Every point of `cloud`, or every k-th of a cloud larger than `maxPoints` (deterministic), with
/// its nearest piece in `index`; points with none are left out. In the cloud's order.
std::vector<NearestTube> nearestTubes(const compare::CylinderModelIndex& index, const geom::PointCloud& cloud,
                                      std::size_t maxPoints);

}  // namespace treesketch::skeleton::detail
