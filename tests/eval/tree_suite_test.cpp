#include "treesketch/eval/tree_suite.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "test_support.h"
#include "treesketch/gen/skeleton.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/util/error.h"

namespace treesketch::eval {
namespace {

TEST(TreeSuite, BuiltinTreesAreDeterministicAndComplete) {
  auto a = builtinTrees(2);
  auto b = builtinTrees(2);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_NE(a[0].name, a[1].name);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_FALSE(a[i].branches.empty());
    EXPECT_FALSE(a[i].leaves.empty());
    ASSERT_EQ(a[i].branches.vertices.size(), b[i].branches.vertices.size());
    EXPECT_EQ(a[i].branches.vertices.front(), b[i].branches.vertices.front());
    ASSERT_FALSE(a[i].axes.empty());
    EXPECT_EQ(a[i].axes.front().parent, -1);
    EXPECT_EQ(std::count_if(a[i].axes.begin(), a[i].axes.end(), [](const auto& x) { return x.parent < 0; }), 1);
    for (std::size_t k = 0; k < a[i].axes.size(); ++k) {
      const auto& ax = a[i].axes[k];
      EXPECT_EQ(ax.points.size(), a[i].axisRadii[k].size());
      if (ax.parent >= 0) {
        ASSERT_LT(ax.parent, static_cast<int>(a[i].axes.size()));
        EXPECT_LT(ax.parentVertex, a[i].axes[ax.parent].points.size());
      }
    }
  }
}

TEST(TreeSuite, LoadsTheThirdPartyTrees) {
  auto dir = test::sharedDataDir() / "trees";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no " << dir;
  // Every tree of the folder, whatever their number: one per "<name>.branches.obj" with its JSON.
  std::vector<std::string> expected;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    const std::string suffix = ".branches.obj";
    if (f.size() > suffix.size() && f.compare(f.size() - suffix.size(), suffix.size(), suffix) == 0)
      expected.push_back(f.substr(0, f.size() - suffix.size()));
  }
  std::sort(expected.begin(), expected.end());
  auto trees = loadTreeFolder(dir);
  ASSERT_EQ(trees.size(), expected.size());
  ASSERT_GE(trees.size(), 1u);
  // Limb counts the folder's README documents (tubes / limbs column), where those trees are present.
  const std::map<std::string, std::size_t> documentedLimbs = {
      {"aspen_medium_s101", 44}, {"bush_2_s45590", 44}, {"oak_medium_s35729", 140}, {"pine_medium_s13977", 83}};
  std::size_t documentedSeen = 0;
  for (std::size_t i = 0; i < trees.size(); ++i) {
    const auto& t = trees[i];
    EXPECT_EQ(t.name, expected[i]);  // sorted by name
    EXPECT_FALSE(t.branches.empty()) << t.name;
    EXPECT_FALSE(t.leaves.empty()) << t.name;
    EXPECT_GT(t.woodVolume, 0.0) << t.name;  // false for NaN too
    ASSERT_FALSE(t.axes.empty()) << t.name;
    if (auto it = documentedLimbs.find(t.name); it != documentedLimbs.end()) {
      EXPECT_EQ(t.axes.size(), it->second) << t.name;
      ++documentedSeen;
    }
    int roots = 0;
    for (std::size_t k = 0; k < t.axes.size(); ++k) {
      const auto& ax = t.axes[k];
      EXPECT_EQ(ax.points.size(), t.axisRadii[k].size()) << t.name;
      if (ax.parent < 0) {
        ++roots;
        continue;
      }
      ASSERT_LT(ax.parent, static_cast<int>(t.axes.size())) << t.name;
      // A limb hangs on a vertex of its parent's axis.
      ASSERT_LT(ax.parentVertex, t.axes[ax.parent].points.size()) << t.name;
    }
    EXPECT_EQ(roots, 1) << t.name;
  }
  if (documentedSeen == 0) std::cout << "[ note ] none of the four documented trees in " << dir << "\n";
}

TEST(TreeSuite, BuiltinTreesKnowTheirMeshsWoodVolume) {
  for (const auto& t : builtinTrees(3)) {
    ASSERT_TRUE(std::isfinite(t.woodVolume)) << t.name;
    // Below the round sections' volume (the rings are inscribed polygons), above the share of the
    // coarsest ring the generator's presets use (4 vertices: 64 %).
    gen::TreeOptions options = gen::presetOptions(t.name.substr(8, t.name.rfind("_s") - 8));
    options.seed = std::stoull(t.name.substr(t.name.rfind("_s") + 2));
    const double round = gen::woodVolume(gen::generateSkeleton(options));
    EXPECT_LT(t.woodVolume, round) << t.name;
    EXPECT_GT(t.woodVolume, 0.63 * round) << t.name;
  }
}

TEST(TreeSuite, EzTreeWoodVolumeOfHandMadeBranches) {
  // A square prism (4 sides inscribed in a circle of radius 1: area 2) 2 long, and a triangular
  // cone (3 sides, radius 1 -> 0: base area 3·√3/4) 3 long, its axis bent in two pieces.
  test::TempDir dir;
  test::writeText(dir / "t.json", R"({"skeleton": {"branches": [
    {"segment_count": 4, "sections": [{"center": [0, 0, 0], "radius": 1}, {"center": [0, 2, 0], "radius": 1}]},
    {"segment_count": 3, "sections": [{"center": [5, 0, 0], "radius": 1}, {"center": [5, 0, 3], "radius": 0}]}],
    "limbs": []}})");
  const double cone = 3.0 * std::sqrt(3.0) / 4.0 * 3.0 / 3.0;
  EXPECT_NEAR(readEzTreeWoodVolume(dir / "t.json"), 2.0 * 2.0 + cone, 1e-12);
  // No branches: the volume is unknown, not zero.
  test::writeText(dir / "u.json", R"({"skeleton": {"limbs": []}})");
  EXPECT_TRUE(std::isnan(readEzTreeWoodVolume(dir / "u.json")));
}

