#include "treesketch/eval/tree_suite.h"

#include <gtest/gtest.h>

#include <algorithm>

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
  auto trees = loadTreeFolder(dir);
  ASSERT_EQ(trees.size(), 4u);
  // Sorted by name; limb counts from the folder's README (tubes / limbs column).
  EXPECT_EQ(trees[0].name, "aspen_medium_s101");
  EXPECT_EQ(trees[0].axes.size(), 44u);
  EXPECT_EQ(trees[0].branches.triangles.size(), 5088u);
  EXPECT_EQ(trees[1].name, "bush_2_s45590");
  EXPECT_EQ(trees[1].axes.size(), 44u);
  EXPECT_EQ(trees[2].name, "oak_medium_s35729");
  EXPECT_EQ(trees[2].axes.size(), 140u);
  EXPECT_EQ(trees[3].name, "pine_medium_s13977");
  EXPECT_EQ(trees[3].axes.size(), 83u);
  for (const auto& t : trees) {
    EXPECT_FALSE(t.leaves.empty()) << t.name;
    int roots = 0;
    for (std::size_t k = 0; k < t.axes.size(); ++k) {
      const auto& ax = t.axes[k];
      if (ax.parent < 0) {
        ++roots;
        continue;
      }
      ASSERT_LT(ax.parent, static_cast<int>(t.axes.size()));
      // A limb starts near the parent vertex it is hung on (within the parent's section spacing).
      const auto& pp = t.axes[ax.parent].points;
      ASSERT_LT(ax.parentVertex, pp.size());
    }
    EXPECT_EQ(roots, 1) << t.name;
  }
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
