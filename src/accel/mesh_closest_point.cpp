// Closest points on a triangle mesh: a BVH built with object-median splits on the longest
// centroid axis, collapsed into 4-wide nodes whose float boxes (relative to the mesh's centre,
// rounded outwards) are tested four at a time with SSE; leaves hold up to 4 triangles as one float
// "packet" whose four approximate distances are computed branch-free at once, and only triangles
// within the best distance so far (plus a margin far above float error) get the exact double test
// (closestPointOnTriangle). Traversal is nearest-box-first and prunes by the best distance.
// Batches are sorted by Morton code and each query starts with the distance to the previous
// query's closest triangle (an upper bound of its answer: the BVH then only opens boxes closer
// than that).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "accel/batch.h"
#include "treesketch/accel/closest_point.h"
#include "treesketch/util/error.h"

namespace treesketch::accel {

using geom::Vec3;

namespace {

// 32 bytes: two nodes per cache line.
struct Node {
  float lo[3];
  std::uint32_t offset;  ///< interior: index of the right child (left child = this + 1); leaf: first slot
  float hi[3];
  std::uint32_t count;  ///< 0 for an interior node, else the number of triangles of the leaf
};

struct Tri {
  Vec3 a, b, c;
};

// Four triangles in float, structure-of-arrays (GCC/Clang vector extensions compile this to SSE),
// relative to the BVH origin: corners, inverse squared edge lengths (0 for a zero-length edge),
// the unnormalised normal and its inverse squared length (0 for a degenerate triangle).
using V4 = float __attribute__((vector_size(16)));
using V4i = std::int32_t __attribute__((vector_size(16)));

struct Packet {
  V4 ax, ay, az, bx, by, bz, cx, cy, cz;
  V4 inv0, inv1, inv2;
  V4 nx, ny, nz, invN2;
};

inline V4 splat(float x) { return V4{x, x, x, x}; }
inline V4 vmin(V4 a, V4 b) { return a < b ? a : b; }
inline V4 vmax(V4 a, V4 b) { return a > b ? a : b; }
inline V4 clamp01(V4 t) { return vmin(vmax(t, splat(0.0f)), splat(1.0f)); }

// Approximate squared distances (float) from q to the packet's four triangles: the plane distance
// when q projects inside the triangle, else the distance to the nearest edge. Branch-free. Its
// error is a few float ulps of the coordinates; the caller keeps a margin well above that and
// decides with the exact double test.
inline V4 packetDistance2(const Packet& p, V4 qx, V4 qy, V4 qz) {
  const V4 e0x = p.bx - p.ax, e0y = p.by - p.ay, e0z = p.bz - p.az;
  const V4 e1x = p.cx - p.bx, e1y = p.cy - p.by, e1z = p.cz - p.bz;
  const V4 e2x = p.ax - p.cx, e2y = p.ay - p.cy, e2z = p.az - p.cz;
  const V4 pax = qx - p.ax, pay = qy - p.ay, paz = qz - p.az;
  const V4 pbx = qx - p.bx, pby = qy - p.by, pbz = qz - p.bz;
  const V4 pcx = qx - p.cx, pcy = qy - p.cy, pcz = qz - p.cz;
  auto edge = [](V4 px, V4 py, V4 pz, V4 ex, V4 ey, V4 ez, V4 inv) {
    const V4 t = clamp01((px * ex + py * ey + pz * ez) * inv);
    const V4 dx = px - t * ex, dy = py - t * ey, dz = pz - t * ez;
    return dx * dx + dy * dy + dz * dz;
  };
  const V4 dEdge = vmin(vmin(edge(pax, pay, paz, e0x, e0y, e0z, p.inv0), edge(pbx, pby, pbz, e1x, e1y, e1z, p.inv1)),
                        edge(pcx, pcy, pcz, e2x, e2y, e2z, p.inv2));
  // q projects inside when it is on the inner side of all three edges: n . (e x (q - start)) >= 0.
  auto side = [&](V4 ex, V4 ey, V4 ez, V4 px, V4 py, V4 pz) {
    const V4 cx = ey * pz - ez * py, cy = ez * px - ex * pz, cz = ex * py - ey * px;
    return p.nx * cx + p.ny * cy + p.nz * cz;
  };
  const V4 s0 = side(e0x, e0y, e0z, pax, pay, paz), s1 = side(e1x, e1y, e1z, pbx, pby, pbz),
           s2 = side(e2x, e2y, e2z, pcx, pcy, pcz);
  const V4i inside = (s0 >= splat(0.0f)) & (s1 >= splat(0.0f)) & (s2 >= splat(0.0f));
  const V4 plane = p.nx * pax + p.ny * pay + p.nz * paz;
  const V4 dPlane = plane * plane * p.invN2;
  return inside ? dPlane : dEdge;
}

// Largest coordinate (metres from the mesh's centre) of a triangle whose float estimate is used to
// skip it: packetDistance2 multiplies up to four coordinates (the edge tests' n . (e x p)), and
// (3.4e38)^(1/4) is 1.4e9. A triangle reaching farther (a sliver to 3e20 did, found by fuzzing) is
// always tested exactly; tree meshes are metres across, far inside this.
constexpr double kPacketRange = 1e9;

float roundDown(double x) {
  float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float roundUp(double x) {
  float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

// The traversed tree: the binary tree collapsed into 4-wide nodes (the four children's boxes in
// SSE lanes). An empty lane has an inverted box (lo = +inf, hi = -inf): infinitely far.
struct Node4 {
  V4 lox, loy, loz, hix, hiy, hiz;
  std::uint32_t child[4];  ///< leaf: first slot; interior: Node4 index
  std::uint32_t count[4];  ///< leaf: triangle count (> 0); interior or empty lane: 0
};

inline V4 boxDistance2(const Node4& n, V4 qx, V4 qy, V4 qz) {
  const V4 zero = splat(0.0f);
  const V4 dx = vmax(vmax(n.lox - qx, qx - n.hix), zero);
  const V4 dy = vmax(vmax(n.loy - qy, qy - n.hiy), zero);
  const V4 dz = vmax(vmax(n.loz - qz, qz - n.hiz), zero);
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

struct MeshClosestPoint::Impl {
  ClosestPointOptions options;
  Vec3 origin = Vec3::Zero();
  double scale = 0;  ///< bounding-box diagonal (metres), for the float-error margin
  std::size_t triangles = 0;
  std::vector<Node> nodes;  ///< binary tree (build only; cleared after collapsing)
  std::vector<Node4> nodes4;
  /// Slots in leaf order; each leaf starts at a multiple of 4 and is padded to one (padding
  /// repeats the leaf's last triangle).
  std::vector<Tri> tris;
  std::vector<Packet> packets;       ///< slot / 4
  /// Per packet, bit `lane` set: that triangle's float estimate is out of float's range (see
  /// kPacketRange), so it is never skipped by it and always gets the exact double test.
  std::vector<std::uint8_t> exactLanes;
  std::vector<std::uint32_t> triId;  ///< slot -> input triangle index

  void build(const geom::TriMesh& mesh);
  std::uint32_t buildNode(std::vector<std::uint32_t>& ids, const std::vector<Vec3>& centroids,
                          const std::vector<geom::BBox>& boxes, std::size_t begin, std::size_t end);
  void layoutSlots(const geom::TriMesh& mesh, const std::vector<std::uint32_t>& ids);
  std::uint32_t collapse(std::uint32_t binaryNode);
  ClosestHit answer(const Vec3& q, double maxDistance, std::int64_t warmSlot) const;

  /// Best-so-far of one query: squared distance (metres²), slot (-1 none), point, and the float
  /// pruning limit derived from them.
  struct Best {
    double d2;
    std::int64_t slot;
    Vec3 point;
    float limit2;
  };
  double marginFor(const Vec3& rel) const { return 4e-6 * (scale + rel.cwiseAbs().maxCoeff()); }
  static float limitOf(double d2, double margin) {
    if (!std::isfinite(d2)) return std::numeric_limits<float>::infinity();
    const double l = std::sqrt(d2) + margin;
    return static_cast<float>(l * l);
  }
  /// Tests the triangles of the leaf at `slot` (`count` of them) against q, updating `best`.
  void testLeaf(std::uint32_t slot, std::uint32_t count, const Vec3& q, V4 qx, V4 qy, V4 qz, double margin,
                Best& best) const;
  /// Improves `best` (a starting bound: +inf, the search distance or a warm start's answer) to
  /// the closest triangle of the mesh.
  void search(const Vec3& q, Best& best) const;
  /// The answer for a query far from the mesh (see kFarQuery): boxes measured in double, every
  /// triangle of an opened leaf tested exactly, no float margin, no warm start (so a batch and a
  /// single query search alike and name the same triangle).
  ClosestHit answerFar(const Vec3& rel, const Vec3& q, double maxDistance) const;
};

void MeshClosestPoint::Impl::build(const geom::TriMesh& mesh) {
  const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
  for (std::size_t i = 0; i < nv; ++i)
    if (!mesh.vertices[i].allFinite())
      throw OptionsError("closest point: mesh vertex " + std::to_string(i) + " is NaN or infinite");
  for (std::size_t i = 0; i < nt; ++i)
    for (auto v : mesh.triangles[i])
      if (v >= nv)
        throw OptionsError("closest point: triangle " + std::to_string(i) + " references vertex " + std::to_string(v) +
                           " of " + std::to_string(nv));
  if (options.leafSize < 1 || options.leafSize > 64)
    throw OptionsError("closest point: leafSize must be in [1, 64], got " + std::to_string(options.leafSize));
  if (options.blockSize < 1)
    throw OptionsError("closest point: blockSize must be positive, got " + std::to_string(options.blockSize));
  if (nt == 0) return;
  if (nt >= std::numeric_limits<std::uint32_t>::max() / 8)
    throw OptionsError("closest point: too many triangles (" + std::to_string(nt) + ")");

  geom::BBox all;
  std::vector<Vec3> centroids(nt);
  std::vector<geom::BBox> boxes(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    const auto& t = mesh.triangles[i];
    for (auto v : t) boxes[i].add(mesh.vertices[v]);
    centroids[i] = boxes[i].centre();
    all.add(boxes[i]);
  }
  origin = all.centre();
  scale = all.diagonal();
  triangles = nt;
  std::vector<std::uint32_t> ids(nt);
  std::iota(ids.begin(), ids.end(), 0u);
  nodes.reserve(2 * (nt / options.leafSize + 1));
  buildNode(ids, centroids, boxes, 0, nt);
  layoutSlots(mesh, ids);
  nodes4.reserve(nodes.size() / 2 + 1);
  collapse(0);
  nodes.clear();
  nodes.shrink_to_fit();
}

std::uint32_t MeshClosestPoint::Impl::collapse(std::uint32_t b) {
  const auto index = static_cast<std::uint32_t>(nodes4.size());
  nodes4.emplace_back();
  // The children: start from the binary node's two and open the largest interior one until four.
  std::vector<std::uint32_t> kids;
  if (nodes[b].count > 0) {
    kids = {b};  // the whole tree is one leaf
  } else {
    kids = {b + 1, nodes[b].offset};
  }
  auto halfArea = [&](std::uint32_t k) {
    const Node& n = nodes[k];
    const float x = n.hi[0] - n.lo[0], y = n.hi[1] - n.lo[1], z = n.hi[2] - n.lo[2];
    return x * y + y * z + z * x;
  };
  while (kids.size() < 4) {
    int open = -1;
    for (int i = 0; i < static_cast<int>(kids.size()); ++i)
      if (nodes[kids[i]].count == 0 && (open < 0 || halfArea(kids[i]) > halfArea(kids[open]))) open = i;
    if (open < 0) break;
    const std::uint32_t k = kids[open];
    kids[open] = k + 1;
    kids.push_back(nodes[k].offset);
  }
  const float inf = std::numeric_limits<float>::infinity();
  std::uint32_t child[4] = {0, 0, 0, 0}, count[4] = {0, 0, 0, 0};
  float lo[3][4], hi[3][4];
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) {
      lo[k][i] = inf;
      hi[k][i] = -inf;
    }
    if (i >= static_cast<int>(kids.size())) continue;
    const Node& n = nodes[kids[i]];
    for (int k = 0; k < 3; ++k) {
      lo[k][i] = n.lo[k];
      hi[k][i] = n.hi[k];
    }
    if (n.count > 0) {
      child[i] = n.offset;
      count[i] = n.count;
    } else {
      child[i] = collapse(kids[i]);  // may reallocate nodes4: write through the index below
    }
  }
  Node4& out = nodes4[index];
  out.lox = V4{lo[0][0], lo[0][1], lo[0][2], lo[0][3]};
  out.loy = V4{lo[1][0], lo[1][1], lo[1][2], lo[1][3]};
  out.loz = V4{lo[2][0], lo[2][1], lo[2][2], lo[2][3]};
  out.hix = V4{hi[0][0], hi[0][1], hi[0][2], hi[0][3]};
  out.hiy = V4{hi[1][0], hi[1][1], hi[1][2], hi[1][3]};
  out.hiz = V4{hi[2][0], hi[2][1], hi[2][2], hi[2][3]};
  for (int i = 0; i < 4; ++i) {
    out.child[i] = child[i];
    out.count[i] = count[i];
  }
  return index;
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
  // A leaf when small enough; otherwise split at the median centroid along the longest axis (when
  // all centroids coincide this is an arbitrary halving: overlapping boxes, still correct).
  if (count <= static_cast<std::size_t>(options.leafSize)) {
    nodes[index].offset = static_cast<std::uint32_t>(begin);  // an index into `ids` until layoutSlots
    nodes[index].count = static_cast<std::uint32_t>(count);
    return index;
  }
  const Vec3 ext = cbox.extent();
  int axis = 0;
  if (ext.y() > ext[axis]) axis = 1;
  if (ext.z() > ext[axis]) axis = 2;
  const std::size_t mid = begin + count / 2;
  std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end,
                   [&](std::uint32_t x, std::uint32_t y) { return centroids[x][axis] < centroids[y][axis]; });
  buildNode(ids, centroids, boxes, begin, mid);
  const std::uint32_t right = buildNode(ids, centroids, boxes, mid, end);
  nodes[index].offset = right;
  nodes[index].count = 0;
  return index;
}

void MeshClosestPoint::Impl::layoutSlots(const geom::TriMesh& mesh, const std::vector<std::uint32_t>& ids) {
  std::size_t slots = 0;
  for (const Node& n : nodes)
    if (n.count > 0) slots += (n.count + 3) / 4 * 4;
  tris.resize(slots);
  triId.resize(slots);
  packets.resize(slots / 4);
  exactLanes.assign(slots / 4, 0);
  std::size_t next = 0;
  for (Node& n : nodes) {
    if (n.count == 0) continue;
    const std::size_t first = n.offset, padded = (n.count + 3) / 4 * 4;
    for (std::size_t j = 0; j < padded; ++j) {
      const std::uint32_t id = ids[first + std::min<std::size_t>(j, n.count - 1)];
      const auto& t = mesh.triangles[id];
      tris[next + j] = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
      triId[next + j] = id;
    }
    n.offset = static_cast<std::uint32_t>(next);
    next += padded;
  }
  for (std::size_t s = 0; s < slots; ++s) {
    Packet& p = packets[s / 4];
    const int lane = static_cast<int>(s % 4);
    const Tri& t = tris[s];
    const Vec3 a = t.a - origin, b = t.b - origin, c = t.c - origin;
    const Vec3 n = (b - a).cross(c - a);
    auto inv = [](double len2) { return len2 > 0 ? static_cast<float>(1.0 / len2) : 0.0f; };
    p.ax[lane] = static_cast<float>(a.x()), p.ay[lane] = static_cast<float>(a.y()),
    p.az[lane] = static_cast<float>(a.z());
    p.bx[lane] = static_cast<float>(b.x()), p.by[lane] = static_cast<float>(b.y()),
    p.bz[lane] = static_cast<float>(b.z());
    p.cx[lane] = static_cast<float>(c.x()), p.cy[lane] = static_cast<float>(c.y()),
    p.cz[lane] = static_cast<float>(c.z());
    p.inv0[lane] = inv((b - a).squaredNorm());
    p.inv1[lane] = inv((c - b).squaredNorm());
    p.inv2[lane] = inv((a - c).squaredNorm());
    p.nx[lane] = static_cast<float>(n.x()), p.ny[lane] = static_cast<float>(n.y()),
    p.nz[lane] = static_cast<float>(n.z());
    p.invN2[lane] = inv(n.squaredNorm());
    const double extent = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), c.cwiseAbs().maxCoeff()});
    const bool finiteInverses = std::isfinite(p.inv0[lane]) && std::isfinite(p.inv1[lane]) &&
                                std::isfinite(p.inv2[lane]) && std::isfinite(p.invN2[lane]);
    // A triangle flat at float precision (|n| below 1e-6 of its longest edge squared, so rounding
    // its corners to float turns its plane): the float estimate may put it far from a query on it.
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const bool flatInFloat = !(n.squaredNorm() > 1e-12 * longest2 * longest2);
    if (!(extent <= kPacketRange) || !finiteInverses || flatInFloat)
      exactLanes[s / 4] |= static_cast<std::uint8_t>(1u << lane);
  }
}

