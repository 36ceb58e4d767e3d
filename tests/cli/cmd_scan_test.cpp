// Tests of `treesketch scan` (apps/cli/cmd_scan.cpp): outputs, summary line, exit codes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_support.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"

namespace {

using treesketch::test::runCli;
using treesketch::test::TempDir;
using treesketch::test::writeText;

// An axis-aligned box as OBJ text.
std::string boxObj(double x0, double y0, double z0, double x1, double y1, double z1) {
  std::string s;
  for (int i = 0; i < 8; ++i)
    s += "v " + std::to_string(i & 1 ? x1 : x0) + " " + std::to_string(i & 2 ? y1 : y0) + " " +
         std::to_string(i & 4 ? z1 : z0) + "\n";
  const int f[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : f) {
    s += "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + " " + std::to_string(q[2] + 1) + "\n";
    s += "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[2] + 1) + " " + std::to_string(q[3] + 1) + "\n";
  }
  return s;
}

class ScanCli : public ::testing::Test {
 protected:
  void SetUp() override {
    writeText(dir / "trunk.obj", boxObj(-0.1, 0, -0.1, 0.1, 3, 0.1));
    writeText(dir / "crown.obj", boxObj(-1, 2, -1, 1, 4, 1));
  }
  std::string q(const std::string& name) { return treesketch::test::quoted(dir / name); }
  TempDir dir;
};

TEST_F(ScanCli, SphereScanWritesCloudWithMeshIdsAndSummary) {
  std::string out;
  ASSERT_EQ(
      runCli("scan " + q("trunk.obj") + " " + q("crown.obj") + " -o " + q("s.ply") + " --subdiv 2 --record-mesh", &out),
      0)
      << out;
  EXPECT_NE(out.find("288 rays"), std::string::npos) << out;
  EXPECT_NE(out.find("wood fraction"), std::string::npos) << out;
  const treesketch::geom::PointCloud cloud = treesketch::io::readPointCloud(dir / "s.ply");
  EXPECT_GT(cloud.size(), 100u);
  EXPECT_LE(cloud.size(), 288u);
  ASSERT_EQ(cloud.meshId.size(), cloud.size());
  EXPECT_NE(out.find(std::to_string(cloud.size()) + " points"), std::string::npos) << out;
}

TEST_F(ScanCli, TlsScanWritesStations) {
  std::string out;
  ASSERT_EQ(runCli("scan " + q("trunk.obj") + " -o " + q("t.ply") +
                       " --pattern tls --step 5 --stations 3 --station-radius 4 --station-height 1 --up y "
                       "--noise 0 --max-range 100 --seed 3",
                   &out),
            0)
      << out;
  const treesketch::geom::PointCloud cloud = treesketch::io::readPointCloud(dir / "t.ply");
  ASSERT_GT(cloud.size(), 0u);
  ASSERT_EQ(cloud.station.size(), cloud.size());
  for (int s : cloud.station) {
    EXPECT_GE(s, 0);
    EXPECT_LT(s, 3);
  }
}

TEST_F(ScanCli, RealisticTlsKeepsScannerPositionsAndCountsMixedReturns) {
  // The trunk box in decimetres (0.2 x 3 x 0.2 units = 2 cm x 30 cm x 2 cm) in front of the crown
  // box: edges over the crown give mixed returns.
  std::string out;
  const std::string common = "scan " + q("trunk.obj") + " " + q("crown.obj") +
                             " --pattern tls --step 1 --stations 2 --station-radius 6 --up y --units-metres 0.1 "
                             "--noise 0.001 --seed 3 --record-scanner";
  ASSERT_EQ(runCli(common + " -o " + q("thin.ply"), &out), 0) << out;
  EXPECT_EQ(out.find("footprint"), std::string::npos) << out;
  ASSERT_EQ(runCli(common + " -o " + q("r.ply") +
                       " --registration-translation 0.01 --registration-rotation 0.05 --footprint --beam-divergence 5"
                       " --beam-diameter 0.01 --beam-rays 8 --beam-min-share 0.25 --beam-tolerance 0.005",
                   &out),
            0)
      << out;
  EXPECT_NE(out.find(" mixed, "), std::string::npos) << out;
  EXPECT_EQ(out.find("footprint: 0 mixed"), std::string::npos) << out;
  const treesketch::geom::PointCloud thin = treesketch::io::readPointCloud(dir / "thin.ply");
  const treesketch::geom::PointCloud cloud = treesketch::io::readPointCloud(dir / "r.ply");
  ASSERT_GT(cloud.size(), 0u);
  ASSERT_EQ(cloud.scanner.size(), cloud.size());
  ASSERT_EQ(thin.scanner.size(), thin.size());
  // Stations 1.5 m = 15 units above the scene's bottom (y = 0); with registration error they move
  // by a few millimetres (tenths of a unit) only.
  for (std::size_t i = 0; i < thin.size(); ++i) ASSERT_NEAR(thin.scanner[i].y(), 15.0, 1e-12);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    ASSERT_NEAR(cloud.scanner[i].y(), 15.0, 0.6);
    ASSERT_NEAR(std::hypot(cloud.scanner[i].x(), cloud.scanner[i].z()), 6.0, 0.6);
  }
  EXPECT_NE(cloud.scanner.front(), thin.scanner.front());
}

TEST_F(ScanCli, BadInputAndOptionsGiveDistinctExitCodes) {
  const std::string trunk = q("trunk.obj");
  EXPECT_EQ(runCli("scan " + q("missing.obj") + " -o " + q("x.ply")), 3);
  writeText(dir / "garbage.obj", "v 1 2\nf 1 2 3\n");
  EXPECT_EQ(runCli("scan " + q("garbage.obj") + " -o " + q("x.ply")), 3);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --pattern cone"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --subdiv 0"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --subdiv 3 --rays 100"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --jitter 120"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --pattern tls --step 0"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --pattern tls --noise -1"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --pattern tls --up w --step 10"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --units-metres 0"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --subdiv 1 --registration-rotation 0.1"), 2);  // sphere
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --pattern tls --step 10 --registration-translation -1"),
            2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --subdiv 1 --footprint --beam-rays 2"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply") + " --subdiv 1 --footprint --beam-min-share 2"), 2);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply")), 0);
  EXPECT_EQ(runCli("scan " + trunk + " -o " + trunk), 4);  // never overwrite an input
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("trunk.obj/x.ply") + " --subdiv 1"),
            4);  // a file where the output folder should be (a missing one is created)
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.ply/y.ply") + " --subdiv 1"), 4);        // x.ply is a file
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("no/such/dir/x.ply") + " --subdiv 1"), 0);  // folders created
  EXPECT_EQ(runCli("scan " + trunk + " -o " + q("x.abc") + " --subdiv 1"), 4);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.abc"));
}

}  // namespace
