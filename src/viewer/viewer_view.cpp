// ViewerState: the up direction (re-orienting the view without touching the data); the colour
// legend is viewer/color_legend.cpp. See viewer_state.h for the map of the files that implement ViewerState.
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

void ViewerState::setUpDirection(UpDirection up) {
  view_.up_ = up;
  if (std::optional<geom::UpAxis> axis = libraryUpAxis(up)) {
    up_ = *axis;
    sketch_.up = *axis;  // metadata of the sketch file; no node moves
  }
  view_.presetView(geom::PresetView::Front);
  scene_.colorsStale_ = true;
  ++sceneVersion_;
  view_.upWarningDismissed_ = false;
  std::string w = lyingDownWarning();
  if (!w.empty())
    info("warning: " + w);
  else
    info(std::string("up axis: ") + toString(up) + (libraryUpAxis(up) ? "" : " (automatic sketches need +y or +z)"));
}

std::string ViewerState::lyingDownWarning() const { return viewer::lyingDownWarning(bounds_, view_.up_); }

}  // namespace treesketch::viewer
