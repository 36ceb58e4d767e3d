#include "treesketch/gen/branch_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "treesketch/gen/tree_generator.h"
#include "treesketch/util/error.h"

namespace treesketch::gen {
namespace {

using geom::Vec3;

Skeleton straightTrunk(int sections, double radius, double height) {
  Skeleton s;
  SkeletonBranch b;
  for (int i = 0; i < sections; ++i)
    b.sections.push_back({Vec3(0, height * i / (sections - 1), 0), radius, Vec3(0, 1, 0)});
  s.branches = {b};
  return s;
}

/// Signed volume enclosed by a closed, consistently oriented mesh (positive when outward).
double signedVolume(const geom::TriMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

TEST(BranchMesh, StraightTubeIsClosedOutwardAndHasTheRightVolume) {
  const int n = 10;
  Skeleton s = straightTrunk(4, 0.3, 2.0);
  BranchMesh bm = buildBranchMesh(s, BranchMeshOptions{{n}});
  EXPECT_EQ(bm.mesh.vertices.size(), 4u * n);
  EXPECT_EQ(bm.mesh.triangles.size(), 3u * n * 2 + 2u * (n - 2));
  EXPECT_NO_THROW(bm.mesh.checkConsistent());
  // Closed: every undirected edge is used by exactly two triangles, once in each direction.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : bm.mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  double prism = 0.5 * n * 0.3 * 0.3 * std::sin(2 * std::numbers::pi / n) * 2.0;
  EXPECT_NEAR(signedVolume(bm.mesh), prism, 1e-9);
  ASSERT_EQ(bm.branchTriangleCount.size(), 1u);
  EXPECT_EQ(bm.branchTriangleCount[0], bm.mesh.triangles.size());
}

TEST(BranchMesh, RingsLieOnTheirSectionsAndDoNotTwist) {
  // A helix-like bent branch with a child.
  Skeleton s;
  SkeletonBranch trunk;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    double a = 0.25 * i;
    Vec3 c(std::cos(a), 0.4 * i, std::sin(a));
    Vec3 d(-std::sin(a) * 0.25, 0.4, std::cos(a) * 0.25);
    trunk.sections.push_back({c, 0.1 - 0.005 * i, d.normalized()});
  }
  SkeletonBranch child;
  child.id = 1;
  child.parent = 0;
  child.parentSection = 5;
  child.level = 1;
  for (int i = 0; i < 4; ++i)
    child.sections.push_back({trunk.sections[5].centre + Vec3(0.3 * i, 0.1 * i, 0), 0.03, Vec3(3, 1, 0).normalized()});
  s.branches = {trunk, child};
  BranchMesh bm = buildBranchMesh(s, BranchMeshOptions{{8, 5}});
  ASSERT_EQ(bm.vertexBranch.size(), bm.mesh.vertices.size());
  EXPECT_EQ(bm.mesh.vertices.size(), 12u * 8 + 4u * 5);
  for (std::size_t v = 0; v < bm.mesh.vertices.size(); ++v) {
    const Section& sec = s.branches[bm.vertexBranch[v]].sections[bm.vertexSection[v]];
    Vec3 d = bm.mesh.vertices[v] - sec.centre;
    EXPECT_NEAR(d.norm(), sec.radius, 1e-12);
    EXPECT_NEAR(d.dot(sec.axis), 0.0, 1e-12);
    EXPECT_NEAR(distanceToSectionAxis(sec, bm.mesh.vertices[v]), sec.radius, 1e-12);
  }
  // No twist: vertex 0 of consecutive rings moves by a minimal rotation, so its direction
  // stays close (the axis turns by a small angle per section here).
  for (int i = 1; i < n; ++i) {
    Vec3 a = (bm.mesh.vertices[(i - 1) * 8] - s.branches[0].sections[i - 1].centre).normalized();
    Vec3 b = (bm.mesh.vertices[i * 8] - s.branches[0].sections[i].centre).normalized();
    double turn = std::acos(std::clamp(s.branches[0].sections[i - 1].axis.dot(s.branches[0].sections[i].axis), -1.0, 1.0));
    EXPECT_LE(std::acos(std::clamp(a.dot(b), -1.0, 1.0)), turn + 1e-9);
  }
  // A child gets a tip cap but no base cap.
  EXPECT_EQ(bm.branchTriangleCount[1], 3u * 5 * 2 + 3u);
  for (const auto& t : bm.mesh.triangles) {
    Vec3 e = (bm.mesh.vertices[t[1]] - bm.mesh.vertices[t[0]]).cross(bm.mesh.vertices[t[2]] - bm.mesh.vertices[t[0]]);
    EXPECT_GT(e.norm(), 1e-8);
  }
}

/// Volume enclosed by one branch's triangles, from the divergence theorem with the origin at the
/// branch's first section centre: a child's tube is open at its base, and that missing cap lies in
/// a plane through the origin, where it would add nothing.
double branchDivergenceVolume(const BranchMesh& bm, const SkeletonBranch& b) {
  const Vec3 o = b.sections.front().centre;
  double v = 0;
  const std::uint32_t first = bm.branchFirstTriangle[b.id], count = bm.branchTriangleCount[b.id];
  for (std::uint32_t t = first; t < first + count; ++t) {
    const auto& tri = bm.mesh.triangles[t];
    const Vec3 a = bm.mesh.vertices[tri[0]] - o, c = bm.mesh.vertices[tri[1]] - o, d = bm.mesh.vertices[tri[2]] - o;
    v += a.dot(c.cross(d)) / 6.0;
  }
  return v;
}

TEST(BranchMesh, InscribedPolygonShareIsThePolygonsArea) {
  // A square inscribed in the unit circle has area 2 (diagonal 2), a hexagon six triangles of side 1.
  EXPECT_NEAR(inscribedPolygonShare(4) * std::numbers::pi, 2.0, 1e-12);
  EXPECT_NEAR(inscribedPolygonShare(6) * std::numbers::pi, 6.0 * std::sqrt(3.0) / 4.0, 1e-12);
  EXPECT_LT(inscribedPolygonShare(3), inscribedPolygonShare(8));
  EXPECT_NEAR(inscribedPolygonShare(100000), 1.0, 1e-8);
  EXPECT_THROW(inscribedPolygonShare(2), OptionsError);
}

TEST(BranchMesh, VolumeOfATaperedTubeIsItsPolygonFrustums) {
  // A straight tapered trunk, closed at both ends: the divergence theorem over the whole mesh.
  Skeleton s = straightTrunk(5, 0.4, 3.0);
  for (std::size_t i = 0; i < s.branches[0].sections.size(); ++i) s.branches[0].sections[i].radius = 0.4 - 0.07 * i;
  for (int n : {3, 4, 7, 12}) {
    BranchMesh bm = buildBranchMesh(s, BranchMeshOptions{{n}});
    ASSERT_EQ(bm.branchRingVertices, std::vector<int>{n});
    EXPECT_NEAR(branchMeshVolume(s, bm), signedVolume(bm.mesh), 1e-9) << n << " sides";
    EXPECT_LT(branchMeshVolume(s, bm), woodVolume(s));  // the polygon is inside its circle
  }
}

TEST(BranchMesh, VolumeOfAGeneratedTreeMatchesItsMesh) {
  // Bent branches of several levels and ring counts: each tube's own enclosed volume.
  TreeOptions options = presetOptions("default");
  options.leaves = false;
  GeneratedTree tree = generateTree(options);
  const BranchMesh& bm = tree.branches;
  ASSERT_EQ(bm.branchRingVertices.size(), tree.skeleton.branches.size());
  double meshVolume = 0;
  for (const auto& b : tree.skeleton.branches) meshVolume += branchDivergenceVolume(bm, b);
  const double volume = branchMeshVolume(tree.skeleton, bm);
  EXPECT_NEAR(volume, meshVolume, 0.002 * meshVolume);  // measured: 0.06 %
  EXPECT_LT(volume, woodVolume(tree.skeleton));
  EXPECT_GT(volume, 0.75 * woodVolume(tree.skeleton));  // rings of 6-12 vertices hold 83-95 % of the circles
  EXPECT_THROW(branchMeshVolume(tree.skeleton, BranchMesh{}), OptionsError);
}

TEST(BranchMesh, EmptySkeletonGivesEmptyMesh) {
  BranchMesh bm = buildBranchMesh(Skeleton{});
  EXPECT_TRUE(bm.mesh.empty());
  EXPECT_TRUE(bm.mesh.vertices.empty());
}

TEST(BranchMesh, RejectsBadInput) {
  Skeleton s = straightTrunk(3, 0.1, 1.0);
  EXPECT_THROW(buildBranchMesh(s, BranchMeshOptions{{2}}), OptionsError);
  EXPECT_THROW(buildBranchMesh(s, BranchMeshOptions{{}}), OptionsError);
  s.branches[0].sections[1].axis = Vec3::Zero();
  EXPECT_THROW(buildBranchMesh(s), OptionsError);
  s = straightTrunk(3, 0.1, 1.0);
  s.branches[0].sections.resize(1);
  EXPECT_THROW(buildBranchMesh(s), OptionsError);
}

}  // namespace
}  // namespace treesketch::gen
