// The simulated correcting user: from a model that misses a limb, it draws that limb
// with the correction tools' stroke and the forward distance drops; no recorded edit leaves the
// model worse than before it.
#include "treesketch/eval/correcting_user.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "test_support.h"
#include "treesketch/sketch/auto_sketch.h"
#include "treesketch/sketch/polyline_sketch.h"
#include "treesketch/sketch/sketch_edits.h"

namespace treesketch::eval {
namespace {

TEST(CorrectingUser, DrawsAMissedLimbAndNeverKeepsAWorseEdit) {
  auto trees = builtinTrees(1);
  const TreeCase& tree = trees[0];
  ScanCondition c = referenceCondition();
  c.targetPoints = 40000;
  TreeScan scan = scanTree(tree, c, false, 3);
  // The ideal sketch of every limb, without the longest child limb of the trunk: what an
  // automatic model that missed that limb would be.
  sketch::PolylineSketchOptions po;
  po.nodeCount = 60;
  po.params = sketch::defaultSamplingFor(scan.cloud.bounds());
  po.up = tree.up;
  std::vector<sketch::BranchPolyline> kept;
  std::size_t longest = 0;
  double best = 0;
  for (std::size_t i = 1; i < tree.axes.size(); ++i) {
    if (tree.axes[i].parent != 0) continue;
    double len = 0;
    for (std::size_t k = 1; k < tree.axes[i].points.size(); ++k)
      len += (tree.axes[i].points[k] - tree.axes[i].points[k - 1]).norm();
    if (len > best) {
      best = len;
      longest = i;
    }
  }
  ASSERT_GT(longest, 0u);
  std::vector<int> newIndex(tree.axes.size(), -1);
  for (std::size_t i = 0; i < tree.axes.size(); ++i) {
    int p = tree.axes[i].parent;
    bool under = int(i) == int(longest);
    while (!under && p >= 0) {
      under = p == int(longest);
      p = tree.axes[p].parent;
    }
    if (under) continue;
    newIndex[i] = int(kept.size());
    kept.push_back(tree.axes[i]);
    if (kept.back().parent >= 0) kept.back().parent = newIndex[kept.back().parent];
  }
  sketch::Sketch start = sketch::pointNodesFromPolylines(kept, po);

  CorrectingUserOptions o;
  o.maxEdits = 4;
  o.distance.minSamples = 3000;
  CorrectingRun run = runCorrectingUser(tree, scan.cloud, start, o);
  ASSERT_GE(run.steps.size(), 2u);
  EXPECT_EQ(run.steps.front().edit, 0);
  bool stroked = false;
  for (std::size_t i = 1; i < run.steps.size(); ++i) {
    const CorrectingStep& s = run.steps[i];
    const CorrectingStep& p = run.steps[i - 1];
    EXPECT_EQ(s.edit, p.edit + 1);
    EXPECT_LE(s.backwardRms + s.forwardRms, p.backwardRms + p.forwardRms + 1e-12) << s.action;
    stroked = stroked || (s.action.rfind("stroke", 0) == 0 && s.action.find("undone") == std::string::npos);
  }
  EXPECT_TRUE(stroked);
  EXPECT_LT(run.steps.back().forwardRms, 0.8 * run.steps.front().forwardRms);
  const std::string md = correctingMarkdown({run}, o);
  EXPECT_NE(md.find("edits to 0.5 %"), std::string::npos);
}

// Leaf-on with leafOnWoodOnly, the person starts from the automatic model of the classified wood
// (as `--leaf-on --wood-only`), not from the model of every point with its tubes through the
// foliage: far fewer nodes, and its tubes lie on the wood (a lower backward error).
TEST(CorrectingUser, LeafOnStartsFromTheModelOfTheClassifiedWood) {
  const std::vector<TreeCase> trees = builtinTrees(1);
  EvalOptions eo;
  eo.sphereTargetPoints = 40000;
  eo.leafOff = false;
  eo.minSamples = 3000;
  CorrectingUserOptions o;
  o.maxEdits = 1;
  const std::vector<CorrectingRun> every = runCorrectingEvaluation(trees, eo, o);
  o.leafOnWoodOnly = true;
  const std::vector<CorrectingRun> wood = runCorrectingEvaluation(trees, eo, o);
  ASSERT_EQ(wood.size(), 1u);
  ASSERT_EQ(every.size(), 1u);
  const CorrectingStep& w = wood[0].steps.front();
  const CorrectingStep& e = every[0].steps.front();
  EXPECT_EQ(wood[0].leaf, "leaf-on");
  EXPECT_EQ(w.action, "start (automatic model of the classified wood)");
  EXPECT_EQ(e.action, "start (automatic model)");
  EXPECT_LT(2 * w.nodes, e.nodes) << w.nodes << " vs " << e.nodes;
  EXPECT_LT(w.backwardRms, e.backwardRms);
}

}  // namespace
}  // namespace treesketch::eval
