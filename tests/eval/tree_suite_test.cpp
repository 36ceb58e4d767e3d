#include "treesketch/eval/tree_suite.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "test_support.h"
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
}

}  // namespace
}  // namespace treesketch::eval
