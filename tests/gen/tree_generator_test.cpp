#include "treesketch/gen/tree_generator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "treesketch/util/error.h"

namespace treesketch::gen {
namespace {

using geom::Vec3;

void expectSameMesh(const geom::TriMesh& a, const geom::TriMesh& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.triangles, b.triangles);
  for (std::size_t i = 0; i < a.vertices.size(); ++i) ASSERT_EQ(a.vertices[i], b.vertices[i]) << "vertex " << i;
}

TEST(TreeGenerator, SameSeedIsBitIdenticalAcrossRunsAndThreads) {
  TreeOptions o;
  o.seed = 1234;
  GeneratedTree a = generateTree(o);
  GeneratedTree b, c;
  std::thread t1([&] { b = generateTree(o); });
  std::thread t2([&] { c = generateTree(o); });
  t1.join();
  t2.join();
  expectSameMesh(a.branches.mesh, b.branches.mesh);
  expectSameMesh(a.branches.mesh, c.branches.mesh);
  expectSameMesh(a.leaves, b.leaves);
  EXPECT_EQ(a.skeleton.sectionCount(), c.skeleton.sectionCount());
}

TEST(TreeGenerator, DifferentSeedsDiffer) {
  TreeOptions o;
  o.seed = 1;
  GeneratedTree a = generateTree(o);
  o.seed = 2;
  GeneratedTree b = generateTree(o);
  bool differs = a.branches.mesh.vertices.size() != b.branches.mesh.vertices.size();
  for (std::size_t i = 0; !differs && i < a.branches.mesh.vertices.size(); ++i)
    differs = a.branches.mesh.vertices[i] != b.branches.mesh.vertices[i];
  EXPECT_TRUE(differs);
}

TEST(TreeGenerator, DefaultLooksLikeASmallTree) {
  GeneratedTree t = generateTree(TreeOptions{});
  const Skeleton& s = t.skeleton;
  geom::BBox box = bounds(s);
  EXPECT_GT(box.max.y(), 6.0);
  EXPECT_LT(box.max.y(), 11.0);
  EXPECT_NEAR(box.min.y(), -0.15, 0.05);  // the capped base ring (trunk axis tilts a little)
  EXPECT_EQ(s.branches[0].sections[0].centre, Vec3::Zero());
  EXPECT_EQ(s.branches[0].sections[0].radius, 0.15);
  int firstOrder = 0;
  for (const auto& b : s.branches) firstOrder += b.level == 1;
  EXPECT_GE(firstOrder, 10);
  EXPECT_LE(firstOrder, 20);
  EXPECT_EQ(s.maxLevel(), 3);
  EXPECT_GE(t.branches.mesh.triangles.size(), 10000u);
  EXPECT_LE(t.branches.mesh.triangles.size(), 40000u);
  EXPECT_GT(t.leaves.triangles.size(), 500u);
  // The trunk grows up, not sideways.
  EXPECT_GT(s.branches[0].sections.back().centre.y(), 5.0);
  EXPECT_LT(std::hypot(s.branches[0].sections.back().centre.x(), s.branches[0].sections.back().centre.z()), 2.0);
}

TEST(TreeGenerator, MeshIsConsistentAndVerticesSitOnTheirSections) {
  GeneratedTree t = generateTree(TreeOptions{});
  const geom::TriMesh& m = t.branches.mesh;
  ASSERT_NO_THROW(m.checkConsistent());
  ASSERT_EQ(t.branches.vertexBranch.size(), m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    ASSERT_TRUE(m.vertices[v].allFinite());
    const Section& sec = t.skeleton.branches[t.branches.vertexBranch[v]].sections[t.branches.vertexSection[v]];
    ASSERT_NEAR(distanceToSectionAxis(sec, m.vertices[v]), sec.radius, 1e-9 + 1e-9 * sec.radius);
    ASSERT_NEAR((m.vertices[v] - sec.centre).dot(sec.axis), 0.0, 1e-9);
  }
  for (const auto& tri : m.triangles) {
    double area = 0.5 * (m.vertices[tri[1]] - m.vertices[tri[0]]).cross(m.vertices[tri[2]] - m.vertices[tri[0]]).norm();
    ASSERT_GT(area, 1e-12);
  }
  ASSERT_NO_THROW(t.leaves.checkConsistent());
  for (const Vec3& v : t.leaves.vertices) ASSERT_TRUE(v.allFinite());
}

TEST(TreeGenerator, HierarchyFollowsThePipeModel) {
  for (const std::string& preset : presetNames()) {
    SCOPED_TRACE(preset);
    Skeleton s = generateSkeleton(presetOptions(preset));
    ASSERT_EQ(findSkeletonProblem(s), "");
    for (const SkeletonBranch& b : s.branches) {
      for (std::size_t i = 1; i < b.sections.size(); ++i) EXPECT_LE(b.sections[i].radius, b.sections[i - 1].radius);
      if (b.parent < 0) continue;
      const SkeletonBranch& p = s.branches[b.parent];
      EXPECT_EQ(b.level, p.level + 1);
      EXPECT_LE(b.sections[0].radius, p.sections[b.parentSection].radius);
      EXPECT_EQ(b.sections[0].centre, p.sections[b.parentSection].centre);  // starts on the parent's axis
      EXPECT_GE(b.sections[0].radius, TreeOptions{}.minRadius);
    }
  }
}

TEST(TreeGenerator, ZUpIsTheYUpTreeRotated) {
  TreeOptions o;
  o.seed = 77;
  GeneratedTree y = generateTree(o);
  o.up = geom::UpAxis::Z;
  GeneratedTree z = generateTree(o);
  EXPECT_EQ(z.skeleton.up, geom::UpAxis::Z);
  ASSERT_EQ(y.branches.mesh.vertices.size(), z.branches.mesh.vertices.size());
  for (std::size_t i = 0; i < y.branches.mesh.vertices.size(); ++i) {
    const Vec3& p = y.branches.mesh.vertices[i];
    ASSERT_EQ(z.branches.mesh.vertices[i], Vec3(p.x(), -p.z(), p.y()));
  }
  EXPECT_EQ(y.branches.mesh.triangles, z.branches.mesh.triangles);
  ASSERT_EQ(y.leaves.vertices.size(), z.leaves.vertices.size());
  for (std::size_t i = 0; i < y.leaves.vertices.size(); ++i)
    ASSERT_EQ(z.leaves.vertices[i], convertUpAxis(y.leaves.vertices[i], geom::UpAxis::Y, geom::UpAxis::Z));
  const Section& tip = z.skeleton.branches[0].sections.back();
  EXPECT_GT(tip.centre.z(), 5.0);
  Skeleton back = z.skeleton;
  convertUpAxis(back, geom::UpAxis::Y);
  EXPECT_EQ(back.branches[0].sections.back().centre, y.skeleton.branches[0].sections.back().centre);
}

TEST(TreeGenerator, DetailRefinesTheSameTree) {
  TreeOptions o;
  o.leaves = false;
  GeneratedTree coarse = generateTree(o);
  o.detail = 2;
  GeneratedTree fine = generateTree(o);
  ASSERT_EQ(coarse.skeleton.branches.size(), fine.skeleton.branches.size());
  for (std::size_t b = 0; b < coarse.skeleton.branches.size(); ++b) {
    const auto& cs = coarse.skeleton.branches[b].sections;
    const auto& fs = fine.skeleton.branches[b].sections;
    ASSERT_EQ(fs.size(), 2 * cs.size() - 1);
    for (std::size_t i = 0; i < cs.size(); ++i) EXPECT_EQ(fs[2 * i].centre, cs[i].centre);
  }
  double ratio = double(fine.branches.mesh.triangles.size()) / double(coarse.branches.mesh.triangles.size());
  EXPECT_GT(ratio, 3.5);
  EXPECT_LT(ratio, 4.5);
  EXPECT_TRUE(coarse.leaves.empty());
}

TEST(TreeGenerator, LeavesAreQuadsOnTheHighestLevelAndDoNotChangeTheBranches) {
  TreeOptions o = presetOptions("sparse");
  GeneratedTree a = generateTree(o);
  int twigs = 0;
  for (const auto& b : a.skeleton.branches) twigs += b.level == a.skeleton.maxLevel();
  EXPECT_EQ(a.leaves.triangles.size(), 2u * o.leavesPerBranch * twigs);
  EXPECT_EQ(a.leaves.vertices.size(), 4u * o.leavesPerBranch * twigs);
  EXPECT_NEAR(a.leaves.area(), twigs * o.leavesPerBranch * o.leafSize * o.leafSize, 1e-9);
  o.leavesPerBranch = 3;
  o.leafSize = 0.2;
  GeneratedTree b = generateTree(o);
  expectSameMesh(a.branches.mesh, b.branches.mesh);
  EXPECT_EQ(b.leaves.triangles.size(), 6u * twigs);
  // Every leaf's first corner pair straddles a point on the surface of a top-level branch.
  geom::BBox box = bounds(a.skeleton);
  for (const Vec3& v : a.leaves.vertices) EXPECT_LT((v - box.centre()).norm(), box.diagonal());
}

TEST(TreeGenerator, PresetsAndBadOptions) {
  for (const std::string& name : presetNames()) EXPECT_NO_THROW(presetOptions(name).validate()) << name;
  EXPECT_THROW(presetOptions("palm"), OptionsError);
  auto expectBad = [](auto mutate) {
    TreeOptions o;
    mutate(o);
    EXPECT_THROW(generateTree(o), OptionsError);
  };
  expectBad([](TreeOptions& o) { o.levels.clear(); });
  expectBad([](TreeOptions& o) { o.levels.resize(6); });
  expectBad([](TreeOptions& o) { o.levels[0].length = -1; });
  expectBad([](TreeOptions& o) { o.levels[1].radius = 1.5; });
  expectBad([](TreeOptions& o) { o.levels[2].sections = 1; });
  expectBad([](TreeOptions& o) { o.levels[2].segments = 2; });
  expectBad([](TreeOptions& o) { o.levels[1].tipRadius = 0; });
  expectBad([](TreeOptions& o) { o.levels[1].gnarlDeg = std::nan(""); });
  expectBad([](TreeOptions& o) { o.levels[0].childStart = 1.0; });
  expectBad([](TreeOptions& o) { o.detail = 0; });
  expectBad([](TreeOptions& o) { o.minRadius = 0; });
  expectBad([](TreeOptions& o) { o.leafSize = -0.1; });
  expectBad([](TreeOptions& o) {  // 1000^3 branches
    for (auto& l : o.levels) l.children = 1000;
  });
}

TEST(TreeGenerator, SingleLevelIsABareTrunk) {
  TreeOptions o;
  o.levels.resize(1);
  GeneratedTree t = generateTree(o);
  ASSERT_EQ(t.skeleton.branches.size(), 1u);
  // Leaves go on the highest level present, here the trunk.
  EXPECT_EQ(t.leaves.triangles.size(), 2u * o.leavesPerBranch);
}

}  // namespace
}  // namespace treesketch::gen
