#include "treesketch/viewer/unsaved_work.h"

#include <exception>
#include <sstream>

#include "treesketch/io/sketch_file.h"

namespace treesketch::viewer {

bool hasUnsavedWork(const ViewerState& state) {
  if (state.sketch().empty()) return false;
  if (state.document().sketchPath().empty()) return true;
  try {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(state.document().sketchPath(), ec)) return true;
    std::ostringstream current, saved;
    io::writeSketch(current, state.sketch());
    io::writeSketch(saved, io::readSketch(state.document().sketchPath()));
    return current.str() != saved.str();
  } catch (const std::exception&) {
    return true;  // an unreadable file does not hold this sketch
  }
}

}  // namespace treesketch::viewer
