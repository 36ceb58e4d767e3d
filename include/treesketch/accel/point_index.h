// Neighbour queries on a fixed set of points: the points within a radius of a query point (ball)
// and its k nearest, on a k-d tree (nanoflann, hidden here: the only k-d tree of the code base).
// The grid of fit::CloudIndex answers the fits' slab and cylinder slices; this answers balls and
// nearest neighbours (the skeleton's neighbourhoods, closest points of a cloud).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"

namespace treesketch::accel {

/// A neighbour of a query point.
struct Neighbour {
  std::uint32_t index = 0;  ///< into the indexed points
  double distance2 = 0;     ///< squared distance to the query point, (p − q).squaredNorm()
};

/// A k-d tree over a copy of the points. Immutable after construction: queries are const and may
/// run from many threads at once. Results are exact (double): the tree only prunes, and every
/// candidate is decided by the same expression a brute-force scan uses.
class PointIndex {
 public:
  /// Builds the tree (O(n log n)). An empty set gives an index whose queries find nothing.
  /// Throws OptionsError for a NaN/Inf point or more than 2^32 − 2 points.
  explicit PointIndex(std::vector<geom::Vec3> points);
  explicit PointIndex(const geom::PointCloud& cloud) : PointIndex(cloud.positions) {}
  ~PointIndex();
  PointIndex(PointIndex&&) noexcept;
  PointIndex& operator=(PointIndex&&) noexcept;

  std::size_t size() const;
  const std::vector<geom::Vec3>& points() const;

  /// Indices of the points inside the open ball, (p − centre).squaredNorm() < radius², in
  /// increasing order (the order of a brute-force scan, whatever the tree's shape). `out` is
  /// overwritten (its capacity reused).
  void withinRadius(const geom::Vec3& centre, double radius, std::vector<std::uint32_t>& out) const;
  std::vector<std::uint32_t> withinRadius(const geom::Vec3& centre, double radius) const;
  /// The same points with their squared distances, nearest first (equal distances: lower index
  /// first).
  void withinRadiusByDistance(const geom::Vec3& centre, double radius, std::vector<Neighbour>& out) const;

  /// The point nearest to `query`; none for an empty index or a NaN/Inf query. Allocates nothing.
  std::optional<Neighbour> nearest(const geom::Vec3& query) const;
  /// The min(k, size()) points nearest to `query`, nearest first. Among points exactly as far as
  /// the k-th, the tree's traversal decides which are returned (deterministic for a given point
  /// set, not necessarily the lowest indices).
  std::vector<Neighbour> nearest(const geom::Vec3& query, std::size_t k) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace treesketch::accel
