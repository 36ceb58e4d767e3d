// `treesketch split`: a plot of three trees cut into three clouds with a table of their stems; the
// automatic model of the whole plot says it holds three trees; a cloud with no stem is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>

#include "cli_support.h"
#include "treesketch/io/point_cloud_io.h"
#include "test_support.h"

namespace treesketch {
namespace {

using geom::Vec3;

/// Three stems (30, 24, 16 cm across, 8 m tall) with a crown each, on level ground.
geom::PointCloud threeTrees() {
  geom::PointCloud c;
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 0.5);
  for (const auto& [x, y, r] : {std::tuple{-4.0, 0.0, 0.15}, std::tuple{0.0, 1.0, 0.12}, std::tuple{4.0, -1.0, 0.08}}) {
    const int around = static_cast<int>(std::ceil(2 * std::numbers::pi * r / 0.01));
    for (double z = 0; z <= 8.0; z += 0.01)
      for (int k = 0; k < around; ++k) {
        const double a = 2 * std::numbers::pi * k / around;
        c.positions.emplace_back(x + r * std::cos(a), y + r * std::sin(a), z);
      }
    for (int k = 0; k < 3000; ++k) c.positions.emplace_back(x + g(rng), y + g(rng), 7.0 + g(rng));
  }
  for (double x = -7; x <= 7; x += 0.04)
    for (double y = -7; y <= 7; y += 0.04) c.positions.emplace_back(x, y, 0.0);
  return c;
}

TEST(SplitCli, APlotBecomesOneCloudPerTreeWithATableOfStems) {
  test::TempDir dir;
  io::writePointCloud(dir / "plot.xyz", threeTrees());
  std::string out;
  ASSERT_EQ(test::runCli("split " + test::quoted(dir / "plot.xyz") + " -o " + test::quoted(dir / "trees") +
                             " --ground " + test::quoted(dir / "ground.ply"),
                         &out),
            0)
      << out;
  EXPECT_NE(out.find("3 trees (3 stems at breast height)"), std::string::npos) << out;
  std::ifstream f(dir / "trees" / "stems.json");
  const nlohmann::json table = nlohmann::json::parse(f);
  ASSERT_EQ(table["trees"].size(), 3u);
  const double dbh[] = {0.30, 0.24, 0.16};
  std::size_t points = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const nlohmann::json& t = table["trees"][k];
    ASSERT_EQ(t["stems"].size(), 1u);
    EXPECT_NEAR(t["stems"][0]["dbhM"].get<double>(), dbh[k], 0.01);
    const geom::PointCloud tree = io::readPointCloud(dir / "trees" / t["file"].get<std::string>());
    EXPECT_EQ(tree.size(), t["points"].get<std::size_t>());
    points += tree.size();
    // Each tree's cloud stands round its own stem.
    const double x = t["stems"][0]["x"].get<double>();
    for (const Vec3& p : tree.positions) ASSERT_LT(std::abs(p.x() - x), 2.0 + 1e-9);
  }
  const geom::PointCloud ground = io::readPointCloud(dir / "ground.ply");
  EXPECT_EQ(points + ground.size(), threeTrees().size());
  EXPECT_EQ(table["groundPoints"].get<std::size_t>(), ground.size());
}

TEST(SplitCli, ASecondSplitIntoTheSameFolderLeavesOnlyItsOwnTrees) {
  test::TempDir dir;
  io::writePointCloud(dir / "plot.xyz", threeTrees());
  geom::PointCloud one;
  for (const Vec3& p : threeTrees().positions)
    if (p.x() < -2) one.positions.push_back(p);  // the first tree and its ground
  io::writePointCloud(dir / "one.xyz", one);
  std::string out;
  ASSERT_EQ(test::runCli("split " + test::quoted(dir / "plot.xyz") + " -o " + test::quoted(dir / "t"), &out), 0) << out;
  ASSERT_TRUE(std::filesystem::exists(dir / "t" / "tree_003.ply"));
  { std::ofstream(dir / "t" / "notes.txt") << "mine\n"; }
  ASSERT_EQ(test::runCli("split " + test::quoted(dir / "one.xyz") + " -o " + test::quoted(dir / "t"), &out), 0) << out;
  EXPECT_TRUE(std::filesystem::exists(dir / "t" / "tree_001.ply"));
  EXPECT_FALSE(std::filesystem::exists(dir / "t" / "tree_002.ply"));
  EXPECT_FALSE(std::filesystem::exists(dir / "t" / "tree_003.ply"));
  EXPECT_TRUE(std::filesystem::exists(dir / "t" / "notes.txt"));  // not this command's: kept
}

TEST(SplitCli, TheModelOfAWholePlotSaysItHoldsSeveralTrees) {
  test::TempDir dir;
  io::writePointCloud(dir / "plot.xyz", threeTrees());
  std::string out;
  ASSERT_EQ(test::runCli("reconstruct " + test::quoted(dir / "plot.xyz") + " --auto -o " + test::quoted(dir / "m.ply") +
                             " --report " + test::quoted(dir / "r.json"),
                         &out),
            0)
      << out;
  EXPECT_NE(out.find("the cloud holds 3 trees"), std::string::npos) << out;
  EXPECT_NE(out.find("treesketch split"), std::string::npos) << out;
  std::ifstream f(dir / "r.json");
  const nlohmann::json r = nlohmann::json::parse(f);
  EXPECT_EQ(r["verdict"]["level"], "not trusted");
  EXPECT_EQ(r["stemsAtBreastHeight"]["trees"], 3);
  EXPECT_EQ(r["stemsAtBreastHeight"]["stems"].size(), 3u);
}

TEST(SplitCli, ACloudWithNoStemIsRefusedWithItsReason) {
  test::TempDir dir;
  geom::PointCloud ball;
  std::mt19937 rng(2);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int k = 0; k < 5000; ++k) ball.positions.emplace_back(g(rng), g(rng), 5 + g(rng));
  io::writePointCloud(dir / "ball.xyz", ball);
  std::string out;
  EXPECT_EQ(test::runCli("split " + test::quoted(dir / "ball.xyz") + " -o " + test::quoted(dir / "t"), &out), 5) << out;
  EXPECT_NE(out.find("no stem found at breast height"), std::string::npos) << out;
  EXPECT_EQ(test::runCli("split " + test::quoted(dir / "ball.xyz") + " -o " + test::quoted(dir / "t") + " --format las",
                         &out),
            2)
      << out;
}

}  // namespace
}  // namespace treesketch
