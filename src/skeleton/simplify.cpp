// Pruning and simplification of the raw level-set nodes, as named steps: radii smoothed along
// the main chains, side sub-trees dropped as spurs or foliage, partial tips dropped, forks put back
// on their parent chain's line, chains between forks and ends simplified (Douglas–Peucker), and
// the kept nodes re-linked with their directions and branch orders.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "skeleton/checks.h"
#include "skeleton/node_tree.h"
#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton {
namespace {

using detail::mainChild;
using geom::Vec3;

// The line a fork is put back on runs through its ancestors from the fork zone's lower end down to
// this many times the zone's depth below the fork...
constexpr double kForkLineDepths = 3;
// ...and needs at least this many of them to have a direction.
constexpr int kMinForkLineNodes = 3;
// Chords and tolerances shorter than this are treated as zero (coincident nodes).
constexpr double kTinyLength = 1e-12;
// A side branch within this angle's cosine of its parent's axis (about 15 degrees) is not
// re-anchored: followed backwards it runs along the parent, so it has no junction point.
constexpr double kReanchorMaxCosine = 0.966;

// What the pruning steps know of the raw nodes.
struct RawTree {
  const std::vector<SkeletonNode>& raw;
  std::vector<double> reach;         ///< longest path down each subtree, world units
  std::vector<std::int32_t> mainOf;  ///< the child continuing each node's branch, -1 for none
  std::vector<double> radius;        ///< smoothed radii
};

// Radius: running median over radiusMedianWindow nodes along the main chain through each node.
std::vector<double> smoothRadii(const std::vector<SkeletonNode>& raw, const std::vector<std::int32_t>& mainOf,
                                int window) {
  std::vector<double> radius(raw.size());
  const int half = window / 2;
  std::vector<double> values;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    values.assign(1, raw[i].radius);
    std::int32_t up = raw[i].parent, down = mainOf[i];
    for (int k = 0; k < half; ++k) {
      if (up >= 0) {
        values.push_back(raw[up].radius);
        up = raw[up].parent;
      }
      if (down >= 0) {
        values.push_back(raw[down].radius);
        down = mainOf[down];
      }
    }
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    radius[i] = values[values.size() / 2];
  }
  return radius;
}

RawTree describe(const std::vector<SkeletonNode>& raw, const SkeletonOptions& options) {
  RawTree t{raw, detail::subtreeReach(raw), {}, {}};
  t.mainOf.resize(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) t.mainOf[i] = mainChild(raw, t.reach, i);
  t.radius = smoothRadii(raw, t.mainOf, options.radiusMedianWindow);
  return t;
}

// Drop spurs: a side child c of node i is kept when its sub-tree is long enough not to be a spur.
// How far a side sub-tree reaches out of its parent's surface: the largest distance of its nodes
// from the parent's axis (the line through node i along its direction) less i's radius.
double reachOutOfParent(const RawTree& t, std::size_t i, std::int32_t c) {
  const Vec3 a = t.raw[i].position, d = t.raw[i].direction;
  double out = -std::numeric_limits<double>::infinity();
  std::vector<std::int32_t> stack{c};
  while (!stack.empty()) {
    const std::int32_t k = stack.back();
    stack.pop_back();
    const Vec3 q = t.raw[k].position - a;
    out = std::max(out, (q - q.dot(d) * d).norm() - t.radius[i]);
    for (std::int32_t g : t.raw[k].children) stack.push_back(g);
  }
  return out;
}

bool keepSideBranch(const RawTree& t, std::size_t i, std::int32_t c, double binWidth, const SkeletonOptions& o) {
  const double spur = std::max(o.spurLengthRadii * t.radius[i], o.spurLengthBins * binWidth);
  const double length = t.reach[c] + (t.raw[c].position - t.raw[i].position).norm();
  if (length >= spur) return true;
  // Shorter than a spur, but standing out of the parent's surface: a twig, not a bump or a strip
  // of bark (those lie on the surface).
  return o.twigOutBins > 0 && reachOutOfParent(t, i, c) >= o.twigOutBins * binWidth;
}

