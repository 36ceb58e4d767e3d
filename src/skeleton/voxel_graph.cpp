// Voxel neighbourhood graph with local shape features and occlusion bridging.
// Bridging follows Xu, Gossett & Chen 2007 ("Knowledge and heuristic-based modeling of
// laser-scanned trees"): a disconnected sub-graph is joined when it lies within a distance and a
// cone; here the cone is around the sub-graph's own axis at the joint, which also admits gaps in
// drooping branches.
#include "treesketch/skeleton/voxel_graph.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "skeleton/voxel_hash.h"
#include "treesketch/accel/point_index.h"
#include "treesketch/util/error.h"
#include "treesketch/util/union_find.h"

namespace treesketch::skeleton {
namespace {

using detail::VoxelHash;
using geom::Vec3;

// Capacity hints for the voxel hashes (they grow as needed): a scan puts several points in a
// voxel, and a shape cell holds several voxels.
constexpr std::size_t kPointsPerVoxelGuess = 8;
constexpr std::size_t kVoxelsPerCellGuess = 4;
// The grid starts half a cell below the cloud's box, and its extent keeps a few cells of the
// packed-key range free, so that rounding never puts a point outside the grid.
constexpr double kOriginMarginCells = 0.5;
constexpr std::int64_t kSpareAxisCells = 4;
// Automatic voxel size: at most this many growth steps towards maxVoxels, each at least 5 %.
constexpr int kMaxSizeSteps = 8;
constexpr double kMinSizeGrowth = 1.05;
// A covariance (local shape, a piece's axis) needs at least three points to have a direction.
constexpr int kMinAxisVoxels = 3;
// Floor of the largest eigenvalue when dividing by it (a cell of coincident voxels).
constexpr double kTinyEigenvalue = 1e-30;
// Parallel tasks: shape cells and bridge searches (a PCA, a ball query each) and voxels' edge rows
// (cheap) per task, enough to amortise the scheduling.
constexpr std::size_t kCellsPerTask = 256;
constexpr std::size_t kRowsPerTask = 1024;

void checkOptions(const VoxelGraphOptions& o) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw OptionsError(std::string("skeleton graph: ") + name + " must be > 0");
  };
  if (!(o.voxelSize >= 0) || !std::isfinite(o.voxelSize))
    throw OptionsError("skeleton graph: voxelSize must be >= 0 (0 = automatic)");
  positive(o.autoDiagonalFraction, "autoDiagonalFraction");
  positive(o.autoSpacingFactor, "autoSpacingFactor");
  positive(o.shapeCellVoxels, "shapeCellVoxels");
  positive(o.coneAngleDeg, "coneAngleDeg");
  positive(o.coneRadiusVoxels, "coneRadiusVoxels");
  if (!(o.maxGapVoxels >= 0)) throw OptionsError("skeleton graph: maxGapVoxels must be >= 0");
  if (!(o.freeGapVoxels >= 0)) throw OptionsError("skeleton graph: freeGapVoxels must be >= 0");
  if (o.reach < 1 || o.reach > 3) throw OptionsError("skeleton graph: reach must be 1, 2 or 3");
  if (!(o.minBridgeLinearity >= 0) || o.minBridgeLinearity > 1)
    throw OptionsError("skeleton graph: minBridgeLinearity must be in [0, 1]");
  if (o.sparseLinkNeighbours < 0 || o.sparseLinkNeighbours > 26)
    throw OptionsError("skeleton graph: sparseLinkNeighbours must be in [0, 26]");
  if (o.maxVoxels < 1) throw OptionsError("skeleton graph: maxVoxels must be >= 1");
}

void checkFinite(const geom::PointCloud& cloud) {
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.positions[i].allFinite()) {
      std::ostringstream s;
      s << "skeleton: point " << i << " has a NaN or infinite coordinate";
      throw OptionsError(s.str());
    }
  }
}

/// Grid corner a little below the box so every point maps to non-negative cells.
Vec3 gridOrigin(const geom::BBox& box, double cell) { return box.min - Vec3::Constant(kOriginMarginCells * cell); }

/// Number of occupied voxels of size `cell`.
std::size_t countVoxels(const geom::PointCloud& cloud, const Vec3& origin, double cell) {
  VoxelHash hash(cloud.size() / kPointsPerVoxelGuess + 16);
  for (const Vec3& p : cloud.positions) hash.findOrInsert(detail::cellKey(p, origin, cell), 0);
  return hash.size();
}

