// Closest-point queries: the exact closest point on a triangle, the Morton order of batches, and
// the nearest point of a point cloud. The mesh BVH is in mesh_closest_point.cpp.
//
// Point-triangle: the Voronoi-region method of Ericson, "Real-Time Collision Detection" (2005),
// §5.1.5, written from the book's description.
// Clouds: the nearest point of accel::PointIndex (a k-d tree).
#include "treesketch/accel/closest_point.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "accel/batch.h"
#include "treesketch/accel/point_index.h"
#include "treesketch/util/error.h"

namespace treesketch::accel {

using geom::Vec3;

// ---- point-triangle ------------------------------------------------------------------------

namespace {

Vec3 closestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  Vec3 ab = b - a;
  double len2 = ab.squaredNorm();
  if (!(len2 > 0)) return a;
  double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

// Degenerate triangle: the closest of its three sides (a collinear or collapsed triangle is the
// union of its sides).
Vec3 closestOnDegenerate(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, TriangleRegion* region) {
  std::array<Vec3, 3> cand = {closestOnSegment(p, a, b), closestOnSegment(p, b, c), closestOnSegment(p, c, a)};
  int best = 0;
  for (int i = 1; i < 3; ++i)
    if ((cand[i] - p).squaredNorm() < (cand[best] - p).squaredNorm()) best = i;
  if (region)
    *region = best == 0 ? TriangleRegion::EdgeAB : best == 1 ? TriangleRegion::EdgeBC : TriangleRegion::EdgeCA;
  return cand[best];
}

// Ericson's region tests multiply four coordinate differences: for differences beyond this (or
// below its inverse) the products overflow (underflow) a double. Such a triangle is solved scaled
// by a power of two around `a` (found by fuzzing: a triangle at 1e106 had no closest point).
constexpr double kUnscaledRange = 1e60;

Vec3 closestUnscaled(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, TriangleRegion* region) {
  auto set = [region](TriangleRegion r) {
    if (region) *region = r;
  };
  const Vec3 ab = b - a, ac = c - a;
  // Projections of p relative to each corner onto the two edge directions decide the region.
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return set(TriangleRegion::VertexA), a;

  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return set(TriangleRegion::VertexB), b;

  // vc: signed area measure of (p, a, b) -> p projects outside edge AB.
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double den = d1 - d3;
    if (!(den > 0)) return closestOnDegenerate(p, a, b, c, region);
    set(TriangleRegion::EdgeAB);
    return a + (d1 / den) * ab;
  }

  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return set(TriangleRegion::VertexC), c;

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double den = d2 - d6;
    if (!(den > 0)) return closestOnDegenerate(p, a, b, c, region);
    set(TriangleRegion::EdgeCA);
    return a + (d2 / den) * ac;
  }

  const double va = d3 * d6 - d5 * d4;
  const double e1 = d4 - d3, e2 = d5 - d6;
  if (va <= 0 && e1 >= 0 && e2 >= 0) {
    const double den = e1 + e2;
    if (!(den > 0)) return closestOnDegenerate(p, a, b, c, region);
    set(TriangleRegion::EdgeBC);
    return b + (e1 / den) * (c - b);
  }

  const double sum = va + vb + vc;
  if (!(sum > 0)) return closestOnDegenerate(p, a, b, c, region);
  set(TriangleRegion::Face);
  const double v = vb / sum, w = vc / sum;
  return a + v * ab + w * ac;
}

}  // namespace

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, TriangleRegion* region) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double m = std::max({ab.cwiseAbs().maxCoeff(), ac.cwiseAbs().maxCoeff(), ap.cwiseAbs().maxCoeff()});
  if ((m > kUnscaledRange || m < 1 / kUnscaledRange) && m > 0 && std::isfinite(m)) {
    // Exact: a power of two. Capped at 2^1000: for a subnormal m (below 2^-1022, found by fuzzing:
    // a triangle 1e-312 across) 2^-ilogb(m) itself overflows to inf; 2^1000 brings such m to at
    // least 2^-74, well inside the unscaled range.
    const double s = std::ldexp(1.0, std::min(-std::ilogb(m), 1000));
    return a + closestUnscaled(ap * s, Vec3::Zero(), ab * s, ac * s, region) / s;
  }
  return closestUnscaled(p, a, b, c, region);
}

// ---- Morton order -----------------------------------------------------------------------------

namespace {

// Spreads the low 16 bits of x so that bit i lands on bit 3i.
std::uint64_t spreadBits16(std::uint64_t x) {
  x &= 0xffff;
  x = (x | x << 16) & 0x0000ff0000ffULL;
  x = (x | x << 8) & 0x00f00f00f00fULL;
  x = (x | x << 4) & 0x0c30c30c30c3ULL;
  x = (x | x << 2) & 0x249249249249ULL;
  return x;
}

}  // namespace

