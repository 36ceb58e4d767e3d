// Slice queries on a uniform grid (thesis §4.4 CollectPoints / CalcDisc, made output-sensitive).
#include "treesketch/fit/cloud_index.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "fit/slice_pretest.h"
#include "treesketch/util/error.h"

namespace treesketch::fit {

using geom::Vec3;

namespace {
#if defined(TREESKETCH_AVX2_DISPATCH)
bool cpuHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#endif
}  // namespace

void SliceRegion::validate() const {
  auto bad = [](const std::string& what) { throw OptionsError("slice region: " + what); };
  if (!planePoint.allFinite() || !planeNormal.allFinite()) bad("plane point and normal must be finite");
  if (std::abs(planeNormal.norm() - 1.0) > 1e-6) bad("plane normal must be a unit vector");
  if (!(halfThickness > 0.0) || !std::isfinite(halfThickness)) bad("half-thickness must be positive and finite");
  if (kind == Kind::Slab) return;
  if (!linePoint.allFinite()) bad("line point / centre must be finite");
  if (!(radius > 0.0) || std::isnan(radius)) bad("radius must be positive");
  if (kind == Kind::Cylinder && std::abs(lineDir.norm() - 1.0) > 1e-6) bad("line direction must be a unit vector");
}

std::vector<std::uint32_t> sliceBruteForce(const geom::PointCloud& cloud, const SliceRegion& region) {
  region.validate();
  std::vector<std::uint32_t> out;
  const auto& pts = cloud.positions;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (region.contains(pts[i])) out.push_back(std::uint32_t(i));
  return out;
}

namespace {

// Grows `cell` by 10 % steps until the grid over `ext` has at most cellCap cells; sets dims.
void fitGridDims(const Vec3& ext, double cellCap, double& cell, int (&dims)[3]) {
  for (;;) {
    double total = 1.0;
    for (int a = 0; a < 3; ++a) {
      dims[a] = std::max(1, int(std::ceil(ext[a] / cell)));
      total *= dims[a];
    }
    if (total <= cellCap) break;
    cell *= 1.1;
  }
}

// Refine: occupied cells of a surface scan hold ~cell² points; shrink cells until they hold about
// pointsPerOccupiedCell (at most 3 passes over the points, within maxCells).
void refineGridCell(const std::vector<Vec3>& pts, const geom::BBox& bounds, std::size_t nFinite,
                    const CloudIndexOptions& options, const Vec3& ext, double cellCap, double& cell, int (&dims)[3]) {
  for (int pass = 0; pass < 3 && options.pointsPerOccupiedCell > 0.0; ++pass) {
    const std::size_t cells = std::size_t(dims[0]) * dims[1] * dims[2];
    // Occupancy as a point sees it (Σ count² / n): what a query pays per hit. The plain mean over
    // occupied cells is dragged down by sparse clutter (one point a cell) while the surface cells
    // that queries hit hold hundreds.
    std::vector<std::uint32_t> counts(cells, 0);
    double sumSq = 0.0;
    for (const auto& p : pts) {
      if (!p.allFinite()) continue;
      std::size_t lin = 0;
      for (int a = 2; a >= 0; --a)
        lin = lin * dims[a] + std::clamp(int(std::floor((p[a] - bounds.min[a]) / cell)), 0, dims[a] - 1);
      sumSq += 2.0 * counts[lin] + 1.0;  // (c + 1)² − c²
      ++counts[lin];
    }
    const double perCell = sumSq / double(nFinite);
    if (perCell < 2.0 * options.pointsPerOccupiedCell) break;
    const double before = cell;
    cell *= std::max(0.25, std::sqrt(options.pointsPerOccupiedCell / perCell));
    fitGridDims(ext, cellCap, cell, dims);
    if (cell >= 0.95 * before) break;  // held back by the cell cap
  }
}

// Each point's grid cell (linear index; -1 for a non-finite point), and the cells' counts into
// cellStart[c + 1].
std::vector<std::uint32_t> cellsOfPoints(const std::vector<Vec3>& pts, const geom::BBox& bounds, double cell,
                                         const int (&dims)[3], std::vector<std::uint32_t>& cellStart) {
  std::vector<std::uint32_t> cellOf(pts.size(), std::uint32_t(-1));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!pts[i].allFinite()) continue;
    std::size_t lin = 0;
    for (int a = 2; a >= 0; --a) {
      int c = std::clamp(int(std::floor((pts[i][a] - bounds.min[a]) / cell)), 0, dims[a] - 1);
      lin = lin * dims[a] + c;
    }
    cellOf[i] = std::uint32_t(lin);
    ++cellStart[lin + 1];
  }
  return cellOf;
}

}  // namespace