struct Voxelized {
  std::vector<Vec3> positions;
  std::vector<std::int32_t> counts;
  std::vector<std::uint32_t> pointVoxel;
  std::vector<std::uint64_t> keys;
  VoxelHash hash;
};

Voxelized voxelize(const geom::PointCloud& cloud, const Vec3& origin, double cell) {
  Voxelized v;
  v.pointVoxel.resize(cloud.size());
  std::vector<Vec3> sums;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const std::uint64_t key = detail::cellKey(cloud.positions[i], origin, cell);
    const std::uint32_t id = v.hash.findOrInsert(key, static_cast<std::uint32_t>(sums.size()));
    if (id == sums.size()) {
      sums.push_back(Vec3::Zero());
      v.counts.push_back(0);
      v.keys.push_back(key);
    }
    sums[id] += cloud.positions[i];
    ++v.counts[id];
    v.pointVoxel[i] = id;
  }
  v.positions.resize(sums.size());
  for (std::size_t i = 0; i < sums.size(); ++i) v.positions[i] = sums[i] / v.counts[i];
  return v;
}

/// Local PCA features: moments of voxel centroids summed per coarse cell, then over each cell's
/// 3×3×3 block of cells.
void computeFeatures(VoxelGraph& g, const std::vector<std::uint64_t>& keys, double shapeCellVoxels) {
  const std::size_t n = g.size();
  const double cell = shapeCellVoxels * g.voxelSize;
  struct Moments {
    double n = 0;
    Vec3 s = Vec3::Zero();
    Eigen::Matrix3d ss = Eigen::Matrix3d::Zero();
  };
  VoxelHash cellHash(n / kVoxelsPerCellGuess + 16);
  std::vector<Moments> moments;
  std::vector<std::uint64_t> cellKeys;
  std::vector<std::uint32_t> voxelCell(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t key = detail::cellKey(g.positions[i], g.origin, cell);
    const std::uint32_t id = cellHash.findOrInsert(key, static_cast<std::uint32_t>(moments.size()));
    if (id == moments.size()) {
      moments.emplace_back();
      cellKeys.push_back(key);
    }
    // Relative to the grid origin keeps the sums well conditioned for georeferenced clouds.
    const Vec3 p = g.positions[i] - g.origin;
    moments[id].n += 1;
    moments[id].s += p;
    moments[id].ss += p * p.transpose();
    voxelCell[i] = id;
  }
  const std::size_t cells = moments.size();
  std::vector<float> lin(cells), pla(cells), sca(cells);
  std::vector<geom::Vec3f> dir(cells);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, cells, kCellsPerTask), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
          std::int64_t x, y, z;
          detail::unpackKey(cellKeys[c], x, y, z);
          Moments m;
          for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dz = -1; dz <= 1; ++dz) {
                if (x + dx < 0 || y + dy < 0 || z + dz < 0) continue;
                const std::uint32_t id = cellHash.find(detail::packKey(x + dx, y + dy, z + dz));
                if (id == VoxelHash::kMissing) continue;
                m.n += moments[id].n;
                m.s += moments[id].s;
                m.ss += moments[id].ss;
              }
          lin[c] = 0;
          pla[c] = 0;
          sca[c] = 1;
          dir[c] = geom::Vec3f::UnitX();
          if (m.n < kMinAxisVoxels) continue;
          const Vec3 mean = m.s / m.n;
          const Eigen::Matrix3d cov = m.ss / m.n - mean * mean.transpose();
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
          eig.computeDirect(cov);
          const Vec3 ev = eig.eigenvalues();  // increasing
          const double l1 = std::max(ev(2), kTinyEigenvalue), l2 = std::max(ev(1), 0.0), l3 = std::max(ev(0), 0.0);
          lin[c] = static_cast<float>((l1 - l2) / l1);
          pla[c] = static_cast<float>((l2 - l3) / l1);
          sca[c] = static_cast<float>(l3 / l1);
          dir[c] = eig.eigenvectors().col(2).cast<float>().normalized();
        }
      });
  g.linearity.resize(n);
  g.planarity.resize(n);
  g.scattering.resize(n);
  g.principal.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    g.linearity[i] = lin[voxelCell[i]];
    g.planarity[i] = pla[voxelCell[i]];
    g.scattering[i] = sca[voxelCell[i]];
    g.principal[i] = dir[voxelCell[i]];
  }
}

