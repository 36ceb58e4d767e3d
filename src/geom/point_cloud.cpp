#include "treesketch/geom/point_cloud.h"

#include "treesketch/util/error.h"

namespace treesketch::geom {

BBox PointCloud::bounds() const {
  BBox b;
  for (const auto& p : positions) b.add(p);
  return b;
}

void PointCloud::append(const PointCloud& other) {
  bool keepStation = (station.size() == size()) && (other.station.size() == other.size());
  bool keepMesh = (meshId.size() == size()) && (other.meshId.size() == other.size());
  bool keepScanner = (scanner.size() == size()) && (other.scanner.size() == other.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  if (keepStation)
    station.insert(station.end(), other.station.begin(), other.station.end());
  else
    station.clear();
  if (keepMesh)
    meshId.insert(meshId.end(), other.meshId.begin(), other.meshId.end());
  else
    meshId.clear();
  if (keepScanner)
    scanner.insert(scanner.end(), other.scanner.begin(), other.scanner.end());
  else
    scanner.clear();
}

void PointCloud::checkConsistent() const {
  if (!station.empty() && station.size() != size())
    throw OptionsError("point cloud: station array has " + std::to_string(station.size()) + " entries for " +
                       std::to_string(size()) + " points");
  if (!meshId.empty() && meshId.size() != size())
    throw OptionsError("point cloud: meshId array has " + std::to_string(meshId.size()) + " entries for " +
                       std::to_string(size()) + " points");
  if (!scanner.empty() && scanner.size() != size())
    throw OptionsError("point cloud: scanner array has " + std::to_string(scanner.size()) + " entries for " +
                       std::to_string(size()) + " points");
}

}  // namespace treesketch::geom