CloudIndex::CloudIndex(const geom::PointCloud& cloud, const CloudIndexOptions& options) {
  if (!(options.pointsPerCell > 0.0) || options.maxCells < 1 || !(options.maxCellsPerPoint >= 0.0))
    throw OptionsError("cloud index: pointsPerCell and maxCells must be positive, maxCellsPerPoint >= 0");
  if (cloud.size() >= std::size_t(std::numeric_limits<std::uint32_t>::max()))
    throw OptionsError("cloud index: too many points (at most 2^32 - 2)");
#if defined(TREESKETCH_AVX2_DISPATCH)
  avx2_ = options.allowAvx2 && cpuHasAvx2();
#endif
  const auto& pts = cloud.positions;
  std::size_t nFinite = 0;
  for (const auto& p : pts)
    if (p.allFinite()) {
      bounds_.add(p);
      ++nFinite;
    }
  if (nFinite == 0) {
    cellStart_.assign(1, 0);
    return;
  }
  const double cellCap =
      options.maxCellsPerPoint > 0.0
          ? std::min(double(options.maxCells), std::max(4096.0, options.maxCellsPerPoint * double(nFinite)))
          : double(options.maxCells);
  Vec3 ext = bounds_.extent();
  double diag = std::max(bounds_.diagonal(), 1e-9);
  Vec3 thick = ext.cwiseMax(Vec3::Constant(1e-3 * diag));
  double targetCells = std::clamp(double(nFinite) / options.pointsPerCell, 1.0, cellCap);
  cell_ = std::cbrt(thick.prod() / targetCells);
  fitGridDims(ext, cellCap, cell_, dims_);
  refineGridCell(pts, bounds_, nFinite, options, ext, cellCap, cell_, dims_);
  const std::size_t nCells = std::size_t(dims_[0]) * dims_[1] * dims_[2];
  cellStart_.assign(nCells + 1, 0);
  const std::vector<std::uint32_t> cellOf = cellsOfPoints(pts, bounds_, cell_, dims_, cellStart_);
  occupied_.assign((nCells + 63) / 64, 0);
  for (std::size_t c = 0; c < nCells; ++c) {
    if (cellStart_[c + 1] != 0) occupied_[c >> 6] |= std::uint64_t(1) << (c & 63);
    cellStart_[c + 1] += cellStart_[c];
  }
  std::vector<std::uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  sorted_.resize(nFinite);
  ids_.resize(nFinite);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (cellOf[i] == std::uint32_t(-1)) continue;
    std::uint32_t slot = fill[cellOf[i]]++;
    sorted_[slot] = pts[i];
    ids_[slot] = std::uint32_t(i);
  }
  centre_ = bounds_.centre();
  for (int a = 0; a < 3; ++a) {
    fpos_[a].assign(nFinite + 8, 0.0f);  // padded: the pre-test reads blocks of 4 (8 with AVX2)
    for (std::size_t s = 0; s < nFinite; ++s) fpos_[a][s] = float(sorted_[s][a] - centre_[a]);
  }
}

std::size_t CloudIndex::setExcluded(const std::function<bool(const Vec3&)>& excluded) {
  if (!excluded) return setExcludedByIndex({});
  return setExcludedByIndex([&excluded](std::uint32_t, const Vec3& p) { return excluded(p); });
}

std::size_t CloudIndex::setExcludedByIndex(const std::function<bool(std::uint32_t, const Vec3&)>& excluded) {
  for (const auto& [slot, p] : excludedSaved_) {
    sorted_[slot] = p;
    for (int a = 0; a < 3; ++a) fpos_[a][slot] = float(p[a] - centre_[a]);
  }
  excludedSaved_.clear();
  if (!excluded) return 0;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t s = 0; s < sorted_.size(); ++s) {
    if (!excluded(ids_[s], sorted_[s])) continue;
    excludedSaved_.emplace_back(std::uint32_t(s), sorted_[s]);
    sorted_[s] = Vec3::Constant(kNaN);
    for (int a = 0; a < 3; ++a) fpos_[a][s] = std::numeric_limits<float>::quiet_NaN();
  }
  return excludedSaved_.size();
}