/// Grid edges (both directions) in compressed rows.
void buildGridEdges(VoxelGraph& g, const Voxelized& v, int reach) {
  const std::size_t n = g.size();
  auto forNeighbours = [&](std::size_t i, auto&& fn) {
    std::int64_t x, y, z;
    detail::unpackKey(v.keys[i], x, y, z);
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dz = -reach; dz <= reach; ++dz) {
          if ((dx | dy | dz) == 0) continue;
          if (x + dx < 0 || y + dy < 0 || z + dz < 0) continue;
          const std::uint32_t id = v.hash.find(detail::packKey(x + dx, y + dy, z + dz));
          if (id != VoxelHash::kMissing) fn(id);
        }
  };
  std::vector<std::uint32_t> degree(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kRowsPerTask), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      std::uint32_t d = 0;
      forNeighbours(i, [&](std::uint32_t) { ++d; });
      degree[i] = d;
    }
  });
  g.offsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) g.offsets[i + 1] = g.offsets[i] + degree[i];
  g.targets.resize(g.offsets[n]);
  g.weights.resize(g.offsets[n]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kRowsPerTask), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      std::uint32_t k = g.offsets[i];
      forNeighbours(i, [&](std::uint32_t j) {
        g.targets[k] = j;
        g.weights[k] = static_cast<float>((g.positions[i] - g.positions[j]).norm());
        ++k;
      });
    }
  });
}

void appendEdges(VoxelGraph& g, const std::vector<Bridge>& edges);

/// Sparse links: each voxel is joined to those of its k nearest voxels (within maxGapVoxels) that
/// lie in another grid-connected piece. Where a stretch is sampled more sparsely than the voxel
/// size (a trunk base or a crown edge seen by few rays), the grid leaves single voxels and small
/// pieces, and these links join them at the local point spacing; where it is dense a voxel's
/// nearest voxels are in its own piece and nothing changes. Links within a piece are never
/// added: they would be shortcuts between touching branches.
void addSparseLinks(VoxelGraph& g, const VoxelGraphOptions& o) {
  const std::size_t n = g.size();
  const auto k = static_cast<std::size_t>(o.sparseLinkNeighbours);
  if (k == 0 || n < 2 || o.maxGapVoxels <= 0) return;
  const accel::PointIndex index(g.positions);
  const double maxLink2 = std::pow(o.maxGapVoxels * g.voxelSize, 2);
  const std::vector<std::int32_t> label = util::labelComponents(g.offsets, g.targets, nullptr);
  std::vector<std::vector<Bridge>> found(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kCellsPerTask), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      for (const accel::Neighbour& nb : index.nearest(g.positions[i], k + 1)) {
        // Same piece (the voxel itself, grid neighbours): the grid joins them already.
        if (label[nb.index] == label[i] || nb.distance2 > maxLink2) continue;
        const auto lo = static_cast<std::uint32_t>(std::min<std::size_t>(i, nb.index));
        const auto hi = static_cast<std::uint32_t>(std::max<std::size_t>(i, nb.index));
        found[i].push_back(Bridge{lo, hi, std::sqrt(nb.distance2)});
      }
    }
  });
  std::vector<Bridge> links;
  for (const auto& f : found) links.insert(links.end(), f.begin(), f.end());
  std::sort(links.begin(), links.end(),
            [](const Bridge& a, const Bridge& b) { return std::tie(a.from, a.to) < std::tie(b.from, b.to); });
  links.erase(std::unique(links.begin(), links.end(),
                          [](const Bridge& a, const Bridge& b) { return a.from == b.from && a.to == b.to; }),
              links.end());
  g.sparseLinks = links.size();
  if (!links.empty()) appendEdges(g, links);
}

/// Connected pieces, numbered by decreasing point count (ties: lowest first vertex).
void labelPieces(VoxelGraph& g) {
  std::int32_t pieces = 0;
  const std::vector<std::int32_t> label = util::labelComponents(g.offsets, g.targets, &pieces);
  std::vector<std::int64_t> pieceCount(pieces, 0);
  for (std::size_t v = 0; v < g.size(); ++v) pieceCount[label[v]] += g.pointCount[v];
  std::vector<std::int32_t> order(pieces);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return pieceCount[a] > pieceCount[b]; });
  std::vector<std::int32_t> rank(order.size());
  for (std::size_t r = 0; r < order.size(); ++r) rank[order[r]] = static_cast<std::int32_t>(r);
  g.piece.resize(g.size());
  for (std::size_t i = 0; i < g.size(); ++i) g.piece[i] = rank[label[i]];
}

