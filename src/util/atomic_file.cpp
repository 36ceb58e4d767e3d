#include "treesketch/util/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>

#include "treesketch/util/error.h"

namespace treesketch {

namespace fs = std::filesystem;

namespace {
std::atomic<bool> gCreateDirectories{false};

// ---- the registry of temporary files being written, read by the signal handler ----------------
// Plain fixed-size storage and lock-free atomics: all a signal handler may touch.
constexpr int kSlotCount = 64;            // writes in progress at once; more are only cleaned up later
constexpr std::size_t kPathBytes = 4096;  // PATH_MAX on Linux
enum SlotState : int { kFree = 0, kFilling = 1, kLive = 2 };
struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathBytes];
};
Slot gSlots[kSlotCount];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

/// Registers a temporary file for removal on a signal; returns its slot, -1 when full or too long.
int registerTempFile(const fs::path& tmp) {
  std::error_code ec;
  const std::string s = fs::absolute(tmp, ec).string();  // the handler must not depend on the cwd
  if (ec || s.size() >= kPathBytes) return -1;
  for (int i = 0; i < kSlotCount; ++i) {
    int expected = kFree;
    if (gSlots[i].state.compare_exchange_strong(expected, kFilling)) {
      std::memcpy(gSlots[i].path, s.c_str(), s.size() + 1);
      gSlots[i].state.store(kLive);
      return i;
    }
  }
  return -1;
}

void unregisterTempFile(int slot) {
  if (slot >= 0) gSlots[slot].state.store(kFree);
}

extern "C" void unlinkTempFilesAndReraise(int sig) {
  const int savedErrno = errno;
  for (Slot& s : gSlots)
    if (s.state.load() == kLive) ::unlink(s.path);
  ::signal(sig, SIG_DFL);
  errno = savedErrno;
  ::raise(sig);  // delivered when the handler returns: the process ends as the signal says
}

/// Test hook: TREESKETCH_TEST_WRITE_DELAY_MS pauses each write after its temporary file exists, so
/// a test can kill the process mid-write deterministically. Unset in normal use.
void testDelay() {
  const char* ms = std::getenv("TREESKETCH_TEST_WRITE_DELAY_MS");
  if (ms && *ms) std::this_thread::sleep_for(std::chrono::milliseconds(std::atol(ms)));
}

bool processRuns(long pid) { return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM; }

/// The PID of a name `.NAME.tmpPID_N` of target file name `name`, or -1 when it is not one.
long tempFilePid(const std::string& entry, const std::string& name) {
  const std::string prefix = "." + name + ".tmp";
  if (entry.size() <= prefix.size() || entry.compare(0, prefix.size(), prefix) != 0) return -1;
  const std::string rest = entry.substr(prefix.size());
  const std::size_t sep = rest.find('_');
  if (sep == 0 || sep == std::string::npos || sep + 1 == rest.size() || sep > 9) return -1;
  for (std::size_t i = 0; i < rest.size(); ++i)
    if (i != sep && (rest[i] < '0' || rest[i] > '9')) return -1;
  return std::stol(rest.substr(0, sep));
}

}  // namespace

std::size_t removeStaleTempFiles(const fs::path& path) {
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  const std::string name = path.filename().string();
  std::size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const long pid = tempFilePid(it->path().filename().string(), name);
    if (pid <= 0 || pid == ::getpid() || processRuns(pid)) continue;
    std::error_code rm;
    removed += fs::remove(it->path(), rm) ? 1 : 0;
  }
  return removed;
}

void setCreateOutputDirectories(bool create) { gCreateDirectories.store(create); }

void writeFileAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write, bool binary) {
  static std::atomic<unsigned> counter{0};
  fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code made;
  if (!fs::is_directory(dir) && gCreateDirectories.load()) fs::create_directories(dir, made);
  if (!fs::is_directory(dir)) {
    std::string why = path.string() + ": directory '" + dir.string() + "' does not exist";
    if (gCreateDirectories.load()) why += " and cannot be created";
    if (made) why += " (" + made.message() + ")";
    throw OutputError(why);
  }
  removeStaleTempFiles(path);
  std::string name = ".";  // built step by step: GCC 12 warns (-Wrestrict, falsely) on one long sum
  name += path.filename().string();
  name += ".tmp";
  name += std::to_string(::getpid());
  name += '_';
  name += std::to_string(counter.fetch_add(1));
  const fs::path tmp = dir / name;
  const int slot = registerTempFile(tmp);  // before the file exists: a signal can never miss it
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary | std::ios::out : std::ios::out);
      if (!out) throw OutputError(path.string() + ": cannot create temporary file '" + tmp.string() + "'");
      testDelay();
      write(out);
      out.flush();
      if (!out) throw OutputError(path.string() + ": write failed (disk full or I/O error)");
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw OutputError(path.string() + ": cannot rename temporary file: " + ec.message());
    unregisterTempFile(slot);
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    unregisterTempFile(slot);
    throw;
  }
}

void checkNotAnInput(const fs::path& output, std::initializer_list<fs::path> inputs) {
  std::error_code ec;
  if (!fs::exists(output, ec)) return;
  for (const auto& in : inputs) {
    if (fs::exists(in, ec) && fs::equivalent(output, in, ec)) {
      throw OutputError(output.string() + ": refusing to overwrite an input file");
    }
  }
}

void checkOutputWritable(const fs::path& path) {
  if (path.empty()) return;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw OutputError(path.string() + ": is a folder, expected a file name");
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  if (!fs::exists(dir, ec)) {
    fs::create_directories(dir, ec);
    if (ec) throw OutputError(path.string() + ": cannot create folder '" + dir.string() + "': " + ec.message());
  }
  if (!fs::is_directory(dir, ec)) throw OutputError(path.string() + ": '" + dir.string() + "' is not a folder");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw OutputError(path.string() + ": folder '" + dir.string() + "' is not writable (" + std::strerror(errno) + ")");
}

void removeTempFilesOnSignals() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;  // e.g. nohup's SIG_IGN
      struct sigaction act {};
      act.sa_handler = unlinkTempFilesAndReraise;
      sigemptyset(&act.sa_mask);
      ::sigaction(sig, &act, nullptr);
    }
  });
}

}  // namespace treesketch
