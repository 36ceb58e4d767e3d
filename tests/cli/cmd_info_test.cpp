// The `treesketch info` subcommand (apps/cli/cmd_info.cpp), run as a process.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>

#include "cli_support.h"
#include "marked_las.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch {
namespace {

TEST(InfoCli, BadFileExitsWithInputCodeAndOneLineNamingIt) {
  test::TempDir dir;
  auto bad = dir / "bad.ply";
  test::writeText(bad,
                  "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                  "property float z\nend_header\n0 0 0\n1 1\n");
  std::string out;
  EXPECT_EQ(test::runCli("info " + test::quoted(bad), &out), 3);
  EXPECT_NE(out.find(bad.string()), std::string::npos) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_EQ(test::runCli("info " + test::quoted(dir / "missing.xyz"), &out), 3);
  EXPECT_NE(out.find("missing.xyz"), std::string::npos) << out;
}

TEST(InfoCli, GoodFilePrintsCounts) {
  test::TempDir dir;
  geom::PointCloud c;
  for (int i = 0; i < 7; ++i) c.positions.emplace_back(i, 0, 0);
  io::writePointCloud(dir / "c.xyz", c);
  std::string out;
  EXPECT_EQ(test::runCli("info " + test::quoted(dir / "c.xyz"), &out), 0) << out;
  EXPECT_NE(out.find("points: 7\n"), std::string::npos) << out;
  EXPECT_NE(out.find("bbox diagonal: 6.000000"), std::string::npos) << out;
}

// A stem standing on level terrain: the terrain's points are counted as ground (Z up, the field's
// convention for a text cloud).
TEST(InfoCli, CountsTheGroundUnderAStem) {
  test::TempDir dir;
  geom::PointCloud c;
  for (double z = 0; z <= 4.0; z += 0.01)
    for (int k = 0; k < 90; ++k) c.positions.emplace_back(0.15 * std::cos(k * 0.0698), 0.15 * std::sin(k * 0.0698), z);
  for (double x = -2.0; x <= 2.0; x += 0.02)
    for (double y = -2.0; y <= 2.0; y += 0.02)
      if (x * x + y * y > 0.0225) c.positions.emplace_back(x, y, 0.002 * std::sin(7 * x));
  io::writePointCloud(dir / "stem.xyz", c);
  std::string out;
  EXPECT_EQ(test::runCli("info " + test::quoted(dir / "stem.xyz"), &out), 0) << out;
  EXPECT_NE(out.find(" on the ground, "), std::string::npos) << out;
}

// LAS 1.2 and 1.4 files with points withheld and points classified as noise: the withheld are
// dropped and counted, the noise counted with the points set aside.
TEST(InfoCli, CountsWithheldPointsAndPointsMarkedAsNoise) {
  test::TempDir dir;
  for (int format : {1, 6}) {
    const test::MarkedLas las = test::markedTreeLas(format);
    const auto file = dir / ("tree" + std::to_string(format) + ".las");
    test::writeText(file, las.bytes);
    std::string out;
    ASSERT_EQ(test::runCli("info " + test::quoted(file), &out), 0) << out;
    for (const std::string line : {"withheld points: " + std::to_string(las.withheld) + " (dropped on read)\n",
                                   "header point count: " + std::to_string(las.treePoints + las.withheld) + "\n",
                                   "points: " + std::to_string(las.treePoints) + "\n",
                                   "(" + std::to_string(las.marked) + " marked as noise by the file, "})
      EXPECT_NE(out.find(line), std::string::npos) << "missing '" << line << "' in\n" << out;
    EXPECT_NE(out.find(", 0 far from the tree"), std::string::npos) << out;  // the withheld are gone
  }
}

// A LAZ file: the compressor, items, chunk size and point format (../shared/data/real; skipped
// without it).
TEST(InfoCli, LazFilePrintsCompressorChunkSizeAndPointFormat) {
  const auto laz = test::sharedDataDir() / "real" / "spanner_TLS_Clip.laz";
  if (!std::filesystem::exists(laz)) GTEST_SKIP() << "no shared data at " << laz.parent_path();
  std::string out;
  ASSERT_EQ(test::runCli("info " + test::quoted(laz), &out), 0) << out;
  for (const char* line :
       {"format: LAZ (compressed LAS) 1.4\n", "point data format: 6\n", "compressor: LASzip layered chunked",
        "compressed items: POINT14 v3\n", "chunk size: 50000 points\n", "chunks: 9\n", "points: 400754\n"})
    EXPECT_NE(out.find(line), std::string::npos) << "missing '" << line << "' in\n" << out;
}

// The automatic model of a LAZ file is the model of the same points as text: the spruce decoded
// and written out with every digit (the shared text copy is rounded to 4 decimals, which moves
// every z by up to 4e-5 and the skeleton by a node) gives the same cylinder table.
TEST(InfoCli, ALazCloudGivesTheModelOfItsPointsAsText) {
  const auto laz = test::sharedDataDir() / "real" / "treels_spruce.laz";
  if (!std::filesystem::exists(laz)) GTEST_SKIP() << "no shared data at " << laz.parent_path();
  test::TempDir dir;
  io::writePointCloud(dir / "spruce.xyz", io::readPointCloud(laz));
  std::string out;
  for (const auto& [in, csv] : {std::pair{laz, dir / "laz.csv"}, std::pair{dir / "spruce.xyz", dir / "xyz.csv"}})
    ASSERT_EQ(test::runCli("reconstruct " + test::quoted(in) + " --auto --leaf-on --up z -o " +
                               test::quoted(dir / "m.obj") + " --cylinders " + test::quoted(csv),
                           &out),
              0)
        << out;
  const std::string fromLaz = test::readText(dir / "laz.csv");
  EXPECT_GT(std::count(fromLaz.begin(), fromLaz.end(), '\n'), 100);
  EXPECT_EQ(fromLaz, test::readText(dir / "xyz.csv"));
}

}  // namespace
}  // namespace treesketch
