// Outputs through the CLI: every command checks its outputs can be written before it
// reads or computes anything (exit 4 even when the inputs are missing), creates missing output
// folders, removes the temporary files a killed run left, and leaves none itself when it is
// stopped by SIGTERM, SIGINT or SIGHUP in the middle of a write.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.h"
#include "test_support.h"

extern char** environ;

namespace treesketch {
namespace {

namespace fs = std::filesystem;
using test::runCli;

constexpr int kExitOutput = 4;  // apps/cli/commands.h
const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

class OutputSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    test::writeText(dir / "tri.obj", kTriangleObj);
    fs::create_directory(dir / "folder");
    test::writeText(dir / "file.txt", "not a folder\n");
  }
  std::string q(const std::string& name) const { return test::quoted(dir / name); }
  /// Names in the test folder starting with '.': temporary files left behind.
  std::vector<std::string> hidden() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir.path()))
      if (e.path().filename().string()[0] == '.') names.push_back(e.path().filename().string());
    return names;
  }
  test::TempDir dir;
};

TEST_F(OutputSafety, AnUnwritableOutputIsReportedBeforeAnyInputIsRead) {
  // The inputs do not exist: an input error (3) would mean the output was checked too late.
  const std::string missing = q("missing.xyz") + " ";
  const std::vector<std::string> commands = {
      "compare " + q("missing.obj") + " " + q("missing2.obj") + " --json " + q("folder"),
      "compare " + q("missing.obj") + " " + q("missing2.obj") + " --error-mesh " + q("file.txt/e.ply"),
      "scan " + q("missing.obj") + " -o " + q("folder"),
      "reconstruct " + missing + "--sketch " + q("missing.json") + " -o " + q("folder"),
      "reconstruct " + missing + "--sketch " + q("missing.json") + " -o " + q("m.obj") + " --report " +
          q("file.txt/r.json"),
      "reconstruct " + missing + "--auto -o " + q("file.txt/m.obj"),
      "reconstruct " + missing + "--auto -o " + q("m.obj") + " --cylinders " + q("folder"),
      "render --cloud " + missing + "-o " + q("folder"),
      "sketch auto " + missing + "-o " + q("folder"),
      "fit-report " + missing + q("missing.csv") + " --json " + q("folder"),
      "demo --out " + q("file.txt"),
      "evaluate --builtin 1 --out " + q("file.txt"),
  };
  for (const std::string& c : commands) {
    std::string out;
    EXPECT_EQ(runCli(c, &out), kExitOutput) << c << "\n" << out;
    EXPECT_TRUE(out.find("folder") != std::string::npos || out.find("file.txt") != std::string::npos) << out;
  }
}

TEST_F(OutputSafety, AReadOnlyFolderIsReportedBeforeTheWork) {
  if (::geteuid() == 0) GTEST_SKIP() << "root may write into read-only folders";
  fs::create_directory(dir / "ro");
  ::chmod((dir / "ro").c_str(), 0555);
  std::string out;
  EXPECT_EQ(runCli("scan " + q("missing.obj") + " -o " + q("ro/c.ply"), &out), kExitOutput) << out;
  EXPECT_NE(out.find("not writable"), std::string::npos) << out;
  ::chmod((dir / "ro").c_str(), 0755);
}

TEST_F(OutputSafety, MissingOutputFoldersAreCreated) {
  std::string out;
  ASSERT_EQ(runCli("compare " + q("tri.obj") + " " + q("tri.obj") + " --json " + q("new/sub/r.json"), &out), 0) << out;
  EXPECT_TRUE(fs::is_regular_file(dir / "new" / "sub" / "r.json"));
}

/// A PID that no longer runs: a child that has exited and been reaped.
pid_t deadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

TEST_F(OutputSafety, StaleTemporaryFilesOfADeadRunAreRemovedByTheNextWrite) {
  const std::string stale = ".r.json.tmp" + std::to_string(deadPid()) + "_0";
  const std::string live = ".r.json.tmp" + std::to_string(::getpid()) + "_0";  // this test runs: kept
  const std::string other = ".x.json.tmp" + std::to_string(deadPid()) + "_0";  // another output's: kept
  for (const auto& n : {stale, live, other}) test::writeText(dir / n, "half a file");
  std::string out;
  ASSERT_EQ(runCli("compare " + q("tri.obj") + " " + q("tri.obj") + " --json " + q("r.json"), &out), 0) << out;
  EXPECT_FALSE(fs::exists(dir / stale));
  EXPECT_TRUE(fs::exists(dir / live));
  EXPECT_TRUE(fs::exists(dir / other));
}

/// Starts the CLI with `args` and TREESKETCH_TEST_WRITE_DELAY_MS (it pauses in each write once its
/// temporary file exists), waits for the temporary file, sends `sig`; returns the wait status.
int killMidWrite(const fs::path& folder, std::vector<std::string> args, int sig) {
  args.insert(args.begin(), test::cliPath().string());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env{"TREESKETCH_TEST_WRITE_DELAY_MS=20000"};
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  std::vector<char*> envp;
  for (auto& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  // The child starts with the default action for the three signals, even when this test was
  // started with one of them ignored (a background job's SIGINT, nohup's SIGHUP).
  posix_spawnattr_t attr;
  ::posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&defaults, s);
  ::posix_spawnattr_setsigdefault(&attr, &defaults);
  ::posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, argv[0], nullptr, &attr, argv.data(), envp.data());
  ::posix_spawnattr_destroy(&attr);
  if (spawned != 0) return -1;
  bool seen = false;
  for (int i = 0; i < 600 && !seen; ++i) {  // up to 60 s (sanitizer builds start slowly)
    for (const auto& e : fs::directory_iterator(folder)) seen |= e.path().filename().string().rfind(".r.", 0) == 0;
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ::kill(pid, sig);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return seen ? status : -1;
}

TEST_F(OutputSafety, ARunStoppedMidWriteLeavesNoTemporaryFile) {
  for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
    SCOPED_TRACE(sig);
    const int status = killMidWrite(
        dir.path(),
        {"compare", (dir / "tri.obj").string(), (dir / "tri.obj").string(), "--json", (dir / "r.json").string()}, sig);
    ASSERT_NE(status, -1) << "the temporary file never appeared";
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;  // ends as the signal says
    EXPECT_TRUE(hidden().empty()) << hidden()[0];
    EXPECT_FALSE(fs::exists(dir / "r.json"));
  }
}

}  // namespace
}  // namespace treesketch
