// Geodesic distances from the root and the level-set nodes: Verroust & Lazarus 1999 ("Extracting
// skeletal curves from 3D scattered data"), with the clustering by distance bins and adjacency of
// Xu, Gossett & Chen 2007. Dijkstra from the lowest region of the tree gives each voxel its
// distance and predecessor; voxels are binned by distance, each bin is cut into connected pieces,
// and each piece becomes a node whose parent is the piece holding its nearest-to-root voxel's
// predecessor.
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "skeleton/checks.h"
#include "skeleton/fork_split.h"
#include "skeleton/node_tree.h"
#include "skeleton/stem_tracking.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/util/error.h"
#include "treesketch/util/union_find.h"

namespace treesketch::skeleton {
namespace {

using geom::Vec3;
using util::UnionFind;

// The foot: a tree stands where the wood of its lowest part is. Its lowest tenth of height (the
// band) holds the stem's foot, or a bush's stems where they meet, and maybe a branch bent down
// below it (a bush's stem arching to the ground, a conifer's lowest branch): the foot is the band's
// points' horizontal median centre, and its disc reaches four times their median distance from it
// (plus a voxel). A lowest voxel outside that disc is such a branch's tip, no root. Measured: the
// lowest voxel lies within 2.2 median distances of the centre on every scan of 29 synthetic trees
// but one, and within 1.8 on 13 real clouds; that one tree's stem bent 20 cm below its foot puts
// its tip 9.5-12 of them away. A part grafted on by the completion is a branch, not a tree: its
// root is its lowest voxel, as before.
constexpr double kFootBandShare = 0.1;
constexpr double kFootDiscMedians = 4.0;
// Each band voxel counts once per point it holds, up to this many: a dense voxel counts more than
// a sparse one, a scanner's near side does not outweigh the rest.
constexpr int kFootVoxelWeightCap = 8;

struct FootDisc {
  geom::Vec3 centre = geom::Vec3::Zero();  ///< in the horizontal plane through the origin
  double radius = std::numeric_limits<double>::infinity();
  double lowest = std::numeric_limits<double>::infinity();  ///< the lowest voxel's height in the disc
};

geom::Vec3 horizontal(const geom::Vec3& p, const geom::Vec3& up) { return p - p.dot(up) * up; }

// The foot's disc over the band's voxels `band` (see kFootBandShare).
FootDisc footDisc(const VoxelGraph& g, const std::vector<std::uint32_t>& band, geom::UpAxis upAxis) {
  FootDisc foot;
  if (band.empty()) return foot;
  const geom::Vec3 up = geom::upVector(upAxis);
  const geom::Vec3 e1 = geom::anyPerpendicular(up);
  const geom::Vec3 e2 = up.cross(e1);
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  std::vector<double> a, b, d;
  for (std::uint32_t v : band)
    for (int k = 0; k < std::min(g.pointCount[v], kFootVoxelWeightCap); ++k) {
      a.push_back(g.positions[v].dot(e1));
      b.push_back(g.positions[v].dot(e2));
    }
  foot.centre = median(a) * e1 + median(b) * e2;
  for (std::uint32_t v : band)
    for (int k = 0; k < std::min(g.pointCount[v], kFootVoxelWeightCap); ++k)
      d.push_back((horizontal(g.positions[v], up) - foot.centre).norm());
  foot.radius = kFootDiscMedians * median(d) + g.voxelSize;
  for (std::uint32_t v : band)
    if ((horizontal(g.positions[v], up) - foot.centre).norm() <= foot.radius)
      foot.lowest = std::min(foot.lowest, geom::height(g.positions[v], upAxis));
  return foot;
}

// Dijkstra sources: the tree's voxels (the connected set, bridges included, holding the most
// points) within rootHeightVoxels of its lowest one, that one within the foot's disc.
std::vector<std::uint32_t> rootRegion(const VoxelGraph& g, const SkeletonOptions& options) {
  const std::size_t n = g.size();
  std::int32_t components = 0;
  const std::vector<std::int32_t> label = util::labelComponents(g.offsets, g.targets, &components);
  std::vector<std::int64_t> points(components, 0);
  for (std::size_t v = 0; v < n; ++v) points[label[v]] += g.pointCount[v];
  const auto tree = static_cast<std::int32_t>(std::max_element(points.begin(), points.end()) - points.begin());
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (std::size_t i = 0; i < n; ++i)
    if (label[i] == tree) {
      lowest = std::min(lowest, geom::height(g.positions[i], options.up));
      highest = std::max(highest, geom::height(g.positions[i], options.up));
    }
  // The tree's lowest voxel in the disc (nearly always): the voxels within rootHeightVoxels of it,
  // wherever they are. Else the foot's, within the disc only: the bent branch passes that height too.
  FootDisc foot;
  if (options.trackStem) {
    std::vector<std::uint32_t> band;
    for (std::size_t i = 0; i < n; ++i)
      if (label[i] == tree && geom::height(g.positions[i], options.up) <= lowest + kFootBandShare * (highest - lowest))
        band.push_back(static_cast<std::uint32_t>(i));
    foot = footDisc(g, band, options.up);
  }
  const bool bentBelow = std::isfinite(foot.lowest) && foot.lowest > lowest + 0.5 * g.voxelSize;
  const double rootTop = (bentBelow ? foot.lowest : lowest) + options.rootHeightVoxels * g.voxelSize;
  const geom::Vec3 up = geom::upVector(options.up);
  std::vector<std::uint32_t> root;
  for (std::size_t i = 0; i < n; ++i)
    if (label[i] == tree && geom::height(g.positions[i], options.up) <= rootTop &&
        (!bentBelow || (horizontal(g.positions[i], up) - foot.centre).norm() <= foot.radius))
      root.push_back(static_cast<std::uint32_t>(i));
  return root;
}

// The stem tracked from the root region (stem_tracking.h), kept in `lv`. When it stands beside the
// root region, its foot becomes the root: from a branch tip on the ground the geodesic distance
// reached the stem along that branch and ran down it as well as up.
void trackStemFromRoot(const VoxelGraph& g, const SkeletonOptions& options, GeodesicLevels& lv) {
  bool beside = false;
  const std::vector<detail::StemSample> stem = detail::trackStem(g, lv.rootVertices, options.up, &beside);
  for (const detail::StemSample& s : stem) {
    lv.stemCentres.push_back(s.centre);
    lv.stemRadii.push_back(s.radius);
  }
  lv.stemBesideRoot = beside;
  if (!beside) return;
  std::int32_t components = 0;
  const std::vector<std::int32_t> label = util::labelComponents(g.offsets, g.targets, &components);
  std::vector<char> reachable(g.size(), 0);
  for (std::size_t v = 0; v < g.size(); ++v) reachable[v] = label[v] == label[lv.rootVertices.front()] ? 1 : 0;
  std::vector<std::uint32_t> foot =
      detail::stemFoot(g, stem, reachable, options.up, options.rootHeightVoxels * g.voxelSize);
  if (!foot.empty()) lv.rootVertices = std::move(foot);
}

// Shortest paths from `lv.rootVertices` over the graph's edge lengths.
void dijkstra(const VoxelGraph& g, GeodesicLevels& lv) {
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (std::uint32_t r : lv.rootVertices) {
    lv.distance[r] = 0;
    queue.emplace(0.0, r);
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > lv.distance[v]) continue;
    for (std::uint32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
      const std::uint32_t w = g.targets[k];
      const double nd = d + g.weights[k];
      if (nd < lv.distance[w]) {
        lv.distance[w] = nd;
        lv.predecessor[w] = v;
        queue.emplace(nd, w);
      }
    }
  }
}

// Pieces of one level set that touch the same piece below and the same piece above are arcs of
// one ring broken by sparse sampling or a junction: join them. Level by level from the root, so
// the pieces below are final when a level is processed.
struct Step {
  std::int32_t level;  ///< of `low`; `high` is one level up
  std::uint32_t low, high;
};
using PiecePairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Joins the pieces of level k that share a piece below (`below`: (piece at k, piece at k-1),
// sorted) and a piece above (`above`: (piece at k+1, piece at k)).
void mergeLevel(UnionFind& uf, const PiecePairs& below, PiecePairs above, const std::vector<char>* apart) {
  std::sort(above.begin(), above.end());
  above.erase(std::unique(above.begin(), above.end()), above.end());
  auto lowerOf = [&](std::uint32_t piece) {
    auto it = std::lower_bound(below.begin(), below.end(), std::make_pair(piece, 0u));
    std::vector<std::uint32_t> out;
    for (; it != below.end() && it->first == piece; ++it) out.push_back(it->second);
    return out;
  };
  for (std::size_t a = 0; a < above.size();) {
    std::size_t b = a;
    while (b < above.size() && above[b].first == above[a].first) ++b;
    for (std::size_t i = a; i < b; ++i)
      for (std::size_t j = i + 1; j < b; ++j) {
        const std::uint32_t pi = uf.find(above[i].second), pj = uf.find(above[j].second);
        if (pi == pj || (apart && (*apart)[pi] != (*apart)[pj])) continue;
        const auto li = lowerOf(above[i].second), lj = lowerOf(above[j].second);
        bool share = false;
        for (std::uint32_t x : li)
          if (std::find(lj.begin(), lj.end(), x) != lj.end()) share = true;
        if (share) uf.unite(pi, pj);
      }
    a = b;
  }
}

// `apart` (null: none): per voxel, the side of a cut no join crosses (levelPieces' stem tube).
void mergeSplitRings(const VoxelGraph& g, const GeodesicLevels& lv, UnionFind& uf, const std::vector<char>* apart) {
  std::vector<Step> steps;
  for (std::size_t v = 0; v < g.size(); ++v) {
    if (lv.level[v] < 0) continue;
    for (std::uint32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k)
      if (lv.level[g.targets[k]] == lv.level[v] + 1)
        steps.push_back(Step{lv.level[v], static_cast<std::uint32_t>(v), g.targets[k]});
  }
  std::stable_sort(steps.begin(), steps.end(), [](const Step& a, const Step& b) { return a.level < b.level; });
  // steps[begin, end) go from level k-1 to k, steps[end, next) from k to k+1.
  std::size_t begin = 0;
  PiecePairs below, above;
  while (begin < steps.size()) {
    const std::int32_t k = steps[begin].level + 1;  // the level being merged
    std::size_t end = begin;
    while (end < steps.size() && steps[end].level == k - 1) ++end;
    std::size_t next = end;
    while (next < steps.size() && steps[next].level == k) ++next;
    below.clear();
    above.clear();
    for (std::size_t i = begin; i < end; ++i) below.emplace_back(uf.find(steps[i].high), uf.find(steps[i].low));
    for (std::size_t i = end; i < next; ++i) above.emplace_back(uf.find(steps[i].high), uf.find(steps[i].low));
    std::sort(below.begin(), below.end());
    below.erase(std::unique(below.begin(), below.end()), below.end());
    mergeLevel(uf, below, above, apart);
    begin = end;
  }
}

// One piece per level set on the tracked stem (stem_tracking.h): its voxels in the stem's tube
// (`tube` empty: no stem).
void joinStemRings(const GeodesicLevels& lv, const std::vector<char>& tube, UnionFind& uf) {
  std::vector<std::int64_t> anchor;
  for (std::size_t v = 0; v < tube.size(); ++v) {
    const std::int32_t l = lv.level[v];
    if (l < 0 || !tube[v]) continue;
    if (static_cast<std::size_t>(l) >= anchor.size()) anchor.resize(static_cast<std::size_t>(l) + 1, -1);
    if (anchor[l] < 0)
      anchor[l] = static_cast<std::int64_t>(v);
    else
      uf.unite(static_cast<std::uint32_t>(anchor[l]), static_cast<std::uint32_t>(v));
  }
}

// The stem's pieces (most of their voxels in its tube) are put on its axis, with its radius: a
// level set of a sparsely scanned stem holds a few voxels, and their centroid lies off the axis
// towards whichever side they are on.
void snapToStem(const GeodesicLevels& lv, const std::vector<char>& tube, const std::vector<detail::StemSample>& stem,
                bool besideRoot, std::vector<SkeletonNode>& nodes) {
  std::vector<std::uint32_t> inside(nodes.size(), 0), all(nodes.size(), 0);
  for (std::size_t v = 0; v < tube.size(); ++v) {
    const std::int32_t id = lv.vertexNode[v];
    if (id < 0) continue;
    ++all[id];
    inside[id] += tube[v] ? 1 : 0;
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    // The root of a stem found beside the root region is the stem's foot (trackStemFromRoot),
    // whatever else its level holds (the dead branches on the ground round a conifer's foot).
    if (2 * inside[i] <= all[i] && !(i == 0 && besideRoot && inside[i] > 0)) continue;
    const detail::StemSample at = detail::stemAt(stem, nodes[i].position);
    nodes[i].position = at.centre;
    nodes[i].radius = at.radius;
    nodes[i].stem = true;
  }
}

// Connected pieces of each level set, as union-find sets; all of level 0 is one piece (a single
// root), the stem's rings are whole and split rings are joined. With `cutAtTube` (the stem found
// beside the root region: a conifer's, stem_tracking.h) a level set's voxels in the stem's tube
// and those outside it are apart: at a whorl a level set holds the stem with the bases of the
// branches leaving it, and their centroid lay off the stem; cut, the stem's part is its
// cross-section and the rest are the branches. For every tracked stem the cut measured worse
// (docs/notes/leaf_on_skeleton.md).
UnionFind levelPieces(const VoxelGraph& g, const GeodesicLevels& lv, const std::vector<char>& stemTube,
                      bool cutAtTube) {
  UnionFind uf(g.size());
  const std::uint32_t anchor = lv.rootVertices.front();
  for (std::size_t v = 0; v < g.size(); ++v) {
    if (lv.level[v] < 0) continue;
    if (lv.level[v] == 0) uf.unite(anchor, static_cast<std::uint32_t>(v));
    for (std::uint32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
      const std::uint32_t w = g.targets[k];
      if (lv.level[w] != lv.level[v] || (cutAtTube && stemTube[v] != stemTube[w])) continue;
      uf.unite(static_cast<std::uint32_t>(v), w);
    }
  }
  joinStemRings(lv, stemTube, uf);
  mergeSplitRings(g, lv, uf, cutAtTube && !stemTube.empty() ? &stemTube : nullptr);
  return uf;
}

// A piece that touches several pieces of the level below grows out of the largest of them (the
// most voxels: the stem, not a limb leaning on it). The shortest path from the root can reach such
// a piece through the limb: on voxr_Tree_t0 the stem's branch then left the stem at its lowest fork
// for a 2 cm limb and met it again 0.7 m higher (docs/notes/radii_and_volume.md). A parent of the
// piece's own level (the stem's tube, levelPieces) stays.
void growFromLargestPieceBelow(const VoxelGraph& g, const GeodesicLevels& lv, const std::vector<std::uint32_t>& count,
                               const std::vector<char>& tube, std::vector<SkeletonNode>& nodes) {
  // A piece on the tracked stem (most of its voxels in the tube) grows out of the stem's piece
  // below it, however large a neighbour: at a conifer's foot the level below holds the dead
  // branches round the stem in one piece larger than the stem's ring.
  std::vector<std::uint32_t> inTube(nodes.size(), 0);
  for (std::size_t v = 0; v < tube.size(); ++v)
    if (tube[v] && lv.vertexNode[v] >= 0) ++inTube[lv.vertexNode[v]];
  const auto onStem = [&](std::int32_t id) { return !tube.empty() && 2 * inTube[id] > count[id]; };
  const auto better = [&](std::int32_t id, std::int32_t c, std::int32_t b) {
    if (onStem(id) && onStem(c) != onStem(b)) return onStem(c);
    return count[c] > count[b];
  };
  std::vector<std::int32_t> best(nodes.size(), -1);
  for (std::size_t v = 0; v < g.size(); ++v) {
    if (lv.level[v] <= 0) continue;
    const std::int32_t id = lv.vertexNode[v];
    for (std::uint32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
      const std::uint32_t w = g.targets[k];
      if (lv.level[w] != lv.level[v] - 1) continue;
      const std::int32_t c = lv.vertexNode[w];
      if (c < 0 || c == id) continue;
      if (best[id] < 0 || better(id, c, best[id])) best[id] = c;
    }
  }
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    const std::int32_t p = nodes[i].parent;
    if (p < 0 || best[i] < 0 || best[i] == p || nodes[p].level != nodes[i].level - 1) continue;
    nodes[i].parent = best[i];
  }
}

// One node per piece, ordered by level, then by the piece's lowest vertex (deterministic; parents
// first): support, linearity, level, the centroid of `at` over the piece, the geodesic distance of
// its vertex nearest the root and the parent through that vertex's predecessor, or, when the piece
// touches several pieces of the level below, the largest of those. Sets
// lv.vertexNode; `count` receives each node's number of voxels. With `cutAtTube` (levelPieces) a
// piece's parent may be a piece of its own level: within a level, pieces nearer the root first.
std::vector<SkeletonNode> pieceNodes(const VoxelGraph& g, GeodesicLevels& lv, UnionFind& uf,
                                     const std::vector<Vec3>& at, const std::vector<char>& tube, bool cutAtTube,
                                     std::vector<std::uint32_t>& count) {
  const std::size_t n = g.size();
  std::vector<std::uint32_t> reps;
  for (std::size_t v = 0; v < n; ++v)
    if (lv.level[v] >= 0 && uf.find(static_cast<std::uint32_t>(v)) == v) reps.push_back(static_cast<std::uint32_t>(v));
  std::vector<double> nearest;
  if (cutAtTube) {
    nearest.assign(n, std::numeric_limits<double>::infinity());
    for (std::size_t v = 0; v < n; ++v) {
      if (lv.level[v] < 0) continue;
      double& d = nearest[uf.find(static_cast<std::uint32_t>(v))];
      d = std::min(d, lv.distance[v]);
    }
  }
  std::stable_sort(reps.begin(), reps.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (lv.level[a] != lv.level[b]) return lv.level[a] < lv.level[b];
    return cutAtTube && nearest[a] < nearest[b];
  });
  std::vector<std::int32_t> repNode(n, -1);
  for (std::size_t i = 0; i < reps.size(); ++i) repNode[reps[i]] = static_cast<std::int32_t>(i);
  std::vector<SkeletonNode> nodes(reps.size());
  count.assign(nodes.size(), 0);
  std::vector<double> linSum(nodes.size(), 0.0);
  std::vector<std::int64_t> firstVertex(nodes.size(), -1);  // the piece's vertex nearest the root
  for (std::size_t v = 0; v < n; ++v) {
    if (lv.level[v] < 0) continue;
    const std::int32_t id = repNode[uf.find(static_cast<std::uint32_t>(v))];
    lv.vertexNode[v] = id;
    auto& node = nodes[id];
    node.position += at[v];
    node.support += g.pointCount[v];
    node.level = lv.level[v];
    linSum[id] += g.linearity[v] * g.pointCount[v];
    ++count[id];
    if (firstVertex[id] < 0 || lv.distance[v] < lv.distance[firstVertex[id]])
      firstVertex[id] = static_cast<std::int64_t>(v);
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    auto& node = nodes[i];
    node.position /= count[i];
    node.linearity = static_cast<float>(linSum[i] / std::max(node.support, 1));
    node.distance = lv.distance[firstVertex[i]];
    const std::int64_t pred = lv.predecessor[firstVertex[i]];
    node.parent = (i == 0 || pred < 0) ? -1 : lv.vertexNode[pred];
  }
  growFromLargestPieceBelow(g, lv, count, tube, nodes);
  detail::linkChildren(nodes);
  return nodes;
}