bool CloudIndex::regionCoversCloud(const SliceRegion& region) const {
  if (region.kind == SliceRegion::Kind::Slab || bounds_.empty()) return true;
  for (int corner = 0; corner < 8; ++corner) {
    Vec3 p((corner & 1) ? bounds_.max.x() : bounds_.min.x(), (corner & 2) ? bounds_.max.y() : bounds_.min.y(),
           (corner & 4) ? bounds_.max.z() : bounds_.min.z());
    Vec3 d = p - region.linePoint;
    if (region.kind == SliceRegion::Kind::Cylinder) d -= d.dot(region.lineDir) * region.lineDir;
    if (!(d.norm() < region.radius)) return false;
  }
  return true;
}

// Visits (as a linear cell index; only occupied cells) every cell that may hold a point of `region`: the cells of the
// region's bounding box (ball, or the clipped cylinder axis ± radius) whose column along the
// normal's dominant axis meets the slab, and whose centre is within radius + half-diagonal of the
// axis/centre. A superset of the cells holding region points; points are then tested exactly.
namespace {

// clamp(floor(v), -1, 1e9) as an int, without a call to floor (baseline x86-64 has no rounding
// instruction; this runs for every column of a query).
int floorClamped(double v) {
  v = std::clamp(v, -1.0, 1e9);
  const int i = int(v);
  return i - (v < double(i));
}

}  // namespace

namespace {

// The range of grid cells [clo, chi] (per axis) whose box the region may reach: the grid clipped
// to a ball's box, or to a cylinder's axis segment inside the grid grown by its radius. False when
// no cell can be reached.
bool candidateCellBox(const SliceRegion& region, const geom::BBox& bounds, const int (&dims)[3], double cell,
                      double margin, int (&clo)[3], int (&chi)[3]) {
  Vec3 lo = bounds.min, hi = bounds.min + Vec3(dims[0], dims[1], dims[2]) * cell;
  const double r = region.radius;
  if (region.kind == SliceRegion::Kind::Ball) {
    lo = lo.cwiseMax(region.linePoint - Vec3::Constant(r + margin));
    hi = hi.cwiseMin(region.linePoint + Vec3::Constant(r + margin));
  } else if (region.kind == SliceRegion::Kind::Cylinder && std::isfinite(r)) {
    // Clip the axis to the grid box grown by r (slab method), then bound the clipped segment ± r.
    Vec3 blo = lo - Vec3::Constant(r + margin), bhi = hi + Vec3::Constant(r + margin);
    double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      double o = region.linePoint[a], d = region.lineDir[a];
      if (std::abs(d) < 1e-300) {
        if (o < blo[a] || o > bhi[a]) return false;
        continue;
      }
      double ta = (blo[a] - o) / d, tb = (bhi[a] - o) / d;
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    if (t0 > t1) return false;
    Vec3 p0 = region.linePoint + t0 * region.lineDir, p1 = region.linePoint + t1 * region.lineDir;
    lo = lo.cwiseMax(p0.cwiseMin(p1) - Vec3::Constant(r + margin));
    hi = hi.cwiseMin(p0.cwiseMax(p1) + Vec3::Constant(r + margin));
  }
  for (int a = 0; a < 3; ++a) {
    if (lo[a] > hi[a]) return false;
    clo[a] = int(std::clamp(std::floor((lo[a] - bounds.min[a]) / cell), 0.0, double(dims[a] - 1)));
    chi[a] = int(std::clamp(std::floor((hi[a] - bounds.min[a]) / cell), 0.0, double(dims[a] - 1)));
  }
  return true;
}

}  // namespace