TEST(TreeSuite, EzTreeWoodVolumeRejectsMalformedBranches) {
  test::TempDir dir;
  const std::map<std::string, std::string> bad = {
      {"segment_count", R"({"skeleton": {"branches": [{"segment_count": 2, "sections": []}]}})"},
      {"sections[1].radius",
       R"({"skeleton": {"branches": [{"segment_count": 5, "sections": [{"center": [0, 0, 0], "radius": 1},
                                                                          {"center": [0, 1, 0], "radius": "x"}]}]}})"},
      {"sections[0].center", R"({"skeleton": {"branches": [{"segment_count": 5, "sections": [{"radius": 1}]}]}})"},
      {"branches[0]", R"({"skeleton": {"branches": [7]}})"},
      {"skeleton.branches", R"({"skeleton": {"branches": 7}})"},
      {"byte offset", R"({"skeleton": )"}};
  for (const auto& [what, text] : bad) {
    test::writeText(dir / "t.json", text);
    try {
      readEzTreeWoodVolume(dir / "t.json");
      ADD_FAILURE() << "expected InputError for " << what;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("t.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  }
}

/// The volume one ez-tree tube of the OBJ encloses once closed at both ends: the divergence theorem
/// over its side triangles with the origin at its first ring's centre (the base cap, in a plane
/// through the origin, adds nothing), plus the flat tip cap's term (1/3)·(tip − base)·area vector.
double ezTreeTubeVolume(const geom::TriMesh& mesh, const nlohmann::json& branch) {
  const std::size_t n = branch["segment_count"], rings = branch["sections"].size();
  const std::size_t v0 = branch["vertex_range"][0], t0 = branch["triangle_range"][0], t1 = branch["triangle_range"][1];
  auto centroid = [&](std::size_t ring) {
    geom::Vec3 c = geom::Vec3::Zero();
    for (std::size_t j = 0; j < n; ++j) c += mesh.vertices[v0 + ring * n + j];
    return geom::Vec3(c / static_cast<double>(n));
  };
  const geom::Vec3 base = centroid(0), tip = centroid(rings - 1);
  double volume = 0;
  for (std::size_t t = t0; t < t1; ++t) {
    const auto& tri = mesh.triangles[t];
    volume += (mesh.vertices[tri[0]] - base).dot((mesh.vertices[tri[1]] - base).cross(mesh.vertices[tri[2]] - base)) / 6;
  }
  geom::Vec3 area = geom::Vec3::Zero();
  for (std::size_t j = 0; j < n; ++j)
    area += 0.5 * (mesh.vertices[v0 + (rings - 1) * n + j] - tip).cross(mesh.vertices[v0 + (rings - 1) * n + (j + 1) % n] - tip);
  return volume + std::abs((tip - base).dot(area)) / 3.0;
}

TEST(TreeSuite, EzTreeWoodVolumeMatchesTheirMeshes) {
  auto dir = test::sharedDataDir() / "trees";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no " << dir;
  // The frustums of polygons assume untwisted rings: measured against the closed tubes' own
  // volume, 0.2-0.5 % on the untwisted aspens and pines, up to 3.9 % on twisted trunks (ash_small:
  // consecutive rings turned against each other cut the tube's corners).
  const std::map<std::string, double> tolerance = {
      {"aspen_small_s914", 0.01}, {"pine_small_s3391", 0.01}, {"ash_small_s2203", 0.05}};
  int checked = 0;
  for (const auto& [name, relative] : tolerance) {
    if (!std::filesystem::exists(dir / (name + ".json"))) continue;
    const geom::TriMesh mesh = io::readMesh(dir / (name + ".branches.obj"));
    nlohmann::json doc;
    std::ifstream(dir / (name + ".json")) >> doc;
    double meshVolume = 0;
    for (const auto& branch : doc["skeleton"]["branches"]) meshVolume += ezTreeTubeVolume(mesh, branch);
    const double volume = readEzTreeWoodVolume(dir / (name + ".json"));
    EXPECT_NEAR(volume, meshVolume, relative * meshVolume) << name;
    EXPECT_GE(volume, meshVolume * 0.999) << name;  // on these three, the tubes hold less than the frustums
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "none of the three trees in " << dir;
}

TEST(TreeSuite, RejectsBadFolders) {
  test::TempDir dir;
  EXPECT_THROW(loadTreeFolder(dir.path()), InputError);
  EXPECT_THROW(loadTreeFolder(dir / "missing"), InputError);
  test::writeText(dir / "t.json", "{\"skeleton\": {\"limbs\": [ {\"sections\": [ {\"center\": [0, 0]} ]} ]}}");
  test::writeText(dir / "t.branches.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  try {
    loadTreeFolder(dir.path());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("center"), std::string::npos) << e.what();
  }
  test::writeText(dir / "t.json", "{\"skeleton\": ");
  EXPECT_THROW(loadTreeFolder(dir.path()), InputError);
  // A folder whose JSON has limbs and no branches: loaded, its wood volume unknown.
  test::writeText(dir / "t.json", "{\"skeleton\": {\"limbs\": [ {\"sections\": [ {\"center\": [0, 0, 0]} ]} ]}}");
  auto trees = loadTreeFolder(dir.path());
  ASSERT_EQ(trees.size(), 1u);
  EXPECT_TRUE(std::isnan(trees[0].woodVolume));
}

}  // namespace
}  // namespace treesketch::eval