// Directions: from the grandparent (or parent) to each node; the root towards its children.
void setDirections(std::vector<SkeletonNode>& nodes, geom::UpAxis upAxis) {
  const Vec3 up = geom::upVector(upAxis);
  for (auto& node : nodes) {
    if (node.parent >= 0) {
      const auto& p = nodes[node.parent];
      const Vec3 from = p.parent >= 0 ? nodes[p.parent].position : p.position;
      node.direction = detail::safeNormalized(node.position - from, up);
    } else {
      Vec3 sum = Vec3::Zero();
      for (std::int32_t c : node.children) sum += nodes[c].position - node.position;
      node.direction = detail::safeNormalized(sum, up);
    }
  }
}

// Per node: the sum and the sum of squares of its voxels' distances (at positions `pos`) to the
// axis through its centroid along its direction.
void axisDistances(const GeodesicLevels& lv, const std::vector<SkeletonNode>& nodes, const std::vector<Vec3>& pos,
                   std::vector<double>& sum, std::vector<double>& sq) {
  sum.assign(nodes.size(), 0.0);
  sq.assign(nodes.size(), 0.0);
  for (std::size_t v = 0; v < lv.vertexNode.size(); ++v) {
    const std::int32_t id = lv.vertexNode[v];
    if (id < 0) continue;
    const Vec3 d = pos[v] - nodes[id].position;
    const double r = (d - d.dot(nodes[id].direction) * nodes[id].direction).norm();
    sum[id] += r;
    sq[id] += r * r;
  }
}

