// The graph step (classify/wood_graph.h): pieces of the neighbour graph over the points that may
// be wood, grown from the base.
#include "treesketch/classify/wood_graph.h"

#include <algorithm>
#include <unordered_map>

#include "treesketch/util/error.h"
#include "treesketch/util/union_find.h"

namespace treesketch::classify {

std::vector<float> smoothOverGraph(const FeatureTable& f, const std::vector<float>& p, double weight, int passes,
                                   double maxEdgeSpacings) {
  const std::size_t n = f.heights.size();
  if (p.size() != n) throw OptionsError("classify: one wood probability per point is needed");
  if (!(weight >= 0.0 && weight <= 1.0)) throw OptionsError("classify: the smoothing weight must be between 0 and 1");
  const float maxEdge = static_cast<float>(maxEdgeSpacings * f.spacing);
  const int g = f.neighbourCount;
  std::vector<float> cur = p, next(n);
  for (int pass = 0; pass < passes; ++pass) {
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0;
      int count = 0;
      for (int k = 0; k < g; ++k) {
        const std::uint32_t j = f.neighbours[i * g + k];
        if (j == i || f.neighbourDistances[i * g + k] > maxEdge) continue;
        sum += cur[j];
        ++count;
      }
      next[i] = count == 0 ? cur[i] : static_cast<float>((1.0 - weight) * cur[i] + weight * sum / count);
    }
    cur.swap(next);
  }
  return cur;
}

WoodGraphResult connectWood(const FeatureTable& f, const std::vector<float>& p, double threshold,
                            const WoodGraphOptions& o) {
  const std::size_t n = f.heights.size();
  if (p.size() != n) throw OptionsError("classify: one wood probability per point is needed");
  WoodGraphResult r;
  r.wood.assign(n, 0);
  const float bridge = static_cast<float>(std::min(o.bridgeProbability, threshold));
  const float maxEdge = static_cast<float>(o.maxEdgeSpacings * f.spacing);
  const int g = f.neighbourCount;
  // Pieces: points that may carry wood, joined by short edges.
  util::UnionFind pieces(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (p[i] < bridge) continue;
    for (int k = 0; k < g; ++k) {
      const std::uint32_t j = f.neighbours[i * g + k];
      if (j != i && p[j] >= bridge && f.neighbourDistances[i * g + k] <= maxEdge)
        pieces.unite(static_cast<std::uint32_t>(i), j);
    }
  }
  // Per piece: its wood points and whether it holds a seed at the base.
  std::unordered_map<std::uint32_t, std::size_t> woodCount;
  std::unordered_map<std::uint32_t, bool> rooted;
  const float baseHeight = static_cast<float>(o.baseFraction * f.treeHeight);
  for (std::size_t i = 0; i < n; ++i) {
    if (p[i] < threshold) continue;
    const std::uint32_t root = pieces.find(static_cast<std::uint32_t>(i));
    ++woodCount[root];
    if (f.heights[i] <= baseHeight) {
      rooted[root] = true;
      ++r.seeds;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (p[i] < threshold) {
      if (p[i] >= o.promoteProbability && rooted.count(pieces.find(static_cast<std::uint32_t>(i)))) {
        r.wood[i] = 1;
        ++r.promoted;
      }
      continue;
    }
    const std::uint32_t root = pieces.find(static_cast<std::uint32_t>(i));
    if (rooted.count(root)) {
      r.wood[i] = 1;
      ++r.reached;
    } else if (woodCount[root] >= static_cast<std::size_t>(o.minPiecePoints)) {
      r.wood[i] = 1;
      ++r.kept;
    } else {
      ++r.demoted;
    }
  }
  return r;
}

}  // namespace treesketch::classify
