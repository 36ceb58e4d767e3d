#include "treesketch/util/union_find.h"

#include <gtest/gtest.h>

#include <random>

namespace treesketch::util {
namespace {

// Reference: components by repeated relabelling (smallest label wins) until nothing changes.
std::vector<std::uint32_t> naiveSets(std::size_t n, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
  std::vector<std::uint32_t> label(n);
  for (std::size_t i = 0; i < n; ++i) label[i] = static_cast<std::uint32_t>(i);
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& [a, b] : edges) {
      const std::uint32_t m = std::min(label[a], label[b]);
      if (label[a] != m || label[b] != m) {
        label[a] = label[b] = m;
        changed = true;
      }
    }
  }
  return label;
}

TEST(UnionFind, SingletonsAreTheirOwnRepresentatives) {
  UnionFind uf(5);
  EXPECT_EQ(uf.size(), 5u);
  for (std::uint32_t i = 0; i < 5; ++i) EXPECT_EQ(uf.find(i), i);
}

TEST(UnionFind, RepresentativeIsTheSmallestElement) {
  UnionFind uf(6);
  uf.unite(5, 3);
  EXPECT_EQ(uf.find(5), 3u);
  uf.unite(4, 5);
  EXPECT_EQ(uf.find(4), 3u);
  uf.unite(3, 1);
  for (std::uint32_t i : {1u, 3u, 4u, 5u}) EXPECT_EQ(uf.find(i), 1u);
  EXPECT_EQ(uf.find(0), 0u);
  EXPECT_EQ(uf.find(2), 2u);
  uf.unite(4, 4);  // a self-union changes nothing
  EXPECT_EQ(uf.find(4), 1u);
}

TEST(UnionFind, MatchesANaiveLabellingOnRandomUnions) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t n = 1 + rng() % 200;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    const std::size_t m = rng() % (2 * n);
    for (std::size_t e = 0; e < m; ++e) edges.emplace_back(rng() % n, rng() % n);
    UnionFind uf(n);
    for (const auto& [a, b] : edges) uf.unite(a, b);
    const auto expected = naiveSets(n, edges);
    for (std::uint32_t i = 0; i < n; ++i) EXPECT_EQ(uf.find(i), expected[i]) << "trial " << trial << " vertex " << i;
  }
}

// Compressed rows of an undirected graph (both directions stored), as VoxelGraph holds them.
void toRows(std::size_t n, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges,
            std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& targets) {
  std::vector<std::vector<std::uint32_t>> adj(n);
  for (const auto& [a, b] : edges) {
    adj[a].push_back(b);
    adj[b].push_back(a);
  }
  offsets.assign(1, 0);
  targets.clear();
  for (const auto& row : adj) {
    targets.insert(targets.end(), row.begin(), row.end());
    offsets.push_back(static_cast<std::uint32_t>(targets.size()));
  }
}

TEST(LabelComponents, NumbersComponentsByTheirLowestVertex) {
  // 0-3, 1-4-2, 5 alone: components {0,3}, {1,2,4}, {5} get labels 0, 1, 2.
  std::vector<std::uint32_t> offsets, targets;
  toRows(6, {{3, 0}, {4, 1}, {2, 4}}, offsets, targets);
  std::int32_t count = -1;
  const auto label = labelComponents(offsets, targets, &count);
  EXPECT_EQ(count, 3);
  EXPECT_EQ(label, (std::vector<std::int32_t>{0, 1, 1, 0, 1, 2}));
}

TEST(LabelComponents, EmptyGraph) {
  std::int32_t count = -1;
  EXPECT_TRUE(labelComponents({}, {}, &count).empty());
  EXPECT_EQ(count, 0);
  EXPECT_TRUE(labelComponents({0}, {}, &count).empty());
  EXPECT_EQ(count, 0);
}

TEST(LabelComponents, AgreesWithUnionFindOnRandomGraphs) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t n = 1 + rng() % 300;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    const std::size_t m = rng() % (n + n / 2 + 1);
    for (std::size_t e = 0; e < m; ++e) edges.emplace_back(rng() % n, rng() % n);
    std::vector<std::uint32_t> offsets, targets;
    toRows(n, edges, offsets, targets);
    std::int32_t count = 0;
    const auto label = labelComponents(offsets, targets, &count);
    UnionFind uf(n);
    for (const auto& [a, b] : edges) uf.unite(a, b);
    // Labels count representatives (lowest vertices) in increasing order.
    std::vector<std::int32_t> expected(n);
    std::int32_t next = 0;
    std::vector<std::int32_t> ofRep(n, -1);
    for (std::uint32_t v = 0; v < n; ++v) {
      const std::uint32_t r = uf.find(v);
      if (ofRep[r] < 0) ofRep[r] = next++;
      expected[v] = ofRep[r];
    }
    EXPECT_EQ(count, next) << "trial " << trial;
    EXPECT_EQ(label, expected) << "trial " << trial;
  }
}

}  // namespace
}  // namespace treesketch::util
