// `--set NAME=VALUE` and `--list-settings` on `reconstruct --auto` and `batch`, run as processes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.h"
#include "skeleton/synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch {
namespace {

using test::quoted;

std::string yTreeCloud(const test::TempDir& dir) {
  io::writePointCloud(dir / "c.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  return quoted(dir / "c.ply");
}

nlohmann::json readJson(const std::filesystem::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

TEST(CmdSettings, HelpAndListPrintTheTableWithoutACloud) {
  for (const std::string cmd : {"reconstruct --set help", "reconstruct --list-settings", "batch --set help"}) {
    std::string out;
    ASSERT_EQ(test::runCli(cmd, &out), 0) << cmd << ": " << out;
    EXPECT_NE(out.find("radii.surfaceBound"), std::string::npos) << cmd;
    EXPECT_NE(out.find("completion.enabled"), std::string::npos) << cmd;
    EXPECT_NE(out.find("--leaf-on starts from"), std::string::npos) << cmd;
  }
}

TEST(CmdSettings, UnknownNamesAndBadValuesAreUsageErrorsBeforeAnyOutput) {
  test::TempDir dir;
  const std::string cloud = yTreeCloud(dir);
  struct Case {
    const char* set;
    const char* says;
  };
  for (const Case c :
       {Case{"radii.medianWindw=3", "nearest: radii.medianWindow"}, Case{"radii.medianWindow=0", "outside"},
        Case{"radii.surfaceBound=2", "not a boolean"}, Case{"radii.medianWindow", "NAME=VALUE"}}) {
    std::string out;
    EXPECT_EQ(test::runCli("reconstruct " + cloud + " --auto -o " + quoted(dir / "m.ply") + " --set " + c.set, &out), 2)
        << c.set << ": " << out;
    EXPECT_NE(out.find(c.says), std::string::npos) << c.set << ": " << out;
    EXPECT_FALSE(std::filesystem::exists(dir / "m.ply")) << c.set;
  }
  std::string out;
  EXPECT_EQ(
      test::runCli("batch " + quoted(dir / "c.ply") + " --out " + quoted(dir / "out") + " --set nonsense=1", &out), 2)
      << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "summary.csv"));
  EXPECT_EQ(test::runCli("reconstruct " + cloud + " --sketch " + quoted(dir / "s.json") + " -o " +
                             quoted(dir / "m.ply") + " --set radii.medianWindow=3",
                         &out),
            2)
      << out;
  EXPECT_NE(out.find("--set needs --auto"), std::string::npos) << out;
}

// A setting reaches the model: with the completion and every radius rule off the model differs
// from the defaults', and the report records the settings it was made with.
TEST(CmdSettings, SettingsChangeTheModelAndAreReported) {
  test::TempDir dir;
  const std::string cloud = yTreeCloud(dir);
  std::string out;
  ASSERT_EQ(test::runCli("reconstruct " + cloud + " --auto -o " + quoted(dir / "a.ply") + " --cylinders " +
                             quoted(dir / "a.csv") + " --report " + quoted(dir / "a.json"),
                         &out),
            0)
      << out;
  ASSERT_EQ(test::runCli("reconstruct " + cloud + " --auto -o " + quoted(dir / "b.ply") + " --cylinders " +
                             quoted(dir / "b.csv") + " --report " + quoted(dir / "b.json") +
                             " --set radii.maxRadiusRatio=0.01 --set radii.surfaceBound=off",
                         &out),
            0)
      << out;
  EXPECT_TRUE(readJson(dir / "a.json")["settings"].empty());
  const nlohmann::json b = readJson(dir / "b.json");
  ASSERT_EQ(b["settings"].size(), 2u);
  EXPECT_EQ(b["settings"][0], "radii.maxRadiusRatio=0.01");
  std::ifstream fa(dir / "a.csv"), fb(dir / "b.csv");
  const std::string ta((std::istreambuf_iterator<char>(fa)), {}), tb((std::istreambuf_iterator<char>(fb)), {});
  EXPECT_NE(ta, tb);  // no fit passes a radius ratio of 0.01: every radius is interpolated
}

// batch hands the settings to each tree's process, records them in done.json, and runs a tree
// again when they change.
TEST(CmdSettings, BatchPassesSettingsToEveryTreeAndKeepsThem) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "in");
  io::writePointCloud(dir / "in" / "t.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  const std::string base = "batch " + quoted(dir / "in") + " --up y --out " + quoted(dir / "out");
  std::string out;
  ASSERT_EQ(test::runCli(base + " --set completion.enabled=off", &out), 0) << out;
  EXPECT_EQ(readJson(dir / "out" / "t" / "report.json")["settings"][0], "completion.enabled=off");
  EXPECT_EQ(readJson(dir / "out" / "t" / "done.json")["options"]["settings"][0], "completion.enabled=off");
  ASSERT_EQ(test::runCli(base + " --set completion.enabled=off", &out), 0) << out;
  EXPECT_NE(out.find("0 to run"), std::string::npos) << out;
  ASSERT_EQ(test::runCli(base, &out), 0) << out;
  EXPECT_NE(out.find("runs again"), std::string::npos) << out;
  EXPECT_TRUE(readJson(dir / "out" / "t" / "report.json")["settings"].empty());
}

}  // namespace
}  // namespace treesketch