// Pruning, from the root down (a dropped node takes its sub-tree with it): main children are kept,
// side children by keepSideBranch; then partial tips are dropped: an end with less support than
// minEndSupportFraction of its parent's.
std::vector<char> pruneNodes(const RawTree& t, double binWidth, const SkeletonOptions& o) {
  const auto& raw = t.raw;
  std::vector<char> kept(raw.size(), 0);
  kept[0] = 1;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (!kept[i]) continue;
    for (std::int32_t c : raw[i].children) kept[c] = c == t.mainOf[i] || keepSideBranch(t, i, c, binWidth, o);
    for (std::int32_t c : raw[i].children)
      if (kept[c] && raw[c].children.empty() && raw[c].support < o.minEndSupportFraction * raw[i].support) kept[c] = 0;
  }
  return kept;
}

// Straighten forks: a fork's level set holds the parent's ring and the children's bases, so its
// centroid (and those of the few pieces below it) drift towards the children. They are put back on
// the support-weighted line through the parent chain further down. Returns the nodes' positions.
std::vector<Vec3> straightenForks(const RawTree& t, const std::vector<char>& kept,
                                  const std::vector<std::vector<std::int32_t>>& keptChildren, double binWidth,
                                  const SkeletonOptions& o) {
  const auto& raw = t.raw;
  std::vector<Vec3> position(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) position[i] = raw[i].position;
  for (std::size_t f = 0; f < raw.size(); ++f) {
    if (!kept[f] || keptChildren[f].size() < 2) continue;
    const double near = o.forkZoneRadii * t.radius[f] + binWidth;
    // The line is the fork's own branch: it stops below the previous fork (a side branch that
    // forks soon after leaving its parent would otherwise be put on the parent's line).
    std::int32_t previousFork = raw[f].parent;
    while (previousFork >= 0 && keptChildren[previousFork].size() < 2) previousFork = raw[previousFork].parent;
    std::int32_t a1 = raw[f].parent;
    while (a1 >= 0 && a1 != previousFork && raw[f].distance - raw[a1].distance < near) a1 = raw[a1].parent;
    if (a1 < 0 || a1 == previousFork) continue;
    auto inLine = [&](std::int32_t a) {
      return a >= 0 && a != previousFork && raw[f].distance - raw[a].distance < kForkLineDepths * near;
    };
    Vec3 mean = Vec3::Zero();
    double weight = 0;
    int count = 0;
    for (std::int32_t a = a1; inLine(a); a = raw[a].parent) {
      mean += raw[a].support * raw[a].position;
      weight += raw[a].support;
      ++count;
    }
    if (count < kMinForkLineNodes || weight <= 0) continue;
    mean /= weight;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::int32_t a = a1; inLine(a); a = raw[a].parent) {
      const Vec3 d = raw[a].position - mean;
      cov += raw[a].support * d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(cov);
    const Vec3 axis = eig.eigenvectors().col(2).normalized();
    for (std::int32_t j = static_cast<std::int32_t>(f); j != a1; j = raw[j].parent)
      position[j] = mean + (raw[j].position - mean).dot(axis) * axis;
  }
  return position;
}

// The child going on most nearly along the parent's axis from the fork at `fork`.
std::int32_t straightOnChild(const std::vector<std::int32_t>& children, const std::vector<Vec3>& position,
                             const Vec3& fork, const Vec3& parentAxis) {
  std::int32_t straightOn = -1;
  double bestCos = -2;
  for (std::int32_t c : children) {
    const double cosine = detail::safeNormalized(position[c] - fork, parentAxis).dot(parentAxis);
    if (cosine > bestCos) {
      bestCos = cosine;
      straightOn = c;
    }
  }
  return straightOn;
}

// The line of a side branch's first nodes from `c`, up to its next fork or end within `reach` of
// it: its mean and its unit direction (away from the fork). False with too few nodes for a line.
template <class RawNodes>
bool sideBranchLine(const RawNodes& raw, const std::vector<std::vector<std::int32_t>>& keptChildren,
                    const std::vector<Vec3>& position, std::int32_t c, double reach, std::vector<std::int32_t>& chain,
                    Vec3& mean, Vec3& u) {
  chain.clear();
  for (std::int32_t cur = c; cur >= 0 && raw[cur].distance - raw[c].distance <= reach;) {
    chain.push_back(cur);
    if (keptChildren[cur].size() != 1) break;
    cur = keptChildren[cur].front();
  }
  if (chain.size() < static_cast<std::size_t>(kMinForkLineNodes)) return false;
  mean = Vec3::Zero();
  for (std::int32_t id : chain) mean += position[id];
  mean /= static_cast<double>(chain.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::int32_t id : chain) cov += (position[id] - mean) * (position[id] - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);
  u = eig.eigenvectors().col(2).normalized();
  if (u.dot(position[chain.back()] - position[chain.front()]) < 0) u = -u;
  return true;
}

