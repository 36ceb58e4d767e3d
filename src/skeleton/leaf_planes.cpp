// Leaf-entry positions (leaf-on scans). A leaf hangs from its twig by one edge, so a level set
// through a leaf cluster has its centroid half a leaf off the twig. Here each voxel on a flat patch
// (a leaf: RANSAC plane test) takes the position where the root's shortest path entered its patch,
// and then moves towards the point where the leaf planes around it meet (a twig's leaves radiate
// from it). The graph, distances and level sets are unchanged: only the centroids see this.
#include "skeleton/leaf_planes.h"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "skeleton/voxel_hash.h"
#include "treesketch/accel/point_index.h"
#include "treesketch/fit/cloud_index.h"

namespace treesketch::skeleton::detail {
namespace {

using geom::Vec3;

// A plane through a voxel's centroid needs a few points around it to mean anything.
constexpr std::size_t kMinPlanePoints = 6;
// Hypotheses are ranked on an evenly strided subset of at most this many points (a dense crown
// has hundreds within the radius; ranking on all of them was most of the leaf-on skeleton's
// time); the winner's support is counted on all.
constexpr std::size_t kScorePoints = 64;
// Cross products shorter than this come from coincident or collinear samples: no plane.
constexpr double kDegenerateNormal = 1e-12;
// Convergence: at most this many planes are summed per origin (evenly strided: the sum is an
// average, and a dense crown holds thousands of flat voxels within the radius)...
constexpr std::size_t kMaxPlanes = 256;
// ...and fewer than three planes do not fix a point.
constexpr int kMinPlanes = 3;
// The planes are thinned to one flat voxel per cell of radius / kPlaneCellsPerRadius once that
// cell is at least kMinPlaneCellVoxels wide, so a query meets a bounded number of planes whatever
// the radius in voxels (a dense scan's leaves span many voxels).
constexpr double kPlaneCellsPerRadius = 8;
constexpr double kMinPlaneCellVoxels = 2;
// The automatic convergence radius follows the long end of the flat voxels' distances to their
// entry: a leaf's length.
constexpr std::size_t kLeafLengthPercentile = 90;

// Ball queries answered in the order of fit::CloudIndex's cells, the index that answered them
// before accel::PointIndex did: the plane test draws its RANSAC samples by position in the answer and both
// stages sum in that order, so keeping the order keeps their results bit for bit. The points are
// kept in that order too, so that reading the hits' positions walks memory forwards.
class BallQuery {
 public:
  explicit BallQuery(const geom::PointCloud& points)
      : order_(fit::CloudIndex(points).storageOrder()),
        ordered_(permuted(points.positions, order_)),
        index_(ordered_) {}
  /// The points within `radius` of `p`, as positions in cell order (see position, input).
  void operator()(const Vec3& p, double radius, std::vector<std::uint32_t>& out) const {
    index_.withinRadius(p, radius, out);
  }
  const Vec3& position(std::uint32_t hit) const { return ordered_[hit]; }
  /// Index into the constructor's points.
  std::uint32_t input(std::uint32_t hit) const { return order_[hit]; }

