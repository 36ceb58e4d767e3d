// Whether anything can be measured in a cloud (see usable_extent.h).
#include "treesketch/cloud/usable_extent.h"

#include <cstdio>

#include "treesketch/util/error.h"

namespace treesketch::cloud {

void requireUsableExtent(const geom::PointCloud& cloud, const std::string& source) {
  const geom::BBox box = cloud.bounds();
  if (box.empty()) return;
  const double extent = box.extent().maxCoeff();
  char what[160];
  std::snprintf(what, sizeof what, " (%zu points, bounding-box diagonal %.6g)", cloud.size(), box.diagonal());
  if (!(extent > 0))
    throw DegenerateInputError(source + what + ": every point is the same; nothing can be made from it; nothing written");
  if (!(extent <= kMaxMeasurableExtent)) {
    char size[96];
    std::snprintf(size, sizeof size, "%.4g", extent);
    throw DegenerateInputError(source + what + ": the points are " + size +
                               " units apart, too far for areas and volumes to be numbers (at most 1e100); wrong units "
                               "or a scale factor from a corrupt header? nothing written");
  }
}

}  // namespace treesketch::cloud
