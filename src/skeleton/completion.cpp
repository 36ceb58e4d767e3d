#include "skeleton/completion.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace treesketch::skeleton::detail {

namespace {

using Near = compare::CylinderModelIndex::NearPiece;

/// The points of `among` (all points without it) grouped by voxel: voxel v holds the positions
/// members[first[v]] .. members[first[v + 1]) (positions in `among`), and the spread of its points
/// (the farthest from its centroid; < 0 when it holds none).
struct VoxelMembers {
  std::vector<std::uint32_t> first, members;
  std::vector<double> spread;
};

VoxelMembers groupByVoxel(const geom::PointCloud& cloud, const VoxelGraph& grid, std::size_t n,
                          const std::vector<std::uint32_t>* among) {
  const std::size_t voxels = grid.positions.size();
  VoxelMembers g;
  g.first.assign(voxels + 1, 0);
  g.spread.assign(voxels, -1.0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t i = among ? (*among)[k] : static_cast<std::uint32_t>(k);
    const std::uint32_t v = grid.pointVoxel[i];
    ++g.first[v + 1];
    g.spread[v] = std::max(g.spread[v], (cloud.positions[i] - grid.positions[v]).norm());
  }
  for (std::size_t v = 0; v < voxels; ++v) g.first[v + 1] += g.first[v];
  g.members.resize(n);
  std::vector<std::uint32_t> next(g.first.begin(), g.first.end() - 1);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t i = among ? (*among)[k] : static_cast<std::uint32_t>(k);
    g.members[next[grid.pointVoxel[i]]++] = static_cast<std::uint32_t>(k);
  }
  return g;
}

/// The test of one point of `cloud` (the k-th of `among`, or of all points): its signed distance
/// against the margin of the piece that gives it.
struct PointTest {
  const geom::PointCloud& cloud;
  const compare::CylinderModelIndex& model;
  double margin;
  const std::vector<std::uint32_t>* among;
  const std::vector<double>* pieceMargin;

  std::uint32_t pointAt(std::size_t k) const { return among ? (*among)[k] : static_cast<std::uint32_t>(k); }
  double marginOf(std::int64_t piece) const {
    return pieceMargin && piece >= 0 && static_cast<std::size_t>(piece) < pieceMargin->size()
               ? (*pieceMargin)[static_cast<std::size_t>(piece)]
               : margin;
  }
  /// The plain test, through the whole index.
  bool outside(const geom::Vec3& p) const {
    std::int64_t piece = -1;
    const double d = model.signedDistance(p, &piece);
    return d > marginOf(piece);
  }

  /// The points of voxel v (centroid c, spread s, d the signed distance at c), out[k] = 1 for
  /// those unexplained. Every point p of the voxel has a signed distance of at most
  /// max(d, 0) + |p - c| (outside the model it is the distance to it, 1-Lipschitz) and, when
  /// d > |p - c|, of at least d - |p - c|; the piece giving it is one of those nearPieces finds at
  /// c with reach s. So a point, or the whole voxel with |p - c| = s, is decided against the
  /// smallest and the largest margin of those pieces; the rest are measured against those pieces
  /// only, or through the whole index where two of them tie. `slack` covers rounding (far below
  /// any distance that matters).
  void decideVoxel(const VoxelGraph& grid, const VoxelMembers& g, std::size_t v, std::vector<Near>& near,
                   std::vector<char>& out) const {
    const geom::Vec3& c = grid.positions[v];
    const double s = g.spread[v];
    const double slack = 1e-9 * (grid.voxelSize + c.cwiseAbs().maxCoeff());
    const double d = model.nearPieces(c, s + slack, near);
    double low = margin, high = margin;  // no piece: the margin of none (an empty model)
    if (!near.empty()) {
      low = std::numeric_limits<double>::infinity();
      high = 0;
      for (const Near& k : near) {
        low = std::min(low, marginOf(k.piece));
        high = std::max(high, marginOf(k.piece));
      }
    }
    if (std::max(d, 0.0) + s + slack <= low) return;  // all explained
    const bool none = d - s - slack > high;           // none explained
    for (std::uint32_t j = g.first[v]; j < g.first[v + 1]; ++j) {
      const std::uint32_t k = g.members[j];
      if (none) {
        out[k] = 1;
        continue;
      }
      const geom::Vec3& p = cloud.positions[pointAt(k)];
      const double off = (p - c).norm();
      if (std::max(d, 0.0) + off + slack <= low) continue;
      if (d - off - slack > high) {
        out[k] = 1;
        continue;
      }
      std::int64_t piece = -1;
      bool tied = false;
      const double e = model.signedDistanceAmong(p, near, &piece, &tied);
      out[k] = tied ? outside(p) : e > marginOf(piece);
    }
  }
};

}  // namespace