 private:
  static std::vector<Vec3> permuted(const std::vector<Vec3>& points, const std::vector<std::uint32_t>& order) {
    std::vector<Vec3> out(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) out[i] = points[order[i]];
    return out;
  }
  std::vector<std::uint32_t> order_;  ///< cell order -> input index
  std::vector<Vec3> ordered_;         ///< the points in cell order
  accel::PointIndex index_;
};

// The plane test's points: all of them (returns false: no voxel holds more than `cap`), or in
// `sample` an even stride through each voxel's points down to at most `cap` (scan order, every
// station's points alike), so that the cost of the ball queries and plane passes stays bounded.
bool thinPlaneTestPoints(const geom::PointCloud& cloud, const VoxelGraph& graph, int cap, geom::PointCloud& sample) {
  const bool thin = cap > 0 && std::any_of(graph.pointCount.begin(), graph.pointCount.end(),
                                           [cap](std::int32_t c) { return c > cap; });
  if (!thin) return false;
  std::vector<std::int32_t> seen(graph.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const std::uint32_t v = graph.pointVoxel[i];
    const std::int32_t stride = (graph.pointCount[v] + cap - 1) / cap;
    if (seen[v]++ % stride == 0) sample.positions.push_back(cloud.positions[i]);
  }
  return true;
}

struct LeafPlane {
  bool flat = false;
  Vec3 normal = Vec3::UnitZ();
};

// RANSAC plane through `p` (a voxel's centroid) over its neighbours `near`, with a fixed per-voxel
// seed (the result does not depend on the thread schedule); flat when the plane's band holds
// enough of them, spread in two dimensions (a blade, not a twig's line).
LeafPlane fitLeafPlane(const std::vector<Vec3>& near, const Vec3& p, std::size_t voxel, double radius, double band,
                       const SkeletonOptions& o) {
  LeafPlane out;
  if (near.size() < kMinPlanePoints) return out;
  std::uint64_t state = voxel * 2654435761u + 1;  // xorshift64, seeded by Knuth's multiplicative hash
  auto next = [&state]() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  };
  const std::size_t stride = (near.size() + kScorePoints - 1) / kScorePoints;
  int bestScore = -1;
  Vec3 best = Vec3::UnitZ();
  for (int it = 0; it < o.leafPlaneHypotheses; ++it) {
    const Vec3 n = (near[next() % near.size()] - p).cross(near[next() % near.size()] - p);
    if (n.norm() < kDegenerateNormal) continue;
    const Vec3 u = n.normalized();
    int score = 0;
    for (std::size_t q = 0; q < near.size(); q += stride) score += std::abs((near[q] - p).dot(u)) < band;
    if (score > bestScore) {
      bestScore = score;
      best = u;
    }
  }
  Vec3 mean = Vec3::Zero();
  int count = 0;
  for (const auto& q : near)
    if (std::abs((q - p).dot(best)) < band) {
      mean += q;
      ++count;
    }
  mean /= std::max(count, 1);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& q : near)
    if (std::abs((q - p).dot(best)) < band) cov += (q - mean) * (q - mean).transpose();
  cov /= std::max(count, 1);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const double spread = std::sqrt(std::max(eig.eigenvalues()[1], 0.0)) / radius;
  out.normal = best;
  out.flat = static_cast<double>(count) / near.size() >= o.leafPlaneMinInliers && spread >= o.leafPlaneMinSpread;
  return out;
}

// Per voxel: the plane test's verdict and the plane's unit normal.
void flatVoxels(const geom::PointCloud& cloud, const VoxelGraph& graph, const SkeletonOptions& o,
                std::vector<char>& flat, std::vector<Vec3>& normal) {
  const std::size_t nv = graph.size();
  flat.assign(nv, 0);
  normal.assign(nv, Vec3::UnitZ());
  geom::PointCloud sample;
  const bool thin = thinPlaneTestPoints(cloud, graph, o.leafPlaneMaxPointsPerVoxel, sample);
  const BallQuery ball(thin ? sample : cloud);
  const double radius = o.leafPlaneRadiusVoxels * graph.voxelSize;
  const double band = o.leafPlaneBandVoxels * graph.voxelSize;
  tbb::parallel_for(std::size_t{0}, nv, [&](std::size_t k) {
    // Per thread: one allocation, not one per voxel.
    thread_local std::vector<std::uint32_t> hits;
    thread_local std::vector<Vec3> near;
    ball(graph.positions[k], radius, hits);
    near.resize(hits.size());
    for (std::size_t i = 0; i < hits.size(); ++i) near[i] = ball.position(hits[i]);
    const LeafPlane plane = fitLeafPlane(near, graph.positions[k], k, radius, band, o);
    flat[k] = plane.flat;
    normal[k] = plane.normal;
  });
}

