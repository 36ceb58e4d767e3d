// Tests of util/progress: when the bar draws, what it draws, that its callback forwards, and that
// it clears its line. Stderr is sent to a file while a test runs; the bar shows nothing during the
// first second of work, so the tests that expect a drawing wait a little over a second first.
#include "treesketch/util/progress.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "test_support.h"

namespace treesketch {
namespace {

/// Sends stderr (file descriptor 2) to `file` while alive.
class StderrToFile {
 public:
  explicit StderrToFile(const std::filesystem::path& file) : file_(file) {
    std::fflush(stderr);
    saved_ = ::dup(STDERR_FILENO);
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, STDERR_FILENO);
    ::close(fd);
  }
  ~StderrToFile() {
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
  }
  /// Everything written to stderr so far.
  std::string text() const {
    std::fflush(stderr);
    return test::readText(file_);
  }

 private:
  std::filesystem::path file_;
  int saved_;
};

/// Past the bar's first second (it draws nothing before).
void waitPastFirstSecond() { std::this_thread::sleep_for(std::chrono::milliseconds(1100)); }

/// One drawing of a bar: carriage return, label, 30 cells, percentage with one decimal.
std::string drawing(const std::string& label, int filled, const std::string& percent) {
  return "\r" + label + " [" + std::string(filled, '#') + std::string(30 - filled, ' ') + "] " + percent + "%";
}

/// What the bar writes when it goes away after drawing: the line blanked, the cursor back at its start.
const std::string kCleared = "\r" + std::string(70, ' ') + "\r";

TEST(ProgressBar, DrawsOnlyWhenEnabledAfterTheFirstSecondAndClearsItsLine) {
  test::TempDir dir;
  StderrToFile capture(dir / "stderr.txt");
  {
    ProgressBar early("early", true);
    early.update(1, 2);  // short work shows no bar
    ProgressBar off("off", false);
    ProgressBar on("scan", true);
    waitPastFirstSecond();
    off.update(5, 10);  // a disabled bar never draws
    on.update(0, 0);    // nothing to count yet
    EXPECT_EQ(capture.text(), "");
    on.update(5, 10);
    EXPECT_EQ(capture.text(), drawing("scan", 15, " 50.0"));
    on.callback()(10, 10);  // the callback forwards; the last step is always drawn
    EXPECT_EQ(capture.text(), drawing("scan", 15, " 50.0") + drawing("scan", 30, "100.0"));
  }
  // Only the bar that drew clears its line.
  EXPECT_EQ(capture.text(), drawing("scan", 15, " 50.0") + drawing("scan", 30, "100.0") + kCleared);
}

TEST(ProgressBar, ConcurrentUpdatesDrawWholeLines) {
  test::TempDir dir;
  StderrToFile capture(dir / "stderr.txt");
  {
    ProgressBar bar("work", true);
    ProgressFn progress = bar.callback();
    waitPastFirstSecond();
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) {
      threads.emplace_back([&] {
        for (std::uint64_t done = 1; done <= 1000; ++done) progress(done, 1000);
      });
    }
    for (auto& t : threads) t.join();
  }
  // Every drawing is a whole line of the bar's fixed width (no two interleaved), the last one is
  // complete, and the bar cleared its line at the end.
  const std::string text = capture.text();
  ASSERT_GE(text.size(), kCleared.size());
  ASSERT_EQ(text.substr(text.size() - kCleared.size()), kCleared);
  const std::string drawn = text.substr(0, text.size() - kCleared.size());
  const std::size_t width = drawing("work", 0, "  0.0").size();
  ASSERT_GE(drawn.size(), width);
  ASSERT_EQ(drawn.size() % width, 0u) << drawn;
  for (std::size_t at = 0; at < drawn.size(); at += width) {
    const std::string one = drawn.substr(at, width);
    EXPECT_EQ(one.rfind("\rwork [", 0), 0u) << one;
    EXPECT_EQ(one.back(), '%') << one;
  }
  EXPECT_EQ(drawn.substr(drawn.size() - width), drawing("work", 30, "100.0"));
}

TEST(ProgressBar, StderrRedirectedToAFileIsNoTerminal) {
  test::TempDir dir;
  StderrToFile capture(dir / "stderr.txt");
  EXPECT_FALSE(ProgressBar::stderrIsTerminal());
}

}  // namespace
}  // namespace treesketch
