// ViewerState's crash recovery: an autosave left by an earlier session (killed, crashed, or closed
// with unsaved edits) is offered back when the same cloud is opened again, and is never
// overwritten before the person chooses to restore, discard or keep it. See viewer_state.h for
// the map of the files that implement ViewerState.
#include "treesketch/io/sketch_file.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/unsaved_work.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

void ViewerState::setAutosavePath(const std::filesystem::path& path) {
  if (runAction("autosave", [&] { doc_.setAutosavePath(path); })) detectRecovery();
}

void ViewerState::discardUnsavedWork() {
  if (!doc_.recoveryPending()) doc_.removeAutosave();
  dirty_ = false;
}

void ViewerState::detectRecovery() {
  bool readable = true;
  std::string text = doc_.findRecovery(readable);
  if (text.empty()) return;
  if (readable)
    info(text);
  else
    error(text);
}

bool ViewerState::resolveRecovery(RecoveryChoice choice) {
  if (!doc_.recoveryPending()) {
    error("recovery: no earlier autosave is waiting");
    return false;
  }
  const std::filesystem::path file = doc_.autosavePath();
  bool ok = false;
  switch (choice) {
    case RecoveryChoice::Restore: {
      sketch::Sketch loaded;
      if (!runAction("restore autosave", [&] { loaded = io::readSketch(file); })) return false;
      ok = edit("restore autosave", "restore autosave", "", [&] {
        sketch_ = std::move(loaded);
        tools_.selected_ = kNoNode;
        tools_.active_ = kNoNode;
      });
      if (ok) tools_.activeChosen_ = false;
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
        std::filesystem::path kept = doc_.keepAutosave();
        info("kept the earlier autosave as " + kept.string() + " (load it with Load sketch)");
      });
      break;
  }
  if (!ok) return false;
  doc_.endRecovery();
  // Edits made while the offer was open are saved now; a restore has just saved itself, unless
  // the pending flag held it back.
  if (!sketch_.empty()) autosave();
  return true;
}

void ViewerState::closeSession() {
  if (doc_.autosavePath().empty() || doc_.recoveryPending()) return;
  // Nothing unsaved: the sketch is empty or is what its file holds (saved, or undone back to it).
  if (!hasUnsavedWork(*this)) doc_.removeAutosave();
}

}  // namespace treesketch::viewer