// The flat voxels whose planes the convergence sums: all of them, or one per cell of
// radius / kPlaneCellsPerRadius (the first in voxel order) once such a cell is wide enough.
std::vector<std::uint32_t> convergencePlanes(const VoxelGraph& graph, const std::vector<char>& flat, double radius) {
  const double cell = radius / kPlaneCellsPerRadius;
  const bool thin = cell >= kMinPlaneCellVoxels * graph.voxelSize;
  VoxelHash taken;
  std::vector<std::uint32_t> planes;
  for (std::size_t k = 0; k < graph.size(); ++k) {
    if (!flat[k]) continue;
    const auto id = static_cast<std::uint32_t>(k);
    if (thin && taken.findOrInsert(cellKey(graph.positions[k], graph.origin, cell), id) != id) continue;
    planes.push_back(id);
  }
  return planes;
}

// The move from `p` to the point nearest (least squares) to the planes of voxels `planes[near]`
// (evenly strided down to kMaxPlanes). Directions the planes leave free (eigenvalues of their normal
// matrix below leafConvergenceFreeShare × the plane count) are not moved along; the move is
// clamped to `radius`.
Vec3 planeMeetingMove(const VoxelGraph& graph, const std::vector<Vec3>& normal,
                      const std::vector<std::uint32_t>& planes, const BallQuery& ball,
                      const std::vector<std::uint32_t>& near, const Vec3& p, double radius, double freeShare) {
  const std::size_t stride = (near.size() + kMaxPlanes - 1) / kMaxPlanes;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  int count = 0;
  for (std::size_t q = 0; q < near.size(); q += stride) {
    const std::uint32_t j = planes[ball.input(near[q])];
    const Eigen::Matrix3d nn = normal[j] * normal[j].transpose();
    a += nn;
    b += nn * (graph.positions[j] - p);
    ++count;
  }
  if (count < kMinPlanes) return Vec3::Zero();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(a);
  Vec3 move = Vec3::Zero();
  for (int e = 0; e < 3; ++e) {
    const double lambda = eig.eigenvalues()[e];
    if (lambda > freeShare * count) move += eig.eigenvectors().col(e) * (eig.eigenvectors().col(e).dot(b) / lambda);
  }
  const double length = move.norm();
  if (length > radius) move *= radius / length;
  return move;
}

// For each voxel in `origins`: its plane-convergence move, over the flat voxels within
// `radiusVoxels` of it.
std::vector<Vec3> planeConvergenceMoves(const VoxelGraph& graph, const std::vector<char>& flat,
                                        const std::vector<Vec3>& normal, const std::vector<std::size_t>& origins,
                                        double radiusVoxels, double freeShare) {
  std::vector<Vec3> moves(origins.size(), Vec3::Zero());
  const double radius = radiusVoxels * graph.voxelSize;
  const std::vector<std::uint32_t> planes = convergencePlanes(graph, flat, radius);
  if (planes.empty()) return moves;
  geom::PointCloud planePositions;
  planePositions.positions.resize(planes.size());
  for (std::size_t i = 0; i < planes.size(); ++i) planePositions.positions[i] = graph.positions[planes[i]];
  const BallQuery ball(planePositions);
  tbb::parallel_for(std::size_t{0}, origins.size(), [&](std::size_t o) {
    thread_local std::vector<std::uint32_t> near;
    const Vec3 p = graph.positions[origins[o]];
    ball(p, radius, near);
    moves[o] = planeMeetingMove(graph, normal, planes, ball, near, p, radius, freeShare);
  });
  return moves;
}

// The automatic plane-convergence radius, voxels: leafConvergenceAutoScale × the 90th percentile
// of the flat voxels' distances to their entry positions, clamped (a fixed radius suits one leaf
// size only).
double automaticConvergenceRadius(const VoxelGraph& graph, const std::vector<char>& flat,
                                  const std::vector<std::size_t>& entry, const SkeletonOptions& o) {
  std::vector<double> reach;
  for (std::size_t k = 0; k < graph.size(); ++k)
    if (flat[k] && entry[k] != k) reach.push_back((graph.positions[entry[k]] - graph.positions[k]).norm());
  if (reach.empty()) return o.leafConvergenceMinRadiusVoxels;
  const auto pk = reach.begin() + static_cast<std::ptrdiff_t>((reach.size() * kLeafLengthPercentile) / 100);
  std::nth_element(reach.begin(), pk, reach.end());
  return std::clamp(o.leafConvergenceAutoScale * *pk / graph.voxelSize, o.leafConvergenceMinRadiusVoxels,
                    o.leafConvergenceMaxRadiusVoxels);
}

