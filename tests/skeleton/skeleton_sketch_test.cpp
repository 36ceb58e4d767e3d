#include "treesketch/skeleton/skeleton_sketch.h"

#include <gtest/gtest.h>

#include <sstream>

#include "skeleton/radius_allometry.h"
#include "synthetic_tree.h"
#include "treesketch/compare/model_fit.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/skeleton/skeleton_export.h"
#include "treesketch/util/error.h"

using namespace treesketch;
using geom::Vec3;

namespace {
skeleton::SkeletonNode chainNode(int parent, double y, double radius) {
  skeleton::SkeletonNode n;
  n.parent = parent;
  n.position = Vec3(0, y, 0);
  n.radius = radius;
  return n;
}
std::vector<skeleton::SkeletonNode> linkUp(std::vector<skeleton::SkeletonNode> nodes) {
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].parent >= 0) nodes[nodes[i].parent].children.push_back(static_cast<std::int32_t>(i));
  return nodes;
}
/// Carried length in segments (parent-first nodes): the node's own segment plus every segment above it.
std::vector<double> carriedSegments(const std::vector<skeleton::SkeletonNode>& nodes) {
  std::vector<double> carried(nodes.size(), 0.0);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    carried[i] += nodes[i].parent >= 0 ? 1.0 : 0.0;
    if (nodes[i].parent >= 0) carried[nodes[i].parent] += carried[i];
  }
  return carried;
}
}  // namespace

TEST(SkeletonSketch, RegularizeInterpolatesSmoothsAndCaps) {
  // A chain of 7 nodes; node 3 failed, node 5 is an outlier thicker than its parent.
  std::vector<skeleton::SkeletonNode> nodes;
  for (int i = 0; i < 7; ++i) nodes.push_back(chainNode(i - 1, i, 0.5));
  nodes = linkUp(nodes);
  std::vector<double> fitted = {0.30, 0.28, 0.26, 0, 0.22, 0.40, 0.18};
  std::vector<char> valid = {1, 1, 1, 0, 1, 1, 1};
  skeleton::RadiusRules rules;
  rules.medianWindow = 1;
  rules.childNotThicker = false;
  rules.allometryMaxRatio = 0;  // the pipe law's bound is tested on its own below
  rules.maxGrowthRatio = 0;     // and the fits wider than the branch below them
  auto r = skeleton::regularizeRadii(nodes, fitted, valid, rules);
  EXPECT_NEAR(r[3], 0.24, 1e-12);  // linear between 0.26 and 0.22
  EXPECT_NEAR(r[5], 0.40, 1e-12);
  rules.childNotThicker = true;
  r = skeleton::regularizeRadii(nodes, fitted, valid, rules);
  // The taper: the least-absolute-deviations non-increasing radii. The outlier 0.40 is pooled
  // with the fit before it and takes their median, that fit's 0.22; the fits below keep theirs
  // (a least-squares taper would have raised nodes 1-4 to the pool's mean, 0.27).
  EXPECT_NEAR(r[5], 0.22, 1e-12);
  EXPECT_NEAR(r[4], 0.22, 1e-12);
  EXPECT_NEAR(r[3], 0.24, 1e-12);
  EXPECT_NEAR(r[1], 0.28, 1e-12);
  EXPECT_NEAR(r[0], 0.30, 1e-12);
  EXPECT_NEAR(r[6], 0.18, 1e-12);
  rules.medianWindow = 3;
  r = skeleton::regularizeRadii(nodes, fitted, valid, rules);
  EXPECT_LT(r[5], 0.30);
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_LE(r[i], r[i - 1]);
  // No valid fit at all: the skeleton's estimates are kept.
  r = skeleton::regularizeRadii(nodes, fitted, std::vector<char>(7, 0), rules);
  for (double x : r) EXPECT_EQ(x, 0.5);
  EXPECT_THROW(skeleton::regularizeRadii(nodes, {0.1}, valid, rules), OptionsError);
  rules.medianWindow = 0;
  EXPECT_THROW(skeleton::regularizeRadii(nodes, fitted, valid, rules), OptionsError);
}