// A bridge candidate: the shortest gap from a voxel of an unconnected piece to another piece.
struct Candidate {
  double length;
  std::uint32_t from, to;  // to = vertex of the piece being attached
};

/// Per voxel of a bridgeable piece (other than the main one): its nearest voxel of another
/// bridgeable piece within maxGapVoxels; sorted by length (ties: by vertex).
std::vector<Candidate> bridgeCandidates(const VoxelGraph& g, const accel::PointIndex& index,
                                        const std::vector<char>& eligible, const VoxelGraphOptions& o) {
  const std::size_t n = g.size();
  const double maxGap = o.maxGapVoxels * g.voxelSize;
  std::vector<Candidate> best(n, Candidate{-1, 0, 0});
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kCellsPerTask),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::vector<accel::Neighbour> hits;
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        if (g.piece[i] == 0 || !eligible[g.piece[i]]) continue;
                        index.withinRadiusByDistance(g.positions[i], maxGap, hits);
                        for (const auto& [j, d2] : hits) {
                          if (g.piece[j] == g.piece[i] || !eligible[g.piece[j]]) continue;
                          best[i] = Candidate{std::sqrt(d2), j, static_cast<std::uint32_t>(i)};
                          break;
                        }
                      }
                    });
  std::vector<Candidate> candidates;
  for (const Candidate& c : best)
    if (c.length >= 0) candidates.push_back(c);
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.length, a.to, a.from) < std::tie(b.length, b.to, b.from);
  });
  return candidates;
}

/// Whether a long gap may be bridged: the attached piece is elongated near its joint
/// (minBridgeLinearity) and the gap runs within coneAngleDeg of its axis there.
bool gapFollowsAxis(const VoxelGraph& g, const accel::PointIndex& index, const Candidate& c,
                    const VoxelGraphOptions& o) {
  thread_local std::vector<accel::Neighbour> hits;
  index.withinRadiusByDistance(g.positions[c.to], o.coneRadiusVoxels * g.voxelSize, hits);
  Vec3 mean = Vec3::Zero();
  int count = 0;
  for (const auto& h : hits)
    if (g.piece[h.index] == g.piece[c.to]) {
      mean += g.positions[h.index];
      ++count;
    }
  if (count < kMinAxisVoxels) return false;
  mean /= count;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& h : hits)
    if (g.piece[h.index] == g.piece[c.to]) {
      const Vec3 d = g.positions[h.index] - mean;
      cov += d * d.transpose();
    }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);
  const Vec3 axis = eig.eigenvectors().col(2);
  const double l1 = std::max(eig.eigenvalues()(2), kTinyEigenvalue), l2 = std::max(eig.eigenvalues()(1), 0.0);
  if ((l1 - l2) / l1 < o.minBridgeLinearity) return false;
  const Vec3 gap = (g.positions[c.from] - g.positions[c.to]) / c.length;
  return std::abs(axis.dot(gap)) >= std::cos(o.coneAngleDeg * M_PI / 180.0);
}

/// The graph's rows rebuilt with `edges` appended (both directions).
void appendEdges(VoxelGraph& g, const std::vector<Bridge>& edges) {
  const std::size_t n = g.size();
  std::vector<std::uint32_t> extra(n, 0);
  for (const Bridge& b : edges) {
    ++extra[b.from];
    ++extra[b.to];
  }
  std::vector<std::uint32_t> offsets(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) offsets[i + 1] = offsets[i] + (g.offsets[i + 1] - g.offsets[i]) + extra[i];
  std::vector<std::uint32_t> targets(offsets[n]);
  std::vector<float> weights(offsets[n]);
  std::vector<std::uint32_t> fill(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t k = offsets[i];
    for (std::uint32_t e = g.offsets[i]; e < g.offsets[i + 1]; ++e, ++k) {
      targets[k] = g.targets[e];
      weights[k] = g.weights[e];
    }
    fill[i] = k;
  }
  for (const Bridge& b : edges) {
    targets[fill[b.from]] = b.to;
    weights[fill[b.from]++] = static_cast<float>(b.length);
    targets[fill[b.to]] = b.from;
    weights[fill[b.to]++] = static_cast<float>(b.length);
  }
  g.offsets = std::move(offsets);
  g.targets = std::move(targets);
  g.weights = std::move(weights);
}

