// `treesketch metrics` and the metrics in `reconstruct --report`, run as processes.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "skeleton/synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch {
namespace {

namespace fs = std::filesystem;
using test::quoted;

TEST(MetricsCli, ReportAndMetricsCommandAgreeAndUpComesFromTheFile) {
  test::TempDir dir;
  io::writePointCloud(dir / "y.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));  // says up y
  std::string out;
  ASSERT_EQ(
      test::runCli("reconstruct " + quoted(dir / "y.ply") + " --auto --cylinders " + quoted(dir / "y.csv") + " --qsm " +
                       quoted(dir / "q.txt") + " --report " + quoted(dir / "r.json") + " -o " + quoted(dir / "y.obj"),
                   &out),
      0)
      << out;
  EXPECT_NE(out.find("up axis: y, as the file declares"), std::string::npos) << out;
  EXPECT_NE(out.find("DBH (cloud slice)"), std::string::npos) << out;
  const auto r = nlohmann::json::parse(test::readText(dir / "r.json"));
  const auto& m = r["metrics"];
  EXPECT_NEAR(m["dbhModelM"].get<double>(), 0.3, 0.03) << m.dump();  // trunk radius 0.15
  EXPECT_NEAR(m["cloud"]["dbh"]["diameterM"].get<double>(), 0.3, 0.02) << m.dump();
  EXPECT_NEAR(m["heightM"].get<double>(), 5.2, 0.3) << m.dump();  // the higher branch tip at y = 5.2
  EXPECT_GE(m["branches"].get<int>(), 1) << m.dump();
  // The metrics command on both tables gives the report's figures.
  ASSERT_EQ(test::runCli("metrics " + quoted(dir / "y.csv") + " " + quoted(dir / "q.txt") + " --cloud " +
                             quoted(dir / "y.ply") + " --json " + quoted(dir / "sub" / "m.json"),
                         &out),
            0)
      << out;
  const auto j = nlohmann::json::parse(test::readText(dir / "sub" / "m.json"));  // the folder was created
  EXPECT_EQ(j["up"], "y");
  ASSERT_EQ(j["models"].size(), 2u);
  for (const auto& model : j["models"]) {
    EXPECT_NEAR(model["metrics"]["volumeM3"].get<double>(), m["volumeM3"].get<double>(), 1e-6);
    EXPECT_NEAR(model["metrics"]["heightM"].get<double>(), m["heightM"].get<double>(), 1e-6);
    EXPECT_EQ(model["metrics"]["branches"], m["branches"]);
  }
  EXPECT_EQ(j["models"][1]["format"], "TreeQSM");
  // Without a cloud the up is z unless given; a bad table or up is refused.
  ASSERT_EQ(test::runCli("metrics " + quoted(dir / "y.csv") + " --up y", &out), 0) << out;
  EXPECT_NE(out.find("--up y"), std::string::npos) << out;
  EXPECT_EQ(test::runCli("metrics " + quoted(dir / "y.csv") + " --up x", &out), 2) << out;
  test::writeText(dir / "bad.csv", "radius,length\n0.1,abc\n");
  EXPECT_EQ(test::runCli("metrics " + quoted(dir / "bad.csv"), &out), 3) << out;
  EXPECT_NE(out.find("bad.csv"), std::string::npos) << out;
}

TEST(MetricsCli, TextCloudWithoutDeclarationIsZUp) {
  test::TempDir dir;
  // The Y tree turned Z-up, written as text (which cannot declare an up): the rule's default z.
  geom::PointCloud c = test::sampleCylinders(test::yTree(), 0.02, 0.003, 7);
  for (auto& p : c.positions) p = geom::Vec3(p.x(), -p.z(), p.y());
  io::writePointCloud(dir / "z.xyz", c);
  std::string out;
  ASSERT_EQ(test::runCli("reconstruct " + quoted(dir / "z.xyz") + " --auto --report " + quoted(dir / "r.json") +
                             " -o " + quoted(dir / "z.obj"),
                         &out),
            0)
      << out;
  EXPECT_NE(out.find("up axis: z, the default"), std::string::npos) << out;
  const auto r = nlohmann::json::parse(test::readText(dir / "r.json"));
  EXPECT_EQ(r["up"], "z");
  EXPECT_NEAR(r["metrics"]["dbhModelM"].get<double>(), 0.3, 0.03) << r["metrics"].dump();
}

TEST(MetricsCli, PublishedSimpleForestModelBesideTheCloud) {
  const fs::path real = test::sharedDataDir() / "real";
  if (!fs::exists(real / "rtwig_QSM_simpleforest.csv")) GTEST_SKIP() << "no shared data at " << real;
  test::TempDir dir;
  std::string out;
  ASSERT_EQ(test::runCli("metrics " + quoted(real / "rtwig_QSM_simpleforest.csv") + " --cloud " +
                             quoted(real / "rtwig_cloud.txt") + " --json " + quoted(dir / "m.json"),
                         &out),
            0)
      << out;
  const auto m = nlohmann::json::parse(test::readText(dir / "m.json"))["models"][0]["metrics"];
  EXPECT_NEAR(m["volumeM3"].get<double>(), 0.030, 0.0005);  // the data README's Σπr²L
  // DBH from the cloud's slice and from the published model agree within 10 %.
  const double model = m["dbhModelM"].get<double>(), cloud = m["cloud"]["dbh"]["diameterM"].get<double>();
  EXPECT_NEAR(cloud, model, 0.1 * model) << m.dump();
  EXPECT_NEAR(m["heightM"].get<double>(), m["cloud"]["heightM"].get<double>(), 0.1);
}

}  // namespace
}  // namespace treesketch
