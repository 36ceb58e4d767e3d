// Closest-point queries on triangle meshes and point clouds.
//
// Point-triangle: the Voronoi-region method of Ericson, "Real-Time Collision Detection" (2005),
// §5.1.5, written from the book's description. Mesh: a binary BVH with float boxes (object-median
// splits on the longest centroid axis), depth-first layout, nearest-child-first traversal pruned by
// the best squared distance so far. Batches are sorted by Morton code and each query starts with the
// distance to the previous query's closest triangle (an upper bound of its answer: the BVH then only
// opens boxes closer than that). Clouds: nanoflann's k-d tree (1-NN).
#include "treesketch/accel/closest_point.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <nanoflann.hpp>
#include <numeric>
#include <string>

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
  if (region) *region = best == 0 ? TriangleRegion::EdgeAB : best == 1 ? TriangleRegion::EdgeBC : TriangleRegion::EdgeCA;
  return cand[best];
}

}  // namespace

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, TriangleRegion* region) {
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

// ---- Morton order -----------------------------------------------------------------------------

namespace {

std::uint64_t spreadBits21(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace

std::vector<std::uint32_t> mortonOrder(const std::vector<Vec3>& points) {
  const std::size_t n = points.size();
  geom::BBox box;
  for (const auto& p : points)
    if (p.allFinite()) box.add(p);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
  const Vec3 ext = box.extent();
  const double maxExt = std::max({ext.x(), ext.y(), ext.z(), 1e-300});
  const double scale = (double((1u << 21) - 1)) / maxExt;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      std::uint64_t code = 0;
      if (points[i].allFinite() && !box.empty()) {
        std::uint64_t q[3];
        for (int k = 0; k < 3; ++k)
          q[k] = static_cast<std::uint64_t>(std::clamp((points[i][k] - box.min[k]) * scale, 0.0, 2097151.0));
        code = spreadBits21(q[0]) | spreadBits21(q[1]) << 1 | spreadBits21(q[2]) << 2;
      }
      keys[i] = {code, static_cast<std::uint32_t>(i)};
    }
  });
  tbb::parallel_sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = keys[i].second;
  return order;
}

// ---- mesh BVH -------------------------------------------------------------------------------