/// Bridges pieces to the main piece (Kruskal over the shortest gap of each voxel): gaps up to
/// freeGapVoxels always, longer ones when they follow the attached piece's axis.
void bridgePieces(VoxelGraph& g, const VoxelGraphOptions& o) {
  const std::size_t n = g.size();
  const std::int32_t pieces = n == 0 ? 0 : *std::max_element(g.piece.begin(), g.piece.end()) + 1;
  if (pieces <= 1 || o.maxGapVoxels <= 0) return;
  std::vector<std::int64_t> piecePoints(pieces, 0);
  for (std::size_t i = 0; i < n; ++i) piecePoints[g.piece[i]] += g.pointCount[i];
  std::vector<char> eligible(pieces);
  for (std::int32_t p = 0; p < pieces; ++p) eligible[p] = p == 0 || piecePoints[p] >= o.minBridgePoints;
  const accel::PointIndex index(g.positions);
  const double freeGap = o.freeGapVoxels * g.voxelSize;
  util::UnionFind uf(static_cast<std::size_t>(pieces));
  for (const Candidate& c : bridgeCandidates(g, index, eligible, o)) {
    const auto a = static_cast<std::uint32_t>(g.piece[c.from]), b = static_cast<std::uint32_t>(g.piece[c.to]);
    if (uf.find(a) == uf.find(b)) continue;
    if (c.length > freeGap && !gapFollowsAxis(g, index, c, o)) continue;
    uf.unite(a, b);
    g.bridges.push_back(Bridge{c.from, c.to, c.length});
  }
  if (!g.bridges.empty()) appendEdges(g, g.bridges);
}

}  // namespace

double chooseVoxelSize(const geom::PointCloud& cloud, const VoxelGraphOptions& options) {
  checkOptions(options);
  if (options.voxelSize > 0) return options.voxelSize;
  const geom::BBox box = cloud.bounds();
  const double diag = box.diagonal();
  if (cloud.size() < 2 || !(diag > 0)) return 1.0;
  double size = diag * options.autoDiagonalFraction;
  // Point spacing from occupancy: a surface sampled every h puts ~ (v/h)^2 points in a voxel.
  const std::size_t occupied = countVoxels(cloud, gridOrigin(box, size), size);
  const double perVoxel = static_cast<double>(cloud.size()) / static_cast<double>(std::max<std::size_t>(occupied, 1));
  const double spacing = size / std::sqrt(std::max(perVoxel, 1.0));
  size = std::max(size, options.autoSpacingFactor * spacing);
  // Keep the grid below the packing limit and the voxel count below the budget.
  size = std::max(size, box.extent().maxCoeff() / static_cast<double>(detail::kAxisCells - kSpareAxisCells));
  for (int step = 0; step < kMaxSizeSteps; ++step) {
    const std::size_t count = countVoxels(cloud, gridOrigin(box, size), size);
    if (count <= options.maxVoxels) break;
    size *= std::max(kMinSizeGrowth, std::sqrt(static_cast<double>(count) / static_cast<double>(options.maxVoxels)));
  }
  return size;
}

VoxelGraph buildVoxelGraph(const geom::PointCloud& cloud, const VoxelGraphOptions& options) {
  checkOptions(options);
  checkFinite(cloud);
  VoxelGraph g;
  g.voxelSize = chooseVoxelSize(cloud, options);
  g.offsets.assign(1, 0);
  if (cloud.empty()) return g;
  const geom::BBox box = cloud.bounds();
  if (box.extent().maxCoeff() / g.voxelSize > static_cast<double>(detail::kAxisCells - kSpareAxisCells))
    throw OptionsError("skeleton graph: voxelSize too small for the cloud's extent (over 2^21 voxels per axis)");
  g.origin = gridOrigin(box, g.voxelSize);
  Voxelized v = voxelize(cloud, g.origin, g.voxelSize);
  g.positions = std::move(v.positions);
  g.pointCount = std::move(v.counts);
  g.pointVoxel = std::move(v.pointVoxel);
  computeFeatures(g, v.keys, options.shapeCellVoxels);
  buildGridEdges(g, v, options.reach);
  addSparseLinks(g, options);
  labelPieces(g);
  bridgePieces(g, options);
  return g;
}

}  // namespace treesketch::skeleton
