// Whether anything can be measured in a cloud at all: its points must span some space (not every
// point the same) and a space whose areas and volumes are finite numbers (a LAS header whose scale
// factor says 1e300 gives points 1e301 apart: their bounding box's diagonal is +inf). Every command
// that models, sketches or draws a cloud asks this first, so such a cloud is one clear data error
// naming the file rather than a NaN camera or an "invalid option" deep inside.
#pragma once

#include <string>

#include "treesketch/geom/point_cloud.h"

namespace treesketch::cloud {

/// Largest extent (cloud units) of a cloud that can be measured: its cube, a volume, must stay a
/// finite double (largest 1.8e308), with room for the factors of areas and volumes (pi, sums).
constexpr double kMaxMeasurableExtent = 1e100;

/// Throws DegenerateInputError naming `source` (the file), its point count and bounding-box
/// diagonal when every point of `cloud` is the same (diagonal 0) or its extent on some axis is over
/// kMaxMeasurableExtent (or not finite). An empty cloud passes: the readers refuse one already.
void requireUsableExtent(const geom::PointCloud& cloud, const std::string& source);

}  // namespace treesketch::cloud
