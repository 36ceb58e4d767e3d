#include "skeleton/nearest_tube.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace treesketch::skeleton::detail {

std::vector<NearestTube> nearestTubes(const compare::CylinderModelIndex& index, const geom::PointCloud& cloud,
                                      std::size_t maxPoints) {
  const std::size_t stride = std::max<std::size_t>(1, (cloud.size() + maxPoints - 1) / std::max<std::size_t>(1, maxPoints));
  const std::size_t count = (cloud.size() + stride - 1) / stride;
  std::vector<NearestTube> all(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k < r.end(); ++k) {
      NearestTube& t = all[k];
      t.point = static_cast<std::uint32_t>(k * stride);
      t.distance = index.signedDistance(cloud.positions[t.point], &t.piece);
    }
  });
  all.erase(std::remove_if(all.begin(), all.end(), [](const NearestTube& t) { return t.piece < 0; }), all.end());
  return all;
}

}  // namespace treesketch::skeleton::detail
