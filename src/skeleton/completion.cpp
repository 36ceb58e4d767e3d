#include "skeleton/completion.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace treesketch::skeleton::detail {

std::vector<std::uint32_t> unexplainedPoints(const geom::PointCloud& cloud, const compare::CylinderModelIndex& model,
                                             double margin, const VoxelGraph* grid,
                                             const std::vector<std::uint32_t>* among,
                                             const std::vector<double>* pieceMargin) {
  // With a margin per piece, a voxel is decided at once only against the smallest (all explained)
  // and the largest (none explained) of them.
  double lowMargin = margin, highMargin = margin;
  if (pieceMargin && !pieceMargin->empty()) {
    lowMargin = *std::min_element(pieceMargin->begin(), pieceMargin->end());
    highMargin = *std::max_element(pieceMargin->begin(), pieceMargin->end());
  }
  const auto outside = [&](const geom::Vec3& p) {
    std::int64_t piece = -1;
    const double d = model.signedDistance(p, &piece);
    const double m = pieceMargin && piece >= 0 && static_cast<std::size_t>(piece) < pieceMargin->size()
                         ? (*pieceMargin)[static_cast<std::size_t>(piece)]
                         : margin;
    return d > m;
  };
  const std::size_t n = among ? among->size() : cloud.size();
  auto pointAt = [&](std::size_t k) { return among ? (*among)[k] : static_cast<std::uint32_t>(k); };
  // Per voxel: 0 = measure each point, 1 = all explained, 2 = none explained.
  std::vector<char> verdict;
  const bool useGrid = grid && grid->pointVoxel.size() == cloud.size() && !grid->positions.empty();
  if (useGrid) {
    const std::size_t voxels = grid->positions.size();
    std::vector<double> spread(voxels, -1.0);  // < 0: no point of `among` in it
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t i = pointAt(k);
      const std::uint32_t v = grid->pointVoxel[i];
      spread[v] = std::max(spread[v], (cloud.positions[i] - grid->positions[v]).norm());
    }
    verdict.assign(voxels, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, voxels, 256), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t v = r.begin(); v < r.end(); ++v) {
        if (spread[v] < 0) continue;
        const double d = model.signedDistance(grid->positions[v]);
        if (std::max(d, 0.0) + spread[v] <= lowMargin)
          verdict[v] = 1;
        else if (d - spread[v] > highMargin)
          verdict[v] = 2;
      }
    });
  }
  std::vector<char> out(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k < r.end(); ++k) {
      const std::uint32_t i = pointAt(k);
      const char known = useGrid ? verdict[grid->pointVoxel[i]] : 0;
      out[k] = known != 0 ? known == 2 : outside(cloud.positions[i]);
    }
  });
  std::vector<std::uint32_t> rest;
  for (std::size_t k = 0; k < n; ++k)
    if (out[k]) rest.push_back(pointAt(k));
  return rest;
}

bool graftPart(std::vector<SkeletonNode>& nodes, const std::vector<SkeletonNode>& part,
               const std::vector<SkeletonNode>& model, const geom::CylinderModel& pieces,
               const compare::CylinderModelIndex& index, double maxGap) {
  const std::size_t m = part.size();
  if (m < 2 || model.empty() || model.size() > nodes.size()) return false;
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