std::vector<std::uint32_t> mortonOrder(const std::vector<Vec3>& points) {
  const std::size_t n = points.size();
  geom::BBox box;
  for (const auto& p : points)
    if (p.allFinite()) box.add(p);
  // 16 bits per axis (48-bit codes): cells of 1/65536 of the box, far finer than the spacing of
  // any sample set this orders.
  struct Key {
    std::uint64_t code;
    std::uint32_t index;
  };
  std::vector<Key> keys(n), tmp(n);
  // Half-coordinates: max − min overflows to inf for points spread near ±DBL_MAX (and then
  // inf × 0 or inf / inf made a NaN cell index, found by fuzzing); halves cannot overflow.
  const Vec3 halfExt = 0.5 * box.max - 0.5 * box.min;
  const double maxExt = std::max({halfExt.x(), halfExt.y(), halfExt.z(), 1e-300});
  const double scale = 65535.0 / maxExt;  // finite: maxExt >= 1e-300
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      std::uint64_t code = 0;
      if (points[i].allFinite() && !box.empty()) {
        std::uint64_t q[3];
        for (int k = 0; k < 3; ++k) {
          const double t = (0.5 * points[i][k] - 0.5 * box.min[k]) * scale;
          q[k] = t >= 0 ? static_cast<std::uint64_t>(std::min(t, 65535.0)) : 0;  // NaN-safe
        }
        code = spreadBits16(q[0]) | spreadBits16(q[1]) << 1 | spreadBits16(q[2]) << 2;
      }
      keys[i] = {code, static_cast<std::uint32_t>(i)};
    }
  });
  // Least-significant-digit radix sort, 4 passes of 12 bits; stable, so equal codes keep input
  // order and the result is deterministic.
  constexpr int kBits = 12, kBuckets = 1 << kBits;
  std::vector<std::size_t> count(kBuckets);
  for (int pass = 0; pass < 4; ++pass) {
    const int shift = pass * kBits;
    std::fill(count.begin(), count.end(), 0);
    for (const Key& k : keys) ++count[(k.code >> shift) & (kBuckets - 1)];
    std::size_t sum = 0;
    for (auto& c : count) {
      const std::size_t x = c;
      c = sum;
      sum += x;
    }
    for (const Key& k : keys) tmp[count[(k.code >> shift) & (kBuckets - 1)]++] = k;
    keys.swap(tmp);
  }
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = keys[i].index;
  return order;
}

// ---- point cloud -------------------------------------------------------------------------------

struct CloudClosestPoint::Impl {
  ClosestPointOptions options;
  std::unique_ptr<PointIndex> index;

  ClosestHit answer(const Vec3& q, double maxDistance) const {
    ClosestHit hit;
    if (!index || !q.allFinite() || !(maxDistance >= 0)) return hit;
    const std::optional<Neighbour> nearest = index->nearest(q);
    if (!nearest) return hit;
    const double d = std::sqrt(nearest->distance2);
    if (d > maxDistance) return hit;
    hit.point = index->point(nearest->index);
    hit.distance = d;
    hit.index = nearest->index;
    return hit;
  }
};

CloudClosestPoint::CloudClosestPoint(const geom::PointCloud& cloud, const ClosestPointOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  for (std::size_t i = 0; i < cloud.positions.size(); ++i)
    if (!cloud.positions[i].allFinite())
      throw OptionsError("closest point: cloud point " + std::to_string(i) + " is NaN or infinite");
  if (cloud.positions.size() >= std::numeric_limits<std::uint32_t>::max())
    throw OptionsError("closest point: too many cloud points (" + std::to_string(cloud.positions.size()) + ")");
  impl_->index = std::make_unique<PointIndex>(cloud.positions);
}
CloudClosestPoint::~CloudClosestPoint() = default;
CloudClosestPoint::CloudClosestPoint(CloudClosestPoint&&) noexcept = default;
CloudClosestPoint& CloudClosestPoint::operator=(CloudClosestPoint&&) noexcept = default;

std::size_t CloudClosestPoint::pointCount() const { return impl_->index->size(); }

ClosestHit CloudClosestPoint::query(const Vec3& p, double maxDistance) const { return impl_->answer(p, maxDistance); }

std::vector<ClosestHit> CloudClosestPoint::queryAll(const std::vector<Vec3>& points, double maxDistance,
                                                    const ProgressFn& progress) const {
  std::vector<ClosestHit> hits(points.size());
  const Impl& im = *impl_;
  detail::runBatch(points, im.options, progress, [&](std::uint32_t qi, std::int64_t warm) {
    hits[qi] = im.answer(points[qi], maxDistance);
    return warm;
  });
  return hits;
}

}  // namespace treesketch::accel