// A query farther from the mesh's centre than this many bounding-box diagonals is answered in
// double (answerFar): the float margin grows with the query's distance (4e-6 of it) and from about
// 10,000 diagonals it spans the whole mesh, so every box was opened and every triangle tested
// exactly (a 7 m model against its cloud moved by 1e6 m took minutes, not a second). Its distances
// stay finite up to the largest doubles. A query within kFarQueryFloor of the centre (a mesh of
// subnormal size) keeps the float path, whose handling of squared distances that underflow was
// fuzzed; no distance that far out underflows.
constexpr double kFarQuery = 1000, kFarQueryFloor = 1e-100;

// A far query's distances: the root of the squared distance, as every answer reports it
// (ClosestHit::distance), unless the square overflowed (past 1.3e154): then std::hypot.
inline double length(double x, double y, double z) {
  const double n2 = x * x + y * y + z * z;
  return std::isfinite(n2) ? std::sqrt(n2) : std::hypot(x, y, z);
}
inline double length(const Vec3& v) { return length(v.x(), v.y(), v.z()); }

// Distance (double) from `rel` to lane i of a 4-wide node's float boxes (exact in double); +inf
// for an empty lane (an inverted box).
inline double boxDistanceExact(const Node4& n, int i, const Vec3& rel) {
  auto axis = [](float lo, float hi, double x) { return std::max({double(lo) - x, x - double(hi), 0.0}); };
  return length(axis(n.lox[i], n.hix[i], rel.x()), axis(n.loy[i], n.hiy[i], rel.y()),
                axis(n.loz[i], n.hiz[i], rel.z()));
}