TEST(SkeletonSketch, AFitWiderThanTheFitsBelowItAndThePipeLawIsSetAside) {
  // A stem tracked to 0.30 at its foot, then a limb of fits: 0.08 on three one-sided arcs, 0.20
  // where the limb's circle is whole again, 0.06 and 0.05, then 0.22 (a circle round the limb and
  // a neighbour), 0.045 and 0.04. The 0.20 is 2.5 times the arcs below it but under the pipe law
  // the stem sets for the length it carries: kept. The 0.22 is over both: set aside, and its node
  // takes the radii either side of it.
  std::vector<skeleton::SkeletonNode> nodes;
  for (int i = 0; i < 14; ++i) nodes.push_back(chainNode(i - 1, i, 0.1));
  for (int i = 0; i < 3; ++i) nodes[i].stem = true, nodes[i].radius = 0.30;
  nodes = linkUp(nodes);
  const std::vector<double> fitted = {0, 0, 0, 0.08, 0.08, 0.08, 0.20, 0.06, 0.05, 0.22, 0.045, 0.04, 0.04, 0.04};
  std::vector<char> valid(14, 1);
  for (int i = 0; i < 3; ++i) valid[i] = 0;
  skeleton::RadiusRules rules;
  rules.medianWindow = 1;
  rules.childNotThicker = false;
  std::vector<char> kept;
  auto r = skeleton::regularizeRadii(nodes, fitted, valid, rules, &kept);
  EXPECT_TRUE(kept[6]);
  EXPECT_NEAR(r[6], 0.20, 1e-12);
  EXPECT_FALSE(kept[9]);
  EXPECT_LT(r[9], 0.06);
  EXPECT_GT(r[9], 0.04);
  rules.maxGrowthRatio = 0;  // the rule off: the neighbour's circle stays
  r = skeleton::regularizeRadii(nodes, fitted, valid, rules, &kept);
  EXPECT_TRUE(kept[9]);
  EXPECT_NEAR(r[9], 0.22, 1e-12);
  rules.maxGrowthRatio = 0.5;
  EXPECT_THROW(skeleton::regularizeRadii(nodes, fitted, valid, rules), OptionsError);
}

TEST(SkeletonSketch, OneThinFitDoesNotCapTheBranchAboveIt) {
  // A trunk of fits 0.30 with one fit of 0.10 (a twig's circle) low on it: a running minimum
  // would make the whole trunk above 0.10 thick; the taper's median outvotes the one odd fit.
  std::vector<skeleton::SkeletonNode> nodes;
  for (int i = 0; i < 10; ++i) nodes.push_back(chainNode(i - 1, i, 0.3));
  nodes = linkUp(nodes);
  std::vector<double> fitted(10, 0.30);
  fitted[2] = 0.10;
  skeleton::RadiusRules rules;
  rules.medianWindow = 1;
  rules.allometryMaxRatio = 0;
  const auto r = skeleton::regularizeRadii(nodes, fitted, std::vector<char>(10, 1), rules);
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_LE(r[i], r[i - 1]);
  EXPECT_NEAR(r[9], 0.30, 1e-12);
  EXPECT_NEAR(r[2], 0.30, 1e-12);
}

TEST(SkeletonSketch, ARunOfThickFitsBelowAForkDoesNotRaiseTheTrunkBelowIt) {
  // A trunk of fits 0.07 with four fits of 0.12 (slices through a crotch hold both limbs) high on
  // it, then its continuation of 0.04: the taper keeps the lower trunk at its own fits.
  std::vector<skeleton::SkeletonNode> nodes;
  for (int i = 0; i < 16; ++i) nodes.push_back(chainNode(i - 1, i, 0.07));
  nodes = linkUp(nodes);
  std::vector<double> fitted(16, 0.07);
  for (int i = 8; i < 12; ++i) fitted[i] = 0.12;
  for (int i = 12; i < 16; ++i) fitted[i] = 0.04;
  skeleton::RadiusRules rules;
  rules.medianWindow = 1;
  rules.allometryMaxRatio = 0;
  const auto r = skeleton::regularizeRadii(nodes, fitted, std::vector<char>(16, 1), rules);
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_LE(r[i], r[i - 1]);
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(r[i], 0.07, 1e-12) << i;  // the mean would give 0.084
  EXPECT_NEAR(r[15], 0.04, 1e-12);
}

TEST(SkeletonSketch, PipeModelGrowsForks) {
  // Root -> fork (radius 0.1) with two children of radius 0.1 each: pipe model gives sqrt(0.02).
  std::vector<skeleton::SkeletonNode> nodes = {chainNode(-1, 0, 0.1), chainNode(0, 1, 0.1), chainNode(1, 2, 0.1),
                                               chainNode(1, 2, 0.1)};
  nodes[3].branchOrder = 1;
  nodes = linkUp(nodes);
  skeleton::RadiusRules rules;
  rules.medianWindow = 1;
  rules.pipeModel = true;
  rules.childNotThicker = false;
  const auto r = skeleton::regularizeRadii(nodes, {0.1, 0.1, 0.1, 0.1}, {1, 1, 1, 1}, rules);
  EXPECT_NEAR(r[1], std::sqrt(0.02), 1e-12);
  EXPECT_NEAR(r[2], 0.1, 1e-12);
}

