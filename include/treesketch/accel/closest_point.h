// Closest-point queries: the exact closest point on a triangle (Ericson's Voronoi-region method),
// a bounding-volume hierarchy over a triangle mesh for batches of queries (Morton-ordered and
// warm-started from the previous query's triangle), and the nearest point of a point cloud (k-d tree).
// Used by compare/ for Metro/MeshLab-style Hausdorff distances.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/util/progress.h"

namespace treesketch::accel {

/// Which feature of a triangle the closest point lies on (Ericson, Real-Time Collision Detection,
/// §5.1.5: the seven Voronoi regions of a triangle).
enum class TriangleRegion : std::uint8_t { VertexA, VertexB, VertexC, EdgeAB, EdgeBC, EdgeCA, Face };

/// The point of triangle (a, b, c) closest to `p`, exactly (double precision, no iteration).
/// `region` (optional) receives the feature it lies on. A degenerate triangle (collinear or
/// coincident corners) is handled as the segment or point it collapses to; the result is still the
/// closest point of that set.
geom::Vec3 closestPointOnTriangle(const geom::Vec3& p, const geom::Vec3& a, const geom::Vec3& b, const geom::Vec3& c,
                                  TriangleRegion* region = nullptr);

/// One closest-point query's answer.
struct ClosestHit {
  geom::Vec3 point = geom::Vec3::Zero();                      ///< closest point on the target (world, metres)
  double distance = std::numeric_limits<double>::infinity();  ///< metres; +inf when not found. Computed as sqrt of the
                                                              ///< squared distance: below ~1e-154 (far below any
                                                              ///< physical scale) it underflows to 0
  /// Index of the target triangle (mesh) or point (cloud) holding `point`; -1 when none lies
  /// within the search distance.
  std::int64_t index = -1;
  bool found() const { return index >= 0; }
};

/// Options of the BVH and its batch queries.
struct ClosestPointOptions {
  /// Most triangles in a BVH leaf, 1 to 64. 4 = one SSE packet of triangles; 8, 12, 16 and 32
  /// measured no faster on the bench_compare tree (within the noise of a shared machine).
  int leafSize = 4;
  /// Queries handed to one task of a batch; the warm start restarts at each block. Larger blocks
  /// keep more coherence, smaller ones balance the two cores better.
  int blockSize = 512;
  /// Sort batch queries by 3D Morton code (16 bits per axis) before answering them, so
  /// consecutive queries are close and the previous answer bounds the next one tightly.
  bool mortonOrder = true;
  /// Start each query with the distance to the previous query's closest triangle as its search
  /// radius (an upper bound of the answer, usually nearly tight).
  bool warmStart = true;
};

/// A bounding-volume hierarchy over a triangle mesh answering exact closest-point queries.
/// Boxes and a first triangle test are float (relative to the mesh's bounding-box centre, with a
/// safety margin); the deciding triangle tests are double, so answers equal a brute-force search
/// over all triangles to rounding (tested to 1e-9 relative, also 5e5 m from the origin).
/// Build once, query from many threads (queries are const).
class MeshClosestPoint {
 public:
  /// Builds the hierarchy over `mesh` (a copy of the triangles is kept; `mesh` may die).
  /// An empty mesh gives an index whose queries find nothing. Throws OptionsError when a triangle
  /// references a missing vertex or a vertex is NaN/Inf.
  explicit MeshClosestPoint(const geom::TriMesh& mesh, const ClosestPointOptions& options = {});
  ~MeshClosestPoint();
  MeshClosestPoint(MeshClosestPoint&&) noexcept;
  MeshClosestPoint& operator=(MeshClosestPoint&&) noexcept;

  /// The closest point of the mesh to `p` within `maxDistance` (metres, inclusive); not found
  /// (index -1) when no triangle is that close or the mesh is empty.
  ClosestHit query(const geom::Vec3& p, double maxDistance = std::numeric_limits<double>::infinity()) const;

  /// Answers all `points` (in parallel, Morton-ordered and warm-started as the options say).
  /// Results are in the order of `points`, with the same distances as query() on each (when two
  /// triangles are exactly equally close, either may be named). Reproducible bit for bit.
  std::vector<ClosestHit> queryAll(const std::vector<geom::Vec3>& points,
                                   double maxDistance = std::numeric_limits<double>::infinity(),
                                   const ProgressFn& progress = {}) const;

  std::size_t triangleCount() const;
  /// Number of BVH nodes (for tests and benchmarks).
  std::size_t nodeCount() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Nearest point of a point cloud (accel::PointIndex, a k-d tree), with the same batch interface.
class CloudClosestPoint {
 public:
  /// Builds a k-d tree over the cloud's positions (copied). An empty cloud finds nothing.
  /// Throws OptionsError for NaN/Inf positions.
  explicit CloudClosestPoint(const geom::PointCloud& cloud, const ClosestPointOptions& options = {});
  ~CloudClosestPoint();
  CloudClosestPoint(CloudClosestPoint&&) noexcept;
  CloudClosestPoint& operator=(CloudClosestPoint&&) noexcept;

  /// The cloud point nearest to `p` within `maxDistance` (metres, inclusive).
  ClosestHit query(const geom::Vec3& p, double maxDistance = std::numeric_limits<double>::infinity()) const;
  /// All `points`, in parallel; results in the order of `points`.
  std::vector<ClosestHit> queryAll(const std::vector<geom::Vec3>& points,
                                   double maxDistance = std::numeric_limits<double>::infinity(),
                                   const ProgressFn& progress = {}) const;
  std::size_t pointCount() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Indices 0..n-1 of `points` sorted by their 3D Morton code (16 bits per axis over the points'
/// bounding box; NaN/Inf points first): consecutive indices are close in space. Exposed for tests and benchmarks.
std::vector<std::uint32_t> mortonOrder(const std::vector<geom::Vec3>& points);

}  // namespace treesketch::accel
