#include "treesketch/viewer/undo_stack.h"

#include <algorithm>
#include <utility>

namespace treesketch::viewer {

UndoStack::UndoStack(std::size_t limit) : limit_(std::max<std::size_t>(limit, 1)) {}

void UndoStack::push(const sketch::Sketch& before, const std::string& label) {
  undo_.push_back(Entry{before, label});
  while (undo_.size() > limit_) undo_.pop_front();
  redo_.clear();
}

std::string UndoStack::undo(sketch::Sketch& current) {
  if (undo_.empty()) return {};
  Entry e = std::move(undo_.back());
  undo_.pop_back();
  redo_.push_back(Entry{std::move(current), e.label});
  current = std::move(e.sketch);
  return e.label;
}

std::string UndoStack::redo(sketch::Sketch& current) {
  if (redo_.empty()) return {};
  Entry e = std::move(redo_.back());
  redo_.pop_back();
  undo_.push_back(Entry{std::move(current), e.label});
  current = std::move(e.sketch);
  return e.label;
}

void UndoStack::clear() {
  undo_.clear();
  redo_.clear();
}

}  // namespace treesketch::viewer