TEST(SkeletonSketch, TheTrackedStemsRadiusIsNotRaised) {
  // A stem node (radius measured by the stem tracker, no fit of its own) with many children:
  // leaf-on, the allometry (fitted mostly to leaf clusters) gave a trunk four times its radius;
  // the pipe model, with these many children, would raise it too.
  std::vector<skeleton::SkeletonNode> nodes = {chainNode(-1, 0, 0.1), chainNode(0, 1, 0.1)};
  for (int k = 0; k < 6; ++k) {
    nodes.push_back(chainNode(1, 2, 0.08));
    nodes.back().branchOrder = k == 0 ? 0 : 1;
  }
  nodes[0].stem = nodes[1].stem = true;
  nodes = linkUp(nodes);
  skeleton::RadiusRules rules;
  rules.medianWindow = 1;
  rules.pipeModel = true;
  std::vector<double> fitted(nodes.size(), 0.08);
  std::vector<char> valid(nodes.size(), 1);
  valid[0] = valid[1] = 0;  // the stem's own nodes did not fit
  auto r = skeleton::regularizeRadii(nodes, fitted, valid, rules);
  EXPECT_NEAR(r[1], 0.1, 1e-12);
  // Not on the tracked stem, the same node is a fork the pipe model raises.
  nodes[0].stem = nodes[1].stem = false;
  r = skeleton::regularizeRadii(nodes, fitted, valid, rules);
  EXPECT_GT(r[1], 0.12);
}

// A trunk of 20 unit segments with four side branches of 5 whose fits follow one allometry
// (r = 0.05·L^0.5, L = the length a node carries plus one segment), and one short side branch
// whose fits took in something else (0.45, thinner than the trunk there, so "no child thicker"
// does not catch it). The allometric bound brings that branch down to within 2× of the law and
// leaves the others as fitted.
TEST(SkeletonSketch, AllometryCapsAFatSideBranch) {
  std::vector<skeleton::SkeletonNode> nodes;
  for (int i = 0; i < 20; ++i) nodes.push_back(chainNode(i - 1, i, 0.5));
  auto side = [&](int at, int count, double dx, int order) {
    int parent = at;
    for (int k = 1; k <= count; ++k) {
      skeleton::SkeletonNode n = chainNode(parent, at, 0.5);
      n.position = Vec3(dx * k, at, 0);
      n.branchOrder = order;
      nodes.push_back(n);
      parent = static_cast<int>(nodes.size()) - 1;
    }
  };
  for (int at : {4, 8, 12, 16}) side(at, 5, 1.0, 1);
  const std::size_t fatStart = nodes.size();
  side(6, 3, -1.0, 1);
  nodes = linkUp(nodes);
  const std::vector<double> carried = carriedSegments(nodes);
  std::vector<double> fitted(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) fitted[i] = 0.05 * std::sqrt(carried[i] + 1.0);
  for (std::size_t i = fatStart; i < nodes.size(); ++i) fitted[i] = 0.45;
  const std::vector<char> valid(nodes.size(), 1);
  skeleton::RadiusRules rules;
  rules.medianWindow = 1;
  rules.childNotThicker = false;
  rules.allometryMaxRatio = 2.0;
  const auto r = skeleton::regularizeRadii(nodes, fitted, valid, rules);
  for (std::size_t i = 0; i < fatStart; ++i) EXPECT_NEAR(r[i], fitted[i], 1e-6) << i;
  for (std::size_t i = fatStart; i < nodes.size(); ++i) {
    const double law = 0.05 * std::sqrt(carried[i] + 1.0);
    EXPECT_LE(r[i], 2.0 * law + 1e-9) << i;
    EXPECT_LT(r[i], 0.3) << i;
  }
  rules.allometryMaxRatio = 0;  // off: the fat fits stay
  const auto off = skeleton::regularizeRadii(nodes, fitted, valid, rules);
  for (std::size_t i = fatStart; i < nodes.size(); ++i) EXPECT_NEAR(off[i], 0.45, 1e-12);
  rules.allometryMaxRatio = 0.5;
  EXPECT_THROW(skeleton::regularizeRadii(nodes, fitted, valid, rules), OptionsError);
}

TEST(SkeletonSketch, SketchFromSkeletonIsValid) {
  const auto cloud = test::sampleCylinders(test::yTree(), 0.02, 0.003, 7);
  const auto s = skeleton::extractSkeleton(cloud);
  const auto sk = skeleton::skeletonToSketch(s);
  ASSERT_EQ(sk.size(), s.nodes.size());
  EXPECT_NO_THROW(sk.validate());
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    const auto& node = sk.node(static_cast<sketch::NodeId>(i));
    EXPECT_FALSE(node.isScreenNode());
    EXPECT_EQ(node.parent, s.nodes[i].parent < 0 ? sketch::kNoNode : s.nodes[i].parent);
    EXPECT_GT(node.params.lineEpsilon, s.nodes[i].radius);
  }
  EXPECT_TRUE(skeleton::skeletonToSketch(skeleton::Skeleton{}).empty());
}

