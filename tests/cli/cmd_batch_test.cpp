// `treesketch batch` run as a process: a folder with two trees, a truncated LAS and a cylinder
// table; failure isolation, the summary, resume, --index, a manifest.
#include <fcntl.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "skeleton/synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch {
namespace {

namespace fs = std::filesystem;
using test::quoted;

class BatchCli : public ::testing::Test {
 protected:
  void SetUp() override {
    plot = dir / "plot";
    fs::create_directories(plot);
    io::writePointCloud(plot / "tree_a.ply", test::sampleCylinders(test::yTree(), 0.03, 0.003, 7));
    io::writePointCloud(plot / "tree_b.ply", test::sampleCylinders(test::threeLevelTree(), 0.03, 0.003, 8));
    test::writeText(plot / "broken.las", std::string("LASF") + std::string(60, '\0'));  // a truncated header
    test::writeText(plot / "model.csv", "ID,parentID,startX,startY,startZ,endX,endY,endZ,radius,length\n");
    test::writeText(plot / "notes.md", "not a cloud\n");
  }
  int batch(const std::string& args, std::string* out) {
    return test::runCli("batch " + quoted(plot) + " --out " + quoted(dir / "out") + args, out);
  }
  test::TempDir dir;
  fs::path plot;
};

TEST_F(BatchCli, FailingTreeIsRecordedTheRestGoOnAndRerunRedoesNothing) {
  std::string out;
  EXPECT_EQ(batch(" --jobs 2", &out), 6) << out;
  const fs::path o = dir / "out";
  for (const char* t : {"tree_a", "tree_b"}) {
    for (const char* f : {"mesh.ply", "cylinders.csv", "qsm.txt", "metrics.json", "report.json", "done.json"})
      EXPECT_TRUE(fs::exists(o / t / f)) << t << "/" << f << "\n" << out;
  }
  ASSERT_TRUE(fs::exists(o / "broken" / "failed.json")) << out;
  const auto failed = nlohmann::json::parse(test::readText(o / "broken" / "failed.json"));
  EXPECT_EQ(failed["exitCode"], 3);
  EXPECT_NE(failed["error"].get<std::string>().find("broken.las"), std::string::npos) << failed.dump();
  EXPECT_FALSE(fs::exists(o / "model")) << "the cylinder table is no tree";
  const auto summary = nlohmann::json::parse(test::readText(o / "summary.json"));
  EXPECT_EQ(summary["trees"], 3);
  EXPECT_EQ(summary["done"], 2);
  ASSERT_EQ(summary["skipped"].size(), 1u);
  const std::string csv = test::readText(o / "summary.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4) << csv;
  EXPECT_NE(csv.find("failed"), std::string::npos) << csv;
  // The metrics are there: the Y tree's trunk (radius 0.15, up y declared by the PLY).
  const auto m = nlohmann::json::parse(test::readText(o / "tree_a" / "metrics.json"));
  EXPECT_NEAR(m["dbhModelM"].get<double>(), 0.3, 0.03) << m.dump();
  EXPECT_NEAR(m["cloud"]["dbh"]["diameterM"].get<double>(), 0.3, 0.02) << m.dump();

  // Resume: nothing is run again, no output is rewritten.
  const auto stamp = fs::last_write_time(o / "tree_a" / "mesh.ply");
  EXPECT_EQ(batch("", &out), 6) << out;
  EXPECT_NE(out.find("0 to run"), std::string::npos) << out;
  EXPECT_EQ(fs::last_write_time(o / "tree_a" / "mesh.ply"), stamp);
  // A changed input is run again (here: the broken file fixed by removing it → a plot of two).
  fs::remove(plot / "broken.las");
  EXPECT_EQ(batch("", &out), 0) << out;
}

TEST_F(BatchCli, IndexRunsOneTreeAndSummariseGathers) {
  std::string out;
  // Sorted: broken.las (0), tree_a.ply (1), tree_b.ply (2).
  EXPECT_EQ(batch(" --index 1", &out), 0) << out;
  EXPECT_TRUE(fs::exists(dir / "out" / "tree_a" / "done.json")) << out;
  EXPECT_FALSE(fs::exists(dir / "out" / "tree_b"));
  EXPECT_EQ(batch(" --index 0", &out), 3) << out;  // the tree's own exit code
  EXPECT_TRUE(fs::exists(dir / "out" / "broken" / "failed.json"));
  EXPECT_EQ(batch(" --index 3", &out), 2) << out;
  EXPECT_EQ(batch(" --summarise", &out), 6) << out;
  const auto summary = nlohmann::json::parse(test::readText(dir / "out" / "summary.json"));
  EXPECT_EQ(summary["done"], 1);
  EXPECT_EQ(summary["results"][2]["status"], "not run");
}

TEST_F(BatchCli, ManifestAndBadInput) {
  test::writeText(dir / "trees.txt", "# one tree\nplot/tree_a.ply\n\n");
  std::string out;
  EXPECT_EQ(test::runCli("batch " + quoted(dir / "trees.txt") + " --out " + quoted(dir / "m"), &out), 0) << out;
  EXPECT_TRUE(fs::exists(dir / "m" / "tree_a" / "done.json"));
  // The same file name in two folders: two trees, two folders.
  fs::create_directories(dir / "other");
  fs::copy_file(plot / "tree_a.ply", dir / "other" / "tree_a.ply");
  test::writeText(dir / "two.txt", "plot/tree_a.ply\nother/tree_a.ply\n");
  EXPECT_EQ(test::runCli("batch " + quoted(dir / "two.txt") + " --out " + quoted(dir / "t") + " --jobs 2", &out), 0)
      << out;
  EXPECT_TRUE(fs::exists(dir / "t" / "tree_a_ply" / "done.json")) << out;
  EXPECT_TRUE(fs::exists(dir / "t" / "tree_a_ply_2" / "done.json")) << out;
  test::writeText(dir / "bad.txt", "plot/nothing.ply\n");
  EXPECT_EQ(test::runCli("batch " + quoted(dir / "bad.txt") + " --out " + quoted(dir / "m2"), &out), 3) << out;
  EXPECT_NE(out.find("bad.txt:1"), std::string::npos) << out;
  EXPECT_EQ(test::runCli("batch " + quoted(dir / "none") + " --out " + quoted(dir / "m3"), &out), 3) << out;
  EXPECT_EQ(batch(" --jobs 0", &out), 2) << out;
}

// done.json keeps the options that shaped the model; a rerun with other options runs the trees
// again (and says why) instead of reporting the old results.
TEST_F(BatchCli, ARerunWithOtherOptionsRunsTheTreesAgain) {
  std::string out;
  EXPECT_EQ(batch("", &out), 6) << out;
  const fs::path done = dir / "out" / "tree_a" / "done.json";
  auto j = nlohmann::json::parse(test::readText(done));
  EXPECT_EQ(j["options"]["seed"], 1);
  EXPECT_EQ(j["options"]["leafOn"], false);
  EXPECT_EQ(batch(" --seed 2", &out), 6) << out;
  EXPECT_NE(out.find("3 to run"), std::string::npos) << out;
  EXPECT_NE(out.find("tree_a runs again: made with other options"), std::string::npos) << out;
  j = nlohmann::json::parse(test::readText(done));
  EXPECT_EQ(j["options"]["seed"], 2);
  EXPECT_EQ(batch(" --seed 2", &out), 6) << out;
  EXPECT_NE(out.find("0 to run"), std::string::npos) << out;
  // --summarise gathers whatever the runs recorded
  EXPECT_EQ(batch(" --summarise", &out), 6) << out;
  EXPECT_EQ(nlohmann::json::parse(test::readText(dir / "out" / "summary.json"))["done"], 2);
}

// A tree killed by a signal (or failed writing its outputs) is run again; a tree whose input is
// broken is not.
TEST_F(BatchCli, ATreeKilledByASignalIsRetried) {
  std::string out;
  EXPECT_EQ(batch("", &out), 6) << out;
  const fs::path tree = dir / "out" / "tree_a";
  const auto done = nlohmann::json::parse(test::readText(tree / "done.json"));
  const nlohmann::json failed = {{"status", "failed"}, {"error", "crashed (signal 9)"}, {"exitCode", 1},
                                 {"signal", 9},        {"input", done["input"]},        {"options", done["options"]}};
  fs::remove(tree / "done.json");
  test::writeText(tree / "failed.json", failed.dump());
  EXPECT_EQ(batch("", &out), 6) << out;
  EXPECT_NE(out.find("1 to run"), std::string::npos) << out;
  EXPECT_NE(out.find("tree_a runs again: failed by killed by signal 9"), std::string::npos) << out;
  EXPECT_TRUE(fs::exists(tree / "done.json"));
  EXPECT_FALSE(fs::exists(tree / "failed.json"));
}

// Two runs on one --out at once: the second is refused (exit 4) while the first holds the lock.
TEST_F(BatchCli, TwoRunsOnOneOutAreRefused) {
  fs::create_directories(dir / "out");
  const int fd = ::open((dir / "out" / ".batch.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  std::string out;
  EXPECT_EQ(batch("", &out), 4) << out;
  EXPECT_NE(out.find("another batch run"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(dir / "out" / "tree_a"));
  ::close(fd);
  EXPECT_EQ(batch("", &out), 6) << out;  // the lock is gone with its holder
}

// --out inside the input folder: the batch's own summary.csv is not taken for a tree.
TEST_F(BatchCli, AnOutInsideTheInputIsNotReadAsTrees) {
  std::string out;
  EXPECT_EQ(test::runCli("batch " + quoted(plot) + " --out " + quoted(plot), &out), 6) << out;
  ASSERT_TRUE(fs::exists(plot / "summary.csv"));
  EXPECT_EQ(test::runCli("batch " + quoted(plot) + " --out " + quoted(plot), &out), 6) << out;
  EXPECT_NE(out.find("3 trees, 0 to run"), std::string::npos) << out;
  EXPECT_EQ(nlohmann::json::parse(test::readText(plot / "summary.json"))["trees"], 3);
  EXPECT_FALSE(fs::exists(plot / "summary"));
}

// --tree-timeout stops a tree and records it in failed.json; a rerun without the limit runs it.
TEST_F(BatchCli, ATreeTimeoutIsRecordedAndALongerLimitRetries) {
  std::string out;
  EXPECT_EQ(batch(" --tree-timeout 0.001", &out), 6) << out;
  const auto failed = nlohmann::json::parse(test::readText(dir / "out" / "tree_a" / "failed.json"));
  EXPECT_EQ(failed["timedOutAfterS"], 0.001);
  EXPECT_NE(failed["error"].get<std::string>().find("--tree-timeout"), std::string::npos) << failed.dump();
  EXPECT_EQ(batch(" --tree-timeout 0.001", &out), 6) << out;
  EXPECT_NE(out.find("0 to run"), std::string::npos) << out;
  EXPECT_EQ(batch("", &out), 6) << out;
  EXPECT_TRUE(fs::exists(dir / "out" / "tree_a" / "done.json")) << out;
  EXPECT_EQ(batch(" --tree-timeout -1", &out), 2) << out;
}

// --tree-memory bounds each tree's process; a tree that needs more is recorded in failed.json,
// and a rerun with a larger limit (or none) runs it again.
TEST_F(BatchCli, ATreeOverItsMemoryLimitIsRecordedAndALargerLimitRetries) {
  // AddressSanitizer reserves terabytes of address space at start: under a limit on it (what
  // --tree-memory sets) a sanitized tree process cannot start at all, so the limit is tested on
  // the release build only (`make test` runs both).
  if (std::getenv("TREESKETCH_SANITIZED"))
    GTEST_SKIP() << "an address-space limit cannot hold an AddressSanitizer process";
  std::string out;
  EXPECT_EQ(batch(" --tree-memory 1", &out), 6) << out;
  const auto failed = nlohmann::json::parse(test::readText(dir / "out" / "tree_a" / "failed.json"));
  EXPECT_EQ(failed["outOfMemoryMb"], 1) << failed.dump();
  EXPECT_NE(failed["error"].get<std::string>().find("--tree-memory"), std::string::npos) << failed.dump();
  EXPECT_EQ(batch(" --tree-memory 1", &out), 6) << out;
  EXPECT_NE(out.find("0 to run"), std::string::npos) << out;
  EXPECT_EQ(batch(" --tree-memory 4000", &out), 6) << out;
  EXPECT_TRUE(fs::exists(dir / "out" / "tree_a" / "done.json")) << out;
}

// An --out that cannot be written is exit 4 before any work (not an internal error).
TEST_F(BatchCli, AnUnwritableOutIsAnOutputError) {
  test::writeText(dir / "file", "x");
  std::string out;
  EXPECT_EQ(test::runCli("batch " + quoted(plot) + " --out " + quoted(dir / "file"), &out), 4) << out;
}

}  // namespace
}  // namespace treesketch
