// Slicing the cloud: the points near a node's plane ("nearPts", thesis §4.4) and those of them
// near the node's line or point ("testPts"). A uniform grid built once answers these queries by
// touching only the cells near the region; the thesis's full scan per node is kept as the
// reference path (sliceBruteForce, CloudIndex::queryBruteForce) and all give identical index sets.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <utility>
#include <limits>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"

namespace treesketch::fit {

/// A query region: the slab |(p − planePoint)·planeNormal| < halfThickness, optionally
/// intersected with the open cylinder of radius `radius` around the line (linePoint, lineDir)
/// (kind Cylinder) or the open ball of radius `radius` around `centre` (kind Ball).
/// All in world units and frame; normal and line direction are unit vectors.
struct SliceRegion {
  enum class Kind { Slab, Cylinder, Ball };
  Kind kind = Kind::Slab;
  geom::Vec3 planePoint = geom::Vec3::Zero();
  geom::Vec3 planeNormal = geom::Vec3::UnitY();
  double halfThickness = 0.05;
  geom::Vec3 linePoint = geom::Vec3::Zero();  ///< Cylinder: a point on the axis; Ball: the centre
  geom::Vec3 lineDir = geom::Vec3::UnitZ();   ///< Cylinder: unit axis direction
  double radius = std::numeric_limits<double>::infinity();

  /// The exact membership test used by every path (strict inequalities, as the thesis).
  bool contains(const geom::Vec3& p) const {
    if (!(std::abs((p - planePoint).dot(planeNormal)) < halfThickness)) return false;
    if (kind == Kind::Slab) return true;
    geom::Vec3 d = p - linePoint;
    if (kind == Kind::Ball) return d.squaredNorm() < radius * radius;
    return (d - d.dot(lineDir) * lineDir).squaredNorm() < radius * radius;
  }
  /// Throws OptionsError for a non-finite or non-positive size or a zero normal/direction.
  void validate() const;
};

/// An orthonormal frame of a node's plane: the 2D coordinates of a point are ((p − origin)·u,
/// (p − origin)·v).
struct PlaneFrame {
  geom::Vec3 origin = geom::Vec3::Zero();
  geom::Vec3 u = geom::Vec3::UnitX(), v = geom::Vec3::UnitZ();
  geom::Vec2 operator()(const geom::Vec3& p) const {
    const geom::Vec3 d = p - origin;
    return geom::Vec2(d.dot(u), d.dot(v));
  }
};

/// Thesis reference path: scans every point of `cloud` (O(n) per query). Returns the indices of
/// the points inside `region`, increasing.
std::vector<std::uint32_t> sliceBruteForce(const geom::PointCloud& cloud, const SliceRegion& region);

struct CloudIndexOptions {
  /// Grid resolution, first guess: one cell per this many points over the bounding box volume.
  double pointsPerCell = 2.0;
  /// Then refined so that the cell of an average point holds about this many points (Σ count² / n,
  /// so sparse clutter in one-point cells does not hide the crowded surface cells that queries
  /// hit; scans cover surfaces, so most cells are empty). Speed design choice: 8. 0 = no refinement.
  double pointsPerOccupiedCell = 8.0;
  /// Upper bound on the number of cells (memory: 4 bytes a cell, 8 while building).
  std::size_t maxCells = std::size_t(1) << 23;
  /// ...and on cells per point. The grid's build time and memory grow with its cells, not its
  /// points: the 40,608-point demo scan refined to 8 M cells took 300 ms to index (page faults
  /// and zeroing of the cell arrays) for 17 ms of fitting; with at most 16 cells a point (650k)
  /// it takes 15-30 ms, and queries on so small a cloud stay cheap (the evaluation's 160k-point
  /// scans: the "ideal" sketches' reconstruct time 105 -> 25 ms, leaf-off). Clouds of 524k points
  /// and more are held by maxCells first (the benchmarks' 1.2 M: unchanged). The grid decides a
  /// slice's storage order, so the fits' random samples (drawn by position in the slice) change
  /// with it: the evaluation moved within its noise (leaf-off skeleton backward / forward RMS
  /// 0.138 / 0.164 -> 0.140 / 0.163 sphere, 0.150 / 0.197 -> 0.147 / 0.197 TLS). 0 = no bound.
  double maxCellsPerPoint = 16.0;
  /// Run the float pre-test eight points at a time with AVX2 when the processor has it (checked
  /// at run time; the build targets baseline x86-64). Results are identical either way (tests
  /// compare both); off only to test the baseline path on an AVX2 machine.
  bool allowAvx2 = true;
};

/// A uniform grid over the cloud. Holds its own copy of the positions (sorted by cell, in double
/// and, relative to the grid's centre, in float for a conservative pre-test); results
/// are indices into the original cloud. Immutable after construction: safe to query from many
/// threads at once. Non-finite points are left out of every query result.
class CloudIndex {
 public:
  /// Builds the grid (O(n)). An empty cloud gives an index whose queries return nothing.
  explicit CloudIndex(const geom::PointCloud& cloud, const CloudIndexOptions& options = {});