// The ancestor nearest the line (mean, u) behind the branch's first node (at `start` along it);
// -1 when none is behind. Sets bestGap to its distance from the line.
std::int32_t nearestBehind(const std::vector<std::int32_t>& ancestors, const std::vector<Vec3>& position,
                           const Vec3& mean, const Vec3& u, double start, double& bestGap) {
  std::int32_t best = -1;
  for (std::int32_t a : ancestors) {
    const double s = (position[a] - mean).dot(u);
    if (s > start) continue;  // only behind the branch's first node
    const double gap = (position[a] - (mean + s * u)).norm();
    if (gap < bestGap) {
      bestGap = gap;
      best = a;
    }
  }
  return best;
}

// A side branch's line, followed backwards from its first nodes, meets its parent's axis at the
// junction; the level sets separate the branch from the parent only higher up, where the two no
// longer touch, and link it there with a near-horizontal segment (a "shelf" under every acute
// fork, clearest on sparse scans where the bins are wide). Each side child of a fork is re-attached
// to the parent-chain node nearest that backward line, when one lies within the two radii of it.
// Returns each raw node's parent after re-attachment (and updates keptChildren and, where a fork
// is left with one child, the positions between it and the new junction).
std::vector<std::int32_t> reanchorSideBranches(const RawTree& t, const std::vector<char>& kept,
                                               std::vector<std::vector<std::int32_t>>& keptChildren,
                                               std::vector<Vec3>& position, double binWidth, const SkeletonOptions& o) {
  const auto& raw = t.raw;
  std::vector<std::int32_t> parentOf(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) parentOf[i] = raw[i].parent;
  std::vector<std::int32_t> ancestors, chain;
  for (std::size_t f = 0; f < raw.size(); ++f) {
    if (!kept[f] || keptChildren[f].size() < 2) continue;
    const double near = o.forkZoneRadii * t.radius[f] + binWidth;
    ancestors.clear();
    for (std::int32_t a = static_cast<std::int32_t>(f);
         a >= 0 && raw[f].distance - raw[a].distance < kForkLineDepths * near; a = parentOf[a])
      ancestors.push_back(a);
    if (ancestors.size() < 2) continue;  // the root's own children have no parent axis
    const Vec3 parentAxis = detail::safeNormalized(position[f] - position[ancestors.back()], Vec3::Zero());
    if (parentAxis.squaredNorm() == 0) continue;
    const std::vector<std::int32_t> children = keptChildren[f];
    std::int32_t highest = -1;  // the highest new junction
    // The child going on most nearly along the parent's axis continues it (not the longest
    // path: a twig near a branch's end can reach further than the branch's own remainder).
    const std::int32_t straightOn = straightOnChild(children, position, position[f], parentAxis);
    for (std::int32_t c : children) {
      if (c == straightOn) continue;
      // The side branch's first nodes, up to its next fork or end, within the fork-line depth.
      const double reachC = kForkLineDepths * (o.forkZoneRadii * t.radius[c] + binWidth);
      Vec3 mean, u;
      if (!sideBranchLine(raw, keptChildren, position, c, reachC, chain, mean, u)) continue;
      // Nearly parallel to the parent, the backward line follows the parent: no junction to find.
      if (std::abs(u.dot(parentAxis)) > kReanchorMaxCosine) continue;
      const double start = (position[c] - mean).dot(u);
      double bestGap = std::numeric_limits<double>::infinity();
      const std::int32_t best = nearestBehind(ancestors, position, mean, u, start, bestGap);
      if (best < 0 || best == static_cast<std::int32_t>(f) || bestGap > t.radius[best] + t.radius[c]) continue;
      auto& list = keptChildren[f];
      list.erase(std::find(list.begin(), list.end(), c));
      keptChildren[best].push_back(c);
      parentOf[c] = best;
      // Nodes of the branch left inside the parent's tube at the junction are dropped: the
      // branch starts at the junction itself.
      for (std::int32_t first = c;
           keptChildren[first].size() == 1 && (position[first] - position[best]).norm() < t.radius[best];) {
        const std::int32_t next = keptChildren[first].front();
        std::replace(keptChildren[best].begin(), keptChildren[best].end(), first, next);
        parentOf[next] = best;
        first = next;
      }
      if (highest < 0 || raw[best].distance > raw[highest].distance) highest = best;
    }
    // No longer a fork: the nodes above the new junction were put on the parent's line only
    // because f was one; the branch goes on from the junction straight to f's remaining child.
    if (highest >= 0 && keptChildren[f].size() == 1) {
      const std::int32_t next = keptChildren[f].front();
      const Vec3 from = position[highest], to = position[next];
      const double span = raw[next].distance - raw[highest].distance;
      for (std::int32_t j = static_cast<std::int32_t>(f); j != highest && span > 0; j = parentOf[j])
        position[j] = from + (raw[j].distance - raw[highest].distance) / span * (to - from);
    }
  }
  return parentOf;
}

