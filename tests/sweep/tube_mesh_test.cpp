#include "treesketch/sweep/tube_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "treesketch/util/error.h"

namespace treesketch::sweep {
namespace {

using geom::Vec3;

// Directed-edge census: closed and consistently oriented means every undirected edge is used by
// exactly two triangles, once in each direction.
void expectClosedAndOriented(const geom::TriMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1) << "edge " << e.first << "-" << e.second << " used twice in one direction";
    auto rev = directed.find({e.second, e.first});
    EXPECT_TRUE(rev != directed.end()) << "edge " << e.first << "-" << e.second << " is a boundary edge";
  }
}

Vec3 faceNormal(const geom::TriMesh& m, const std::array<std::uint32_t, 3>& t) {
  return (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
}

double signedVolume(const geom::TriMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

// A straight chain of 5 discs on the y axis (radius 0.5, y = 0..4), with plane normals of
// alternating sign (the sweep must not depend on the sketch's normal signs).
std::vector<SweepNode> straightChain() {
  std::vector<SweepNode> nodes;
  for (int i = 0; i < 5; ++i) {
    SweepNode n;
    n.id = 10 + i;
    n.parent = i == 0 ? kNoNode : 10 + i - 1;
    n.fitted = true;
    n.disc = {Vec3(0, i, 0), Vec3(0, i % 2 ? -1 : 1, 0), 0.5};
    nodes.push_back(n);
  }
  return nodes;
}

TEST(TubeSweeper, StraightTubeIsClosedWithOutwardNormals) {
  SweepOptions opt;
  opt.ringVertices = 12;
  geom::TriMesh m = sweepTubes(straightChain(), opt);
  // 5 rings + 2 cap centres; 4 bands of 2K triangles + 2 caps of K.
  EXPECT_EQ(m.vertices.size(), 5u * 12 + 2);
  EXPECT_EQ(m.triangles.size(), 4u * 24 + 2 * 12);
  m.checkConsistent();
  expectClosedAndOriented(m);
  const Vec3 centroid(0, 2, 0);
  for (const auto& t : m.triangles) {
    Vec3 n = faceNormal(m, t);
    ASSERT_GT(n.norm(), 1e-6) << "degenerate triangle";
    Vec3 c = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0;
    // Convex tube: every face points away from the centre; band faces away from the axis.
    EXPECT_GT(n.dot(c - centroid), 0.0);
    if (std::abs(n.normalized().y()) < 0.5) EXPECT_GT(n.dot(Vec3(c.x(), 0, c.z())), 0.0);
  }
  // Volume of the 12-gon prism: (K/2) r² sin(2π/K) · length.
  double expected = 6 * 0.25 * std::sin(2 * M_PI / 12) * 4.0;
  EXPECT_NEAR(signedVolume(m), expected, 1e-9);
}

TEST(TubeSweeper, TiltedPlanesOnACurveDoNotTwist) {
  // Discs along a quarter circle, planes tilted ±15° off the tangent: a twisted band would
  // cross itself and lose volume.
  std::vector<SweepNode> nodes;
  const double bend = 5.0, r = 0.3;
  for (int i = 0; i < 9; ++i) {
    double a = (M_PI / 2) * i / 8;
    Vec3 p(bend * (1 - std::cos(a)), bend * std::sin(a), 0);
    Vec3 tangent(std::sin(a), std::cos(a), 0);
    double tilt = (i % 2 ? 1 : -1) * 15.0 * M_PI / 180;
    Vec3 n = Eigen::AngleAxisd(tilt, Vec3::UnitZ()) * tangent;
    SweepNode s;
    s.id = i;
    s.parent = i == 0 ? kNoNode : i - 1;
    s.fitted = true;
    s.disc = {p, i % 3 == 0 ? Vec3(-n) : n, r};
    nodes.push_back(s);
  }
  geom::TriMesh m = sweepTubes(nodes, {});
  expectClosedAndOriented(m);
  for (const auto& t : m.triangles) EXPECT_GT(faceNormal(m, t).norm(), 1e-8);
  // Tilted discs are ellipse-free circles, so the volume is close to π r² × arc length.
  double expected = M_PI * r * r * bend * M_PI / 2;
  EXPECT_NEAR(signedVolume(m), expected, 0.1 * expected);
}

TEST(TubeSweeper, SkippedNodesAreBridged) {
  auto nodes = straightChain();
  nodes[2].fitted = false;  // node 12 skipped: 13 joins 11
  TubeSweeper s;
  s.update(nodes);
  std::vector<SegmentKey> expected = {{10, 11}, {11, 13}, {13, 14}};
  EXPECT_EQ(s.segmentKeys(), expected);
  expectClosedAndOriented(s.mesh());
  nodes[0].fitted = false;  // the root skipped: 11 becomes a start with a cap
  nodes[4].disc.radius = 0.0;  // an unusable disc counts as not fitted
  s.update(nodes);
  expected = {{11, 13}};
  EXPECT_EQ(s.segmentKeys(), expected);
  expectClosedAndOriented(s.mesh());
  auto parents = fittedParents(nodes);
  EXPECT_EQ(parents.at(11), kNoNode);
  EXPECT_EQ(parents.at(13), 11);
  EXPECT_EQ(parents.count(12), 0u);
}

TEST(TubeSweeper, BranchingAndSingleNode) {
  std::vector<SweepNode> nodes(3);
  nodes[0] = {0, kNoNode, true, {Vec3(0, 0, 0), Vec3(0, 1, 0), 0.4}};
  nodes[1] = {1, 0, true, {Vec3(-1, 2, 0), Vec3(-1, 2, 0).normalized(), 0.2}};
  nodes[2] = {2, 0, true, {Vec3(1, 2, 0), Vec3(1, 2, 0).normalized(), 0.2}};
  TubeSweeper s;
  s.update(nodes);
  std::vector<SegmentKey> expected = {{0, 1}, {0, 2}};
  EXPECT_EQ(s.segmentKeys(), expected);
  // 3 caps (root + two tips), 2 bands.
  EXPECT_EQ(s.mesh().triangles.size(), 3u * 16 + 2u * 32);

  std::vector<SweepNode> single = {{5, kNoNode, true, {Vec3(1, 1, 1), Vec3(0, 0, 1), 0.1}}};
  geom::TriMesh m = sweepTubes(single);
  EXPECT_EQ(m.triangles.size(), 32u);  // a flat disc, closed (two fans)
  expectClosedAndOriented(m);
  EXPECT_TRUE(sweepTubes({}).empty());
}

TEST(TubeSweeper, EditsRebuildOnlyTheTouchedBands) {
  auto nodes = straightChain();
  TubeSweeper s;
  s.update(nodes);
  EXPECT_EQ(s.segmentBuilds(), 4u);
  s.update(nodes);  // nothing changed
  EXPECT_EQ(s.segmentBuilds(), 4u);
  nodes[2].disc.radius = 0.6;  // the middle node: its two bands
  s.update(nodes);
  EXPECT_EQ(s.segmentBuilds(), 6u);
  nodes[4].disc.centre.x() += 0.1;  // the tip: one band
  s.update(nodes);
  EXPECT_EQ(s.segmentBuilds(), 7u);
  nodes.pop_back();  // delete the tip: no new band
  s.update(nodes);
  EXPECT_EQ(s.segmentBuilds(), 7u);
  EXPECT_EQ(s.segmentKeys().size(), 3u);
  // The incremental mesh equals a fresh sweep.
  geom::TriMesh fresh = sweepTubes(nodes);
  EXPECT_EQ(s.mesh().vertices, fresh.vertices);
  EXPECT_EQ(s.mesh().triangles, fresh.triangles);
}

// Random edit sequences on a branching sketch (discs moved, nodes skipped and fitted again,
// re-parented, deleted, added): after every update the incremental mesh equals a fresh sweep.
TEST(TubeSweeper, RandomEditsMatchAFreshSweep) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u01(0, 1);
  std::vector<SweepNode> nodes;
  NodeId nextId = 0;
  auto addNode = [&](NodeId parent) {
    SweepNode n;
    n.id = nextId++;
    n.parent = parent;
    n.fitted = true;
    n.disc = {Vec3(u01(rng), 4 * u01(rng), u01(rng)), Vec3(0.2 * u01(rng), 1, 0.2 * u01(rng)).normalized(),
              0.1 + 0.3 * u01(rng)};
    nodes.push_back(n);
  };
  addNode(kNoNode);
  for (int i = 0; i < 11; ++i) addNode(nodes[std::size_t(u01(rng) * double(nodes.size()))].id);
  TubeSweeper s;
  for (int step = 0; step < 60; ++step) {
    const std::size_t i = std::size_t(u01(rng) * double(nodes.size()));
    auto& n = nodes[i];
    switch (step % 5) {
      case 0: n.disc.centre.x() += 0.05; break;
      case 1: n.fitted = !n.fitted; break;
      case 2: n.disc.radius *= 1.1; break;
      case 3:  // re-parent onto an earlier node (parents always have smaller ids: no cycle)
        if (i > 0) n.parent = nodes[std::size_t(u01(rng) * double(i))].id;
        break;
      case 4:
        if (nodes.size() > 4 && step % 10 == 4) {
          const NodeId gone = nodes.back().id;  // a node that nothing can be the parent of...
          for (auto& m : nodes)
            if (m.parent == gone) m.parent = kNoNode;  // ...or that its children lose
          nodes.pop_back();
        } else {
          addNode(nodes[std::size_t(u01(rng) * double(nodes.size()))].id);
        }
        break;
    }
    s.update(nodes);
    const geom::TriMesh fresh = sweepTubes(nodes);
    ASSERT_EQ(s.mesh().vertices, fresh.vertices) << "step " << step;
    ASSERT_EQ(s.mesh().triangles, fresh.triangles) << "step " << step;
  }
  EXPECT_FALSE(s.mesh().empty());
}

TEST(TubeSweeper, BadInput) {
  SweepOptions opt;
  opt.ringVertices = 2;
  EXPECT_THROW(TubeSweeper{opt}, OptionsError);
  std::vector<SweepNode> cycle(2);
  cycle[0] = {0, 1, false, {}};
  cycle[1] = {1, 0, false, {}};
  cycle.push_back({2, 0, true, {Vec3(0, 0, 0), Vec3(0, 1, 0), 1.0}});
  EXPECT_THROW(fittedParents(cycle), OptionsError);
  // NaN discs count as not fitted.
  std::vector<SweepNode> nan = {{0, kNoNode, true, {Vec3(NAN, 0, 0), Vec3(0, 1, 0), 1.0}}};
  EXPECT_TRUE(sweepTubes(nan).empty());
}

}  // namespace
}  // namespace treesketch::sweep
