// `treesketch fit-report` and `treesketch reconstruct --auto --report`, run as processes.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "cli_support.h"
#include "skeleton/synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch::compare {
namespace {

using test::runCli;
using test::TempDir;

std::string q(const std::filesystem::path& p) { return test::quoted(p); }

/// 400 points on a cylinder of radius 0.1 along z from 0 to 2 (ring by ring), 100 points 0.3 off
/// its side (missed wood), all times `scale` (1 = metres, 1000 = millimetres).
geom::PointCloud cylinderCloud(double scale) {
  geom::PointCloud c;
  for (int i = 0; i < 400; ++i) {
    const double phi = 2 * std::numbers::pi * (i % 20) / 20.0, z = 0.05 + 1.9 * (i / 20) / 19.0;
    c.positions.emplace_back(scale * 0.1 * std::cos(phi), scale * 0.1 * std::sin(phi), scale * z);
  }
  for (int i = 0; i < 100; ++i) c.positions.emplace_back(scale * 0.4, 0, scale * (0.1 + 0.018 * i));
  return c;
}

class FitReportCli : public ::testing::Test {
 protected:
  void writeTables(double s) {
    std::ostringstream ts, sf, tq;
    // The cylinder as two rows of each format: z 0..1.2 and its child 1.2..2.
    ts << "id,parent,start_x,start_y,start_z,end_x,end_y,end_z,radius,length,branch_order,start_radius\n"
       << "1,-1,0,0,0,0,0," << 1.2 * s << "," << 0.1 * s << "," << 1.2 * s << ",0," << 0.1 * s << "\n"
       << "2,1,0,0," << 1.2 * s << ",0,0," << 2 * s << "," << 0.1 * s << "," << 0.8 * s << ",0," << 0.1 * s << "\n";
    sf << " ID, parentID, startX, startY, startZ, endX, endY, endZ, radius, length, growthLength, branchOrder\n"
       << "0,-1,0,0,0,0,0," << 1.2 * s << "," << 0.1 * s << "," << 1.2 * s << ",2,0\n"
       << "1,0,0,0," << 1.2 * s << ",0,0," << 2 * s << "," << 0.1 * s << "," << 0.8 * s << ",0.8,0\n";
    tq << 0.1 * s << "\t" << 1.2 * s << "\t0\t0\t0\t0\t0\t1\t0\n"
       << 0.1 * s << "\t" << 0.8 * s << "\t0\t0\t" << 1.2 * s << "\t0\t0\t1\t1\n";
    test::writeText(dir / "ts.csv", ts.str());
    test::writeText(dir / "sf.csv", sf.str());
    test::writeText(dir / "tq.txt", tq.str());
  }
  TempDir dir;
};

TEST_F(FitReportCli, ThreeFormatsGiveTheSameReport) {
  io::writePointCloud(dir / "c.xyz", cylinderCloud(1));
  writeTables(1);
  for (const char* table : {"ts.csv", "sf.csv", "tq.txt"}) {
    std::string out;
    ASSERT_EQ(runCli("fit-report " + q(dir / "c.xyz") + " " + q(dir / table) + " --json " + q(dir / "r.json"), &out), 0)
        << table << ": " << out;
    EXPECT_NE(out.find("80.0 % within ±2 cm"), std::string::npos) << out;
    EXPECT_NE(out.find("20.0 % missed"), std::string::npos) << out;
    const auto j = nlohmann::json::parse(test::readText(dir / "r.json"));
    EXPECT_EQ(j["fit"]["points"], 500);
    EXPECT_DOUBLE_EQ(j["fit"]["within1cm"].get<double>(), 0.8) << table;
    EXPECT_DOUBLE_EQ(j["fit"]["outsideFarther5cm"].get<double>(), 0.2) << table;
    EXPECT_DOUBLE_EQ(j["fit"]["insideDeeper2cm"].get<double>(), 0.0) << table;
    EXPECT_NEAR(j["fit"]["medianSignedDistanceM"].get<double>(), 0.0, 1e-12) << table;
    EXPECT_EQ(j["figures"]["cylinders"], 2);
    EXPECT_NEAR(j["figures"]["volumeM3"].get<double>(), std::numbers::pi * 0.01 * 2, 1e-9) << table;
    EXPECT_NEAR(j["figures"]["lengthM"].get<double>(), 2.0, 1e-9) << table;
    EXPECT_NEAR(j["figures"]["trunkDiameterM"].get<double>(), 0.2, 1e-9) << table;
    EXPECT_EQ(j["figures"]["trunkPiece"], 1) << table;  // z 1.3 is in the second piece
  }
}

TEST_F(FitReportCli, UnitsMetres) {
  io::writePointCloud(dir / "c.xyz", cylinderCloud(1000));
  writeTables(1000);
  std::string out;
  ASSERT_EQ(runCli("fit-report " + q(dir / "c.xyz") + " " + q(dir / "sf.csv") + " --units-metres 0.001 --json " +
                       q(dir / "r.json"),
                   &out),
            0)
      << out;
  auto j = nlohmann::json::parse(test::readText(dir / "r.json"));
  EXPECT_DOUBLE_EQ(j["fit"]["within2cm"].get<double>(), 0.8);
  EXPECT_NEAR(j["figures"]["volumeM3"].get<double>(), std::numbers::pi * 0.01 * 2, 1e-9);
  EXPECT_NEAR(j["figures"]["trunkDiameterM"].get<double>(), 0.2, 1e-9);
  // Read as metres, the same files give the same shares (distances are relative to the model)
  // but figures 1000 times larger: 1.3 "m" above the base is in the first piece.
  ASSERT_EQ(runCli("fit-report " + q(dir / "c.xyz") + " " + q(dir / "sf.csv") + " --json " + q(dir / "m.json"), &out),
            0);
  j = nlohmann::json::parse(test::readText(dir / "m.json"));
  EXPECT_DOUBLE_EQ(j["fit"]["within2cm"].get<double>(), 0.8);
  EXPECT_NEAR(j["figures"]["volumeM3"].get<double>(), std::numbers::pi * 0.01 * 2 * 1e9, 1e-3);
  EXPECT_NEAR(j["figures"]["trunkDiameterM"].get<double>(), 200, 1e-9);
  EXPECT_EQ(j["figures"]["trunkPiece"], 0);
}

TEST_F(FitReportCli, Errors) {
  io::writePointCloud(dir / "c.xyz", cylinderCloud(1));
  writeTables(1);
  test::writeText(dir / "bad.csv",
                  "id,parent,start_x,start_y,start_z,end_x,end_y,end_z,radius,length,branch_order\n"
                  "1,-1,0,0,0,0,0,1,0.1,1,0\n1,-1,0,0,0,0,0,1,thick,1,0\n");
  std::string out;
  EXPECT_EQ(runCli("fit-report " + q(dir / "c.xyz") + " " + q(dir / "bad.csv"), &out), 3) << out;
  EXPECT_NE(out.find("bad.csv:3:"), std::string::npos) << out;
  EXPECT_NE(out.find("'radius'"), std::string::npos) << out;
  test::writeText(dir / "empty.csv", "radius,start_x,start_y,start_z,end_x,end_y,end_z\n");
  EXPECT_EQ(runCli("fit-report " + q(dir / "c.xyz") + " " + q(dir / "empty.csv"), &out), 3) << out;
  EXPECT_NE(out.find("no cylinders"), std::string::npos) << out;
  EXPECT_EQ(runCli("fit-report " + q(dir / "missing.xyz") + " " + q(dir / "sf.csv"), &out), 3) << out;
  EXPECT_EQ(runCli("fit-report " + q(dir / "c.xyz") + " " + q(dir / "sf.csv") + " --units-metres 0", &out), 2) << out;
  EXPECT_EQ(runCli("fit-report " + q(dir / "c.xyz"), &out), 2) << out;
  EXPECT_EQ(runCli("fit-report " + q(dir / "c.xyz") + " " + q(dir / "sf.csv") + " --json " +
                       q(dir / "c.xyz" / "r.json"),  // a file is no folder (missing folders are created)
                   &out),
            4)
      << out;
  // The report never overwrites an input.
  EXPECT_EQ(runCli("fit-report " + q(dir / "c.xyz") + " " + q(dir / "sf.csv") + " --json " + q(dir / "sf.csv"), &out),
            4)
      << out;
  EXPECT_NE(test::readText(dir / "sf.csv").find("parentID"), std::string::npos);
}

TEST_F(FitReportCli, ReconstructAutoReportMatchesItsCylinderTable) {
  io::writePointCloud(dir / "y.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  std::string out;
  ASSERT_EQ(runCli("reconstruct " + q(dir / "y.ply") + " --auto --cylinders " + q(dir / "y.csv") + " --report " +
                       q(dir / "r.json") + " --sketch " + q(dir / "s.json") + " -o " + q(dir / "y.obj"),
                   &out),
            0)
      << out;
  EXPECT_NE(out.find("model fit: "), std::string::npos) << out;
  EXPECT_NE(out.find("within ±2 cm"), std::string::npos) << out;
  const auto r = nlohmann::json::parse(test::readText(dir / "r.json"));
  EXPECT_EQ(r["auto"], true);
  EXPECT_GT(r["skeletonNodes"].get<int>(), 3);
  const auto& fit = r["model"]["fit"];
  // The Y tree's surface is sampled with 3 mm noise; the automatic model follows it.
  EXPECT_GT(fit["within2cm"].get<double>(), 0.9) << fit.dump();
  EXPECT_LT(fit["outsideFarther5cm"].get<double>(), 0.05) << fit.dump();
  EXPECT_LT(std::abs(fit["medianSignedDistanceM"].get<double>()), 0.01) << fit.dump();
  // Trunk radius 0.15 (units as metres, up y): the diameter at 1.3 is about 0.3.
  EXPECT_NEAR(r["model"]["figures"]["trunkDiameterM"].get<double>(), 0.3, 0.03) << r["model"].dump();
  // The cylinder table holds the same frustums (9 significant digits): fit-report agrees.
  ASSERT_EQ(
      runCli("fit-report " + q(dir / "y.ply") + " " + q(dir / "y.csv") + " --up y --json " + q(dir / "f.json"), &out),
      0)
      << out;
  const auto f = nlohmann::json::parse(test::readText(dir / "f.json"));
  EXPECT_EQ(f["format"], "treesketch");
  for (const char* k : {"within1cm", "within2cm", "within5cm", "insideDeeper2cm", "outsideFarther5cm"})
    EXPECT_NEAR(f["fit"][k].get<double>(), fit[k].get<double>(), 1e-3) << k;
  EXPECT_NEAR(f["figures"]["volumeM3"].get<double>(), r["model"]["figures"]["volumeM3"].get<double>(), 1e-6);
  EXPECT_NEAR(f["figures"]["trunkDiameterM"].get<double>(), r["model"]["figures"]["trunkDiameterM"].get<double>(),
              1e-6);
  // Rebuilt from its sketch (the kept circles; forks the mesh bridges are disabled and bridged
  // here too), the report measures nearly the same model.
  ASSERT_EQ(runCli("reconstruct " + q(dir / "y.ply") + " --sketch " + q(dir / "s.json") + " --report " +
                       q(dir / "k.json") + " -o " + q(dir / "k.obj"),
                   &out),
            0)
      << out;
  EXPECT_NE(out.find("model fit: "), std::string::npos) << out;
  const auto k = nlohmann::json::parse(test::readText(dir / "k.json"));
  ASSERT_TRUE(k["nodes"].is_array());
  EXPECT_GT(k["model"]["fit"]["within2cm"].get<double>(), 0.9) << k["model"].dump();
  EXPECT_NEAR(k["model"]["figures"]["volumeM3"].get<double>(), r["model"]["figures"]["volumeM3"].get<double>(),
              0.1 * r["model"]["figures"]["volumeM3"].get<double>());
  // --units-metres is checked like fit-report's, and only goes with --report.
  EXPECT_EQ(runCli("reconstruct " + q(dir / "y.ply") + " --auto --units-metres 0.001 -o " + q(dir / "y3.obj"), &out), 2)
      << out;
  EXPECT_NE(out.find("needs --report"), std::string::npos) << out;
  EXPECT_EQ(runCli("reconstruct " + q(dir / "y.ply") + " --auto --report " + q(dir / "r2.json") +
                       " --units-metres 0 -o " + q(dir / "y2.obj"),
                   &out),
            2)
      << out;
}

/// TreeQSM's total volume of a shared cloud (../shared/data/real/treeqsm/NAME_treedata.txt, litres)
/// in m³; NaN when it is not there.
double treeQsmVolume(const std::filesystem::path& real, const std::string& name) {
  std::istringstream in(test::readText(real / "treeqsm" / (name + "_treedata.txt")));
  std::string key;
  double value = 0;
  while (in >> key >> value)
    if (key == "TotalVolume") return value / 1000.0;
  return std::nan("");
}

// The automatic model on real leaf-off scans (../shared/data/real; skipped without it), as
// docs/evaluation/real/table.md reports it: a floor under the share of points within ±2 cm and a
// ceiling over the share deeper than 2 cm inside, a little beyond the measured figures (rtwig
// 94.7 %, archi_Tree_2 94.2 %, adtree_tree7 77.1 % within; 0.0 / 0.1 / 1.0 % inside; adtree_tree1,
// not used to choose any setting, 63.3 % and 2.7 %), and the volume within 0.67–1.5× of TreeQSM's
// credible model of the same cloud (measured 0.99, 0.85, 1.28, 1.11).
TEST(RealScans, TheAutomaticModelExplainsEachCloudAsReported) {
  const auto real = test::sharedDataDir() / "real";
  if (!std::filesystem::exists(real)) GTEST_SKIP() << "no " << real;
  struct Case {
    const char* file;
    const char* name;
    double minWithin2cm, maxInside2cm;
  };
  TempDir dir;
  for (const Case& c : {Case{"rtwig_cloud.txt", "rtwig_cloud", 0.94, 0.005},
                        Case{"archi_Tree_2_point_cloud.las", "archi_Tree_2_point_cloud", 0.935, 0.005},
                        Case{"adtree_tree7.xyz", "adtree_tree7", 0.765, 0.015},
                        Case{"adtree_tree1.xyz", "adtree_tree1", 0.62, 0.035}}) {
    std::string out;
    ASSERT_EQ(runCli("reconstruct " + q(real / c.file) + " --auto --up z --report " + q(dir / "r.json") + " -o " +
                         q(dir / "m.ply"),
                     &out),
              0)
        << out;
    const auto report = nlohmann::json::parse(test::readText(dir / "r.json"));
    const auto fit = report["model"]["fit"];
    EXPECT_GE(fit["within2cm"].get<double>(), c.minWithin2cm) << c.file << ": " << fit.dump();
    EXPECT_LE(fit["insideDeeper2cm"].get<double>(), c.maxInside2cm) << c.file << ": " << fit.dump();
    const double reference = treeQsmVolume(real, c.name);
    if (std::isnan(reference)) continue;
    const double ratio = report["metrics"]["volumeM3"].get<double>() / reference;
    EXPECT_GE(ratio, 0.67) << c.file;
    EXPECT_LE(ratio, 1.5) << c.file;
  }
}

}  // namespace
}  // namespace treesketch::compare