template <class Visit>
void CloudIndex::forEachCandidateCell(const SliceRegion& region, Visit&& visit) const {
  if (sorted_.empty()) return;
  const double margin = 1e-6 * cell_;
  const double r = region.radius;
  int clo[3], chi[3];
  if (!candidateCellBox(region, bounds_, dims_, cell_, margin, clo, chi)) return;
  const Vec3& n = region.planeNormal;
  int k = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(n[a]) > std::abs(n[k])) k = a;
  const int ia = (k + 1) % 3, ib = (k + 2) % 3;
  const double halfDiag = 0.5 * std::sqrt(3.0) * cell_;
  const double reach = r + halfDiag + margin;
  const double nk = n[k];
  const double slabK = (region.halfThickness + margin) / std::abs(nk);
  const double planeD = n.dot(region.planePoint);
  const double invNk = 1.0 / nk;
  const double spreadK = 0.5 * cell_ * (std::abs(n[ia]) + std::abs(n[ib])) * std::abs(invNk) + slabK;
  const std::size_t stride[3] = {1, std::size_t(dims_[0]), std::size_t(dims_[0]) * std::size_t(dims_[1])};
  for (int i = clo[ia]; i <= chi[ia]; ++i) {
    double a0 = bounds_.min[ia] + i * cell_, a1 = a0 + cell_;
    for (int j = clo[ib]; j <= chi[ib]; ++j) {
      double b0 = bounds_.min[ib] + j * cell_, b1 = b0 + cell_;
      int ballK0 = clo[k], ballK1 = chi[k];
      if (region.kind == SliceRegion::Kind::Ball) {
        // The column (unbounded along k) misses the ball when its rectangle is farther than r;
        // otherwise the ball spans ±√(r² − e²) along k over it.
        const double ea = std::max({a0 - region.linePoint[ia], region.linePoint[ia] - a1, 0.0});
        const double eb = std::max({b0 - region.linePoint[ib], region.linePoint[ib] - b1, 0.0});
        const double e2 = ea * ea + eb * eb, rr = (r + margin) * (r + margin);
        if (e2 > rr) continue;
        const double hk = std::sqrt(rr - e2) + margin;
        ballK0 = floorClamped((region.linePoint[k] - hk - bounds_.min[k]) / cell_);
        ballK1 = floorClamped((region.linePoint[k] + hk - bounds_.min[k]) / cell_);
      }
      // The plane's k coordinate over the column's rectangle is linear: its value at the centre
      // ± the half-spread to the corners (rounding differs from the corner values by far less
      // than the margin in slabK).
      const double kc = (planeD - n[ia] * (a0 + 0.5 * cell_) - n[ib] * (b0 + 0.5 * cell_)) * invNk;
      const double kmin = kc - spreadK, kmax = kc + spreadK;
      int k0 = std::max({clo[k], ballK0, floorClamped((kmin - bounds_.min[k]) / cell_)});
      int k1 = std::min({chi[k], ballK1, floorClamped((kmax - bounds_.min[k]) / cell_)});
      // Linear index by strides (an index array written and re-read as a whole stalled on
      // store forwarding).
      const std::size_t column = std::size_t(i) * stride[ia] + std::size_t(j) * stride[ib];
      Vec3 centre;
      centre[ia] = a0 + 0.5 * cell_;
      centre[ib] = b0 + 0.5 * cell_;
      for (int c = k0; c <= k1; ++c) {
        const std::size_t cell = column + std::size_t(c) * stride[k];
        if (!((occupied_[cell >> 6] >> (cell & 63)) & 1)) continue;  // empty: most candidate cells
        if (region.kind == SliceRegion::Kind::Cylinder) {
          centre[k] = bounds_.min[k] + (c + 0.5) * cell_;
          Vec3 d = centre - region.linePoint;
          d -= d.dot(region.lineDir) * region.lineDir;
          if (d.squaredNorm() > reach * reach) continue;
        }
        visit(cell);
      }
    }
  }
}

