// The classification's measurement: scores from known counts, leaf warping, and one labelled scan
// of a built-in tree scored end to end.
#include "treesketch/eval/classify_eval.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "treesketch/eval/evaluation.h"

namespace treesketch::eval {
namespace {

TEST(ClassifyEval, ScoresFromKnownCounts) {
  WoodScore s;
  s.tp = 80;
  s.fp = 20;
  s.fn = 10;
  s.tn = 890;
  EXPECT_NEAR(s.precision(), 0.8, 1e-12);
  EXPECT_NEAR(s.recall(), 80.0 / 90.0, 1e-12);
  EXPECT_NEAR(s.f1(), 160.0 / 190.0, 1e-12);
  EXPECT_NEAR(s.mcc(), (80.0 * 890 - 20.0 * 10) / std::sqrt(100.0 * 90 * 910 * 900), 1e-12);
  WoodScore none;
  EXPECT_EQ(none.mcc(), 0.0);
  none.add(true, true);
  none.add(false, true);
  EXPECT_EQ(none.tp, 1u);
  EXPECT_EQ(none.fp, 1u);
}

TEST(ClassifyEval, WarpedLeavesKeepTheirPlaceButChangeShape) {
  geom::TriMesh leaves;
  for (int k = 0; k < 20; ++k) {
    const geom::Vec3 c(k, 0, 0);
    const auto b = static_cast<std::uint32_t>(leaves.vertices.size());
    leaves.vertices.insert(leaves.vertices.end(), {c + geom::Vec3(-0.1, -0.1, 0), c + geom::Vec3(0.1, -0.1, 0),
                                                   c + geom::Vec3(0.1, 0.1, 0), c + geom::Vec3(-0.1, 0.1, 0)});
    leaves.triangles.push_back({b, b + 1, b + 2});
    leaves.triangles.push_back({b, b + 2, b + 3});
  }
  const geom::TriMesh w = warpLeaves(leaves, {});
  ASSERT_EQ(w.vertices.size(), leaves.vertices.size());
  EXPECT_EQ(w.triangles, leaves.triangles);
  double moved = 0, offPlane = 0;
  for (std::size_t v = 0; v < w.vertices.size(); ++v) {
    moved += (w.vertices[v] - leaves.vertices[v]).norm();
    offPlane = std::max(offPlane, std::abs(w.vertices[v].z()));
    EXPECT_LT((w.vertices[v] - leaves.vertices[v]).norm(), 0.25) << v;  // a leaf stays where it was
  }
  EXPECT_GT(moved / w.vertices.size(), 0.01);
  EXPECT_GT(offPlane, 0.01);  // leaves bent out of their plane
  const geom::TriMesh again = warpLeaves(leaves, {});
  EXPECT_EQ(again.vertices, w.vertices);  // deterministic
}

TEST(ClassifyEval, ScoresALabelledScanOfABuiltInTree) {
  const std::vector<TreeCase> trees = builtinTrees(1);
  ClassifyEvalOptions o;
  o.conditions = selectConditions(fullMatrix(), {"sphere-73k"});
  const std::vector<ClassifyRow> rows = evaluateClassifier(trees, o);
  ASSERT_EQ(rows.size(), 1u);
  const ClassifyRow& r = rows[0];
  EXPECT_GT(r.points, 1000u);
  EXPECT_GT(r.woodPoints, 100u);
  EXPECT_EQ(r.score.tp + r.score.fp + r.score.fn + r.score.tn, r.points);
  EXPECT_EQ(r.score.tp + r.score.fn, r.woodPoints);
  EXPECT_GT(r.score.f1(), 0.5);
  const std::string report = classifyReport(rows);
  EXPECT_NE(report.find("| sphere-73k |"), std::string::npos) << report;
}

}  // namespace
}  // namespace treesketch::eval

namespace treesketch::eval {
namespace {

// The skeleton on the classified wood: a leaf-on scan is modelled from fewer points (the leaves
// left out), so its sketch has far fewer tips than the skeleton on every point; not an evaluation
// default.
TEST(ClassifyEval, SkeletonOnTheClassifiedWood) {
  const std::vector<TreeCase> trees = builtinTrees(1);
  const TreeScan scan = scanTree(trees[0], selectConditions(fullMatrix(), {"sphere-73k"})[0], true, 1);
  EvalOptions o;
  const MethodOutput wood = runMethod("skeleton-wood", MethodInput{trees[0], scan.cloud, o, 0, true});
  const MethodOutput all = runMethod("skeleton", MethodInput{trees[0], scan.cloud, o, 0, true});
  EXPECT_GT(wood.mesh.triangles.size(), 0u);
  EXPECT_GT(wood.fitted, 0);
  EXPECT_LT(wood.nodes, all.nodes);
  const auto names = defaultMethodNames();
  EXPECT_EQ(std::find(names.begin(), names.end(), "skeleton-wood"), names.end());
  const auto every = methodNames();
  EXPECT_NE(std::find(every.begin(), every.end(), "skeleton-wood"), every.end());
}

}  // namespace
}  // namespace treesketch::eval
