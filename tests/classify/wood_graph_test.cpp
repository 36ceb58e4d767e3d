// The graph step: wood connected to the base stays, a small isolated patch of "wood" in the crown
// is demoted, a large one stays, growth crosses points the classifier is unsure of, and the smoothing
// pulls each point's probability towards its neighbours'.
#include "treesketch/classify/wood_graph.h"

#include <gtest/gtest.h>

#include "treesketch/util/error.h"

namespace treesketch::classify {
namespace {

// A chain of `n` points 1 unit apart starting at height h0, each linked to its chain neighbours.
void addChain(FeatureTable& t, int n, float h0) {
  const auto first = static_cast<std::uint32_t>(t.heights.size());
  for (int i = 0; i < n; ++i) {
    const std::uint32_t me = first + i;
    t.heights.push_back(h0 + i);
    const std::uint32_t prev = i > 0 ? me - 1 : me, next = i + 1 < n ? me + 1 : me;
    t.neighbours.insert(t.neighbours.end(), {prev, next});
    t.neighbourDistances.insert(t.neighbourDistances.end(), {prev == me ? 0.0f : 1.0f, next == me ? 0.0f : 1.0f});
  }
}

TEST(WoodGraph, GrowsFromTheBaseAndDemotesSmallIsolatedWood) {
  FeatureTable t;
  t.neighbourCount = 2;
  t.spacing = 1.0;
  t.treeHeight = 100;
  addChain(t, 50, 0);   // 0..49: the stem, from the ground
  addChain(t, 10, 80);  // 50..59: a small patch in the crown
  addChain(t, 40, 60);  // 60..99: a long limb whose link to the stem is hidden
  std::vector<float> p(100, 0.9f);
  p[20] = 0.3f;  // unsure, but above the bridge probability: growth passes, the point stays leaf
  WoodGraphOptions o;
  o.minPiecePoints = 30;
  const WoodGraphResult r = connectWood(t, p, 0.5, o);
  for (int i = 0; i < 50; ++i) EXPECT_EQ(r.wood[i], i == 20 ? 0 : 1) << i;
  for (int i = 50; i < 60; ++i) EXPECT_EQ(r.wood[i], 0) << i;
  for (int i = 60; i < 100; ++i) EXPECT_EQ(r.wood[i], 1) << i;
  EXPECT_EQ(r.reached, 49u);
  EXPECT_EQ(r.kept, 40u);
  EXPECT_EQ(r.demoted, 10u);
  EXPECT_GE(r.seeds, 1u);
  // Promotion: the unsure point on the stem, reached from the base, becomes wood.
  WoodGraphOptions promote = o;
  promote.promoteProbability = 0.25;
  const WoodGraphResult pr = connectWood(t, p, 0.5, promote);
  EXPECT_EQ(pr.wood[20], 1);
  EXPECT_EQ(pr.promoted, 1u);
  // A confident leaf cuts the stem: points 21..49 are a piece of their own, 29 points: demoted.
  p[20] = 0.05f;
  const WoodGraphResult cut = connectWood(t, p, 0.5, o);
  EXPECT_EQ(cut.wood[30], 0);
  EXPECT_EQ(cut.wood[10], 1);
  // Edges longer than the gap limit join nothing.
  o.maxEdgeSpacings = 0.5;
  p[20] = 0.9f;
  EXPECT_EQ(connectWood(t, p, 0.5, o).reached, 6u);  // heights 0..5: the base seeds alone
}

TEST(WoodGraph, SmoothingPullsEachPointTowardsItsNeighbours) {
  FeatureTable t;
  t.neighbourCount = 2;
  t.spacing = 1.0;
  t.treeHeight = 100;
  addChain(t, 20, 0);  // 0..19: a limb
  std::vector<float> p(20, 0.9f);
  p[5] = 0.6f;   // a core of the limb the classifier is unsure of
  p[19] = 0.1f;  // the limb's end, a leaf
  const std::vector<float> once = smoothOverGraph(t, p, 0.5, 1);
  EXPECT_FLOAT_EQ(once[5], 0.5f * 0.6f + 0.5f * 0.9f);  // up towards the limb
  EXPECT_FLOAT_EQ(once[4], 0.5f * 0.9f + 0.5f * (0.9f + 0.6f) / 2);
  EXPECT_FLOAT_EQ(once[0], 0.9f);  // one neighbour, as sure as itself
  EXPECT_FLOAT_EQ(once[18], 0.5f * 0.9f + 0.5f * (0.9f + 0.1f) / 2);
  // Two passes reach the neighbours' neighbours; none leaves the probabilities as they are.
  EXPECT_LT(smoothOverGraph(t, p, 0.5, 2)[3], 0.9f);
  EXPECT_EQ(smoothOverGraph(t, p, 0.5, 0), p);
  // Edges longer than the gap limit are not neighbours: every point keeps its probability.
  EXPECT_EQ(smoothOverGraph(t, p, 0.5, 2, 0.5), p);
  EXPECT_THROW(smoothOverGraph(t, p, 1.5, 1), OptionsError);
}

TEST(WoodGraph, OneProbabilityPerPoint) {
  FeatureTable t;
  t.neighbourCount = 2;
  addChain(t, 5, 0);
  EXPECT_THROW(connectWood(t, std::vector<float>(4, 1.0f), 0.5), OptionsError);
  EXPECT_THROW(smoothOverGraph(t, std::vector<float>(4, 1.0f), 0.5, 1), OptionsError);
}

}  // namespace
}  // namespace treesketch::classify
