// The tools' names. See include/treesketch/viewer/tool_state.h.
#include "treesketch/viewer/tool_state.h"

namespace treesketch::viewer {

const char* toolLabel(Tool tool) {
  switch (tool) {
    case Tool::Select:
      return "select";
    case Tool::AddNodes:
      return "add nodes";
    case Tool::Stroke:
      return "stroke";
    case Tool::Lasso:
      return "not-wood lasso";
    case Tool::Region:
      return "automatic in region";
    case Tool::Reattach:
      return "re-attach";
    case Tool::LassoWood:
      return "wood lasso";
  }
  return "?";
}

const char* toolHelp(Tool t) {
  switch (t) {
    case Tool::Select:
      return "select (click a node to select it, drag it to move it; Shift+click adds a node)";
    case Tool::AddNodes:
      return "add nodes (a click on the cloud adds a node under the active node)";
    case Tool::Stroke:
      return "stroke (drag along a missing limb, from the node it grows from)";
    case Tool::Lasso:
      return "lasso (drag around points that are not wood)";
    case Tool::Region:
      return "automatic in region (drag around the region)";
    case Tool::Reattach:
      return "re-attach (click the node to move, then its new parent)";
    case Tool::LassoWood:
      return "wood lasso (drag around points that are wood, whatever the classification says)";
  }
  return "?";
}

}  // namespace treesketch::viewer
