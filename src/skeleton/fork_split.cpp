#include "skeleton/fork_split.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <limits>
#include <numeric>

#include "skeleton/node_tree.h"

namespace treesketch::skeleton::detail {
namespace {

using geom::Vec3;

// A limb's line runs through its first this many level-set nodes (at least kMinLineNodes): long
// enough to average a sparse limb's one-sided centroids, short enough for a curved limb.
constexpr int kLineNodes = 4;
constexpr int kMinLineNodes = 2;

// A limb's piece below its fork holds at least this share of its pieces' mean support above (most
// of a cross-section); less is an arc where the limbs already merge, its centroid off the axis
// (the Y-tree test's 0.22). 0.5 stopped the split short on sparse scans (tls-base backward
// 0.134 → 0.144 %, real scans 0.1–1.5 points fewer within ±2 cm); putting the pieces on the
// limbs' lines instead of at their centroids was worse on every condition.
constexpr double kMinGroupSupport = 0.25;

// The voxels of each node, as offsets into one list.
struct Pieces {
  std::vector<std::uint32_t> offsets, voxels;
};

Pieces piecesOf(const GeodesicLevels& lv, std::size_t nodeCount) {
  Pieces p;
  p.offsets.assign(nodeCount + 1, 0);
  for (std::int32_t id : lv.vertexNode)
    if (id >= 0) ++p.offsets[id + 1];
  std::partial_sum(p.offsets.begin(), p.offsets.end(), p.offsets.begin());
  p.voxels.resize(p.offsets.back());
  std::vector<std::uint32_t> next(p.offsets.begin(), p.offsets.end() - 1);
  for (std::size_t v = 0; v < lv.vertexNode.size(); ++v)
    if (lv.vertexNode[v] >= 0) p.voxels[next[lv.vertexNode[v]]++] = static_cast<std::uint32_t>(v);
  return p;
}

struct Line {
  Vec3 point = Vec3::Zero(), direction = Vec3::UnitZ();
  double radius = 0;
  double firstT = 0, span = 0;  ///< the first node's position along the line, and the nodes' extent
  double support = 0;           ///< the mean support (points) of its nodes: a cross-section's worth

