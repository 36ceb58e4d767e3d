// A progress bar on stderr for long work: shown only when stderr is a terminal and the work has
// run for more than a second; thread-safe updates, cheap enough to call per chunk of work.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>

namespace treesketch {

/// Progress callback used by long library calls: (done, total). May be empty.
using ProgressFn = std::function<void(std::uint64_t done, std::uint64_t total)>;

class ProgressBar {
 public:
  /// `enabled=false` turns it into a no-op (e.g. when stderr is not a terminal).
  ProgressBar(std::string label, bool enabled);
  ~ProgressBar();
  /// Reports progress; redraws at most ten times a second, only after the first second.
  void update(std::uint64_t done, std::uint64_t total);
  /// A ProgressFn forwarding to this bar.
  ProgressFn callback();
  /// True when stderr is a terminal.
  static bool stderrIsTerminal();

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point lastDraw_;
  std::mutex mutex_;
};

}  // namespace treesketch