ClosestHit MeshClosestPoint::Impl::answerFar(const Vec3& rel, const Vec3& q, double maxDistance) const {
  double bestDistance = maxDistance;
  std::int64_t bestSlot = -1;
  Vec3 bestPoint = Vec3::Zero();
  // A box is skipped when it is farther than the best by more than the rounding of its distance
  // (a subtraction and a hypot: a few parts in 1e16). And once a triangle is found, when the whole
  // mesh is narrower than that rounding (a 7 m model seen from 1e300 away), all its triangles are
  // equally close to the last digit and any is the answer: searching on would test them all.
  auto beyond = [&](double d) {
    return d > bestDistance * (1 + 1e-15) || (bestSlot >= 0 && scale < 1e-15 * bestDistance);
  };
  std::uint32_t stackIndex[128], stackCount[128];
  double stackDistance[128];
  stackIndex[0] = 0, stackCount[0] = 0, stackDistance[0] = 0.0;
  int top = 1;
  while (top > 0) {
    --top;
    if (beyond(stackDistance[top])) continue;
    const std::uint32_t index = stackIndex[top], count = stackCount[top];
    if (count > 0) {
      for (std::uint32_t s = index; s < index + count; ++s) {
        const Vec3 c = closestPointOnTriangle(q, tris[s].a, tris[s].b, tris[s].c);
        const double d = length(c - q);
        if (d < bestDistance || (bestSlot < 0 && d <= bestDistance)) bestDistance = d, bestSlot = s, bestPoint = c;
      }
      continue;
    }
    const Node4& n = nodes4[index];
    double d[4];
    int order[4], k = 0;
    for (int i = 0; i < 4; ++i) {
      if (n.count[i] == 0 && n.child[i] == 0) continue;  // an empty lane (see search)
      d[i] = boxDistanceExact(n, i, rel);
      if (beyond(d[i])) continue;
      int j = k++;  // by decreasing distance: the nearest ends on top of the stack
      while (j > 0 && d[order[j - 1]] < d[i]) {
        order[j] = order[j - 1];
        --j;
      }
      order[j] = i;
    }
    if (top + k > 128) k = 128 - top;  // unreachable (as in search)
    for (int j = 0; j < k; ++j) {
      stackIndex[top] = n.child[order[j]], stackCount[top] = n.count[order[j]], stackDistance[top] = d[order[j]];
      ++top;
    }
  }
  ClosestHit hit;
  if (bestSlot < 0) return hit;
  hit.point = bestPoint;
  hit.distance = bestDistance;
  hit.index = bestSlot;  // a slot, as answer's
  return hit;
}