  /// Indices of the points inside `region`, in the index's storage order (cell by cell,
  /// increasing within a cell): the same list in the same order as queryBruteForce, and the same
  /// set as sliceBruteForce (sort it for increasing indices). Design choice: the storage order is
  /// the canonical order of a slice, so that neither path sorts its hits (sorting them by index
  /// was a tenth of a node fit) and fits, which draw their samples by position in the list, give
  /// identical results on both paths. When `positions` is given it receives the matching
  /// positions (same order). When `frame` and `coords` are given, `coords` receives each hit's 2D
  /// coordinates in that frame, computed from the index's float copy of the positions (relative
  /// to the grid's centre; the same numbers on both paths). Why the float copy: the query has just
  /// read it, while the double positions of a node's few thousand hits are tens of kB from memory
  /// (15 % of a full reconstruction). Its error, ~6e-8 of the cloud's half-diagonal (0.4 µm on a
  /// 12 m tree, 30 µm on a 1 km plot), is far below any scanner's noise.
  std::vector<std::uint32_t> query(const SliceRegion& region, std::vector<geom::Vec3>* positions = nullptr,
                                   const PlaneFrame* frame = nullptr, std::vector<geom::Vec2>* coords = nullptr) const;
  /// The same lists, by scanning every stored point in storage order (the thesis's cost; the
  /// reference path for tests and benchmarks).
  std::vector<std::uint32_t> queryBruteForce(const SliceRegion& region, std::vector<geom::Vec3>* positions = nullptr,
                                             const PlaneFrame* frame = nullptr,
                                             std::vector<geom::Vec2>* coords = nullptr) const;
  /// Number of points inside `region` (same cost as query, no allocation of the result).
  std::size_t count(const SliceRegion& region) const;

  /// True when the region's line/ball test cannot exclude any point of the cloud (the cylinder
  /// or ball contains the whole bounding box), i.e. the region equals its slab within the cloud.
  bool regionCoversCloud(const SliceRegion& region) const;

  /// Leaves out of every later query the stored points for which `excluded(position)` is true
  /// (e.g. the points a not-wood lasso marks), and brings back every point an earlier call left
  /// out. Returns how many points are now left out. The points keep their cells and slots (their
  /// positions are set to NaN, which no region test accepts, on both query paths), so results
  /// stay in the same storage order. Not safe while other threads query this index.
  std::size_t setExcluded(const std::function<bool(const geom::Vec3&)>& excluded);
  /// The same, deciding by the point's index in the cloud the index was built from as well as its
  /// position (a per-point class, such as the wood/leaf classification's).
  std::size_t setExcludedByIndex(const std::function<bool(std::uint32_t index, const geom::Vec3&)>& excluded);
  std::size_t excludedCount() const { return excludedSaved_.size(); }

  /// Original indices of the stored (finite) points in storage order, the order every query
  /// answers in. For callers that must reproduce that order with another index.
  const std::vector<std::uint32_t>& storageOrder() const { return ids_; }

  std::size_t size() const { return ids_.size(); }
  const geom::BBox& bounds() const { return bounds_; }
  double cellSize() const { return cell_; }

 private:
  template <class Visit>
  void forEachCandidateCell(const SliceRegion& region, Visit&& visit) const;
  /// Calls hit(slot) for every stored point inside `region`, in cell order.
  template <class Hit>
  void forEachHit(const SliceRegion& region, Hit&& hit) const;

  geom::BBox bounds_;
  double cell_ = 1.0;
  bool avx2_ = false;  ///< the pre-test runs eight-wide (allowAvx2 and the processor has AVX2)
  int dims_[3] = {0, 0, 0};
  std::vector<std::uint32_t> cellStart_;  ///< size cells+1, into sorted arrays
  /// One bit per cell, set when the cell holds a point: a query's cell walk tests these (1/32 of
  /// cellStart_'s bytes, mostly cached) instead of reading cellStart_ for the many empty cells
  /// around a branch's surface.
  std::vector<std::uint64_t> occupied_;
  std::vector<geom::Vec3> sorted_;  ///< finite positions, sorted by cell
  std::vector<std::uint32_t> ids_;  ///< original index of each sorted point
  /// Float copy of sorted_ relative to centre_ (one array per axis, so the pre-test vectorizes):
  /// a conservative pre-test that streams half the bytes; points it cannot decide are tested
  /// exactly on sorted_. Padded with 8 zeros: the pre-test reads blocks of 4 (8 with AVX2).
  geom::Vec3 centre_ = geom::Vec3::Zero();
  std::vector<float> fpos_[3];
  /// setExcluded: the slots left out and their positions, to restore them.
  std::vector<std::pair<std::uint32_t, geom::Vec3>> excludedSaved_;
};

}  // namespace treesketch::fit