TEST(SkeletonSketch, AutoSketchFitsRadiiAndRegularises) {
  const auto cyls = test::yTree();
  const auto cloud = test::sampleCylinders(cyls, 0.02, 0.003, 7);
  const auto res = skeleton::autoSkeletonSketch(cloud);
  ASSERT_FALSE(res.model.empty());
  ASSERT_EQ(res.fits.size(), res.model.size());
  EXPECT_FALSE(res.mesh.empty());
  int checked = 0, accepted = 0;
  for (std::size_t i = 0; i < res.model.size(); ++i) {
    const auto& n = res.model[i];
    accepted += res.fitAccepted[i];
    if (n.parent >= 0) EXPECT_LE(n.radius, res.model[n.parent].radius);  // no child thicker
    // Radii within 10 % away from the fork (y in [2.6, 3.6]) and the tips.
    const double y = n.position.y();
    if (y > 2.6 && y < 3.6) continue;
    if (n.children.empty()) continue;
    double best = 1e300, radius = 0;
    for (const auto& c : cyls) {
      const double d = test::distanceToSegment(n.position, c.a, c.b);
      if (d < best) {
        best = d;
        radius = c.radius;
      }
    }
    EXPECT_NEAR(n.radius, radius, 0.1 * radius) << "node " << i;
    EXPECT_LT(best, 0.25 * radius) << "node " << i;
    ++checked;
  }
  EXPECT_GE(checked, 8);
  EXPECT_GE(accepted, static_cast<int>(res.model.size()) * 3 / 4);
}

// The sketch hands over the model: rebuilt by the sketch path (viewer, `reconstruct --sketch`),
// after a trip through the sketch file, it gives the automatic mesh; with the kept circles
// cleared (`reconstruct --refit`) the same rebuild fits every node from the cloud.
TEST(SkeletonSketch, TheSketchRebuildsTheAutomaticModel) {
  const auto cloud = test::sampleCylinders(test::threeLevelTree(), 0.02, 0.003, 2);
  for (double ratio : {2.0, 0.6}) {  // 0.6: many fits rejected, forks without a fit among them
    skeleton::AutoSkeletonOptions o;
    o.radii.maxRadiusRatio = ratio;
    const auto res = skeleton::autoSkeletonSketch(cloud, o);
    ASSERT_FALSE(res.mesh.empty());
    for (std::size_t i = 0; i < res.model.size(); ++i) {
      const sketch::Node& node = res.sketch.node(static_cast<sketch::NodeId>(i));
      EXPECT_TRUE(node.params.enabled) << "node " << i;
      ASSERT_TRUE(node.kept.has_value()) << "node " << i;
      EXPECT_EQ(node.kept->radius, res.model[i].radius) << "node " << i;
    }
    std::stringstream file;
    io::writeSketch(file, res.sketch);
    const sketch::Sketch back = io::readSketch(file, "auto.json");
    const auto rebuilt = recon::reconstruct(cloud, back);
    ASSERT_EQ(rebuilt.mesh.triangles, res.mesh.triangles) << "ratio " << ratio;
    ASSERT_EQ(rebuilt.mesh.vertices.size(), res.mesh.vertices.size());
    double worst = 0;
    for (std::size_t v = 0; v < res.mesh.vertices.size(); ++v)
      worst = std::max(worst, (rebuilt.mesh.vertices[v] - res.mesh.vertices[v]).norm());
    EXPECT_LT(worst, 1e-12) << "ratio " << ratio;
    std::size_t kept = 0;
    for (const auto& [id, r] : rebuilt.results) kept += r.kept;
    EXPECT_EQ(kept, res.sketch.keptCircleCount());
    EXPECT_EQ(kept, res.model.size());
  }
  sketch::Sketch refit = skeleton::autoSkeletonSketch(cloud).sketch;
  refit.clearKeptCircles();
  EXPECT_EQ(refit.keptCircleCount(), 0u);
  const auto fromCloud = recon::reconstruct(cloud, refit);
  std::size_t fitted = 0;
  for (const auto& [id, r] : fromCloud.results) {
    EXPECT_FALSE(r.kept);
    fitted += r.status == fit::NodeStatus::Fitted;
  }
  EXPECT_GE(fitted, fromCloud.results.size() / 2);
}