// Douglas–Peucker on pts[first..last]: marks the kept interior indices. A node is kept when it lies
// farther than its tolerance from the chord; a straight chord longer than the smaller maxSegment
// of its ends is split at the node nearest its middle.
void douglasPeucker(const std::vector<Vec3>& pts, const std::vector<double>& tolerance,
                    const std::vector<double>& maxSegment, std::size_t first, std::size_t last,
                    std::vector<char>& keep) {
  if (last <= first + 1) return;
  const Vec3 a = pts[first], b = pts[last];
  const Vec3 ab = b - a;
  const double len = ab.norm();
  double worst = -1;
  std::size_t worstIndex = first;
  for (std::size_t i = first + 1; i < last; ++i) {
    double d;
    if (len < kTinyLength) {
      d = (pts[i] - a).norm();
    } else {
      const double t = std::clamp((pts[i] - a).dot(ab) / (len * len), 0.0, 1.0);
      d = (pts[i] - (a + t * ab)).norm();
    }
    const double excess = d / std::max(tolerance[i], kTinyLength);
    if (excess > worst) {
      worst = excess;
      worstIndex = i;
    }
  }
  const bool tooFar = len > std::min(maxSegment[first], maxSegment[last]);
  if (worst <= 1.0 && !tooFar) return;
  if (worst <= 1.0) {
    double bestGap = std::numeric_limits<double>::infinity();
    for (std::size_t i = first + 1; i < last; ++i) {
      const double gap = std::abs((pts[i] - a).dot(ab) / len - 0.5 * len);
      if (gap < bestGap) {
        bestGap = gap;
        worstIndex = i;
      }
    }
  }
  keep[worstIndex] = 1;
  douglasPeucker(pts, tolerance, maxSegment, first, worstIndex, keep);
  douglasPeucker(pts, tolerance, maxSegment, worstIndex, last, keep);
}

// Simplify chains: the nodes kept after Douglas–Peucker on each chain between key nodes (root,
// forks, ends), with tolerances and segment limits from each node's radius.
std::vector<char> simplifyChains(const RawTree& t, const std::vector<char>& kept,
                                 const std::vector<std::vector<std::int32_t>>& keptChildren,
                                 const std::vector<Vec3>& position, double voxelSize, double binWidth,
                                 const SkeletonOptions& o) {
  const std::size_t n = t.raw.size();
  std::vector<char> select(n, 0);
  select[0] = 1;
  auto isKey = [&](std::size_t i) { return i == 0 || keptChildren[i].size() != 1; };
  std::vector<std::int32_t> chain;
  std::vector<Vec3> pts;
  std::vector<double> tol, maxSeg;
  for (std::size_t k = 0; k < n; ++k) {
    if (!kept[k] || !isKey(k)) continue;
    select[k] = 1;
    for (std::int32_t c : keptChildren[k]) {
      chain.assign(1, static_cast<std::int32_t>(k));
      for (std::int32_t cur = c;; cur = keptChildren[cur].front()) {
        chain.push_back(cur);
        if (isKey(cur)) break;
      }
      pts.clear();
      tol.clear();
      maxSeg.clear();
      for (std::int32_t id : chain) {
        pts.push_back(position[id]);
        tol.push_back(std::max(o.collinearToleranceRadii * t.radius[id], o.collinearToleranceVoxels * voxelSize));
        maxSeg.push_back(std::max(o.maxSegmentRadii * t.radius[id], o.maxSegmentBins * binWidth));
      }
      std::vector<char> keep(chain.size(), 0);
      keep.front() = keep.back() = 1;
      douglasPeucker(pts, tol, maxSeg, 0, chain.size() - 1, keep);
      for (std::size_t j = 0; j < chain.size(); ++j)
        if (keep[j]) select[chain[j]] = 1;
    }
  }
  return select;
}

