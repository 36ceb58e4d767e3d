// Requests that cannot be met are refused with exit 2 before any work: the inputs named here do
// not exist, so a command that read them first would exit 3 (or run out of memory) instead.
#include <gtest/gtest.h>

#include <string>

#include "cli_support.h"
#include "test_support.h"

namespace treesketch {
namespace {

using test::quoted;

int run(const std::string& args, std::string* out) { return test::runCli(args, out); }

TEST(ImpossibleRequests, AreRefusedBeforeAnyInputIsRead) {
  test::TempDir dir;
  const std::string missing = quoted(dir / "missing.obj"), cloud = quoted(dir / "missing.ply");
  std::string out;
  EXPECT_EQ(run("scan " + missing + " -o " + quoted(dir / "s.ply") + " --rays 0", &out), 2) << out;
  EXPECT_NE(out.find("--rays"), std::string::npos) << out;
  EXPECT_EQ(run("scan " + missing + " -o " + quoted(dir / "s.ply") + " --rays 100000000000", &out), 2) << out;
  EXPECT_EQ(run("scan " + missing + " -o " + quoted(dir / "s.ply") + " --subdiv 30", &out), 2) << out;
  EXPECT_EQ(run("compare " + missing + " " + missing + " --samples 4000000000", &out), 2) << out;
  EXPECT_NE(out.find("--samples 4000000000: at most 20000000"), std::string::npos) << out;
  EXPECT_EQ(run("sketch auto " + cloud + " --nodes 100000000 -o " + quoted(dir / "s.json"), &out), 2) << out;
  EXPECT_NE(out.find("--nodes must be at most 100000"), std::string::npos) << out;
  // within the bounds, the missing input is what is reported
  EXPECT_EQ(run("compare " + missing + " " + missing + " --samples 1000", &out), 3) << out;
  EXPECT_EQ(run("sketch auto " + cloud + " --nodes 18 -o " + quoted(dir / "s.json"), &out), 3) << out;
}

// Data problems are data errors naming the file (exit 3 or 5), not "bad command line" (exit 2).
TEST(ImpossibleRequests, DataProblemsAreNotCommandLineErrors) {
  test::TempDir dir;
  std::string out;
  test::writeText(dir / "cycle.csv",
                  "ID,parentID,startX,startY,startZ,endX,endY,endZ,radius,length\n"
                  "1,2,0,0,0,0,0,1,0.1,1\n2,1,0,0,1,0,0,2,0.05,1\n");
  EXPECT_EQ(run("metrics " + quoted(dir / "cycle.csv"), &out), 3) << out;
  EXPECT_NE(out.find("cycle.csv"), std::string::npos) << out;
  EXPECT_NE(out.find("cycle"), std::string::npos) << out;
  test::writeText(dir / "equal.xyz", "1 1 1\n1 1 1\n1 1 1\n1 1 1\n1 1 1\n");
  EXPECT_EQ(run("sketch auto " + quoted(dir / "equal.xyz") + " -o " + quoted(dir / "s.json"), &out), 5) << out;
  EXPECT_NE(out.find("equal.xyz"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "s.json"));
}

}  // namespace
}  // namespace treesketch