namespace {

// 32 bytes: two nodes per cache line.
struct Node {
  float lo[3];
  std::uint32_t offset;  ///< interior: index of the right child (left child = this + 1); leaf: first triangle
  float hi[3];
  std::uint32_t count;  ///< 0 for an interior node, else the number of triangles of the leaf
};

struct Tri {
  Vec3 a, b, c;
};

// Cheap lower bounds of a triangle's distance, tested before the exact double test: its box and
// its plane, in float, relative to the BVH origin (the plane normal is zero for a degenerate
// triangle, so that bound never culls it).
struct TriCull {
  float lo[3], hi[3];
  float n[3], offset;  ///< unit normal and n . a (relative to the origin)
};

float roundDown(double x) {
  float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float roundUp(double x) {
  float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

inline float boxDistance2(const Node& n, float qx, float qy, float qz) {
  float dx = std::max(std::max(n.lo[0] - qx, qx - n.hi[0]), 0.0f);
  float dy = std::max(std::max(n.lo[1] - qy, qy - n.hi[1]), 0.0f);
  float dz = std::max(std::max(n.lo[2] - qz, qz - n.hi[2]), 0.0f);
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

struct MeshClosestPoint::Impl {
  ClosestPointOptions options;
  Vec3 origin = Vec3::Zero();
  double scale = 0;                  ///< bounding-box diagonal (metres), for the float-error margin
  std::vector<Node> nodes;
  std::vector<Tri> tris;             ///< in leaf order
  std::vector<TriCull> culls;        ///< in leaf order
  std::vector<std::uint32_t> triId;  ///< leaf order -> input triangle index

  void build(const geom::TriMesh& mesh);
  std::uint32_t buildNode(std::vector<std::uint32_t>& ids, const std::vector<Vec3>& centroids,
                          const std::vector<geom::BBox>& boxes, std::size_t begin, std::size_t end);
  /// Closest point with a starting bound: best2 (squared distance, metres²) and its triangle
  /// (leaf-order index, -1 for none) and point. Returns the leaf-order index of the best triangle.
  std::int64_t search(const Vec3& q, double& best2, std::int64_t bestTri, Vec3& bestPoint) const;
  ClosestHit answer(const Vec3& q, double maxDistance, std::int64_t warmTri) const;
};

void MeshClosestPoint::Impl::build(const geom::TriMesh& mesh) {
  const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
  for (std::size_t i = 0; i < nv; ++i)
    if (!mesh.vertices[i].allFinite())
      throw OptionsError("closest point: mesh vertex " + std::to_string(i) + " is NaN or infinite");
  for (std::size_t i = 0; i < nt; ++i)
    for (auto v : mesh.triangles[i])
      if (v >= nv)
        throw OptionsError("closest point: triangle " + std::to_string(i) + " references vertex " +
                           std::to_string(v) + " of " + std::to_string(nv));
  if (nt == 0) return;
  if (nt >= std::numeric_limits<std::uint32_t>::max() / 2)
    throw OptionsError("closest point: too many triangles (" + std::to_string(nt) + ")");
  if (options.leafSize < 1 || options.leafSize > 64)
    throw OptionsError("closest point: leafSize must be in [1, 64], got " + std::to_string(options.leafSize));
  if (options.blockSize < 1)
    throw OptionsError("closest point: blockSize must be positive, got " + std::to_string(options.blockSize));

  geom::BBox all;
  std::vector<Vec3> centroids(nt);
  std::vector<geom::BBox> boxes(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    const auto& t = mesh.triangles[i];
    for (auto v : t) boxes[i].add(mesh.vertices[v]);
    centroids[i] = boxes[i].center();
    all.add(boxes[i]);
  }
  origin = all.center();
  scale = all.diagonal();
  std::vector<std::uint32_t> ids(nt);
  std::iota(ids.begin(), ids.end(), 0u);
  nodes.reserve(2 * (nt / options.leafSize + 1));
  buildNode(ids, centroids, boxes, 0, nt);
  triId = ids;
  tris.resize(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    const auto& t = mesh.triangles[ids[i]];
    tris[i] = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
  }
  culls.resize(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    const Tri& t = tris[i];
    TriCull& c = culls[i];
    const Vec3 a = t.a - origin, b = t.b - origin, cc = t.c - origin;
    for (int k = 0; k < 3; ++k) {
      c.lo[k] = roundDown(std::min({a[k], b[k], cc[k]}));
      c.hi[k] = roundUp(std::max({a[k], b[k], cc[k]}));
    }
    Vec3 n = (b - a).cross(cc - a);
    const double len = n.norm();
    // Slivers get no plane bound: their normal is too unreliable to cull with.
    const double longest = std::max({(b - a).norm(), (cc - b).norm(), (a - cc).norm()});
    if (len > 1e-6 * longest * longest) {
      n /= len;
    } else {
      n.setZero();
    }
    for (int k = 0; k < 3; ++k) c.n[k] = static_cast<float>(n[k]);
    c.offset = static_cast<float>(n.dot(a));
  }
}

std::uint32_t MeshClosestPoint::Impl::buildNode(std::vector<std::uint32_t>& ids, const std::vector<Vec3>& centroids,
                                                const std::vector<geom::BBox>& boxes, std::size_t begin,
                                                std::size_t end) {
  const auto index = static_cast<std::uint32_t>(nodes.size());
  nodes.emplace_back();
  geom::BBox box, cbox;
  for (std::size_t i = begin; i < end; ++i) {
    box.add(boxes[ids[i]]);
    cbox.add(centroids[ids[i]]);
  }
  {
    Node& n = nodes[index];
    for (int k = 0; k < 3; ++k) {
      n.lo[k] = roundDown(box.min[k] - origin[k]);
      n.hi[k] = roundUp(box.max[k] - origin[k]);
    }
  }
  const std::size_t count = end - begin;
  const Vec3 ext = cbox.extent();
  int axis = 0;
  if (ext.y() > ext[axis]) axis = 1;
  if (ext.z() > ext[axis]) axis = 2;
  // A leaf when small enough; otherwise split at the median centroid along the longest axis (when
  // all centroids coincide this is an arbitrary halving: overlapping boxes, still correct).
  if (count <= static_cast<std::size_t>(options.leafSize)) {
    nodes[index].offset = static_cast<std::uint32_t>(begin);
    nodes[index].count = static_cast<std::uint32_t>(count);
    return index;
  }
  const std::size_t mid = begin + count / 2;
  std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end,
                   [&](std::uint32_t x, std::uint32_t y) { return centroids[x][axis] < centroids[y][axis]; });
  buildNode(ids, centroids, boxes, begin, mid);
  const std::uint32_t right = buildNode(ids, centroids, boxes, mid, end);
  nodes[index].offset = right;
  nodes[index].count = 0;
  return index;
}

std::int64_t MeshClosestPoint::Impl::search(const Vec3& q, double& best2, std::int64_t bestTri,
                                            Vec3& bestPoint) const {
  if (nodes.empty()) return bestTri;
  const Vec3 rel = q - origin;
  const float qx = static_cast<float>(rel.x()), qy = static_cast<float>(rel.y()), qz = static_cast<float>(rel.z());
  // Float box distances may be short of the true ones by rounding: prune a box only when it is
  // farther than the best distance plus a margin well above float error at this scale.
  const double margin = 1e-6 * (scale + rel.cwiseAbs().maxCoeff());
  auto limitOf = [margin](double b2) {
    if (!std::isfinite(b2)) return std::numeric_limits<float>::infinity();
    double l = std::sqrt(b2) + margin;
    return static_cast<float>(l * l * (1 + 1e-6));
  };
  float limit2 = limitOf(best2);

  struct Entry {
    std::uint32_t node;
    float d2;
  };
  Entry stack[128];
  int top = 0;
  std::uint32_t node = 0;
  if (boxDistance2(nodes[0], qx, qy, qz) > limit2) return bestTri;
  for (;;) {
    const Node& n = nodes[node];
    if (n.count > 0) {
      for (std::uint32_t i = n.offset, e = n.offset + n.count; i < e; ++i) {
        const TriCull& tc = culls[i];
        const float dx = std::max(std::max(tc.lo[0] - qx, qx - tc.hi[0]), 0.0f);
        const float dy = std::max(std::max(tc.lo[1] - qy, qy - tc.hi[1]), 0.0f);
        const float dz = std::max(std::max(tc.lo[2] - qz, qz - tc.hi[2]), 0.0f);
        const float plane = tc.n[0] * qx + tc.n[1] * qy + tc.n[2] * qz - tc.offset;
        if (std::max(dx * dx + dy * dy + dz * dz, plane * plane) > limit2) continue;
        const Tri& t = tris[i];
        Vec3 c = closestPointOnTriangle(q, t.a, t.b, t.c);
        double d2 = (c - q).squaredNorm();
        if (d2 < best2 || (bestTri < 0 && d2 <= best2)) {
          best2 = d2;
          bestTri = i;
          bestPoint = c;
          limit2 = limitOf(best2);
        }
      }
    } else {
      std::uint32_t near = node + 1, far = n.offset;
      float dn = boxDistance2(nodes[near], qx, qy, qz), df = boxDistance2(nodes[far], qx, qy, qz);
      if (df < dn) {
        std::swap(near, far);
        std::swap(dn, df);
      }
      if (dn <= limit2) {
        if (df <= limit2 && top < 128) stack[top++] = {far, df};
        node = near;
        continue;
      }
    }
    // Pop the next box still within reach.
    bool next = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.d2 <= limit2) {
        node = e.node;
        next = true;
        break;
      }
    }
    if (!next) break;
  }
  return bestTri;
}

ClosestHit MeshClosestPoint::Impl::answer(const Vec3& q, double maxDistance, std::int64_t warmTri) const {
  ClosestHit hit;
  if (tris.empty() || !q.allFinite() || !(maxDistance >= 0)) return hit;
  double best2 = std::isfinite(maxDistance) ? maxDistance * maxDistance : std::numeric_limits<double>::infinity();
  std::int64_t bestTri = -1;
  Vec3 bestPoint = Vec3::Zero();
  if (warmTri >= 0) {
    const Tri& t = tris[warmTri];
    Vec3 c = closestPointOnTriangle(q, t.a, t.b, t.c);
    double d2 = (c - q).squaredNorm();
    if (d2 <= best2) {
      best2 = d2;
      bestTri = warmTri;
      bestPoint = c;
    }
  }
  bestTri = search(q, best2, bestTri, bestPoint);
  if (bestTri < 0) return hit;
  hit.point = bestPoint;
  hit.distance = std::sqrt(best2);
  hit.index = bestTri;  // leaf order; mapped by the caller
  return hit;
}

MeshClosestPoint::MeshClosestPoint(const geom::TriMesh& mesh, const ClosestPointOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->build(mesh);
}
MeshClosestPoint::~MeshClosestPoint() = default;
MeshClosestPoint::MeshClosestPoint(MeshClosestPoint&&) noexcept = default;
MeshClosestPoint& MeshClosestPoint::operator=(MeshClosestPoint&&) noexcept = default;

std::size_t MeshClosestPoint::triangleCount() const { return impl_->tris.size(); }
std::size_t MeshClosestPoint::nodeCount() const { return impl_->nodes.size(); }

ClosestHit MeshClosestPoint::query(const Vec3& p, double maxDistance) const {
  ClosestHit hit = impl_->answer(p, maxDistance, -1);
  if (hit.found()) hit.index = impl_->triId[hit.index];
  return hit;
}

namespace {

// Runs `answerOne(queryIndex, warmState)` over all queries, Morton-ordered, in parallel blocks.
template <class AnswerFn>
void runBatch(const std::vector<Vec3>& points, const ClosestPointOptions& options, const ProgressFn& progress,
              AnswerFn&& answerOne) {
  const std::size_t n = points.size();
  std::vector<std::uint32_t> order;
  if (options.mortonOrder) {
    order = mortonOrder(points);
  } else {
    order.resize(n);
    std::iota(order.begin(), order.end(), 0u);
  }
  std::atomic<std::uint64_t> done{0};
  const std::size_t block = static_cast<std::size_t>(std::max(1, options.blockSize));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, block), [&](const tbb::blocked_range<std::size_t>& r) {
    std::int64_t warm = -1;
    for (std::size_t i = r.begin(); i < r.end(); ++i) warm = answerOne(order[i], warm);
    if (progress) progress(done += r.size(), n);
  });
}

}  // namespace

