// Tests of util/atomic_file: a write lands completely or not at all, leaves no temporary file
// behind, and an input file is never overwritten.
#include "treesketch/util/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "test_support.h"
#include "treesketch/util/error.h"

namespace treesketch {
namespace {

namespace fs = std::filesystem;
using Names = std::vector<std::string>;

/// The names of the entries of `dir`, sorted: a temporary file left behind shows up here.
Names entries(const fs::path& dir) {
  Names names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// A writer that puts some bytes out and then fails the way a full disk does: the stream goes bad.
void failingStream(std::ostream& out) {
  out << "part of the new contents";
  out.setstate(std::ios::badbit);
}

/// Runs `f`, expects an OutputError whose message holds every one of `parts`.
template <class F>
void expectOutputError(F&& f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "expected an OutputError, none was thrown";
  } catch (const OutputError& e) {
    const std::string msg = e.what();
    for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  }
}

TEST(AtomicFile, WritesTheExactBytesAndReplacesAnOldFile) {
  test::TempDir dir;
  const std::string bytes("a\0b\r\nc\xff\n", 8);  // a NUL, a CR LF, a high byte: binary mode keeps them
  writeFileAtomically(dir / "f.bin", [&](std::ostream& out) { out.write(bytes.data(), bytes.size()); });
  EXPECT_EQ(test::readText(dir / "f.bin"), bytes);
  // A shorter new version replaces the whole file (no tail of the old one survives).
  writeFileAtomically(dir / "f.bin", [](std::ostream& out) { out << "new"; });
  EXPECT_EQ(test::readText(dir / "f.bin"), "new");
  EXPECT_EQ(entries(dir.path()), Names{"f.bin"});
}

TEST(AtomicFile, AThrowingWriterLeavesTheOldFileAndNoTemporaryFile) {
  test::TempDir dir;
  test::writeText(dir / "f.txt", "old contents\n");
  try {
    writeFileAtomically(dir / "f.txt", [](std::ostream& out) {
      out << "half of the new contents";
      out.flush();  // the bytes reach the temporary file before the failure
      throw std::runtime_error("the writer failed");
    });
    ADD_FAILURE() << "the writer's exception did not propagate";
  } catch (const OutputError& e) {
    ADD_FAILURE() << "the writer's exception was replaced: " << e.what();
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "the writer failed");  // propagated as it was thrown
  }
  EXPECT_EQ(test::readText(dir / "f.txt"), "old contents\n");
  EXPECT_EQ(entries(dir.path()), Names{"f.txt"});
}

TEST(AtomicFile, AFailedStreamIsAnOutputErrorAndTheOldFileSurvives) {
  test::TempDir dir;
  test::writeText(dir / "f.txt", "old contents\n");
  expectOutputError([&] { writeFileAtomically(dir / "f.txt", failingStream); }, {"f.txt", "write failed"});
  EXPECT_EQ(test::readText(dir / "f.txt"), "old contents\n");
  // A new target whose write failed does not appear at all.
  expectOutputError([&] { writeFileAtomically(dir / "new.txt", failingStream); }, {"new.txt", "write failed"});
  EXPECT_EQ(entries(dir.path()), Names{"f.txt"});
}

TEST(AtomicFile, MissingDirectoryIsAnOutputErrorNamingIt) {
  test::TempDir dir;
  const auto ok = [](std::ostream& out) { out << "x"; };
  expectOutputError([&] { writeFileAtomically(dir / "no" / "f.txt", ok); }, {"f.txt", "no", "does not exist"});
  // A regular file where the directory should be is no directory either.
  test::writeText(dir / "file", "x");
  expectOutputError([&] { writeFileAtomically(dir / "file" / "f.txt", ok); }, {"f.txt", "does not exist"});
  EXPECT_EQ(entries(dir.path()), Names{"file"});
  EXPECT_EQ(test::readText(dir / "file"), "x");
}

TEST(AtomicFile, CreatesMissingFoldersWhenAskedNotOtherwise) {
  test::TempDir dir;
  const auto ok = [](std::ostream& out) { out << "x"; };
  setCreateOutputDirectories(true);
  writeFileAtomically(dir / "new" / "deeper" / "f.txt", ok);
  EXPECT_EQ(test::readText(dir / "new" / "deeper" / "f.txt"), "x");
  test::writeText(dir / "file", "x");  // a regular file in the way: still an error, naming it
  expectOutputError([&] { writeFileAtomically(dir / "file" / "f.txt", ok); }, {"f.txt", "cannot be created"});
  setCreateOutputDirectories(false);
  expectOutputError([&] { writeFileAtomically(dir / "other" / "f.txt", ok); }, {"other", "does not exist"});
  EXPECT_FALSE(std::filesystem::exists(dir / "other"));
}

TEST(AtomicFile, ATargetThatIsADirectoryFailsAtTheRenameAndIsLeftAlone) {
  test::TempDir dir;
  fs::create_directories(dir / "d" / "inside");
  expectOutputError([&] { writeFileAtomically(dir / "d", [](std::ostream& out) { out << "x"; }); },
                    {"d", "cannot rename"});
  EXPECT_TRUE(fs::is_directory(dir / "d" / "inside"));
  EXPECT_EQ(entries(dir.path()), Names{"d"});
}

TEST(AtomicFile, ABareFileNameIsWrittenInTheCurrentDirectory) {
  test::TempDir dir;
  const fs::path before = fs::current_path();
  fs::current_path(dir.path());
  EXPECT_NO_THROW(writeFileAtomically("bare.txt", [](std::ostream& out) { out << "here"; }));
  fs::current_path(before);
  EXPECT_EQ(test::readText(dir / "bare.txt"), "here");
  EXPECT_EQ(entries(dir.path()), Names{"bare.txt"});
}

// Each writer has its own temporary file: writers racing on one target leave exactly one of
// their complete versions, never a mix, and nothing else.
TEST(AtomicFile, ConcurrentWritersLeaveOneCompleteVersion) {
  test::TempDir dir;
  constexpr int kWriters = 4, kRounds = 10;
  constexpr std::size_t kBytes = 1 << 16;  // several stream buffers: a write is not one syscall
  std::vector<std::thread> threads;
  for (int w = 0; w < kWriters; ++w) {
    threads.emplace_back([&, w] {
      for (int r = 0; r < kRounds; ++r) {
        writeFileAtomically(dir / "f.bin", [&](std::ostream& out) {
          const std::string block(kBytes, static_cast<char>('a' + w));
          out.write(block.data(), block.size());
        });
      }
    });
  }
  for (auto& t : threads) t.join();
  const std::string text = test::readText(dir / "f.bin");
  ASSERT_EQ(text.size(), kBytes);
  EXPECT_EQ(std::count(text.begin(), text.end(), text.front()), static_cast<std::ptrdiff_t>(kBytes));
  EXPECT_EQ(entries(dir.path()), Names{"f.bin"});
}

TEST(CheckNotAnInput, RefusesAnOutputThatIsAnInputUnderAnySpelling) {
  test::TempDir dir;
  test::writeText(dir / "in.xyz", "1 2 3\n");
  fs::create_directories(dir / "sub");
  expectOutputError(
      [&] {
        checkNotAnInput(dir / "in.xyz", {dir / "other.xyz", dir / "in.xyz"});
      },
      {"in.xyz", "refusing to overwrite an input"});
  // The same file through "sub/..", and through a hard link, is still the input.
  EXPECT_THROW(checkNotAnInput(dir / "sub" / ".." / "in.xyz", {dir / "in.xyz"}), OutputError);
  fs::create_hard_link(dir / "in.xyz", dir / "link.xyz");
  EXPECT_THROW(checkNotAnInput(dir / "link.xyz", {dir / "in.xyz"}), OutputError);
  EXPECT_EQ(test::readText(dir / "in.xyz"), "1 2 3\n");
}

TEST(CheckNotAnInput, AcceptsNewFilesOtherFilesAndMissingInputs) {
  test::TempDir dir;
  test::writeText(dir / "in.xyz", "1 2 3\n");
  test::writeText(dir / "old.ply", "x");
  EXPECT_NO_THROW(checkNotAnInput(dir / "new.ply", {dir / "in.xyz"}));             // does not exist yet
  EXPECT_NO_THROW(checkNotAnInput(dir / "old.ply", {dir / "in.xyz"}));             // exists, another file
  EXPECT_NO_THROW(checkNotAnInput(dir / "old.ply", {dir / "missing.xyz"}));        // the input is absent
  EXPECT_NO_THROW(checkNotAnInput(dir / "old.ply", {}));                           // no inputs at all
  EXPECT_NO_THROW(checkNotAnInput(dir / "in.xyz", {dir / "old.ply", dir / "x"}));  // not among the inputs
}

/// A PID that no longer runs: a child that has exited and been reaped.
pid_t deadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

TEST(RemoveStaleTempFiles, RemovesOnlyOurNamesOfDeadProcesses) {
  test::TempDir dir;
  const std::string dead = std::to_string(deadPid()), self = std::to_string(::getpid());
  const Names kept{
      ".f.txt.tmp" + self + "_3",  // this process's write in progress
      ".f.txt.tmp" + dead + "_",   // not our naming: no counter
      ".f.txt.tmp" + dead + "_0x", ".f.txt.tmpabc_0", ".g.txt.tmp" + dead + "_0", "f.txt.tmp" + dead + "_0", "f.txt"};
  for (const auto& n : kept) test::writeText(dir / n, "x");
  test::writeText(dir / (".f.txt.tmp" + dead + "_0"), "stale");
  test::writeText(dir / (".f.txt.tmp" + dead + "_17"), "stale");
  EXPECT_EQ(removeStaleTempFiles(dir / "f.txt"), 2u);
  Names expected = kept;
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(entries(dir.path()), expected);
  // The next atomic write to the output removes them too.
  test::writeText(dir / (".f.txt.tmp" + dead + "_5"), "stale");
  writeFileAtomically(dir / "f.txt", [](std::ostream& out) { out << "new"; });
  EXPECT_EQ(entries(dir.path()), expected);
}

TEST(CheckOutputWritable, CreatesMissingFoldersAndRejectsFoldersAndFiles) {
  test::TempDir dir;
  EXPECT_NO_THROW(checkOutputWritable(""));  // an output not asked for
  EXPECT_NO_THROW(checkOutputWritable(dir / "a" / "b" / "f.txt"));
  EXPECT_TRUE(fs::is_directory(dir / "a" / "b"));
  EXPECT_FALSE(fs::exists(dir / "a" / "b" / "f.txt"));  // nothing written yet
  expectOutputError([&] { checkOutputWritable(dir / "a"); }, {"is a folder"});
  test::writeText(dir / "file", "x");
  expectOutputError([&] { checkOutputWritable(dir / "file" / "f.txt"); }, {"f.txt", "file"});
  if (::geteuid() != 0) {  // root may write anywhere
    fs::create_directory(dir / "ro");
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
    expectOutputError([&] { checkOutputWritable(dir / "ro" / "f.txt"); }, {"f.txt", "not writable"});
    fs::permissions(dir / "ro", fs::perms::owner_all);
  }
}

}  // namespace
}  // namespace treesketch
