// Node-list helpers (src/skeleton/node_tree.h): the tracked stem made one chain.
#include "skeleton/node_tree.h"

#include <gtest/gtest.h>

#include <vector>

namespace treesketch {
namespace {

using skeleton::SkeletonNode;

SkeletonNode node(std::int32_t parent, double distance, bool stem, std::int32_t order) {
  SkeletonNode n;
  n.parent = parent;
  n.distance = distance;
  n.stem = stem;
  n.branchOrder = order;
  n.position = geom::Vec3(stem ? 0.0 : 0.3, distance, 0.0);
  return n;
}

// The stem's chain leaves the stem at a whorl (nodes 2 and 3 are a limb's pieces) and comes back
// to it (node 4): the geodesic path reached the stem's next piece through the limb. Chained, node 4
// hangs from node 1, the stem below it, and the limb is a side branch ending where it was.
std::vector<SkeletonNode> stemWithADetour() {
  std::vector<SkeletonNode> nodes{node(-1, 0.0, true, 0),  node(0, 0.5, true, 0),  node(1, 0.8, false, 0),
                                  node(2, 1.0, false, 0),  node(3, 1.2, true, 0),  node(4, 1.6, true, 0),
                                  node(1, 0.9, false, 1)};
  skeleton::detail::linkChildren(nodes);
  return nodes;
}

TEST(NodeTree, ChainsTheTrackedStemPastADetourThroughALimb) {
  std::vector<SkeletonNode> nodes = stemWithADetour();
  ASSERT_TRUE(skeleton::detail::chainTrackedStem(nodes));
  EXPECT_EQ(nodes[4].parent, 1);
  EXPECT_EQ(nodes[3].children.size(), 0u);
  EXPECT_EQ(nodes[1].children, (std::vector<std::int32_t>{2, 4, 6}));
  for (int i : {0, 1, 4, 5}) EXPECT_EQ(nodes[i].branchOrder, 0) << "stem node " << i;
  EXPECT_EQ(nodes[2].branchOrder, 1);  // the limb now starts a branch of its own
  EXPECT_EQ(nodes[3].branchOrder, 1);
  EXPECT_EQ(nodes[6].branchOrder, 1);  // a side branch as before
}

TEST(NodeTree, LeavesAStemThatIsOneChainAsItIs) {
  std::vector<SkeletonNode> nodes = stemWithADetour();
  nodes[4].parent = 1;
  skeleton::detail::linkChildren(nodes);
  const std::vector<SkeletonNode> before = nodes;
  EXPECT_FALSE(skeleton::detail::chainTrackedStem(nodes));
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    EXPECT_EQ(nodes[i].parent, before[i].parent);
    EXPECT_EQ(nodes[i].branchOrder, before[i].branchOrder);
  }
}

TEST(NodeTree, NoTrackedStemNoChange) {
  std::vector<SkeletonNode> nodes = stemWithADetour();
  for (auto& n : nodes) n.stem = false;
  EXPECT_FALSE(skeleton::detail::chainTrackedStem(nodes));
  EXPECT_EQ(nodes[4].parent, 3);
  std::vector<SkeletonNode> none;
  EXPECT_FALSE(skeleton::detail::chainTrackedStem(none));
}

}  // namespace
}  // namespace treesketch
