#include "treesketch/io/read_options.h"

#include "treesketch/util/error.h"

namespace treesketch::io {

void checkCloudSize(const geom::PointCloud& cloud, const std::string& source, std::size_t minPoints) {
  if (cloud.size() >= minPoints) return;
  if (cloud.empty()) throw InputError(source + ": holds no points, expected at least " + std::to_string(minPoints));
  throw InputError(source + ": holds only " + std::to_string(cloud.size()) + " point" + (cloud.size() == 1 ? "" : "s") +
                   ", expected at least " + std::to_string(minPoints) + " (a tree cloud this small cannot be fitted)");
}

}  // namespace treesketch::io
