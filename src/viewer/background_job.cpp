// ViewerState's long work on a worker thread: the automatic skeleton sketch runs there with
// progress and cancel while the window keeps drawing; its result is taken in on the window's
// thread as one undoable edit. See viewer_state.cpp for the map of the files that implement
// ViewerState.
//
// Threading: the worker reads only the cloud (setCloud is refused while a job runs) and its own
// copy of the options; it writes only the Job's fields, under its mutex or as atomics. The sketch,
// the undo stack and the messages are touched on the caller's thread only (pollJob).
#include <atomic>
#include <mutex>
#include <optional>
#include <thread>

#include "treesketch/edit/correction_tools.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/cancel.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

struct ViewerState::Job {
  std::string name;
  std::atomic<bool> cancel{false}, finished{false}, hold{false};
  std::atomic<std::uint64_t> done{0}, total{0};
  std::atomic<int> step{1};
  std::mutex mutex;  // guards the results below
  std::optional<sketch::Sketch> result;
  std::string error;
  bool cancelled = false;
  Stopwatch timer;  // started with the job
  std::thread thread;

  ~Job() {
    cancel = true;
    if (thread.joinable()) thread.join();
  }
};

ViewerState::~ViewerState() { job_.reset(); }  // cancels and joins a running job

bool ViewerState::busy() const { return job_ != nullptr; }

bool ViewerState::refuseWhileBusy(const std::string& name) {
  if (!job_) return false;
  error(name + ": busy (" + job_->name + " is running; Cancel it or wait)");
  return true;
}

bool ViewerState::startAutoSkeletonJob(bool leafOn) {
  if (refuseWhileBusy("automatic skeleton sketch")) return false;
  if (cloud_.empty()) {
    error("automatic skeleton sketch: open a point cloud first");
    return false;
  }
  std::optional<geom::UpAxis> axis = libraryUpAxis(viewUp_);
  if (!axis) {
    error(std::string("automatic skeleton sketch: needs up +y or +z (the view's up is ") + toString(viewUp_) + ")");
    return false;
  }
  auto job = std::make_shared<Job>();
  job->name = "automatic skeleton";
  Job* j = job.get();
  j->hold = holdJobs_;
  const skeleton::AutoSkeletonOptions options =
      skeleton::autoSkeletonPreset(leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, *axis);
  // The lassoed points are not wood: the job is given the cloud without them (a copy only when
  // there are lassos; setCloud is refused while a job runs, so the open cloud outlives it).
  std::shared_ptr<const geom::PointCloud> cloud(&cloud_, [](const geom::PointCloud*) {});
  if (!sketch_.notWood().empty()) cloud = std::make_shared<const geom::PointCloud>(edit::woodOnly(cloud_, sketch_));
  job->thread = std::thread([j, options, cloud] {
    // The extraction reports d of 4, then the fit pass d of n: a new total is the next step.
    ProgressFn report = [j](std::uint64_t done, std::uint64_t total) {
      if (j->total.load() != total && j->done.load() > 0) j->step = 2;
      j->total = total;
      j->done = done;
    };
    std::optional<sketch::Sketch> result;
    std::string error;
    bool cancelled = false;
    try {
      while (j->hold && !j->cancel) std::this_thread::sleep_for(std::chrono::milliseconds(5));
      skeleton::AutoSkeletonResult r =
          skeleton::autoSkeletonSketch(*cloud, options, cancellableProgress(j->cancel, report));
      if (r.sketch.empty()) throw OptionsError("no skeleton found in this cloud");
      result = std::move(r.sketch);
    } catch (const Cancelled&) {
      cancelled = true;
    } catch (const std::bad_alloc&) {
      error = "out of memory";
    } catch (const std::exception& e) {
      error = e.what();
    }
    {
      std::lock_guard<std::mutex> lock(j->mutex);
      j->result = std::move(result);
      j->error = std::move(error);
      j->cancelled = cancelled;
    }
    j->finished = true;
  });
  job_ = std::move(job);
  info("automatic skeleton: running (Cancel stops it; the sketch stays as it is until it is done)");
  return true;
}

ViewerState::JobProgress ViewerState::jobProgress() const {
  JobProgress p;
  if (!job_) return p;
  const std::uint64_t done = job_->done, total = job_->total;
  p.step = job_->step;
  p.fraction = total > 0 ? double(done) / double(total) : 0.0;
  p.cancelling = job_->cancel;
  p.what = job_->name + (p.step == 1 ? ": skeleton (step " + std::to_string(done) + " of 4)"
                                     : ": fitting nodes " + std::to_string(done) + " / " + std::to_string(total));
  if (p.cancelling) p.what += " — cancelling";
  return p;
}

void ViewerState::cancelJob() {
  if (job_) job_->cancel = true;
}

bool ViewerState::pollJob() {
  if (!job_ || !job_->finished) return false;
  std::shared_ptr<Job> job = std::move(job_);  // busy() is false from here on
  if (job->thread.joinable()) job->thread.join();
  const double seconds = job->timer.seconds();
  std::lock_guard<std::mutex> lock(job->mutex);
  // A cancel that came after the last progress report still wins: the person asked for the
  // sketch as it was, so a result finished meanwhile is dropped.
  if (job->cancelled || job->cancel) {
    info(job->name + ": cancelled; the sketch is as it was");
  } else if (!job->error.empty()) {
    error(job->name + ": " + job->error);
  } else if (job->result) {
    sketch::Sketch result = std::move(*job->result);
    bool ok = edit("automatic skeleton sketch", "automatic skeleton sketch", "", [&] {
      edit::copyNotWood(sketch_, result);  // the person's lassos stay
      sketch_ = std::move(result);
      selected_ = kNoNode;
      active_ = sketch_.root();
    });
    if (ok) {
      untouchedAuto_ = true;
      activeChosen_ = false;
      char secs[32];
      std::snprintf(secs, sizeof secs, "%.1f s", seconds);
      info("automatic skeleton sketch: " + std::to_string(sketch_.size()) + " nodes in " + secs +
           "; they keep the automatic model's circles (edit a node, or Refit, to fit it from the cloud)");
    }
  }
  return true;
}

void ViewerState::holdJobs(bool hold) {
  holdJobs_ = hold;
  if (job_) job_->hold = hold;
}

void ViewerState::waitForJob() {
  if (!job_) return;
  if (job_->thread.joinable()) job_->thread.join();
  pollJob();
}

}  // namespace treesketch::viewer