std::vector<std::uint32_t> unexplainedPoints(const geom::PointCloud& cloud, const compare::CylinderModelIndex& model,
                                             double margin, const VoxelGraph* grid,
                                             const std::vector<std::uint32_t>* among,
                                             const std::vector<double>* pieceMargin) {
  const PointTest test{cloud, model, margin, among, pieceMargin};
  const std::size_t n = among ? among->size() : cloud.size();
  std::vector<char> out(n, 0);
  if (grid && grid->pointVoxel.size() == cloud.size() && !grid->positions.empty()) {
    const VoxelMembers g = groupByVoxel(cloud, *grid, n, among);
    tbb::enumerable_thread_specific<std::vector<Near>> buffers;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.spread.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::vector<Near>& near = buffers.local();
                        for (std::size_t v = r.begin(); v < r.end(); ++v)
                          if (g.spread[v] >= 0) test.decideVoxel(*grid, g, v, near, out);
                      });
  } else {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k < r.end(); ++k) out[k] = test.outside(cloud.positions[test.pointAt(k)]);
    });
  }
  std::vector<std::uint32_t> rest;
  for (std::size_t k = 0; k < n; ++k)
    if (out[k]) rest.push_back(test.pointAt(k));
  return rest;
}

void reachStubTip(std::vector<SkeletonNode>& part, const geom::PointCloud& points,
                  const compare::CylinderModelIndex& index) {
  if (part.size() != 1 || points.empty()) return;
  double farthest = -std::numeric_limits<double>::infinity();
  for (const geom::Vec3& p : points.positions) {
    const double d = index.signedDistance(p);
    if (d > farthest) {
      farthest = d;
      part[0].position = p;
    }
  }
}

bool graftPart(std::vector<SkeletonNode>& nodes, const std::vector<SkeletonNode>& part,
               const std::vector<SkeletonNode>& model, const geom::CylinderModel& pieces,
               const compare::CylinderModelIndex& index, double maxGap) {
  // A part of one node is a stub shorter than two level sets (a short shoot, a twig's tip past
  // the model's end): its tube runs from the node it grows from to that node.
  const std::size_t m = part.size();
  if (m < 1 || model.empty() || model.size() > nodes.size()) return false;
  // Each node's distance outside the model, and whether it lies farther out than the radius of
  // the piece nearest to it.
  std::vector<double> gap(m);
  bool leaves = false;
  for (std::size_t i = 0; i < m; ++i) {
    std::int64_t piece = -1;
    gap[i] = index.signedDistance(part[i].position, &piece);
    if (piece >= 0) {
      const auto& c = pieces.cylinders[static_cast<std::size_t>(piece)];
      leaves = leaves || gap[i] > std::max(c.startRadius, c.endRadius);
    }
  }
  if (!leaves) return false;  // along a limb's side: that limb's own surface
  // Where the part is nearest to the model: its foot.
  const auto foot = static_cast<std::int32_t>(std::min_element(gap.begin(), gap.end()) - gap.begin());
  if (!(gap[foot] <= maxGap)) return false;

  // The node the part grows from: the node nearest to its foot, of the model or of a part
  // grafted before (its skeleton's position and radius).
  auto at = [&](std::size_t k) -> const SkeletonNode& { return k < model.size() ? model[k] : nodes[k]; };
  std::int32_t host = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const double d = (at(k).position - part[foot].position).squaredNorm();
    if (d < best) {
      best = d;
      host = static_cast<std::int32_t>(k);
    }
  }

  // Re-rooted at the foot: breadth-first over the part's links, parents first.
  std::vector<std::int32_t> order{foot}, newParent(m, -1);
  std::vector<char> seen(m, 0), reversed(m, 0);
  seen[foot] = 1;
  for (std::size_t head = 0; head < order.size(); ++head) {
    const std::int32_t u = order[head];
    auto visit = [&](std::int32_t v, bool up) {
      if (v < 0 || seen[v]) return;
      seen[v] = 1;
      newParent[v] = u;
      reversed[v] = up;  // reached from its old child: it now points the other way
      order.push_back(v);
    };
    visit(part[u].parent, true);
    for (std::int32_t c : part[u].children) visit(c, false);
  }
  if (order.size() != m) return false;  // not one tree

  const auto base = static_cast<std::int32_t>(nodes.size());
  std::vector<std::int32_t> newIndex(m, -1);
  for (std::size_t k = 0; k < m; ++k) newIndex[order[k]] = base + static_cast<std::int32_t>(k);
  const double cap = at(host).radius;
  const std::int32_t order1 = nodes[host].branchOrder + 1;
  for (std::size_t k = 0; k < m; ++k) {
    const std::int32_t v = order[k];
    SkeletonNode node = part[v];
    node.parent = k == 0 ? host : newIndex[newParent[v]];
    node.children.clear();
    if (reversed[v]) node.direction = -node.direction;
    node.radius = std::min(node.radius, cap);
    node.raw = -1;  // not one of the skeleton's raw nodes
    node.stem = false;
    node.grafted = true;
    node.branchOrder = order1;
    const SkeletonNode& p = nodes[node.parent];
    node.level = p.level + 1;
    node.distance = p.distance + (node.position - p.position).norm();
    nodes[node.parent].children.push_back(base + static_cast<std::int32_t>(k));
    nodes.push_back(std::move(node));
  }
  return true;
}

}  // namespace treesketch::skeleton::detail