namespace {

// Sorts disjoint slot ranges and merges the touching ones.
void sortAndMerge(std::vector<std::pair<std::uint32_t, std::uint32_t>>& ranges) {
  std::sort(ranges.begin(), ranges.end());
  std::size_t merged = 0;
  for (std::size_t i = 1; i < ranges.size(); ++i) {
    if (ranges[merged].second == ranges[i].first)
      ranges[merged].second = ranges[i].second;
    else
      ranges[++merged] = ranges[i];
  }
  if (!ranges.empty()) ranges.resize(merged + 1);
}

// Per-thread buffers reused across queries: a node fit runs a few queries of a few thousand
// hits, where heap allocation was a visible share of the cost.
struct QueryScratch {
  std::vector<std::size_t> cells;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges;
  std::vector<std::uint32_t> slots;
};
QueryScratch& scratch() {
  thread_local QueryScratch s;
  return s;
}
// Keeps a thread's buffers from holding on to a whole-cloud query's memory.
template <class T>
void trim(std::vector<T>& v) {
  constexpr std::size_t kKeep = std::size_t(1) << 16;
  if (v.capacity() > kKeep) {
    v.clear();
    v.shrink_to_fit();
  }
}

}  // namespace

// Every stored point inside `region`, in cell order. A float pre-test on fpos_ (relative to the
// grid's centre) rejects the points that are outside by far more than float rounding can explain
// (tolerance 1e-5 of the coordinates' magnitude, ~100x the worst rounding error) and accepts those
// inside by as much; only the few undecided points in between get the exact double test, so the
// result equals the brute-force scan.
template <class Hit>
void CloudIndex::forEachHit(const SliceRegion& region, Hit&& hit) const {
  const double mag = 0.5 * bounds_.diagonal();
  const Vec3 pp = region.planePoint - centre_, lp = region.linePoint - centre_;
  const bool radial = region.kind != SliceRegion::Kind::Slab &&
                      region.radius + 1e-5 * (mag + lp.norm() + region.radius) < 1e15;
  // Coordinates beyond float range: every candidate gets the exact test.
  const bool useFloat = mag < 1e30 && pp.norm() < 1e30 && lp.norm() < 1e30;
  const FloatTest ft = floatTest(region, pp, lp, mag, radial);
  // The candidate cells are scattered over large arrays, so a query is bound by memory latency:
  // collect the cells first, then read their bounds and their points with prefetches a few cells
  // ahead (many misses in flight instead of one at a time). Consecutive cells are stored
  // consecutively, so their ranges merge into longer runs.
  QueryScratch& sc = scratch();
  auto& cells = sc.cells;
  auto& ranges = sc.ranges;
  cells.clear();
  ranges.clear();
  forEachCandidateCell(region, [&](std::size_t cell) { cells.push_back(cell); });
  constexpr std::size_t kAhead = 8;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i + kAhead < cells.size()) __builtin_prefetch(&cellStart_[cells[i + kAhead]]);
    const std::uint32_t s0 = cellStart_[cells[i]], s1 = cellStart_[cells[i] + 1];
    if (!ranges.empty() && ranges.back().second == s0)
      ranges.back().second = s1;
    else
      ranges.emplace_back(s0, s1);
  }
  trim(cells);
  // Ranges in storage order (they are disjoint): hits then come out in slot order, the order the
  // brute-force scan of the same index visits them, with no sort of the hits (sorting a node's
  // few hundred ranges is several times cheaper than sorting its thousands of hits). Sorting also
  // merges runs that the column-wise cell walk visited apart.
  sortAndMerge(ranges);
  const float* f[3] = {fpos_[0].data(), fpos_[1].data(), fpos_[2].data()};
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    if (i + kAhead < ranges.size()) {
      const std::uint32_t p0 = ranges[i + kAhead].first;
      for (int a = 0; a < 3; ++a) __builtin_prefetch(f[a] + p0);
      // The original ids of the whole range (most of a cell's points in the slab are hits). Not
      // the double positions: the exact test needs few of them, and the hits' positions are read
      // afterwards in slot order, which the hardware prefetcher follows (measured: prefetching
      // them here too was ~10 % slower).
      const std::uint32_t p1 = ranges[i + kAhead].second;
      const char* b = reinterpret_cast<const char*>(ids_.data() + p0);
      const char* e = reinterpret_cast<const char*>(ids_.data() + p1);
      for (; b < e; b += 64) __builtin_prefetch(b);
    }
    const auto [s0, s1] = ranges[i];
    // Blocks of 64 points: the pre-test yields bit masks (in / surely in), then only the set bits
    // are visited, so the loop costs per hit rather than per tested point and the unpredictable
    // in/out pattern of a slab through a cell causes no branch misses.
    for (std::uint32_t b0 = s0; b0 < s1; b0 += 64) {
      const std::uint32_t len = std::min<std::uint32_t>(64, s1 - b0);
      std::uint64_t in, sure;
      if (useFloat) {
#if defined(TREESKETCH_AVX2_DISPATCH)
        if (avx2_)
          ft.block8(f, b0, len, &in, &sure);
        else
#endif
          ft.block(f, b0, len, &in, &sure);
      } else {
        in = len == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << len) - 1;
        sure = 0;
      }
      for (; in; in &= in - 1) {
        const int q = __builtin_ctzll(in);
        if (((sure >> q) & 1) || region.contains(sorted_[b0 + q])) hit(b0 + std::uint32_t(q));
      }
    }
  }
  trim(ranges);
}

