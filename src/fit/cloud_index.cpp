// Slice queries on a uniform grid (thesis §4.4 CollectPoints / CalcDisc, made output-sensitive).
#include "treesketch/fit/cloud_index.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "treesketch/util/error.h"

namespace treesketch::fit {

using geom::Vec3;

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

CloudIndex::CloudIndex(const geom::PointCloud& cloud, const CloudIndexOptions& options) {
  if (!(options.pointsPerCell > 0.0) || options.maxCells < 1)
    throw OptionsError("cloud index: pointsPerCell and maxCells must be positive");
  if (cloud.size() >= std::size_t(std::numeric_limits<std::uint32_t>::max()))
    throw OptionsError("cloud index: too many points (at most 2^32 - 2)");
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
  Vec3 ext = bounds_.extent();
  double diag = std::max(bounds_.diagonal(), 1e-9);
  Vec3 thick = ext.cwiseMax(Vec3::Constant(1e-3 * diag));
  double targetCells = std::clamp(double(nFinite) / options.pointsPerCell, 1.0, double(options.maxCells));
  cell_ = std::cbrt(thick.prod() / targetCells);
  auto fitDims = [&] {
    for (;;) {
      double total = 1.0;
      for (int a = 0; a < 3; ++a) {
        dims_[a] = std::max(1, int(std::ceil(ext[a] / cell_)));
        total *= dims_[a];
      }
      if (total <= double(options.maxCells)) break;
      cell_ *= 1.1;
    }
  };
  fitDims();
  // Refine: occupied cells of a surface scan hold ~cell² points; shrink cells until they hold about
  // pointsPerOccupiedCell (at most 3 passes over the points, within maxCells).
  for (int pass = 0; pass < 3 && options.pointsPerOccupiedCell > 0.0; ++pass) {
    const std::size_t cells = std::size_t(dims_[0]) * dims_[1] * dims_[2];
    // Occupancy as a point sees it (Σ count² / n): what a query pays per hit. The plain mean over
    // occupied cells is dragged down by sparse clutter (one point a cell) while the surface cells
    // that queries hit hold hundreds.
    std::vector<std::uint32_t> counts(cells, 0);
    double sumSq = 0.0;
    for (const auto& p : pts) {
      if (!p.allFinite()) continue;
      std::size_t lin = 0;
      for (int a = 2; a >= 0; --a)
        lin = lin * dims_[a] + std::clamp(int(std::floor((p[a] - bounds_.min[a]) / cell_)), 0, dims_[a] - 1);
      sumSq += 2.0 * counts[lin] + 1.0;  // (c + 1)² − c²
      ++counts[lin];
    }
    const double perCell = sumSq / double(nFinite);
    if (perCell < 2.0 * options.pointsPerOccupiedCell) break;
    const double before = cell_;
    cell_ *= std::max(0.25, std::sqrt(options.pointsPerOccupiedCell / perCell));
    fitDims();
    if (cell_ >= 0.95 * before) break;  // held back by maxCells
  }
  const std::size_t nCells = std::size_t(dims_[0]) * dims_[1] * dims_[2];
  std::vector<std::uint32_t> cellOf(pts.size(), std::uint32_t(-1));
  cellStart_.assign(nCells + 1, 0);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!pts[i].allFinite()) continue;
    std::size_t lin = 0;
    for (int a = 2; a >= 0; --a) {
      int c = std::clamp(int(std::floor((pts[i][a] - bounds_.min[a]) / cell_)), 0, dims_[a] - 1);
      lin = lin * dims_[a] + c;
    }
    cellOf[i] = std::uint32_t(lin);
    ++cellStart_[lin + 1];
  }
  for (std::size_t c = 0; c < nCells; ++c) cellStart_[c + 1] += cellStart_[c];
  std::vector<std::uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  sorted_.resize(nFinite);
  ids_.resize(nFinite);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (cellOf[i] == std::uint32_t(-1)) continue;
    std::uint32_t slot = fill[cellOf[i]]++;
    sorted_[slot] = pts[i];
    ids_[slot] = std::uint32_t(i);
  }
  idBits_ = 0;
  while (idBits_ < 32 && (std::uint64_t(pts.size()) >> idBits_) != 0) ++idBits_;
  centre_ = bounds_.center();
  for (int a = 0; a < 3; ++a) {
    fpos_[a].resize(nFinite);
    for (std::size_t s = 0; s < nFinite; ++s) fpos_[a][s] = float(sorted_[s][a] - centre_[a]);
  }
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

