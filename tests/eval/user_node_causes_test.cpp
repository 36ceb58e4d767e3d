#include "treesketch/eval/user_node_causes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "eval/eval_methods.h"
#include "treesketch/eval/evaluation.h"
#include "treesketch/eval/evaluation_report.h"
#include "treesketch/io/view_camera.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/sketch/auto_sketch.h"
#include "treesketch/sketch/polyline_sketch.h"
#include "treesketch/util/error.h"

namespace treesketch::eval {
namespace {

using geom::Vec3;

// A vertical limb (axis x = z = 0, y from 0 to 4, radius 0.2) scanned all round, labelled wood,
// and the careful user's front-view sketch along it with the true point under each node.
struct Limb {
  static constexpr double kRadius = 0.2;
  geom::PointCloud cloud;
  std::vector<sketch::BranchPolyline> axes;
  sketch::Sketch sketch;
  std::vector<TrueNode> truth;
  Limb() {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> angle(0, 2 * M_PI), height(0, 4);
    for (int i = 0; i < 20000; ++i) {
      const double a = angle(rng);
      cloud.positions.emplace_back(kRadius * std::cos(a), height(rng), kRadius * std::sin(a));
      cloud.meshId.push_back(0);
    }
    sketch::BranchPolyline trunk;
    trunk.points = {Vec3(0, 0, 0), Vec3(0, 4, 0)};
    axes = {trunk};
    const geom::Camera cam =
        io::cameraForView("front", cloud.bounds(), geom::UpAxis::Y, geom::Viewport{0, 0, 1280, 800}, false);
    sketch::PolylineSketchOptions po;
    po.nodeSpacing = 1.0;
    po.params = sketch::defaultSamplingFor(cloud.bounds());
    sketch = sketch::sketchFromPolylines(axes, cam, po);
    const sketch::Sketch ideal = sketch::pointNodesFromPolylines(axes, po);
    for (const auto& [id, node] : ideal.nodes()) truth.push_back(TrueNode{node.point, node.normal, kRadius});
  }
};

std::map<NodeCause, int> causesOf(const std::vector<NodeCauseRecord>& records) { return countCauses(records).causes; }

TEST(UserNodeCauses, FittedNodesOnTheirLimb) {
  Limb l;
  const recon::ReconstructionResult r = recon::reconstruct(l.cloud, l.sketch, {});
  const std::vector<std::uint8_t> kept(l.cloud.size(), 1);
  const auto records = userNodeCauses(NodeCauseInput{l.cloud, kept, l.sketch, l.truth, r.results, {}});
  ASSERT_EQ(records.size(), l.sketch.size());
  const NodeCauseCounts counts = countCauses(records);
  // The base node slices the cut end of the limb; every node above it fits, on the limb.
  EXPECT_GE(counts.causes.at(NodeCause::Fitted), 4);
  EXPECT_EQ(counts.onLimb, counts.causes.at(NodeCause::Fitted));
  for (const auto& rec : records) {
    EXPECT_GT(rec.woodPoints, 8u);
    EXPECT_EQ(rec.classedWood, rec.woodPoints);
    EXPECT_DOUBLE_EQ(rec.radius, Limb::kRadius);
    EXPECT_LT(rec.offAxis, 0.1);
  }
  EXPECT_NE(counts.text().find("on its limb " + std::to_string(counts.onLimb)), std::string::npos) << counts.text();
}

TEST(UserNodeCauses, TellsHiddenClassedLeafOffLimbAndRejectedApart) {
  Limb l;
  const std::map<sketch::NodeId, fit::NodeResult> none;  // no node fitted
  const int n = static_cast<int>(l.sketch.size());
  std::vector<std::uint8_t> kept(l.cloud.size(), 1);
  // Wood there and kept, but no fit: the fit rejected it (here the fit was never run).
  EXPECT_EQ(causesOf(userNodeCauses(NodeCauseInput{l.cloud, kept, l.sketch, l.truth, none, {}}))[NodeCause::Rejected],
            n);
  // The classification called every point leaf.
  const std::vector<std::uint8_t> leaf(l.cloud.size(), 0);
  EXPECT_EQ(
      causesOf(userNodeCauses(NodeCauseInput{l.cloud, leaf, l.sketch, l.truth, none, {}}))[NodeCause::ClassedLeaf], n);
  // The scanner's rays hit leaves only.
  geom::PointCloud leaves = l.cloud;
  std::fill(leaves.meshId.begin(), leaves.meshId.end(), 1);
  EXPECT_EQ(causesOf(userNodeCauses(NodeCauseInput{leaves, kept, l.sketch, l.truth, none, {}}))[NodeCause::Hidden], n);
  // The true limb is far from every node's line.
  std::vector<TrueNode> away = l.truth;
  for (auto& t : away) t.point += Vec3(1.0, 0, 0);
  EXPECT_EQ(causesOf(userNodeCauses(NodeCauseInput{l.cloud, kept, l.sketch, away, none, {}}))[NodeCause::OffLimb], n);
}

TEST(UserNodeCauses, NamesTheRejectingTest) {
  EXPECT_EQ(rejectionTest("no circle found (the inliers cover only 40 degrees of the circle); lineEpsilon grew"),
            "arc");
  EXPECT_EQ(rejectionTest("best circle has too few inliers (5 < 12 of 120)"), "support");
  EXPECT_EQ(rejectionTest("too few points for the minimum support (4 < 8)"), "too few points");
  EXPECT_EQ(rejectionTest("no admissible 3-point circle (collinear points, ...)"), "no admissible circle");
  EXPECT_EQ(rejectionTest("the best circle's centre lies outside the centre region"), "centre off the line");
  EXPECT_EQ(rejectionTest("no points within 0.05 of the node's plane"), "empty slice");
  EXPECT_EQ(rejectionTest("something else"), "other");
  NodeCauseCounts c;
  c.causes[NodeCause::Rejected] = 3;
  c.tests["arc"] = 2;
  c.tests["support"] = 1;
  EXPECT_NE(c.text().find("rejected 3 (arc 2, support 1)"), std::string::npos) << c.text();
}

TEST(UserNodeCauses, RejectsMismatchedInput) {
  Limb l;
  const std::map<sketch::NodeId, fit::NodeResult> none;
  const std::vector<std::uint8_t> kept(l.cloud.size(), 1), short_(3, 1);
  std::vector<TrueNode> fewer(l.truth.begin(), l.truth.end() - 1);
  EXPECT_THROW(userNodeCauses(NodeCauseInput{l.cloud, kept, l.sketch, fewer, none, {}}), OptionsError);
  EXPECT_THROW(userNodeCauses(NodeCauseInput{l.cloud, short_, l.sketch, l.truth, none, {}}), OptionsError);
  geom::PointCloud unlabelled = l.cloud;
  unlabelled.meshId.clear();
  EXPECT_THROW(userNodeCauses(NodeCauseInput{unlabelled, kept, l.sketch, l.truth, none, {}}), OptionsError);
}

TEST(CarefulUserFitOptions, GrowthAndBandInTheTreesUnits) {
  EvalOptions o;
  const double defaultBand = fit::CircleFitOptions{}.inlierThreshold;
  recon::ReconstructionOptions ro = carefulUserFitOptions(o, 0.1);
  EXPECT_TRUE(ro.fit.growScreenNodes);  // the thesis's fit unless asked
  EXPECT_DOUBLE_EQ(ro.fit.circle.inlierThreshold, 0.1);  // the fit's 1 cm, in decimetres
  EXPECT_FALSE(ro.fit.chooseDepth);
  o.userInlierBandMetres = 0;  // the fit's value taken in scene units
  EXPECT_DOUBLE_EQ(carefulUserFitOptions(o, 0.1).fit.circle.inlierThreshold, defaultBand);
  o.userGrowth = false;
  o.userInlierBandMetres = 0.01;
  o.chooseDepth = true;
  ro = carefulUserFitOptions(o, 0.1);  // decimetres: 1 cm is 0.1 units
  EXPECT_FALSE(ro.fit.growScreenNodes);
  EXPECT_DOUBLE_EQ(ro.fit.circle.inlierThreshold, 0.1);
  EXPECT_TRUE(ro.fit.chooseDepth);
  EXPECT_TRUE(ro.radii.enabled);
  EXPECT_DOUBLE_EQ(carefulUserFitOptions(o, 1.0).fit.circle.inlierThreshold, 0.01);
}

TEST(CarefulUserSketch, DrawsABranchAsFarAsItsPointsShowIt) {
  // A trunk up the y axis (radius 0.2, a vertex per unit) whose points stop at 6 units; three
  // side branches along x: one at 2 units with points, one at 3 without, one at 8 with points
  // but above where the trunk can be followed.
  std::vector<sketch::BranchPolyline> axes(4);
  std::vector<std::vector<double>> radii(4);
  for (int i = 0; i <= 10; ++i) axes[0].points.emplace_back(0, i, 0);
  radii[0].assign(11, 0.2);
  const int bases[] = {2, 3, 8};
  for (int b = 1; b <= 3; ++b) {
    axes[b].parent = 0;
    axes[b].parentVertex = static_cast<std::size_t>(bases[b - 1]);
    for (int i = 0; i <= 4; ++i) axes[b].points.emplace_back(i, bases[b - 1], 0);
    radii[b].assign(5, 0.1);
  }
  geom::PointCloud seen;
  auto ring = [&](const Vec3& c, const Vec3& u, const Vec3& v, double r) {
    for (int k = 0; k < 16; ++k) seen.positions.push_back(c + r * (std::cos(k * 0.39) * u + std::sin(k * 0.39) * v));
  };
  for (double y = 0; y <= 6.0; y += 0.05) ring(Vec3(0, y, 0), Vec3::UnitX(), Vec3::UnitZ(), 0.2);
  for (double x = 0.3; x <= 4.0; x += 0.05) {
    ring(Vec3(x, 2, 0), Vec3::UnitY(), Vec3::UnitZ(), 0.1);
    ring(Vec3(x, 8, 0), Vec3::UnitY(), Vec3::UnitZ(), 0.1);
  }
  const auto drawn = detail::seenBranches(axes, radii, seen, 0.05, 8);
  ASSERT_EQ(drawn.size(), 2u);
  EXPECT_EQ(drawn[0].parent, -1);
  EXPECT_EQ(drawn[0].points.size(), 7u);  // vertices 0-6: the points stop at 6
  EXPECT_EQ(drawn[1].parent, 0);
  EXPECT_DOUBLE_EQ(drawn[1].points.front().y(), 2.0);
  EXPECT_EQ(drawn[1].points.size(), 5u);
  // With every point seen nothing is cut: the same cloud plus the missing parts.
  for (double y = 6.05; y <= 10.0; y += 0.05) ring(Vec3(0, y, 0), Vec3::UnitX(), Vec3::UnitZ(), 0.2);
  for (double x = 0.3; x <= 4.0; x += 0.05) ring(Vec3(x, 3, 0), Vec3::UnitY(), Vec3::UnitZ(), 0.1);
  const auto all = detail::seenBranches(axes, radii, seen, 0.05, 8);
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[0].points.size(), 11u);
}

TEST(CarefulUserCauses, ReachTheCsv) {
  EvalRow r;
  r.tree = "t";
  r.method = "user";
  r.skippedOffLimb = 1;
  r.skippedHidden = 12;
  r.skippedClassedLeaf = 3;
  r.skippedRejected = 4;
  r.rejectedBy = "arc:3;support:1";
  r.fittedOnLimb = 7;
  std::istringstream csv(csvTable({r}));
  std::string header, line;
  std::getline(csv, header);
  std::getline(csv, line);
  EXPECT_NE(header.find("rejected_by,skipped_off_limb,skipped_hidden,skipped_classed_leaf,skipped_rejected,fitted_on_limb"),
            std::string::npos);
  EXPECT_NE(line.find(",arc:3;support:1,1,12,3,4,7"), std::string::npos) << line;
}

}  // namespace
}  // namespace treesketch::eval