// Radius: the mean distance of the piece's voxels to its axis over the centroid positions (for
// leaf voxels at their entry positions: the spread of the leaf bases about the twig, not of the
// blades). Shape, which tells a ring or a branch from a blob (foliage): over the voxels' own
// positions, the scanned surface (over the moved ones, needle-covered limbs read as foliage).
void setRadiiAndShape(const VoxelGraph& g, const GeodesicLevels& lv, const std::vector<Vec3>* centroids,
                      const std::vector<std::uint32_t>& count, const SkeletonOptions& options,
                      std::vector<SkeletonNode>& nodes) {
  std::vector<double> ownSum, ownSq, atSum, atSq;
  axisDistances(lv, nodes, g.positions, ownSum, ownSq);
  if (centroids) axisDistances(lv, nodes, *centroids, atSum, atSq);
  const std::vector<double>& radiusSum = centroids ? atSum : ownSum;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    // A stem piece keeps the tracked stem's radius (snapToStem): its few voxels' spread is not it.
    if (!nodes[i].stem) nodes[i].radius = std::max(radiusSum[i] / count[i], options.minRadiusVoxels * g.voxelSize);
    const double mean = ownSum[i] / count[i];
    const double var = std::max(ownSq[i] / count[i] - mean * mean, 0.0);
    nodes[i].ringVariation = static_cast<float>(mean > 0 ? std::sqrt(var) / mean : 0.0);
  }
}

}  // namespace

