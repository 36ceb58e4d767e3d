// Shortest-path features of the core points (graph_features.h): one multi-source Dijkstra from the
// base, then the points below every core of the shortest-path tree.
#include "graph_features.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace treesketch::classify::detail {

std::vector<std::string> graphFeatureNames() { return {"passage", "path_length", "path_detour"}; }

void graphFeatures(const std::vector<geom::Vec3>& cores, double baseFraction, int column, FeatureTable& t) {
  const std::size_t n = cores.size();
  const int g = t.neighbourCount;
  std::vector<double> dist(n, INFINITY), length(n, 0.0);
  std::vector<std::int64_t> parent(n, -1);
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  const float seedHeight = static_cast<float>(baseFraction * t.treeHeight);
  geom::Vec3 base = geom::Vec3::Zero();
  std::size_t seeds = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (t.heights[i] <= seedHeight) {
      dist[i] = 0;
      queue.emplace(0.0, static_cast<std::uint32_t>(i));
      base += cores[i];
      ++seeds;
    }
  base /= static_cast<double>(std::max<std::size_t>(seeds, 1));
  std::vector<std::uint32_t> order;  // settled cores, nearest first
  order.reserve(n);
  const double unit2 = t.spacing * t.spacing;
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > dist[i]) continue;
    order.push_back(i);
    for (int k = 0; k < g; ++k) {
      const std::uint32_t j = t.neighbours[static_cast<std::size_t>(i) * g + k];
      const double e = t.neighbourDistances[static_cast<std::size_t>(i) * g + k];
      const double nd = d + e * e / unit2;
      if (j != i && nd < dist[j]) {
        dist[j] = nd;
        parent[j] = i;
        length[j] = length[i] + e;
        queue.emplace(nd, j);
      }
    }
  }
  std::vector<double> passage(n, 0.0);
  double total = 0;
  for (std::size_t k = order.size(); k-- > 0;) {
    const std::uint32_t i = order[k];
    passage[i] += t.coreSize[i];
    total += t.coreSize[i];
    if (parent[i] >= 0) passage[parent[i]] += passage[i];
  }
  const double logTotal = std::log1p(std::max(total, 1.0));
  for (std::size_t i = 0; i < n; ++i) {
    float* row = t.values.data() + i * t.count + column;
    const bool reached = std::isfinite(dist[i]);
    row[0] = static_cast<float>(std::log1p(passage[i]) / logTotal);
    row[1] = reached ? static_cast<float>(length[i] / t.treeHeight) : -1.0f;
    const double straight = (cores[i] - base).norm();
    row[2] = reached ? static_cast<float>(length[i] / std::max(straight, t.spacing)) : -1.0f;
  }
}

}  // namespace treesketch::classify::detail
