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

struct PointIndexOptions {
  /// Most points in a leaf of the tree. Large leaves suit both query kinds here: a ball takes or
  /// rejects whole leaves, and a leaf's points are read contiguously. On the 1 M-point leafy
  /// benchmark scan, balls of ~260 points ran 1.2× faster at 128 than at 64 (256 about as 128), and
  /// nearest points at 128 as fast as at 32-64.
  std::size_t leafSize = 128;
};

/// A k-d tree over a copy of the points. Immutable after construction: queries are const and may
/// run from many threads at once. Results are exact (double): the tree only prunes, and every
/// candidate is decided by the same expression a brute-force scan uses.
class PointIndex {
 public:
  /// Builds the tree (O(n log n)). An empty set gives an index whose queries find nothing.
  /// Throws OptionsError for a NaN/Inf point, more than 2^32 − 2 points or a zero leaf size.
  explicit PointIndex(std::vector<geom::Vec3> points, const PointIndexOptions& options = {});
  explicit PointIndex(const geom::PointCloud& cloud, const PointIndexOptions& options = {})
      : PointIndex(cloud.positions, options) {}
  ~PointIndex();
  PointIndex(PointIndex&&) noexcept;
  PointIndex& operator=(PointIndex&&) noexcept;

  std::size_t size() const;
  /// The point of input index `index` (< size()).
  const geom::Vec3& point(std::uint32_t index) const;

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