// The automatic path is a sketch source: its mesh is recon's sweep of its sketch, and its fits are
// recon's fits of the skeleton's nodes (same seeds, same options), not a second fitting path.
TEST(SkeletonSketch, FitsAndMeshComeFromRecon) {
  const auto cloud = test::sampleCylinders(test::yTree(), 0.02, 0.003, 7);
  skeleton::AutoSkeletonOptions o;
  const auto res = skeleton::autoSkeletonSketch(cloud, o);
  ASSERT_FALSE(res.model.empty());
  recon::ReconstructionOptions ro;
  ro.fit = o.fit;
  ro.fit.circle.inlierThreshold =
      std::max(ro.fit.circle.inlierThreshold, o.minInlierBandVoxels * res.skeleton.graph.voxelSize);
  ro.seed = o.seed;
  ro.sweep.ringVertices = o.ringVertices;
  const auto direct = recon::reconstruct(cloud, skeleton::skeletonToSketch(res.skeleton), ro);
  ASSERT_EQ(direct.results.size(), res.fits.size());
  for (std::size_t i = 0; i < res.fits.size(); ++i) {
    const auto& r = direct.results.at(static_cast<sketch::NodeId>(i));
    EXPECT_EQ(r.status, res.fits[i].status) << "node " << i;
    EXPECT_EQ(r.radius, res.fits[i].radius) << "node " << i;
  }
  std::vector<std::uint64_t> reported;
  const auto again = skeleton::autoSkeletonSketch(cloud, o, [&](std::uint64_t done, std::uint64_t total) {
    EXPECT_LE(done, total);
    reported.push_back(done);
  });
  ASSERT_FALSE(reported.empty());
  EXPECT_EQ(reported.back(), res.model.size());
  EXPECT_EQ(again.mesh.triangles, res.mesh.triangles);
}

TEST(SkeletonSketch, PresetsNameTheCondition) {
  const auto off = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOff, geom::UpAxis::Z);
  const auto on = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOn, geom::UpAxis::Z);
  EXPECT_EQ(off.skeleton.up, geom::UpAxis::Z);
  EXPECT_EQ(on.skeleton.up, geom::UpAxis::Z);
  EXPECT_FALSE(off.skeleton.leafEntryPositions);
  EXPECT_TRUE(on.skeleton.leafEntryPositions);
  EXPECT_EQ(on.skeleton.binWidthVoxels, skeleton::leafOnSkeletonOptions().binWidthVoxels);
  EXPECT_TRUE(off.completion.enabled);
  EXPECT_FALSE(on.completion.enabled);  // leaf-on, the points off the model are leaves
  const geom::PointCloud one{{Vec3(0, 0, 0)}};
  for (auto bad : {&skeleton::CompletionRules::marginVoxels, &skeleton::CompletionRules::maxGapVoxels}) {
    skeleton::AutoSkeletonOptions o;
    o.completion.*bad = -1;
    EXPECT_THROW(skeleton::autoSkeletonSketch(one, o), OptionsError);
  }
  skeleton::AutoSkeletonOptions o;
  o.completion.minPoints = 0;
  EXPECT_THROW(skeleton::autoSkeletonSketch(one, o), OptionsError);
}

// An edit in the handed-over sketch re-fits the node it touches, from the cloud, and no other.
TEST(SkeletonSketch, AnEditRefitsOnlyTheTouchedNode) {
  const auto cloud = test::sampleCylinders(test::yTree(), 0.02, 0.003, 7);
  const auto res = skeleton::autoSkeletonSketch(cloud);
  sketch::Sketch sk = res.sketch;
  recon::Reconstruction rec(cloud);
  rec.update(sk);
  const std::size_t resolved = rec.fitCount();
  const sketch::NodeId id = 2;
  ASSERT_TRUE(sk.node(id).kept.has_value());
  sketch::SamplingParams p = sk.node(id).params;
  p.lineEpsilon *= 1.5;
  sk.setParams(id, p);
  EXPECT_EQ(rec.update(sk), (std::vector<sketch::NodeId>{id}));
  EXPECT_EQ(rec.fitCount(), resolved + 1);
  EXPECT_FALSE(rec.result(id)->kept);
  EXPECT_TRUE(rec.result(id + 1)->kept);
  ASSERT_EQ(rec.result(id)->status, fit::NodeStatus::Fitted);  // measured from the trunk's points
  EXPECT_GT(rec.result(id)->inlierIndices.size(), 10u);
}

// The fits' band follows the cloud's scale: the same tree in millimetres is fitted as in metres
// (without the voxel floor its 0.01-unit band would be 0.01 mm and most fits would fail).
TEST(SkeletonSketch, FitsDoNotDependOnTheCloudsUnits) {
  const auto metres = test::sampleCylinders(test::yTree(), 0.02, 0.003, 7);
  geom::PointCloud millimetres = metres;
  for (auto& p : millimetres.positions) p *= 1000.0;
  auto accepted = [](const skeleton::AutoSkeletonResult& r) {
    std::size_t n = 0;
    for (char a : r.fitAccepted) n += a != 0;
    return n;
  };
  const auto m = skeleton::autoSkeletonSketch(metres);
  const auto mm = skeleton::autoSkeletonSketch(millimetres);
  ASSERT_EQ(m.model.size(), mm.model.size());  // the skeleton is scale-free
  EXPECT_GE(accepted(mm), accepted(m) * 9 / 10);
  EXPECT_GE(accepted(m), m.model.size() * 3 / 4);
  for (std::size_t i = 0; i < m.model.size(); ++i)
    EXPECT_NEAR(mm.model[i].radius / 1000.0, m.model[i].radius, 0.1 * m.model[i].radius) << "node " << i;
  skeleton::AutoSkeletonOptions fixedBand;
  fixedBand.minInlierBandVoxels = 0;
  EXPECT_LT(accepted(skeleton::autoSkeletonSketch(millimetres, fixedBand)), accepted(m) / 2);
  fixedBand.minInlierBandVoxels = -1;
  EXPECT_THROW(skeleton::autoSkeletonSketch(metres, fixedBand), OptionsError);
}

