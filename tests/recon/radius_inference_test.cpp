#include "treesketch/recon/radius_inference.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "../test_support.h"
#include "fit/synthetic_cylinder.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/sketch/auto_sketch.h"

namespace treesketch::recon {
namespace {

using geom::Vec3;

/// The sampling a stroke gives its nodes (edit::drawLimb): the sketch's defaults, lineEpsilon at
/// most four radii of the node the stroke starts on, three growth steps.
sketch::SamplingParams strokeParams(double slice, double lineEpsilon) {
  sketch::SamplingParams p;
  p.sliceHalfThickness = slice;
  p.lineEpsilon = lineEpsilon;
  p.lineEpsilonStep = 0.5 * lineEpsilon;
  p.maxGrowthSteps = 3;
  return p;
}

/// Point nodes from `from` to `to` (`count` of them, the first one step past `from`) under `parent`.
std::vector<NodeId> addLimb(sketch::Sketch& s, NodeId parent, const Vec3& from, const Vec3& to, int count,
                            const sketch::SamplingParams& p) {
  std::vector<NodeId> ids;
  const Vec3 dir = (to - from).normalized();
  for (int k = 1; k <= count; ++k) {
    parent = s.addPointNode(parent, from + (to - from) * (double(k) / count), dir, p);
    ids.push_back(parent);
  }
  return ids;
}

/// Every circle of `ids` (base to tip) no wider than the one before it, the first no wider than
/// `forkRadius`; returns how many had a circle.
int expectTapers(const ReconstructionResult& r, const std::vector<NodeId>& ids, double forkRadius) {
  double before = forkRadius;
  int circles = 0;
  for (NodeId id : ids) {
    const NodeRadius& c = r.radii.at(id);
    if (c.source == RadiusSource::None) continue;
    ++circles;
    EXPECT_LE(c.radius, before * (1 + 1e-9)) << "node " << id << " (" << toString(c.source) << ", " << c.why << ")";
    before = c.radius;
  }
  return circles;
}

// A dense trunk (radius 0.15) and a sparse limb (radius 0.03, 60 points over 1.5 m): most of the
// limb's slices hold too few points for a circle, and the slices near the fork fit the trunk.
geom::PointCloud sparseLimbCloud(Vec3* limbFrom, Vec3* limbTo) {
  std::mt19937_64 rng(7);
  geom::PointCloud cloud;
  test::CylinderSpec trunk;
  trunk.radius = 0.15;
  trunk.length = 3.0;
  trunk.points = 30000;
  test::addCylinder(cloud, trunk, rng);
  const Vec3 dir = Vec3(1, 1, 0).normalized();
  test::CylinderSpec limb;
  limb.base = Vec3(0.15, 2.0, 0) + 0.05 * dir;
  limb.axis = dir;
  limb.radius = 0.03;
  limb.length = 1.5;
  limb.points = 60;
  test::addCylinder(cloud, limb, rng);
  *limbFrom = limb.base;
  *limbTo = limb.base + limb.length * dir;
  return cloud;
}

TEST(RadiusInference, ASparseLimbIsNoThickerThanItsParentAndTapers) {
  Vec3 from, to;
  const geom::PointCloud cloud = sparseLimbCloud(&from, &to);
  sketch::Sketch s;
  const sketch::SamplingParams trunkP = strokeParams(0.04, 0.4);
  NodeId fork = sketch::kNoNode;
  for (double y : {0.5, 1.0, 1.5, 2.0, 2.5}) {
    const NodeId id = s.addPointNode(fork == sketch::kNoNode ? sketch::kNoNode : fork, Vec3(0.01, y, 0.01), Vec3::UnitY(), trunkP);
    if (y <= 2.0) fork = id;
  }
  // The stroke's nodes: lineEpsilon four trunk radii (the radius of the node it starts on).
  const std::vector<NodeId> limb = addLimb(s, fork, from, to, 10, strokeParams(0.04, 0.6));
  const ReconstructionResult r = reconstruct(cloud, s, sketchReconstructionOptions());
  const NodeRadius& forkCircle = r.radii.at(fork);
  ASSERT_EQ(forkCircle.source, RadiusSource::Fitted);
  EXPECT_NEAR(forkCircle.radius, 0.15, 0.02);
  EXPECT_EQ(expectTapers(r, limb, forkCircle.radius), 10) << "every stroke node has a circle";
  std::size_t skipped = 0;
  for (NodeId id : limb) skipped += r.results.at(id).status == fit::NodeStatus::Skipped;
  EXPECT_GE(skipped, 5u) << "the limb is sparse: most of its slices do not fit";
  // The limb is thinner than the trunk (a side limb takes at most an even fork's share), and the
  // model says which radii were inferred.
  EXPECT_LT(r.radii.at(limb.front()).radius, 0.75 * forkCircle.radius);
  const model::TreeModel tree = model::fromReconstruction(r, s.up);
  std::size_t inferred = 0;
  for (char m : tree.measured) inferred += m == 0;
  EXPECT_GE(inferred, skipped);
  const FitSummary summary = summarizeFits(r.results, r.radii, limb);
  EXPECT_EQ(summary.nodes, 10u);
  EXPECT_EQ(summary.fitted + summary.inferred, 10u);
  EXPECT_NE(summary.text().find("not: too few points"), std::string::npos) << summary.text();
}

TEST(RadiusInference, AWideFitOnALimbIsSetAsideAndAThinGapIsFilled) {
  // Hand-made fits: a trunk of 0.1 and a limb 0.04, 0.035, skipped, 0.2 (a noisy arc), skipped, 0.025.
  std::vector<fit::NodeResult> fits(8);
  const double radii[] = {0.1, 0.1, 0.04, 0.035, 0, 0.2, 0, 0.025};
  std::vector<RadiusInput> in;
  for (int i = 0; i < 8; ++i) {
    fit::NodeResult& f = fits[i];
    f.status = radii[i] > 0 ? fit::NodeStatus::Fitted : fit::NodeStatus::Skipped;
    f.radius = radii[i];
    f.rms = 0.002;
    f.centre = Vec3(i < 2 ? 0 : 0.2 * (i - 1), i < 2 ? i : 1 + 0.2 * (i - 1), 0);
    if (!(radii[i] > 0)) {
      f.reason = "no circle found (too few points for the minimum support (4 < 12))";
      f.testIndices = {1, 2, 3, 4};  // a few points, too few for a circle
    }
    RadiusInput n;
    n.id = i;
    n.parent = i == 0 ? sketch::kNoNode : i - 1;
    n.fit = &fits[i];
    n.geometry.planePoint = f.centre;  // point nodes
    in.push_back(n);
  }
  RadiusInferenceOptions on;
  on.enabled = true;
  const auto out = inferRadii(in, on);
  EXPECT_EQ(out.at(5).source, RadiusSource::Inferred);
  EXPECT_NE(out.at(5).why.find("wider"), std::string::npos) << out.at(5).why;
  for (int i = 1; i < 8; ++i) EXPECT_LE(out.at(i).radius, out.at(i - 1).radius + 1e-12) << i;
  EXPECT_EQ(out.at(4).source, RadiusSource::Inferred);
  EXPECT_GT(out.at(6).radius, 0.02);
  EXPECT_LT(out.at(6).radius, 0.04);
  // Off (the thesis's procedure, the default): the fits as they are, the skipped nodes bridged.
  const auto raw = inferRadii(in);
  EXPECT_EQ(raw.at(5).radius, 0.2);
  EXPECT_EQ(raw.at(4).source, RadiusSource::None);
}

TEST(RadiusInference, ReasonsAreCountedByKind) {
  EXPECT_EQ(reasonKind("no circle found (too few points for the minimum support (5 < 12)); lineEpsilon grew"),
            reasonKind("no circle found (too few points for the minimum support (3 < 12)); lineEpsilon grew"));
  EXPECT_EQ(reasonKind("something new"), "something new");
}

// A sparse limb of a real scan (AdTree's tree1: a small deciduous tree with a noisy, sparse
// crown): nodes placed by hand up the stem and along a limb that leaves it at 0.9 m (about 140
// points over 3 m), with the sampling a stroke gives them.
TEST(RadiusInference, ASparseLimbOfARealScanIsNoThickerThanItsParent) {
  const std::filesystem::path path = test::sharedDataDir() / "real" / "adtree_tree1.xyz";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const geom::PointCloud cloud = io::readPointCloud(path);
  sketch::Sketch s;
  s.up = geom::UpAxis::Z;
  s.defaults = sketch::defaultSamplingFor(cloud.bounds());
  NodeId fork = sketch::kNoNode;
  for (double z : {-0.7, -0.3, 0.1, 0.5, 0.86})
    fork = s.addPointNode(fork, Vec3(-0.77, 18.22, z), Vec3::UnitZ(), s.defaults);
  NodeId stem = fork;  // the stem goes on above the limb
  for (const Vec3& q : {Vec3(-0.72, 18.12, 1.10), Vec3(-0.80, 18.05, 1.35), Vec3(-0.84, 17.93, 1.55)})
    stem = s.addPointNode(stem, q, Vec3::UnitZ(), s.defaults);
  const std::vector<Vec3> limbPath = {{-0.89, 18.22, 1.09}, {-1.07, 18.25, 1.40}, {-1.28, 18.28, 1.57},
                                      {-1.68, 18.32, 1.62}, {-1.76, 18.20, 1.81}, {-1.95, 18.41, 1.75},
                                      {-2.17, 18.63, 2.10}, {-2.35, 18.69, 2.29}};
  sketch::SamplingParams p = s.defaults;
  p.lineEpsilon = std::min(s.defaults.lineEpsilon, std::max(4 * 0.085, 2 * s.defaults.sliceHalfThickness));
  p.maxGrowthSteps = 3;
  std::vector<NodeId> limb;
  NodeId parent = fork;
  for (std::size_t k = 0; k < limbPath.size(); ++k) {
    const Vec3 dir = (k + 1 < limbPath.size() ? limbPath[k + 1] - limbPath[k] : limbPath[k] - limbPath[k - 1]);
    parent = s.addPointNode(parent, limbPath[k], dir.normalized(), p);
    limb.push_back(parent);
  }
  const ReconstructionResult r = reconstruct(cloud, s, sketchReconstructionOptions());
  // The stem's node at the fork does not fit (the limb's slice beside it): its radius is inferred
  // from the stem's fits below it.
  const NodeRadius& forkCircle = r.radii.at(fork);
  ASSERT_NE(forkCircle.source, RadiusSource::None);
  EXPECT_EQ(expectTapers(r, limb, forkCircle.radius), int(limb.size())) << "every node of the limb has a circle";
  // The fits beside the fork took in the stem; the limb is a side limb's share of it at most.
  EXPECT_LE(r.radii.at(limb.front()).radius, 0.71 * forkCircle.radius);
  const FitSummary summary = summarizeFits(r.results, r.radii, limb);
  EXPECT_EQ(summary.inferred, limb.size() - summary.fitted);
  EXPECT_FALSE(summary.notFitted.empty()) << summary.text();
}

}  // namespace
}  // namespace treesketch::recon