// Visits (as a linear cell index, empty cells included) every cell that may hold a point of `region`: the cells of the
// region's bounding box (ball, or the clipped cylinder axis ± radius) whose column along the
// normal's dominant axis meets the slab, and whose centre is within radius + half-diagonal of the
// axis/centre. A superset of the cells holding region points; points are then tested exactly.
template <class Visit>
void CloudIndex::forEachCandidateCell(const SliceRegion& region, Visit&& visit) const {
  if (sorted_.empty()) return;
  const double margin = 1e-6 * cell_;
  Vec3 lo = bounds_.min, hi = bounds_.min + Vec3(dims_[0], dims_[1], dims_[2]) * cell_;
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
        if (o < blo[a] || o > bhi[a]) return;
        continue;
      }
      double ta = (blo[a] - o) / d, tb = (bhi[a] - o) / d;
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    if (t0 > t1) return;
    Vec3 p0 = region.linePoint + t0 * region.lineDir, p1 = region.linePoint + t1 * region.lineDir;
    lo = lo.cwiseMax(p0.cwiseMin(p1) - Vec3::Constant(r + margin));
    hi = hi.cwiseMin(p0.cwiseMax(p1) + Vec3::Constant(r + margin));
  }
  int clo[3], chi[3];
  for (int a = 0; a < 3; ++a) {
    if (lo[a] > hi[a]) return;
    clo[a] = int(std::clamp(std::floor((lo[a] - bounds_.min[a]) / cell_), 0.0, double(dims_[a] - 1)));
    chi[a] = int(std::clamp(std::floor((hi[a] - bounds_.min[a]) / cell_), 0.0, double(dims_[a] - 1)));
  }
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
        ballK0 = int(std::clamp(std::floor((region.linePoint[k] - hk - bounds_.min[k]) / cell_), -1.0, 1e9));
        ballK1 = int(std::clamp(std::floor((region.linePoint[k] + hk - bounds_.min[k]) / cell_), -1.0, 1e9));
      }
      // The plane's k coordinate over the column's rectangle is linear: extremes at corners.
      double kmin = std::numeric_limits<double>::infinity(), kmax = -kmin;
      for (double av : {a0, a1})
        for (double bv : {b0, b1}) {
          double kv = (planeD - n[ia] * av - n[ib] * bv) / nk;
          kmin = std::min(kmin, kv);
          kmax = std::max(kmax, kv);
        }
      kmin -= slabK;
      kmax += slabK;
      int k0 = std::max({clo[k], ballK0, int(std::clamp(std::floor((kmin - bounds_.min[k]) / cell_), -1.0, 1e9))});
      int k1 = std::min({chi[k], ballK1, int(std::clamp(std::floor((kmax - bounds_.min[k]) / cell_), -1.0, 1e9))});
      for (int c = k0; c <= k1; ++c) {
        int idx[3];
        idx[k] = c;
        idx[ia] = i;
        idx[ib] = j;
        std::size_t lin = (std::size_t(idx[2]) * dims_[1] + idx[1]) * dims_[0] + idx[0];
        if (region.kind == SliceRegion::Kind::Cylinder) {  // geometry first: cheaper than a cache miss
          Vec3 centre = bounds_.min + (Vec3(idx[0], idx[1], idx[2]) + Vec3::Constant(0.5)) * cell_;
          Vec3 d = centre - region.linePoint;
          if (region.kind == SliceRegion::Kind::Cylinder) d -= d.dot(region.lineDir) * region.lineDir;
          if (d.squaredNorm() > reach * reach) continue;
        }
        visit(lin);
      }
    }
  }
}