// A cloud written twice (every point repeated, the copies after the originals) gives the model it
// gives once: the repeats are set aside, and the voxels are sized by the surfaces' sampling. Before,
// the doubled density made finer voxels and another model.
TEST(SkeletonSketch, RepeatedPointsDoNotChangeTheModel) {
  const auto once = test::sampleCylinders(test::yTree(), 0.02, 0.003, 7);
  geom::PointCloud twice = once;
  twice.positions.insert(twice.positions.end(), once.positions.begin(), once.positions.end());
  const auto a = skeleton::autoSkeletonSketch(once);
  const auto b = skeleton::autoSkeletonSketch(twice);
  EXPECT_EQ(a.strays.repeated, 0u);
  EXPECT_EQ(b.strays.repeated, once.size());
  EXPECT_EQ(b.skeleton.graph.voxelSize, a.skeleton.graph.voxelSize);
  ASSERT_EQ(b.model.size(), a.model.size());
  for (std::size_t i = 0; i < a.model.size(); ++i) EXPECT_EQ(b.model[i].radius, a.model[i].radius) << "node " << i;
  EXPECT_EQ(b.mesh.vertices.size(), a.mesh.vertices.size());
}

TEST(SkeletonSketch, EmptyCloud) {
  const auto res = skeleton::autoSkeletonSketch(geom::PointCloud{});
  EXPECT_TRUE(res.model.empty());
  EXPECT_TRUE(res.sketch.empty());
  EXPECT_TRUE(res.mesh.empty());
}

TEST(SkeletonSketch, EveryNodeIsAKeptCircleForksWithoutAFitToo) {
  // Forks without an accepted fit keep their ring in the sketch (and so in the mesh), at the
  // model's position and radius: the sketch a person edits is the model.
  const auto cloud = test::sampleCylinders(test::threeLevelTree(), 0.02, 0.003, 2);
  skeleton::AutoSkeletonOptions o;
  o.radii.maxRadiusRatio = 1e-6;  // reject (nearly) every fit, so the forks have none
  const auto res = skeleton::autoSkeletonSketch(cloud, o);
  ASSERT_EQ(res.sketch.size(), res.model.size());
  int unfittedForks = 0;
  for (std::size_t i = 0; i < res.model.size(); ++i) {
    unfittedForks += res.model[i].parent >= 0 && res.model[i].children.size() >= 2 && !res.fitAccepted[i];
    const sketch::Node& node = res.sketch.node(static_cast<sketch::NodeId>(i));
    ASSERT_TRUE(node.kept.has_value()) << "node " << i;
    EXPECT_EQ(node.kept->centre, res.model[i].position) << "node " << i;
    EXPECT_EQ(node.kept->radius, res.model[i].radius) << "node " << i;
  }
  EXPECT_GE(unfittedForks, 1);
}

TEST(SkeletonSketch, ABranchTapersPastItsLastFit) {
  // A trunk and four side branches with fits on the tree's law r = 0.05·sqrt(carried + 1), and
  // one more side branch fitted only at its base. Past that fit the branch follows the law's
  // shape scaled to the fit (tapering towards its tip), not the fit's radius out to the tip; a
  // branch with no fit at all takes the law itself, not the level sets' own estimates.
  std::vector<skeleton::SkeletonNode> nodes;
  for (int i = 0; i < 20; ++i) nodes.push_back(chainNode(i - 1, i, 0.5));
  auto side = [&](int at, int count, double dx) {
    int parent = at;
    const std::size_t first = nodes.size();
    for (int k = 1; k <= count; ++k) {
      skeleton::SkeletonNode n = chainNode(parent, at, 0.5);
      n.position = Vec3(dx * k, at, 0);
      n.branchOrder = 1;
      nodes.push_back(n);
      parent = static_cast<int>(nodes.size()) - 1;
    }
    return first;
  };
  for (int at : {4, 8, 12, 16}) side(at, 5, 1.0);
  const std::size_t once = side(6, 8, -1.0), never = side(10, 6, -1.0);
  nodes = linkUp(nodes);
  const std::vector<double> carried = carriedSegments(nodes);
  std::vector<double> fitted(nodes.size());
  std::vector<char> valid(nodes.size(), 1);
  for (std::size_t i = 0; i < nodes.size(); ++i) fitted[i] = 0.05 * std::sqrt(carried[i] + 1.0);
  for (std::size_t i = once + 1; i < once + 8; ++i) valid[i] = 0;
  for (std::size_t i = never; i < never + 6; ++i) valid[i] = 0;
  skeleton::RadiusRules rules;
  rules.medianWindow = 1;
  const auto r = skeleton::regularizeRadii(nodes, fitted, valid, rules);
  EXPECT_NEAR(r[once], fitted[once], 1e-9);
  for (std::size_t i = once + 1; i < once + 8; ++i) EXPECT_LT(r[i], r[i - 1]) << i;
  EXPECT_LT(r[once + 7], 0.6 * r[once]);
  for (std::size_t i = never; i < never + 6; ++i) {
    EXPECT_LT(r[i], 0.5) << i;  // the level sets' estimate was 0.5
    EXPECT_NEAR(r[i], fitted[i], 0.25 * fitted[i]) << i;
  }
}

