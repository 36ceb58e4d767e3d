// Jobs: the desktop tool's work on a worker thread. See include/treesketch/viewer/jobs.h.
#include "treesketch/viewer/jobs.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <new>
#include <thread>

#include "treesketch/util/cancel.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::viewer {

struct Jobs::Job {
  std::string name;
  JobSteps steps = JobSteps::Skeleton;
  std::atomic<bool> cancel{false}, finished{false}, hold{false};
  std::atomic<std::uint64_t> done{0}, total{0};
  std::atomic<int> step{1};
  std::mutex mutex;  // guards the outcome below
  Outcome outcome;
  Stopwatch timer;  // started with the job
  std::thread thread;

  ~Job() {
    cancel = true;
    if (thread.joinable()) thread.join();
  }
};

Jobs::Jobs() = default;
Jobs::~Jobs() { job_.reset(); }

std::string Jobs::runningName() const { return job_ ? job_->name : std::string(); }

JobProgress Jobs::progress() const {
  JobProgress p;
  if (!job_) return p;
  const std::uint64_t done = job_->done, total = job_->total;
  p.step = job_->step;
  p.fraction = total > 0 ? double(done) / double(total) : 0.0;
  p.cancelling = job_->cancel;
  const bool classifying =
      job_->steps == JobSteps::Classify || (job_->steps == JobSteps::ClassifyThenSkeleton && total == 0);
  if (classifying)
    p.what = job_->name + ": classifying wood and leaves (a few seconds; a cancel takes effect when it ends)";
  else
    p.what = job_->name + (p.step == 1 ? ": skeleton (step " + std::to_string(done) + " of 4)"
                                       : ": fitting nodes " + std::to_string(done) + " / " + std::to_string(total));
  if (p.cancelling) p.what += " — cancelling";
  return p;
}

void Jobs::cancel() {
  if (job_) job_->cancel = true;
}

void Jobs::hold(bool hold) {
  hold_ = hold;
  if (job_) job_->hold = hold;
}

bool Jobs::start(const std::string& name, Work work, JobSteps steps) {
  if (job_) return false;
  auto job = std::make_shared<Job>();
  job->name = name;
  job->steps = steps;
  Job* j = job.get();
  j->hold = hold_;
  job->thread = std::thread([j, work = std::move(work)] {
    ProgressFn report = [j](std::uint64_t done, std::uint64_t total) {
      if (j->total.load() != total && j->done.load() > 0) j->step = 2;
      j->total = total;
      j->done = done;
    };
    Outcome out;
    out.name = j->name;
    try {
      while (j->hold && !j->cancel) std::this_thread::sleep_for(std::chrono::milliseconds(5));
      out.result = work(cancellableProgress(j->cancel, report));
    } catch (const Cancelled&) {
      out.cancelled = true;
    } catch (const std::bad_alloc&) {
      out.error = "out of memory";
    } catch (const std::exception& e) {
      out.error = e.what();
    }
    {
      std::lock_guard<std::mutex> lock(j->mutex);
      j->outcome = std::move(out);
    }
    j->finished = true;
  });
  job_ = std::move(job);
  return true;
}

std::optional<Jobs::Outcome> Jobs::takeFinished() {
  if (!job_ || !job_->finished) return std::nullopt;
  std::shared_ptr<Job> job = std::move(job_);  // busy() is false from here on
  if (job->thread.joinable()) job->thread.join();
  std::lock_guard<std::mutex> lock(job->mutex);
  Outcome out = std::move(job->outcome);
  out.seconds = job->timer.seconds();
  // A cancel that came after the last progress report still wins: the person asked for the
  // sketch as it was, so a result finished meanwhile is dropped.
  if (job->cancel) {
    out.cancelled = true;
    out.result.reset();
  }
  return out;
}

std::optional<Jobs::Outcome> Jobs::wait() {
  if (!job_) return std::nullopt;
  if (job_->thread.joinable()) job_->thread.join();
  return takeFinished();
}

}  // namespace treesketch::viewer