void MeshClosestPoint::Impl::search(const Vec3& q, Best& best) const {
  if (nodes4.empty()) return;
  const Vec3 rel = q - origin;
  // Clamped into float's range first (a cast out of range is undefined): a farther query sees
  // every box at +inf, and the exact double test below decides.
  auto toFloat = [](double x) {
    constexpr double kMax = std::numeric_limits<float>::max();
    return static_cast<float>(std::clamp(x, -kMax, kMax));
  };
  const float qx = toFloat(rel.x()), qy = toFloat(rel.y()), qz = toFloat(rel.z());
  const V4 vqx = splat(qx), vqy = splat(qy), vqz = splat(qz);
  // Float distances may be short of the true ones by rounding: a box or triangle is skipped only
  // when it is farther than the best distance plus a margin well above float error at this scale
  // (float carries ~6e-8 relative; the margin is ~100 times that).
  const double margin = marginFor(rel);
  best.limit2 = limitOf(best.d2, margin);

  // Stack of boxes still to visit, with their squared distance at push time: leaves (count > 0)
  // and 4-wide nodes. Nearer boxes are pushed last, so they are opened first. It never overflows:
  // at most 3 entries per level, and the tree has < 24 levels of 4-wide nodes for 2^32 triangles.
  // (Three separate arrays rather than an array of structs: whole-struct copies in and out of
  // the stack stall store-to-load forwarding.)
  std::uint32_t stackIndex[128], stackCount[128];
  float stackD2[128];
  stackIndex[0] = 0, stackCount[0] = 0, stackD2[0] = 0.0f;
  int top = 1;
  while (top > 0) {
    --top;
    if (stackD2[top] > best.limit2) continue;
    const std::uint32_t index = stackIndex[top], count = stackCount[top];
    if (count > 0) {
      testLeaf(index, count, q, vqx, vqy, vqz, margin, best);
      continue;
    }
    const Node4& n = nodes4[index];
    const V4 d = boxDistance2(n, vqx, vqy, vqz);
    int order[4];
    int k = 0;
    for (int i = 0; i < 4; ++i) {
      // An empty lane (child 0 = the root, which is nobody's child) is skipped by its index, not by
      // its infinite box distance: when the query is so far that float distances overflow, the
      // limit is +inf too, and the lane would lead back to the root without end.
      if (n.count[i] == 0 && n.child[i] == 0) continue;
      if (!(d[i] <= best.limit2)) continue;
      // Insertion by decreasing distance: the nearest ends last, on top of the stack.
      int j = k++;
      while (j > 0 && d[order[j - 1]] < d[i]) {
        order[j] = order[j - 1];
        --j;
      }
      order[j] = i;
    }
    if (top + k > 128) k = 128 - top;  // unreachable (see above); keeps the arrays in bounds
    for (int j = 0; j < k; ++j) {
      const int i = order[j];
      stackIndex[top] = n.child[i];
      stackCount[top] = n.count[i];
      stackD2[top] = d[i];
      ++top;
    }
  }
}

