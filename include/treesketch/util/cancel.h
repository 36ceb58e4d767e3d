// Cancelling long library work: a ProgressFn that throws Cancelled when a flag is set. Library
// calls that take a ProgressFn report between steps of their work, so a cancel takes effect at the
// next report; the exception propagates (through TBB's parallel loops too) and the call's partial
// results are dropped, leaving the caller's data as it was.
#pragma once

#include <atomic>
#include <stdexcept>

#include "treesketch/util/progress.h"

namespace treesketch {

/// Thrown by a cancellable progress callback; not an error (no exit code).
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

/// Forwards to `inner` (may be empty), and throws Cancelled at any report once `cancel` is true.
/// `cancel` must outlive the returned function.
inline ProgressFn cancellableProgress(const std::atomic<bool>& cancel, ProgressFn inner = {}) {
  return [&cancel, inner = std::move(inner)](std::uint64_t done, std::uint64_t total) {
    if (cancel.load(std::memory_order_relaxed)) throw Cancelled();
    if (inner) inner(done, total);
  };
}

}  // namespace treesketch
