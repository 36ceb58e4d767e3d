// `treesketch reconstruct --auto` and `sketch auto --method skeleton`, run as processes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_support.h"
#include "skeleton/synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"

namespace treesketch {
namespace {

using test::quoted;

/// Writes the Y-shaped test tree's cloud to DIR/c.ply; returns that path, quoted for the shell.
std::string yTreeCloud(const test::TempDir& dir) {
  io::writePointCloud(dir / "c.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  return quoted(dir / "c.ply");
}

TEST(CmdAuto, ReconstructAutoWritesMeshSketchAndCylinders) {
  test::TempDir dir;
  io::writePointCloud(dir / "c.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  for (const std::string extra : {"", " --leaf-on"}) {
    std::string out;
    const int rc = test::runCli("reconstruct " + quoted(dir / "c.ply") + " --auto" + extra + " --sketch " +
                                    quoted(dir / "s.json") + " --cylinders " + quoted(dir / "c.csv") + " -o " +
                                    quoted(dir / "m.ply"),
                                &out);
    ASSERT_EQ(rc, 0) << extra << ": " << out;
    EXPECT_NE(out.find("fits accepted"), std::string::npos) << out;
    EXPECT_NE(out.find("leaf pieces not fitted"), std::string::npos) << out;
    EXPECT_FALSE(io::readMesh(dir / "m.ply").empty()) << extra;
    EXPECT_GE(io::readSketch(dir / "s.json").size(), 3u) << extra;
    std::ifstream csv(dir / "c.csv");
    std::string header, row;
    ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, row)) << extra;
    std::filesystem::remove(dir / "m.ply");
  }
}

TEST(CmdAuto, LeafOnNeedsAuto) {
  test::TempDir dir;
  io::writePointCloud(dir / "c.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  std::string out;
  EXPECT_EQ(test::runCli("reconstruct " + quoted(dir / "c.ply") + " --sketch " + quoted(dir / "s.json") +
                             " --leaf-on -o " + quoted(dir / "m.ply"),
                         &out),
            2)
      << out;
  EXPECT_NE(out.find("--leaf-on"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.ply"));
}

TEST(CmdAuto, SketchAutoSkeletonLeafOn) {
  test::TempDir dir;
  io::writePointCloud(dir / "c.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  std::string out;
  const int rc = test::runCli(
      "sketch auto " + quoted(dir / "c.ply") + " --method skeleton --leaf-on -o " + quoted(dir / "s.json"), &out);
  ASSERT_EQ(rc, 0) << out;
  EXPECT_GE(io::readSketch(dir / "s.json").size(), 3u);
}

// The saved automatic sketch rebuilds the automatic mesh (`reconstruct --sketch` uses its kept
// circles); --refit fits every node from the cloud instead.
TEST(CmdAuto, SavedSketchRebuildsTheAutomaticMeshAndRefitFitsIt) {
  test::TempDir dir;
  const std::string cloud = yTreeCloud(dir), sketchFile = quoted(dir / "s.json");
  std::string out;
  ASSERT_EQ(
      test::runCli("reconstruct " + cloud + " --auto --sketch " + sketchFile + " -o " + quoted(dir / "auto.ply"), &out),
      0)
      << out;
  const sketch::Sketch sk = io::readSketch(dir / "s.json");
  ASSERT_GE(sk.keptCircleCount(), 3u);
  const std::string again = "reconstruct " + cloud + " --sketch " + sketchFile + " --report " + quoted(dir / "r.json");
  ASSERT_EQ(test::runCli(again + " -o " + quoted(dir / "again.ply"), &out), 0) << out;
  EXPECT_NE(out.find(std::to_string(sk.keptCircleCount()) + " kept circles"), std::string::npos) << out;
  const geom::TriMesh a = io::readMesh(dir / "auto.ply"), b = io::readMesh(dir / "again.ply");
  ASSERT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t v = 0; v < a.vertices.size(); ++v) EXPECT_LT((a.vertices[v] - b.vertices[v]).norm(), 1e-6);
  EXPECT_NE(test::readText(dir / "r.json").find("\"kept\": true"), std::string::npos);
  ASSERT_EQ(test::runCli(again + " --refit -o " + quoted(dir / "refit.ply"), &out), 0) << out;
  EXPECT_NE(out.find(" 0 kept circles"), std::string::npos) << out;
  // `sketch auto --method skeleton` saves the same handed-over model.
  ASSERT_EQ(test::runCli("sketch auto " + cloud + " --method skeleton -o " + quoted(dir / "s2.json"), &out), 0) << out;
  EXPECT_EQ(io::readSketch(dir / "s2.json").keptCircleCount(), sk.keptCircleCount());
  // --refit is for sketch files.
  EXPECT_EQ(test::runCli("reconstruct " + cloud + " --auto --refit -o " + quoted(dir / "x.ply"), &out), 2) << out;
  EXPECT_NE(out.find("--refit"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.ply"));
}

}  // namespace
}  // namespace treesketch

namespace treesketch {
namespace {

// Stray points far from the tree are set aside, counted in the summary line and the report, and
// written to --outliers; the model is the one made without them.
TEST(CmdAuto, StrayPointsAreSetAsideCountedAndWrittenOut) {
  test::TempDir dir;
  const geom::PointCloud clean = test::sampleCylinders(test::yTree(), 0.02, 0.003, 7);
  geom::PointCloud withStrays = clean;
  withStrays.positions.emplace_back(1e6, 0, 0);    // 1,000 km out
  withStrays.positions.emplace_back(0, 50.0, 20);  // 50 m out
  io::writePointCloud(dir / "clean.ply", clean);
  io::writePointCloud(dir / "strays.ply", withStrays);
  std::string out;
  ASSERT_EQ(test::runCli("reconstruct " + quoted(dir / "clean.ply") + " --auto --report " + quoted(dir / "r0.json") +
                             " -o " + quoted(dir / "m0.ply"),
                         &out),
            0)
      << out;
  EXPECT_NE(out.find("no stray point set aside"), std::string::npos) << out;
  ASSERT_EQ(test::runCli("reconstruct " + quoted(dir / "strays.ply") + " --auto --report " + quoted(dir / "r.json") +
                             " --outliers " + quoted(dir / "out.xyz") + " -o " + quoted(dir / "m.ply"),
                         &out),
            0)
      << out;
  EXPECT_NE(out.find("2 stray points set aside (2 far from the tree"), std::string::npos) << out;
  const auto r0 = nlohmann::json::parse(test::readText(dir / "r0.json"));
  const auto r = nlohmann::json::parse(test::readText(dir / "r.json"));
  EXPECT_EQ(r0["strayPoints"]["setAside"], 0);
  EXPECT_EQ(r["strayPoints"]["setAside"], 2);
  EXPECT_EQ(r["strayPoints"]["far"], 2);
  EXPECT_EQ(r["points"], clean.size() + 2);
  EXPECT_EQ(r["metrics"]["volumeM3"], r0["metrics"]["volumeM3"]);
  EXPECT_EQ(r["metrics"]["heightM"], r0["metrics"]["heightM"]);
  io::CloudReadOptions any;
  any.minPoints = 1;
  const geom::PointCloud set = io::readPointCloud(dir / "out.xyz", any);
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(set.positions[0].x(), 1e6);
  // --outliers belongs to the automatic model
  EXPECT_EQ(test::runCli("reconstruct " + quoted(dir / "strays.ply") + " --sketch " + quoted(dir / "s.json") +
                             " --outliers " + quoted(dir / "o.xyz") + " -o " + quoted(dir / "x.ply"),
                         &out),
            2)
      << out;
}

}  // namespace
}  // namespace treesketch
