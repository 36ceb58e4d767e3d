// Undo/redo for the viewer: a bounded history of sketch snapshots, each labelled with the edit
// that produced the next state ("add node 3", "move node 1"). Sketches are small (tens of nodes),
// so whole snapshots are simpler and safer than inverse commands. Plain C++, no GL.
#pragma once

#include <cstddef>
#include <deque>
#include <string>

#include "treesketch/sketch/sketch.h"

namespace treesketch::viewer {

class UndoStack {
 public:
  /// Keeps at most `limit` undo steps (the oldest are dropped); a limit of 0 is taken as 1.
  explicit UndoStack(std::size_t limit = 500);

  /// Records `before` (the sketch as it was before the edit named `label`) and clears the redo
  /// history. Call it just before (or just after, with the old copy) every edit.
  void push(const sketch::Sketch& before, const std::string& label);
  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  /// Undoes the last edit: `current` becomes the snapshot taken before it, and the replaced sketch
  /// goes to the redo history. Returns the edit's label, or "" (and leaves `current`) when there is
  /// nothing to undo.
  std::string undo(sketch::Sketch& current);
  /// Redoes the last undone edit; returns its label, or "" when there is nothing to redo.
  std::string redo(sketch::Sketch& current);
  /// Label of the edit undo() would revert ("" when none).
  std::string undoLabel() const { return undo_.empty() ? std::string() : undo_.back().label; }
  std::string redoLabel() const { return redo_.empty() ? std::string() : redo_.back().label; }
  std::size_t undoCount() const { return undo_.size(); }
  std::size_t redoCount() const { return redo_.size(); }
  void clear();

 private:
  struct Entry {
    sketch::Sketch sketch;
    std::string label;
  };
  std::size_t limit_;
  std::deque<Entry> undo_;
  std::deque<Entry> redo_;
};

}  // namespace treesketch::viewer
