// ViewerState's long work: the automatic skeleton sketch runs as a job of its Jobs part (a worker
// thread, progress and cancel) while the window keeps drawing; its result is taken in on the
// window's thread as one undoable edit. See viewer_state.h for the map of the files that implement
// ViewerState.
//
// Threading: the job reads only the cloud (setCloud is refused while a job runs; the lassoed
// points' copy is its own) and its own copy of the options. The sketch, the undo stack and the
// messages are touched on the caller's thread only (pollJob, waitForJob).
#include <optional>

#include "treesketch/edit/correction_tools.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

ViewerState::~ViewerState() = default;  // jobs_ cancels and joins a running job

bool ViewerState::refuseWhileBusy(const std::string& name) {
  if (!jobs_.busy()) return false;
  error(name + ": busy (" + jobs_.runningName() + " is running; Cancel it or wait)");
  return true;
}

bool ViewerState::startAutoSkeletonJob(bool leafOn) {
  if (refuseWhileBusy("automatic skeleton sketch")) return false;
  if (cloud_.empty()) {
    error("automatic skeleton sketch: open a point cloud first");
    return false;
  }
  std::optional<geom::UpAxis> axis = libraryUpAxis(view_.up_);
  if (!axis) {
    error(std::string("automatic skeleton sketch: needs up +y or +z (the view's up is ") + toString(view_.up_) + ")");
    return false;
  }
  const skeleton::AutoSkeletonOptions options =
      skeleton::autoSkeletonPreset(leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, *axis);
  // The lassoed points are not wood: the job is given the cloud without them (a copy only when
  // there are lassos; setCloud is refused while a job runs, so the open cloud outlives it).
  std::shared_ptr<const geom::PointCloud> cloud(&cloud_, [](const geom::PointCloud*) {});
  if (!sketch_.notWood().empty()) cloud = std::make_shared<const geom::PointCloud>(edit::woodOnly(cloud_, sketch_));
  jobs_.start("automatic skeleton", [options, cloud](const ProgressFn& progress) {
    skeleton::AutoSkeletonResult r = skeleton::autoSkeletonSketch(*cloud, options, progress);
    if (r.sketch.empty()) throw OptionsError("no skeleton found in this cloud");
    JobResult out;
    out.sketch = std::move(r.sketch);
    return out;
  });
  info("automatic skeleton: running (Cancel stops it; the sketch stays as it is until it is done)");
  return true;
}

bool ViewerState::pollJob() { return takeJobOutcome(jobs_.takeFinished()); }

void ViewerState::waitForJob() { takeJobOutcome(jobs_.wait()); }

bool ViewerState::takeJobOutcome(std::optional<Jobs::Outcome> job) {
  if (!job) return false;
  const double seconds = job->seconds;
  if (job->cancelled) {
    info(job->name + ": cancelled; the sketch is as it was");
  } else if (!job->error.empty()) {
    error(job->name + ": " + job->error);
  } else if (job->result && job->result->classes && !job->result->sketch) {
    takeClassification(std::move(job->result->classes));
  } else if (job->result && job->result->sketch) {
    if (job->result->classes) takeClassification(std::move(job->result->classes));
    sketch::Sketch result = std::move(*job->result->sketch);
    bool ok = edit("automatic skeleton sketch", "automatic skeleton sketch", "", [&] {
      edit::copyNotWood(sketch_, result);  // the person's lassos stay
      sketch_ = std::move(result);
      tools_.selected_ = kNoNode;
      tools_.active_ = sketch_.root();
    });
    if (ok) {
      untouchedAuto_ = true;
      tools_.activeChosen_ = false;
      char secs[32];
      std::snprintf(secs, sizeof secs, "%.1f s", seconds);
      info("automatic skeleton sketch: " + std::to_string(sketch_.size()) + " nodes in " + secs +
           "; they keep the automatic model's circles (edit a node, or Refit, to fit it from the cloud)");
    }
  }
  return true;
}

}  // namespace treesketch::viewer
