#include "treesketch/geom/point_cloud.h"

#include <string>

#include "treesketch/util/error.h"

namespace treesketch::geom {

BBox PointCloud::bounds() const {
  BBox b;
  for (const auto& p : positions) b.add(p);
  return b;
}

namespace {

/// Appends `b` to `a` when both clouds have the attribute (one per point); else drops it.
template <class T>
void appendAttribute(std::vector<T>& a, std::size_t aPoints, const std::vector<T>& b, std::size_t bPoints) {
  if (a.size() == aPoints && b.size() == bPoints)
    a.insert(a.end(), b.begin(), b.end());
  else
    a.clear();
}

template <class T>
void checkAttribute(const std::vector<T>& a, std::size_t points, const char* name) {
  if (!a.empty() && a.size() != points)
    throw OptionsError(std::string("point cloud: ") + name + " array has " + std::to_string(a.size()) +
                       " entries for " + std::to_string(points) + " points");
}

}  // namespace

void PointCloud::append(const PointCloud& other) {
  const std::size_t n = size();
  appendAttribute(intensity, n, other.intensity, other.size());
  appendAttribute(color, n, other.color, other.size());
  appendAttribute(classification, n, other.classification, other.size());
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
  checkAttribute(intensity, size(), "intensity");
  checkAttribute(color, size(), "color");
  checkAttribute(classification, size(), "classification");
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