namespace {
// The slots of a query's hits (they arrive in slot order, see forEachHit: the output needs no
// sort), collected through a local pointer (push_back re-reads and stores the vector's end on
// every hit), in the thread's scratch buffer (valid until the next query).
template <class ForEach>
std::pair<const std::uint32_t*, std::size_t> gatherSlots(ForEach&& forEach) {
  auto& slots = scratch().slots;
  if (slots.size() < 1024) slots.resize(1024);
  std::uint32_t* slot = slots.data();
  std::size_t nHits = 0;
  forEach([&](std::uint32_t s) {
    if (nHits == slots.size()) {
      slots.resize(2 * slots.size());
      slot = slots.data();
    }
    slot[nHits++] = s;
  });
  return {slot, nHits};
}
}  // namespace

namespace {
// A hit's plane coordinates from the float copy (see CloudIndex::query): one expression for both
// paths, so they give the same numbers.
struct FloatProjector {
  Vec3 offset, u, v;  ///< offset = grid centre − frame origin
  const float* f[3];
  geom::Vec2 operator()(std::uint32_t s) const {
    const Vec3 d = offset + Vec3(double(f[0][s]), double(f[1][s]), double(f[2][s]));
    return geom::Vec2(d.dot(u), d.dot(v));
  }
};
}  // namespace

std::vector<std::uint32_t> CloudIndex::query(const SliceRegion& region, std::vector<Vec3>* positions,
                                             const PlaneFrame* frame, std::vector<geom::Vec2>* coords) const {
  region.validate();
  const auto [slot, nHits] = gatherSlots([&](auto&& hit) { forEachHit(region, hit); });
  std::vector<std::uint32_t> out(nHits);
  for (std::size_t i = 0; i < nHits; ++i) out[i] = ids_[slot[i]];
  if (positions) {
    positions->resize(nHits);
    for (std::size_t i = 0; i < nHits; ++i) (*positions)[i] = sorted_[slot[i]];
  }
  if (frame && coords) {
    const FloatProjector project{
        centre_ - frame->origin, frame->u, frame->v, {fpos_[0].data(), fpos_[1].data(), fpos_[2].data()}};
    coords->resize(nHits);
    for (std::size_t i = 0; i < nHits; ++i) (*coords)[i] = project(slot[i]);
  }
  trim(scratch().slots);
  return out;
}

std::vector<std::uint32_t> CloudIndex::queryBruteForce(const SliceRegion& region, std::vector<Vec3>* positions,
                                                       const PlaneFrame* frame, std::vector<geom::Vec2>* coords) const {
  region.validate();
  std::vector<std::uint32_t> out;
  if (positions) positions->clear();
  const bool project = frame && coords;
  if (project) coords->clear();
  const FloatProjector projector{project ? Vec3(centre_ - frame->origin) : Vec3::Zero(),
                                 project ? frame->u : Vec3::Zero(),
                                 project ? frame->v : Vec3::Zero(),
                                 {fpos_[0].data(), fpos_[1].data(), fpos_[2].data()}};
  for (std::size_t s = 0; s < sorted_.size(); ++s)
    if (region.contains(sorted_[s])) {
      out.push_back(ids_[s]);
      if (positions) positions->push_back(sorted_[s]);
      if (project) coords->push_back(projector(std::uint32_t(s)));
    }
  return out;
}

std::size_t CloudIndex::count(const SliceRegion& region) const {
  region.validate();
  std::size_t n = 0;
  forEachHit(region, [&](std::uint32_t) { ++n; });
  return n;
}

}  // namespace treesketch::fit
