// A stopwatch on the steady clock: how long a step took, in milliseconds (or seconds). The one
// timer of the library and the apps; timings are reported, never used in a computation.
#pragma once

#include <chrono>

namespace treesketch {

class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;

  /// Starts timing now.
  Stopwatch() : start_(Clock::now()) {}
  /// Milliseconds since construction or the last restart().
  double ms() const { return std::chrono::duration<double, std::milli>(Clock::now() - start_).count(); }
  /// Seconds since construction or the last restart().
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  /// Starts timing again from now.
  void restart() { start_ = Clock::now(); }

 private:
  Clock::time_point start_;
};

}  // namespace treesketch