// A twig that leaves its limb at a narrow angle (here 4.4°, 0.1 m from the 0.06 m limb's surface
// at its tip, voxels of 0.05 m) lies within a voxel or two of the limb for its length: the level sets hold both
// as one piece and one node on the limb, and the twig's points lie outside the model. The completion models those
// points on their own and grafts the part onto the limb, so the model explains them; the tree stays one tree.
TEST(SkeletonSketch, ATwigAlongItsLimbIsGraftedOn) {
  const std::vector<test::Cyl> cyls = {{Vec3(0, 0, 0), Vec3(0, 3, 0), 0.06, -1},
                                       {Vec3(0.04, 1.0, 0), Vec3(0.18, 2.8, 0), 0.015, 0}};
  const auto cloud = test::sampleCylinders(cyls, 0.012, 0.002, 5);
  std::vector<std::size_t> twig;  // the twig's points, where it is off the trunk's surface
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (test::distanceToSegment(cloud.positions[i], cyls[1].a, cyls[1].b) < 0.025 &&
        test::distanceToSegment(cloud.positions[i], cyls[0].a, cyls[0].b) > cyls[0].radius + 0.03)
      twig.push_back(i);
  ASSERT_GT(twig.size(), 100u);
  struct Outcome {
    // Share of those twig points the model covers: inside it or at most 1.5 cm (the twig's radius)
    // outside its surface. How thick the grafted twig is follows the radius rules, not the completion.
    double explained = 0;
    std::size_t nodes = 0, ends = 0;
  };
  auto run = [&](bool complete) {
    skeleton::AutoSkeletonOptions o;
    o.skeleton.graph.voxelSize = 0.05;
    o.completion.enabled = complete;
    const auto res = skeleton::autoSkeletonSketch(cloud, o);
    const compare::CylinderModelIndex index(skeleton::cylinderModelFromSkeleton(res.model));
    Outcome out;
    for (std::size_t i : twig) out.explained += index.signedDistance(cloud.positions[i]) < 0.015;
    out.explained /= static_cast<double>(twig.size());
    out.nodes = res.model.size();
    out.ends = skeleton::countEnds(res.model);
    // One tree: every node but the root has a parent before it, and the sketch holds them all.
    for (std::size_t i = 1; i < res.model.size(); ++i) {
      EXPECT_GE(res.model[i].parent, 0) << i;
      EXPECT_LT(res.model[i].parent, static_cast<std::int32_t>(i)) << i;
    }
    EXPECT_EQ(res.sketch.size(), res.model.size());
    EXPECT_EQ(res.fits.size(), res.model.size());
    double thickest = 0;  // the grafted twig's thickest node
    for (const auto& n : res.model)
      if (n.grafted) thickest = std::max(thickest, n.radius);
    if (complete) EXPECT_LT(thickest, 0.03);  // the twig is 0.015 thick, its limb 0.06
    std::printf("completion %d: %zu nodes, %zu ends, %.3f of the twig's points explained, grafts up to %.4f\n",
                complete, out.nodes, out.ends, out.explained, thickest);
    return out;
  };
  const Outcome without = run(false), with = run(true);
  EXPECT_LT(without.explained, 0.1);  // measured 0.000 without, 1.000 with
  EXPECT_GT(with.explained, 0.75);
  EXPECT_GT(with.nodes, without.nodes);
  EXPECT_LE(with.ends, without.ends + 1);  // the twig is one branch, not a fringe of stubs
}

