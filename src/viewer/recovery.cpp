// ViewerState's crash recovery: an autosave left by an earlier session (killed, crashed, or closed
// with unsaved edits) is offered back when the same cloud is opened again, and is never
// overwritten before the person chooses to restore, discard or keep it. See viewer_state.cpp for
// the map of the files that implement ViewerState.
#include <chrono>
#include <ctime>
#include <system_error>

#include "treesketch/io/sketch_file.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/unsaved_work.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

namespace {

/// "<autosave stem>.kept-YYYYmmdd-HHMMSS.sketch.json" beside `autosave`, not yet existing.
std::filesystem::path keptName(const std::filesystem::path& autosave) {
  std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  localtime_r(&now, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
  std::string base = autosave.filename().string();
  const std::string suffix = ".sketch.json";
  if (base.size() > suffix.size() && base.compare(base.size() - suffix.size(), suffix.size(), suffix) == 0)
    base.resize(base.size() - suffix.size());
  std::filesystem::path p = autosave.parent_path() / (base + ".kept-" + stamp + suffix);
  for (int i = 2; std::filesystem::exists(p); ++i)
    p = autosave.parent_path() / (base + ".kept-" + stamp + "-" + std::to_string(i) + suffix);
  return p;
}

}  // namespace

void ViewerState::setAutosavePath(const std::filesystem::path& path) {
  if (runAction("autosave", [&] { doc_.setAutosavePath(path); })) detectRecovery();
}

void ViewerState::discardUnsavedWork() {
  if (!recoveryPending_) doc_.removeAutosave();
  dirty_ = false;
}

void ViewerState::detectRecovery() {
  recoveryPending_ = false;
  recoveryNodes_ = 0;
  recoveryError_.clear();
  std::error_code ec;
  if (autosavePath().empty() || !std::filesystem::is_regular_file(autosavePath(), ec)) return;
  recoveryPending_ = true;
  try {
    recoveryNodes_ = io::readSketch(autosavePath()).size();
    info("found unsaved work from an earlier session: " + autosavePath().string() + " (" +
         std::to_string(recoveryNodes_) + " nodes): restore, discard or keep it");
  } catch (const std::exception& e) {
    recoveryError_ = e.what();
    error("the earlier session's autosave cannot be read: " + recoveryError_ + " (discard it or keep it)");
  }
}

bool ViewerState::resolveRecovery(RecoveryChoice choice) {
  if (!recoveryPending_) {
    error("recovery: no earlier autosave is waiting");
    return false;
  }
  const std::filesystem::path file = autosavePath();
  bool ok = false;
  switch (choice) {
    case RecoveryChoice::Restore: {
      sketch::Sketch loaded;
      if (!runAction("restore autosave", [&] { loaded = io::readSketch(file); })) return false;
      ok = edit("restore autosave", "restore autosave", "", [&] {
        sketch_ = std::move(loaded);
        selected_ = kNoNode;
        active_ = kNoNode;
      });
      if (ok) activeChosen_ = false;
      if (ok) info("restored " + std::to_string(sketch_.size()) + " nodes from " + file.string());
      break;
    }
    case RecoveryChoice::Discard:
      ok = runAction("discard autosave", [&] {
        std::filesystem::remove(file);
        info("discarded the earlier autosave " + file.string());
      });
      break;
    case RecoveryChoice::Keep:
      ok = runAction("keep autosave", [&] {
        std::filesystem::path kept = keptName(file);
        std::filesystem::rename(file, kept);
        info("kept the earlier autosave as " + kept.string() + " (load it with Load sketch)");
      });
      break;
  }
  if (!ok) return false;
  recoveryPending_ = false;
  recoveryNodes_ = 0;
  recoveryError_.clear();
  // Edits made while the offer was open are saved now; a restore has just saved itself, unless
  // the pending flag held it back.
  if (!sketch_.empty()) autosave();
  return true;
}

void ViewerState::closeSession() {
  if (autosavePath().empty() || recoveryPending_) return;
  // Nothing unsaved: the sketch is empty or is what its file holds (saved, or undone back to it).
  if (!hasUnsavedWork(*this)) doc_.removeAutosave();
}

}  // namespace treesketch::viewer