// The selected nodes, re-indexed (raw order is parent-first, so the result is too), each linked to
// its nearest selected ancestor, with its straightened position and smoothed radius.
std::vector<SkeletonNode> selectedNodes(const RawTree& t, const std::vector<char>& select,
                                        const std::vector<Vec3>& position, const std::vector<std::int32_t>& parentOf) {
  const auto& raw = t.raw;
  std::vector<SkeletonNode> out;
  std::vector<std::int32_t> newIndex(raw.size(), -1);
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (!select[i]) continue;
    newIndex[i] = static_cast<std::int32_t>(out.size());
    SkeletonNode node = raw[i];
    node.raw = static_cast<std::int32_t>(i);
    node.position = position[i];
    node.radius = t.radius[i];
    node.children.clear();
    std::int32_t p = parentOf[i];
    while (p >= 0 && !select[p]) p = parentOf[p];
    node.parent = p >= 0 ? newIndex[p] : -1;
    out.push_back(node);
  }
  detail::linkChildren(out);
  return out;
}

// Directions (from the previous to the next node along the main chain) and branch orders (+1 for
// a side child) of the simplified nodes.
void setDirectionsAndOrders(std::vector<SkeletonNode>& out, geom::UpAxis upAxis) {
  // The branch continues into the child carrying the most wood (the longest total length below
  // it), not the longest path: a long thin limb past a fork is a side branch of the thick stem
  // (on adtree_tree7 the longest path took the stem up a 3 cm limb at 1.1 m). Pruning keeps the
  // longest path (RawTree::mainOf): a spur is judged by how far it reaches.
  const std::vector<double> carried = detail::subtreeLength(out);
  const Vec3 up = geom::upVector(upAxis);
  for (std::size_t i = 0; i < out.size(); ++i) {
    auto& node = out[i];
    const std::int32_t m = mainChild(out, carried, i);
    const Vec3 next = m >= 0 ? out[m].position : node.position;
    const Vec3 prev = node.parent >= 0 ? out[node.parent].position : node.position;
    node.direction = detail::safeNormalized(next - prev, node.direction.norm() > 0 ? node.direction : up);
    node.branchOrder = node.parent < 0 ? 0 : out[node.parent].branchOrder;
    if (node.parent >= 0 && mainChild(out, carried, node.parent) != static_cast<std::int32_t>(i)) ++node.branchOrder;
  }
}

}  // namespace

std::vector<SkeletonNode> simplifySkeleton(const std::vector<SkeletonNode>& raw, double voxelSize, double binWidth,
                                           const SkeletonOptions& options) {
  detail::checkOptions(options);
  if (raw.empty()) return {};
  const RawTree tree = describe(raw, options);
  const std::vector<char> kept = pruneNodes(tree, binWidth, options);
  std::vector<std::vector<std::int32_t>> keptChildren(raw.size());
  for (std::size_t i = 1; i < raw.size(); ++i)
    if (kept[i]) keptChildren[raw[i].parent].push_back(static_cast<std::int32_t>(i));
  std::vector<Vec3> position = straightenForks(tree, kept, keptChildren, binWidth, options);
  const std::vector<std::int32_t> parentOf =
      reanchorSideBranches(tree, kept, keptChildren, position, binWidth, options);
  const std::vector<char> select = simplifyChains(tree, kept, keptChildren, position, voxelSize, binWidth, options);
  std::vector<SkeletonNode> out = selectedNodes(tree, select, position, parentOf);
  setDirectionsAndOrders(out, options.up);
  return out;
}

}  // namespace treesketch::skeleton