TEST(SkeletonSketch, AGraftedPartCarriesNoMoreThanThePipeModelGives) {
  // A limb of five nodes 0.1 apart (radius 0.06) and a part of four nodes grafted on its third,
  // each fitted as thick as the limb: the part thins as the pipe model says, the limb keeps its radii.
  std::vector<skeleton::SkeletonNode> nodes(9);
  for (int i = 0; i < 5; ++i) {
    nodes[i].position = Vec3(0, 0.1 * i, 0);
    nodes[i].parent = i - 1;
    nodes[i].radius = 0.06;
  }
  for (int k = 0; k < 4; ++k) {
    nodes[5 + k].position = Vec3(0.1 * (k + 1), 0.2, 0);
    nodes[5 + k].parent = k == 0 ? 2 : 4 + k;
    nodes[5 + k].radius = 0.06;
  }
  skeleton::detail::capByPipeModel(nodes, 5);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(nodes[i].radius, 0.06) << i;
  const std::vector<double> carried = skeleton::detail::carriedLengths(nodes);
  for (int i = 5; i < 9; ++i) {
    const auto& p = nodes[nodes[i].parent];
    EXPECT_NEAR(nodes[i].radius, p.radius * std::sqrt(carried[i] / carried[nodes[i].parent]), 1e-12) << i;
    EXPECT_LT(nodes[i].radius, p.radius) << i;
  }
  // The tip carries 0.2 (its segment and one more beyond its end), the host 0.8: half its radius.
  EXPECT_NEAR(nodes[8].radius, 0.5 * 0.06, 1e-12);
}

namespace {

// A small tree whose limbs are thinner than its scan's noise: a trunk 8 cm in radius and 2 m tall,
// eight limbs of 1.5-2 cm leaving it in two whorls, each with two twigs of 1 cm 12 cm apart.
std::vector<test::Cyl> limbsUnderTheNoise() {
  std::vector<test::Cyl> c{{Vec3(0, 0, 0), Vec3(0, 2.0, 0), 0.08, -1}};
  for (int k = 0; k < 8; ++k) {
    const double a = 2.0 * M_PI * (k + 0.5 * (k / 4)) / 4.0, y = k < 4 ? 1.0 : 1.6;
    const Vec3 base(0, y, 0), dir = Vec3(std::cos(a), 0.6, std::sin(a)).normalized();
    const Vec3 tip = base + 0.9 * dir;
    c.push_back({base, tip, k % 2 ? 0.015 : 0.02, 0});
    const int limb = static_cast<int>(c.size()) - 1;
    for (int t = -1; t <= 1; t += 2)
      c.push_back({tip, tip + 0.35 * dir + Vec3(-std::sin(a), 0, std::cos(a)) * (0.12 * t), 0.01, limb});
  }
  return c;
}

// The volume of the branches off the stem: the tree's limbs and twigs, the model's nodes of order 1
// and more (from each node's parent).
double branchVolume(const std::vector<test::Cyl>& tree) {
  double v = 0;
  for (const auto& c : tree)
    if (c.parent >= 0) v += M_PI * c.radius * c.radius * (c.b - c.a).norm();
  return v;
}
double branchVolume(const skeleton::AutoSkeletonResult& r) {
  double v = 0;
  for (const auto& n : r.model)
    if (n.parent >= 0 && n.branchOrder > 0)
      v += M_PI * n.radius * n.radius * (n.position - r.model[static_cast<std::size_t>(n.parent)].position).norm();
  return v;
}

}  // namespace

// Under 2 cm of noise the limbs' points are shells twice their radius wide, and neighbouring twigs
// share one: the skeleton on the scan's own points ran between them and the limbs came out at 1.8
// times their volume. On the points drawn together by twice the noise each limb is a line of
// points again: 0.96 times. A scan whose noise is under the voxel is modelled on its own points.
TEST(SkeletonSketch, ANoisyScansSkeletonIsGrownOnItsPointsDrawnTogether) {
  const auto tree = limbsUnderTheNoise();
  skeleton::AutoSkeletonOptions o = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOff, geom::UpAxis::Y);
  const geom::PointCloud noisy = test::sampleCylinders(tree, 0.01, 0.02, 3);
  const skeleton::AutoSkeletonResult drawn = skeleton::autoSkeletonSketch(noisy, o);
  EXPECT_GT(drawn.contraction, 0.0);
  EXPECT_NEAR(branchVolume(drawn), branchVolume(tree), 0.25 * branchVolume(tree));
  skeleton::AutoSkeletonOptions off = o;
  off.contractionNoises = 0;
  const skeleton::AutoSkeletonResult own = skeleton::autoSkeletonSketch(noisy, off);
  EXPECT_EQ(own.contraction, 0.0);
  EXPECT_GT(branchVolume(own), 1.5 * branchVolume(tree));

  const geom::PointCloud clean = test::sampleCylinders(tree, 0.01, 0.001, 3);
  const skeleton::AutoSkeletonResult asIs = skeleton::autoSkeletonSketch(clean, o);
  EXPECT_EQ(asIs.contraction, 0.0);
  EXPECT_EQ(asIs.model.size(), skeleton::autoSkeletonSketch(clean, off).model.size());
}