// Every stored point inside `region`, in cell order. A float pre-test on fpos_ (relative to the
// grid's centre) rejects the points that are outside by far more than float rounding can explain
// (tolerance 1e-5 of the coordinates' magnitude, ~100x the worst rounding error); the survivors
// get the exact double test, so the result equals the brute-force scan.
template <class Hit>
void CloudIndex::forEachHit(const SliceRegion& region, Hit&& hit) const {
  const double mag = 0.5 * bounds_.diagonal();
  const Vec3 pp = region.planePoint - centre_, lp = region.linePoint - centre_;
  const Vec3& n = region.planeNormal;
  const float nx = float(n.x()), ny = float(n.y()), nz = float(n.z());
  const float pd = float(n.dot(pp));
  const double slabTol = 1e-5 * (mag + pp.norm()) + 1e-30;
  const float hs = float(region.halfThickness + slabTol);
  const float hsIn = float(std::max(0.0, region.halfThickness - slabTol));  // surely inside below
  const bool radial = region.kind != SliceRegion::Kind::Slab &&
                      region.radius + 1e-5 * (mag + lp.norm() + region.radius) < 1e15;
  const bool ball = region.kind == SliceRegion::Kind::Ball;
  // Without a usable radial pre-test only pure slabs can be decided in float.
  const bool radialSure = region.kind == SliceRegion::Kind::Slab;
  // Coordinates beyond float range: every candidate gets the exact test.
  const bool useFloat = mag < 1e30 && pp.norm() < 1e30 && lp.norm() < 1e30;
  const double rTol = radial ? region.radius + 1e-5 * (mag + lp.norm() + region.radius) + 1e-30 : 0.0;
  const float r2 = float(rTol * rTol);
  const double rIn = radial ? std::max(0.0, region.radius - 1e-5 * (mag + lp.norm() + region.radius)) : 0.0;
  const float r2In = float(rIn * rIn);
  const float lx = float(lp.x()), ly = float(lp.y()), lz = float(lp.z());
  const float ax = float(region.lineDir.x()), ay = float(region.lineDir.y()), az = float(region.lineDir.z());
  const float *fx = fpos_[0].data(), *fy = fpos_[1].data(), *fz = fpos_[2].data();
  // The candidate cells are scattered over large arrays, so a query is bound by memory latency:
  // collect the cells first, then read their bounds and their points with prefetches a few cells
  // ahead (many misses in flight instead of one at a time).
  std::vector<std::size_t> cells;
  forEachCandidateCell(region, [&](std::size_t cell) { cells.push_back(cell); });
  constexpr std::size_t kAhead = 8;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges;
  ranges.reserve(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i + kAhead < cells.size()) __builtin_prefetch(&cellStart_[cells[i + kAhead]]);
    const std::uint32_t s0 = cellStart_[cells[i]], s1 = cellStart_[cells[i] + 1];
    if (s0 < s1) ranges.emplace_back(s0, s1);
  }
  // Per cell, a branch-free float pass compacts the candidate slots (the in/out pattern of a slab
  // through a cell is unpredictable), then the exact test runs on the candidates.
  std::vector<std::uint32_t> cand;
  std::vector<std::uint8_t> sure, code;
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    if (i + kAhead < ranges.size()) {
      const std::uint32_t p0 = ranges[i + kAhead].first;
      __builtin_prefetch(fx + p0);
      __builtin_prefetch(fy + p0);
      __builtin_prefetch(fz + p0);
      // The double positions of the whole cell (most of a cell's points in the slab are hits).
      const char* b = reinterpret_cast<const char*>(sorted_.data() + p0);
      const char* e = reinterpret_cast<const char*>(sorted_.data() + ranges[i + kAhead].second);
      for (; b < e; b += 64) __builtin_prefetch(b);
    }
    const auto [s0, s1] = ranges[i];
    const std::uint32_t len = s1 - s0;
    if (cand.size() < len) {
      cand.resize(std::max<std::size_t>(len, 2 * cand.size()));
      sure.resize(cand.size());
      code.resize(cand.size());
    }
    // Pass 1 (vectorizable): per point 0 = out, 1 = undecided, 3 = surely in.
    const float *x = fx + s0, *y = fy + s0, *z = fz + s0;
    std::uint8_t* cd = code.data();
    if (!useFloat) std::fill(cd, cd + len, std::uint8_t(1));
    if (useFloat)
    for (std::uint32_t q = 0; q < len; ++q) {
      const float ds = std::abs(nx * x[q] + ny * y[q] + nz * z[q] - pd);
      float dx = x[q] - lx, dy = y[q] - ly, dz = z[q] - lz;
      const float t = ball ? 0.0f : dx * ax + dy * ay + dz * az;
      dx -= t * ax;
      dy -= t * ay;
      dz -= t * az;
      const float rq = dx * dx + dy * dy + dz * dz;
      const bool in = (ds < hs) & (!radial | (rq < r2));
      const bool inner = (ds < hsIn) & ((radial & (rq < r2In)) | (!radial & radialSure));
      cd[q] = std::uint8_t(std::uint8_t(in) | std::uint8_t(inner << 1));
    }
    // Pass 2: branch-free compaction of the candidates.
    std::uint32_t* out = cand.data();
    std::uint8_t* isIn = sure.data();
    std::size_t k = 0;
    for (std::uint32_t q = 0; q < len; ++q) {
      out[k] = s0 + q;
      isIn[k] = cd[q] >> 1;
      k += cd[q] & 1;
    }
    // Points inside by more than the float tolerance need no exact test.
    for (std::size_t c = 0; c < k; ++c)
      if (isIn[c] || region.contains(sorted_[out[c]])) hit(out[c]);
  }
}