GeodesicLevels computeGeodesicLevels(const VoxelGraph& g, const SkeletonOptions& options) {
  detail::checkOptions(options);
  GeodesicLevels lv;
  const std::size_t n = g.size();
  lv.binWidth = options.binWidthVoxels * g.voxelSize;
  lv.distance.assign(n, std::numeric_limits<double>::infinity());
  lv.predecessor.assign(n, -1);
  lv.level.assign(n, -1);
  lv.vertexNode.assign(n, -1);
  if (n == 0) return lv;
  lv.rootVertices = rootRegion(g, options);
  if (options.trackStem) trackStemFromRoot(g, options, lv);
  dijkstra(g, lv);
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(lv.distance[i]))
      lv.level[i] = static_cast<std::int32_t>(std::floor(lv.distance[i] / lv.binWidth));
  return lv;
}

std::vector<SkeletonNode> levelSetNodes(const VoxelGraph& g, GeodesicLevels& lv, const SkeletonOptions& options,
                                        const std::vector<Vec3>* centroids) {
  detail::checkOptions(options);
  if (centroids && centroids->size() != g.size())
    throw OptionsError("skeleton: levelSetNodes needs one centroid position per voxel");
  if (g.size() == 0 || lv.rootVertices.empty()) return {};
  std::vector<detail::StemSample> stem;
  if (options.trackStem)
    for (std::size_t k = 0; k < lv.stemCentres.size() && k < lv.stemRadii.size(); ++k)
      stem.push_back({lv.stemCentres[k], lv.stemRadii[k]});
  const bool besideRoot = !stem.empty() && lv.stemBesideRoot;
  const std::vector<char> tube = stem.empty() ? std::vector<char>{} : detail::stemTube(g, stem);
  UnionFind uf = levelPieces(g, lv, tube, besideRoot);
  std::vector<std::uint32_t> count;
  const std::vector<Vec3>& at = centroids ? *centroids : g.positions;
  std::vector<SkeletonNode> nodes = pieceNodes(g, lv, uf, at, tube, besideRoot, count);
  if (options.splitMergedForks) detail::splitMergedForks(g, lv, at, tube, options, nodes, count);
  if (!stem.empty()) snapToStem(lv, tube, stem, besideRoot, nodes);
  setDirections(nodes, options.up);
  setRadiiAndShape(g, lv, centroids, count, options, nodes);
  return nodes;
}

}  // namespace treesketch::skeleton