  double along(const Vec3& p) const { return (p - point).dot(direction); }
  Vec3 nearest(const Vec3& p) const { return point + along(p) * direction; }
  double distance(const Vec3& p) const { return (p - nearest(p)).norm(); }
};

// The line of the limb starting at node `c`: a support-weighted principal axis through its first
// nodes, following at each fork the child whose sub-tree reaches the highest level; false when
// the limb has too few nodes to give a direction.
bool limbLine(const std::vector<SkeletonNode>& nodes, const std::vector<std::int32_t>& topLevel, const Pieces& pieces,
              const std::vector<Vec3>& at, std::int32_t c, double minRadius, Line& line) {
  std::vector<std::int32_t> chain{c};
  while (static_cast<int>(chain.size()) < kLineNodes && !nodes[chain.back()].children.empty()) {
    std::int32_t best = -1;
    for (std::int32_t k : nodes[chain.back()].children)
      if (best < 0 || topLevel[k] > topLevel[best] ||
          (topLevel[k] == topLevel[best] && nodes[k].support > nodes[best].support))
        best = k;
    chain.push_back(best);
  }
  if (static_cast<int>(chain.size()) < kMinLineNodes) return false;
  Vec3 mean = Vec3::Zero();
  double weight = 0;
  for (std::int32_t k : chain) {
    mean += nodes[k].support * nodes[k].position;
    weight += nodes[k].support;
  }
  if (!(weight > 0)) return false;
  line.support = weight / static_cast<double>(chain.size());
  mean /= weight;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::int32_t k : chain) {
    const Vec3 d = nodes[k].position - mean;
    cov += nodes[k].support * d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);
  line.point = mean;
  line.direction = eig.eigenvectors().col(2).normalized();
  if (line.direction.dot(nodes[chain.back()].position - nodes[chain.front()].position) < 0)
    line.direction = -line.direction;
  line.firstT = line.along(nodes[chain.front()].position);
  line.span = line.along(nodes[chain.back()].position) - line.firstT;
  if (!(line.span > 0)) return false;
  double sum = 0;
  std::size_t n = 0;
  for (std::int32_t k : chain)
    for (std::uint32_t i = pieces.offsets[k]; i < pieces.offsets[k + 1]; ++i, ++n)
      sum += line.distance(at[pieces.voxels[i]]);
  line.radius = std::max(n > 0 ? sum / static_cast<double>(n) : 0.0, minRadius);
  return true;
}

// Whether node `cur`'s piece may be cut along `lines`: each line within its reach backwards (no
// further below its first node than its nodes' extent, or one level set), and every two lines
// more than their two radii apart at the piece (their tubes do not overlap there).
bool separate(const Vec3& x, const std::vector<Line>& lines, double binWidth) {
  for (const Line& l : lines)
    if (l.along(x) < l.firstT - std::max(l.span, binWidth)) return false;
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (std::size_t j = i + 1; j < lines.size(); ++j)
      if ((lines[i].nearest(x) - lines[j].nearest(x)).norm() <= lines[i].radius + lines[j].radius) return false;
  return true;
}

// Per node: the highest level its sub-tree reaches (nodes parent-first).
std::vector<std::int32_t> topLevels(const std::vector<SkeletonNode>& nodes) {
  std::vector<std::int32_t> top(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) top[i] = nodes[i].level;
  for (std::size_t i = nodes.size(); i-- > 0;)
    if (nodes[i].parent >= 0) top[nodes[i].parent] = std::max(top[nodes[i].parent], top[i]);
  return top;
}

// Node fields of a piece made of `voxels` (as pieceNodes sets them).
void setPiece(const VoxelGraph& g, const GeodesicLevels& lv, const std::vector<Vec3>& at,
              const std::vector<std::uint32_t>& voxels, SkeletonNode& node) {
  node.position = Vec3::Zero();
  node.support = 0;
  node.distance = std::numeric_limits<double>::infinity();
  double lin = 0;
  for (std::uint32_t v : voxels) {
    node.position += at[v];
    node.support += g.pointCount[v];
    lin += g.linearity[v] * g.pointCount[v];
    node.distance = std::min(node.distance, lv.distance[v]);
  }
  node.position /= static_cast<double>(voxels.size());
  node.linearity = static_cast<float>(lin / std::max(node.support, 1));
}

// Each voxel of node `cur`'s piece (as first cut) to the nearest line.
void groupByNearestLine(const Pieces& pieces, const GeodesicLevels& lv, const std::vector<Vec3>& at,
                        const std::vector<Line>& lines, std::int32_t cur,
                        std::vector<std::vector<std::uint32_t>>& groups) {
  groups.assign(lines.size(), {});
  for (std::uint32_t i = pieces.offsets[cur]; i < pieces.offsets[cur + 1]; ++i) {
    const std::uint32_t v = pieces.voxels[i];
    if (lv.vertexNode[v] != cur) continue;
    std::size_t best = 0;
    double nearest = lines[0].distance(at[v]);
    for (std::size_t l = 1; l < lines.size(); ++l)
      if (const double d = lines[l].distance(at[v]); d < nearest) {
        nearest = d;
        best = l;
      }
    groups[best].push_back(v);
  }
}

// Whether every line's group holds enough of the line's support to stand as a piece.
bool wholeGroups(const VoxelGraph& g, const std::vector<Line>& lines,
                 const std::vector<std::vector<std::uint32_t>>& groups) {
  bool whole = true;
  for (std::size_t l = 0; l < lines.size(); ++l) {
    std::int64_t support = 0;
    for (std::uint32_t v : groups[l]) support += g.pointCount[v];
    whole = whole && !groups[l].empty() && support >= kMinGroupSupport * lines[l].support;
  }
  return whole;
}

// Back to level order (parents first), indices remapped (nodes, counts and the voxels' nodes).
// Within a level, a piece whose parent is of its own level (levels cut at a conifer's stem tube:
// level_sets.cpp) comes after that parent: a split parent's new piece is appended after its
// children, and a child before its parent made a second root in the sketch.
void sortByLevel(std::vector<SkeletonNode>& nodes, std::vector<std::uint32_t>& count, GeodesicLevels& lv) {
  std::vector<std::int32_t> depth(nodes.size(), 0);  // same-level ancestors above each node
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (std::int32_t p = nodes[i].parent; p >= 0 && nodes[p].level == nodes[i].level &&
                                           depth[i] <= static_cast<std::int32_t>(nodes.size());
         p = nodes[p].parent)
      ++depth[i];
  std::vector<std::int32_t> order(nodes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return nodes[a].level != nodes[b].level ? nodes[a].level < nodes[b].level : depth[a] < depth[b];
  });
  std::vector<std::int32_t> newIndex(nodes.size());
  for (std::size_t i = 0; i < order.size(); ++i) newIndex[order[i]] = static_cast<std::int32_t>(i);
  std::vector<SkeletonNode> sorted(nodes.size());
  std::vector<std::uint32_t> sortedCount(nodes.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    sorted[i] = nodes[order[i]];
    sortedCount[i] = count[order[i]];
    if (sorted[i].parent >= 0) sorted[i].parent = newIndex[sorted[i].parent];
  }
  for (auto& id : lv.vertexNode)
    if (id >= 0) id = newIndex[id];
  nodes = std::move(sorted);
  count = std::move(sortedCount);
}

}  // namespace

