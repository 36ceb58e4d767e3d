// The desktop tool's long work on a worker thread: at most one job at a time (the automatic
// skeleton, the wood/leaf classification), its progress, a cancel that stops it at its next
// progress report, and its outcome, handed back on the window's thread. It never touches the
// sketch: ViewerState starts a job with what it needs copied or kept alive, and takes the
// finished sketch in as one undoable edit (and a classification as the cloud's classes).
//
// Threading: the worker writes only the job's own fields, under its mutex or as atomics; every
// function here is called on the window's thread.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "treesketch/sketch/sketch.h"
#include "treesketch/util/progress.h"

namespace treesketch::classify {
struct Classification;
}

namespace treesketch::viewer {

/// What a job made: a sketch (the automatic skeleton), a wood/leaf classification of the open
/// cloud, or both (the skeleton on the wood of a cloud not classified before).
struct JobResult {
  std::optional<sketch::Sketch> sketch;
  std::shared_ptr<const classify::Classification> classes;
};

/// What the progress line says a job is doing: the automatic skeleton's two steps, the
/// classification (one step; it reports no progress inside), or the classification and then the
/// skeleton.
enum class JobSteps { Skeleton, Classify, ClassifyThenSkeleton };

struct JobProgress {
  std::string what;         ///< "automatic skeleton: fitting nodes 128 / 640"
  double fraction = 0.0;    ///< 0..1 within the current step
  int step = 1, steps = 2;  ///< extraction, then the fit pass
  bool cancelling = false;
};

class Jobs {
 public:
  Jobs();
  ~Jobs();  ///< cancels and joins a running job
  Jobs(const Jobs&) = delete;
  Jobs& operator=(const Jobs&) = delete;

  /// A job runs (or has finished and was not taken in yet).
  bool busy() const { return job_ != nullptr; }
  /// The running job's name ("" when none).
  std::string runningName() const;
  JobProgress progress() const;
  /// Asks the running job to stop at its next progress report (no effect when none runs).
  void cancel();
  /// Test seam: while held, a started job waits before its first step (busy, cancellable), so a
  /// script can check "the window works while a job runs" and "cancel" without racing the job.
  void hold(bool hold);

  /// The work: makes a sketch or a classification, reporting progress through the function it is
  /// given (which throws util's Cancelled once cancel() was called). A new total after some
  /// progress counts as the next step. A cancel during a step that reports nothing (the
  /// classification) takes effect when the step ends: its result is dropped.
  using Work = std::function<JobResult(const ProgressFn&)>;
  /// Starts `work` on a worker thread. The caller checks busy() first; a second job replaces
  /// nothing (false).
  bool start(const std::string& name, Work work, JobSteps steps = JobSteps::Skeleton);

  struct Outcome {
    std::string name;
    std::optional<JobResult> result;  ///< when it finished without error or cancel
    std::string error;                ///< why it failed ("" otherwise)
    bool cancelled = false;
    double seconds = 0.0;
  };
  /// The finished job's outcome, once (nullopt while it runs or when none ran); busy() is false
  /// afterwards.
  std::optional<Outcome> takeFinished();
  /// Blocks until the running job has ended and returns its outcome (nullopt when none ran).
  std::optional<Outcome> wait();

 private:
  struct Job;
  std::shared_ptr<Job> job_;  // shared_ptr: Job is complete only in jobs.cpp
  bool hold_ = false;
};

}  // namespace treesketch::viewer