std::vector<ClosestHit> MeshClosestPoint::queryAll(const std::vector<Vec3>& points, double maxDistance,
                                                   const ProgressFn& progress) const {
  if (points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw OptionsError("closest point: too many queries (" + std::to_string(points.size()) + ")");
  std::vector<ClosestHit> hits(points.size());
  const Impl& im = *impl_;
  const bool warmStart = im.options.warmStart;
  runBatch(points, im.options, progress, [&](std::uint32_t qi, std::int64_t warm) {
    ClosestHit h = im.answer(points[qi], maxDistance, warmStart ? warm : -1);
    std::int64_t leaf = h.index;
    if (h.found()) h.index = im.triId[leaf];
    hits[qi] = h;
    // Keep the last found triangle as the next warm start (a dropped query keeps the previous one).
    return leaf >= 0 ? leaf : warm;
  });
  return hits;
}

// ---- point cloud -------------------------------------------------------------------------------

namespace {

struct CloudAdaptor {
  std::vector<Vec3> pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return pts[i][dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CloudAdaptor>, CloudAdaptor,
                                                   3, std::uint32_t>;

}  // namespace

struct CloudClosestPoint::Impl {
  ClosestPointOptions options;
  CloudAdaptor data;
  std::unique_ptr<KdTree> tree;

  ClosestHit answer(const Vec3& q, double maxDistance) const {
    ClosestHit hit;
    if (!tree || !q.allFinite() || !(maxDistance >= 0)) return hit;
    std::uint32_t idx = 0;
    double d2 = 0;
    if (tree->knnSearch(q.data(), 1, &idx, &d2) == 0) return hit;
    // Recompute in double from the stored point (nanoflann's accumulated distance is the same
    // formula; this keeps the answer exact for the point it names).
    d2 = (data.pts[idx] - q).squaredNorm();
    double d = std::sqrt(d2);
    if (d > maxDistance) return hit;
    hit.point = data.pts[idx];
    hit.distance = d;
    hit.index = idx;
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
  impl_->data.pts = cloud.positions;
  if (!impl_->data.pts.empty())
    impl_->tree = std::make_unique<KdTree>(3, impl_->data, nanoflann::KDTreeSingleIndexAdaptorParams(10));
}
CloudClosestPoint::~CloudClosestPoint() = default;
CloudClosestPoint::CloudClosestPoint(CloudClosestPoint&&) noexcept = default;
CloudClosestPoint& CloudClosestPoint::operator=(CloudClosestPoint&&) noexcept = default;

std::size_t CloudClosestPoint::pointCount() const { return impl_->data.pts.size(); }

ClosestHit CloudClosestPoint::query(const Vec3& p, double maxDistance) const { return impl_->answer(p, maxDistance); }

std::vector<ClosestHit> CloudClosestPoint::queryAll(const std::vector<Vec3>& points, double maxDistance,
                                                    const ProgressFn& progress) const {
  if (points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw OptionsError("closest point: too many queries (" + std::to_string(points.size()) + ")");
  std::vector<ClosestHit> hits(points.size());
  const Impl& im = *impl_;
  runBatch(points, im.options, progress, [&](std::uint32_t qi, std::int64_t warm) {
    hits[qi] = im.answer(points[qi], maxDistance);
    return warm;
  });
  return hits;
}

}  // namespace treesketch::accel