namespace {

// Sorts keys (id << 32 | payload) by id, ids unique and below 2^idBits: LSD radix sort with
// digits of equal width (at most 8 bits) spanning idBits, so each digit is spread over its
// buckets; all histograms in one pass; std::sort for short lists.
void sortById(std::vector<std::uint64_t>& keys, int idBits) {
  if (keys.size() < 64 || idBits <= 0) {
    std::sort(keys.begin(), keys.end());
    return;
  }
  const int passes = (idBits + 7) / 8;
  const int width = (idBits + passes - 1) / passes;
  const std::uint64_t mask = (std::uint64_t(1) << width) - 1;
  std::uint32_t count[4][256] = {};
  for (auto k : keys)
    for (int d = 0; d < passes; ++d) ++count[d][(k >> (32 + d * width)) & mask];
  std::vector<std::uint64_t> tmp(keys.size());
  for (int d = 0; d < passes; ++d) {
    std::uint32_t* c = count[d];
    const int shift = 32 + d * width;
    std::uint32_t sum = 0;
    for (std::uint64_t b = 0; b <= mask; ++b) {
      const std::uint32_t v = c[b];
      c[b] = sum;
      sum += v;
    }
    for (auto k : keys) tmp[c[(k >> shift) & mask]++] = k;
    keys.swap(tmp);
  }
}

// Hits as (original id << 32 | sorted slot): sorting the keys orders by original id.
std::vector<std::uint32_t> finish(std::vector<std::uint64_t>& hits, const std::vector<Vec3>& sorted,
                                  std::vector<Vec3>* positions) {
  std::sort(hits.begin(), hits.end());
  std::vector<std::uint32_t> out(hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i) out[i] = std::uint32_t(hits[i] >> 32);
  if (positions) {
    positions->resize(hits.size());
    for (std::size_t i = 0; i < hits.size(); ++i) (*positions)[i] = sorted[std::uint32_t(hits[i])];
  }
  return out;
}

}  // namespace

std::vector<std::uint32_t> CloudIndex::query(const SliceRegion& region, std::vector<Vec3>* positions) const {
  region.validate();
  // Keys (original id << 32 | hit number); the hits' positions are copied in cell order (a
  // contiguous read) and permuted from that small buffer after the sort.
  std::vector<std::uint64_t> keys;
  std::vector<Vec3> buf;
  keys.reserve(1024);
  if (positions) buf.reserve(1024);
  forEachHit(region, [&](std::uint32_t s) {
    keys.push_back(std::uint64_t(ids_[s]) << 32 | std::uint64_t(keys.size()));
    if (positions) buf.push_back(sorted_[s]);
  });
  sortById(keys, idBits_);
  std::vector<std::uint32_t> out(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) out[i] = std::uint32_t(keys[i] >> 32);
  if (positions) {
    positions->resize(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) (*positions)[i] = buf[std::uint32_t(keys[i])];
  }
  return out;
}

std::vector<std::uint32_t> CloudIndex::queryBruteForce(const SliceRegion& region, std::vector<Vec3>* positions) const {
  region.validate();
  std::vector<std::uint64_t> hits;
  for (std::size_t s = 0; s < sorted_.size(); ++s)
    if (region.contains(sorted_[s])) hits.push_back(std::uint64_t(ids_[s]) << 32 | s);
  return finish(hits, sorted_, positions);
}

std::size_t CloudIndex::count(const SliceRegion& region) const {
  region.validate();
  std::size_t n = 0;
  forEachHit(region, [&](std::uint32_t) { ++n; });
  return n;
}

}  // namespace treesketch::fit