void MeshClosestPoint::Impl::testLeaf(std::uint32_t slot, std::uint32_t count, const Vec3& q, V4 qx, V4 qy, V4 qz,
                                      double margin, Best& best) const {
  for (std::uint32_t s = slot, e = slot + count; s < e; s += 4) {
    const V4 d2f = packetDistance2(packets[s / 4], qx, qy, qz);
    const std::uint32_t exact = exactLanes[s / 4];
    const std::uint32_t lanes = std::min<std::uint32_t>(4, e - s);
    for (std::uint32_t lane = 0; lane < lanes; ++lane) {
      if (d2f[lane] > best.limit2 && !(exact >> lane & 1u)) continue;
      const Tri& t = tris[s + lane];
      const Vec3 c = closestPointOnTriangle(q, t.a, t.b, t.c);
      const double d2 = (c - q).squaredNorm();
      if (d2 < best.d2 || (best.slot < 0 && d2 <= best.d2)) {
        best.d2 = d2;
        best.slot = s + lane;
        best.point = c;
        best.limit2 = limitOf(d2, margin);
      }
    }
  }
}

ClosestHit MeshClosestPoint::Impl::answer(const Vec3& q, double maxDistance, std::int64_t warmSlot) const {
  ClosestHit hit;
  if (tris.empty() || !q.allFinite() || !(maxDistance >= 0)) return hit;
  const Vec3 rel = q - origin;
  const double far = rel.cwiseAbs().maxCoeff();
  if (far > kFarQuery * scale && far > kFarQueryFloor && std::isfinite(far)) return answerFar(rel, q, maxDistance);
  Best best{std::isfinite(maxDistance) ? maxDistance * maxDistance : std::numeric_limits<double>::infinity(), -1,
            Vec3::Zero(), 0.0f};
  if (warmSlot >= 0) {
    const Tri& t = tris[warmSlot];
    const Vec3 c = closestPointOnTriangle(q, t.a, t.b, t.c);
    const double d2 = (c - q).squaredNorm();
    if (d2 <= best.d2) best = {d2, warmSlot, c, 0.0f};
  }
  search(q, best);
  if (best.slot < 0) return hit;
  hit.point = best.point;
  hit.distance = std::sqrt(best.d2);
  hit.index = best.slot;  // a slot; mapped to the input triangle by the caller
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

std::size_t MeshClosestPoint::triangleCount() const { return impl_->triangles; }
std::size_t MeshClosestPoint::nodeCount() const { return impl_->nodes4.size(); }

ClosestHit MeshClosestPoint::query(const Vec3& p, double maxDistance) const {
  ClosestHit hit = impl_->answer(p, maxDistance, -1);
  if (hit.found()) hit.index = impl_->triId[hit.index];
  return hit;
}

std::vector<ClosestHit> MeshClosestPoint::queryAll(const std::vector<Vec3>& points, double maxDistance,
                                                   const ProgressFn& progress) const {
  std::vector<ClosestHit> hits(points.size());
  const Impl& im = *impl_;
  const ClosestPointOptions& o = im.options;
  const bool warmStart = o.warmStart;
  detail::runBatch(points, o, progress, [&](std::uint32_t qi, std::int64_t warm) {
    ClosestHit h = im.answer(points[qi], maxDistance, warmStart ? warm : -1);
    std::int64_t leaf = h.index;
    if (h.found()) h.index = im.triId[leaf];
    hits[qi] = h;
    // Keep the last found triangle as the next warm start (a dropped query keeps the previous one).
    return leaf >= 0 ? leaf : warm;
  });
  return hits;
}

}  // namespace treesketch::accel