void splitMergedForks(const VoxelGraph& g, GeodesicLevels& lv, const std::vector<Vec3>& at,
                      const std::vector<char>& tube, const SkeletonOptions& options, std::vector<SkeletonNode>& nodes,
                      std::vector<std::uint32_t>& count) {
  const std::size_t original = nodes.size();
  if (original < 3) return;
  const Pieces pieces = piecesOf(lv, original);
  const std::vector<std::int32_t> topLevel = topLevels(nodes);
  const double minRadius = options.minRadiusVoxels * g.voxelSize;
  const double binWidth = lv.binWidth;
  auto onStem = [&](std::int32_t k) {
    if (tube.empty()) return false;
    std::size_t in = 0, all = pieces.offsets[k + 1] - pieces.offsets[k];
    for (std::uint32_t i = pieces.offsets[k]; i < pieces.offsets[k + 1]; ++i) in += tube[pieces.voxels[i]] ? 1 : 0;
    return 2 * in > all;
  };

  std::vector<Line> lines;
  std::vector<std::int32_t> limbs, above, groupNode;
  std::vector<std::vector<std::uint32_t>> groups;
  // Lowest forks first: a fork's lines run through the unsplit nodes above it. The children lists
  // stay those of the pieces as first cut (only parents are rewritten until the end).
  for (std::size_t f = 0; f < original; ++f) {
    if (nodes[f].children.size() < 2) continue;
    limbs.clear();
    lines.clear();
    for (std::int32_t c : nodes[f].children) {  // no node is added in this loop
      Line line;
      if (topLevel[c] - nodes[c].level + 1 < options.spurLengthBins) continue;  // a spur, not a limb
      if (!limbLine(nodes, topLevel, pieces, at, c, minRadius, line)) continue;
      limbs.push_back(c);
      lines.push_back(line);
    }
    if (limbs.size() < 2) continue;
    above = limbs;
    for (auto cur = static_cast<std::int32_t>(f);;) {
      if (cur >= static_cast<std::int32_t>(original)) break;  // a piece of a fork below, already cut
      if (nodes[cur].level <= 0 || onStem(cur)) break;
      if (cur != static_cast<std::int32_t>(f) && nodes[cur].children.size() != 1) break;  // another fork
      if (!separate(nodes[cur].position, lines, binWidth)) break;
      // Each voxel to the nearest line (over the voxels of the piece as first cut).
      groupByNearestLine(pieces, lv, at, lines, cur, groups);
      if (!wholeGroups(g, lines, groups)) break;
      groupNode.assign(lines.size(), cur);
      const SkeletonNode base = nodes[cur];
      for (std::size_t l = 0; l < lines.size(); ++l) {
        if (l > 0) {
          groupNode[l] = static_cast<std::int32_t>(nodes.size());
          nodes.push_back(base);
          count.push_back(0);
        }
        SkeletonNode& node = nodes[groupNode[l]];
        setPiece(g, lv, at, groups[l], node);
        count[groupNode[l]] = static_cast<std::uint32_t>(groups[l].size());
        for (std::uint32_t v : groups[l]) lv.vertexNode[v] = groupNode[l];
        nodes[above[l]].parent = groupNode[l];
      }
      if (cur == static_cast<std::int32_t>(f))  // the fork's spurs go with the nearest limb's piece
        for (std::int32_t c : nodes[f].children) {
          if (std::find(limbs.begin(), limbs.end(), c) != limbs.end()) continue;
          std::size_t best = 0;
          for (std::size_t l = 1; l < lines.size(); ++l)
            if ((nodes[c].position - nodes[groupNode[l]].position).norm() <
                (nodes[c].position - nodes[groupNode[best]].position).norm())
              best = l;
          nodes[c].parent = groupNode[best];
        }
      above = groupNode;
      cur = base.parent;
      if (cur < 0) break;
    }
  }
  if (nodes.size() == original) return;

  sortByLevel(nodes, count, lv);
  linkChildren(nodes);
}

}  // namespace treesketch::skeleton::detail