// The entry voxel of each voxel: the first voxel of its flat patch along its shortest path from the
// root (itself when it is not flat). The path stays on one patch while successive voxels are flat,
// their planes within leafPlaneMaxAngleDeg and each within leafPatchMaxOffsetVoxels of the other's plane.
std::vector<std::size_t> patchEntries(const VoxelGraph& graph, const GeodesicLevels& levels,
                                      const std::vector<char>& flat, const std::vector<Vec3>& normal,
                                      const SkeletonOptions& o) {
  const std::size_t nv = graph.size();
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < nv; ++k)
    if (std::isfinite(levels.distance[k])) order.push_back(k);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return levels.distance[a] < levels.distance[b] || (levels.distance[a] == levels.distance[b] && a < b);
  });
  std::vector<std::size_t> entry(nv);
  std::iota(entry.begin(), entry.end(), std::size_t{0});
  const double minCos = std::cos(o.leafPlaneMaxAngleDeg * M_PI / 180.0);
  const double maxOffset = o.leafPatchMaxOffsetVoxels * graph.voxelSize;
  for (std::size_t k : order) {  // predecessors come first
    const std::int64_t u = levels.predecessor[k];
    if (u < 0 || !flat[k] || !flat[u]) continue;
    if (std::abs(normal[k].dot(normal[u])) < minCos) continue;
    if (std::abs((graph.positions[u] - graph.positions[k]).dot(normal[k])) > maxOffset) continue;
    entry[k] = entry[u];
  }
  return entry;
}

}  // namespace

std::vector<Vec3> leafEntryPositions(const geom::PointCloud& cloud, const VoxelGraph& graph,
                                     const GeodesicLevels& levels, const SkeletonOptions& o, std::vector<char>& flat) {
  std::vector<Vec3> normal;
  flatVoxels(cloud, graph, o, flat, normal);
  const std::size_t nv = graph.size();
  const std::vector<std::size_t> entry = patchEntries(graph, levels, flat, normal, o);
  std::vector<Vec3> positions(nv);
  for (std::size_t k = 0; k < nv; ++k) positions[k] = graph.positions[entry[k]];
  if (o.leafConvergenceWeight <= 0) return positions;
  // From the entry positions (near the twig, where its leaves' planes meet); voxels that share an
  // entry share its move, so it is computed once per entry voxel.
  std::vector<std::size_t> origins;
  std::vector<std::int64_t> slot(nv, -1);
  for (std::size_t k = 0; k < nv; ++k)
    if (flat[k] && slot[entry[k]] < 0) {
      slot[entry[k]] = static_cast<std::int64_t>(origins.size());
      origins.push_back(entry[k]);
    }
  const double radiusVoxels = o.leafConvergenceRadiusVoxels > 0 ? o.leafConvergenceRadiusVoxels
                                                                : automaticConvergenceRadius(graph, flat, entry, o);
  const std::vector<Vec3> moves =
      planeConvergenceMoves(graph, flat, normal, origins, radiusVoxels, o.leafConvergenceFreeShare);
  for (std::size_t k = 0; k < nv; ++k)
    if (flat[k]) positions[k] += o.leafConvergenceWeight * moves[slot[entry[k]]];
  return positions;
}

void setFlatFractions(const GeodesicLevels& levels, const std::vector<char>& flat, std::vector<SkeletonNode>& nodes) {
  std::vector<std::uint32_t> voxels(nodes.size(), 0), flatCount(nodes.size(), 0);
  for (std::size_t v = 0; v < levels.vertexNode.size(); ++v) {
    const std::int32_t id = levels.vertexNode[v];
    if (id < 0) continue;
    ++voxels[id];
    flatCount[id] += flat[v] != 0;
  }
  for (std::size_t i = 0; i < nodes.size(); ++i)
    nodes[i].flatFraction = voxels[i] ? static_cast<float>(flatCount[i]) / static_cast<float>(voxels[i]) : 0.0f;
}

}  // namespace treesketch::skeleton::detail
