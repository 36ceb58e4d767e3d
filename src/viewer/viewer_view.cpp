// ViewerState: the up direction (re-orienting the view without touching the data) and the colour
// legend. See viewer_state.cpp for the map of the files that implement ViewerState.
#include <algorithm>
#include <cstdio>

#include "treesketch/render/color_map.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

void ViewerState::setUpDirection(UpDirection up) {
  viewUp_ = up;
  if (std::optional<geom::UpAxis> axis = libraryUpAxis(up)) {
    up_ = *axis;
    sketch_.up = *axis;  // metadata of the sketch file; no node moves
  }
  presetView(geom::PresetView::Front);
  colorsStale_ = true;
  ++sceneVersion_;
  upWarningDismissed_ = false;
  std::string w = lyingDownWarning();
  if (!w.empty())
    info("warning: " + w);
  else
    info(std::string("up axis: ") + toString(up) + (libraryUpAxis(up) ? "" : " (automatic sketches need +y or +z)"));
}

std::string ViewerState::lyingDownWarning() const { return viewer::lyingDownWarning(bounds_, viewUp_); }

namespace {

std::string metres(double v, double percentOf) {
  char text[64];
  if (percentOf > 0)
    std::snprintf(text, sizeof text, "%.3g m (%.2g %%)", v, 100.0 * v / percentOf);
  else
    std::snprintf(text, sizeof text, "%.3g m", v);
  return text;
}

}  // namespace

ColorLegend ViewerState::colorLegend() const {
  ColorLegend legend;
  if (cloud_.empty()) return legend;
  constexpr int kStops = 5;
  const double diag = std::max(bounds_.diagonal(), 1e-12);
  switch (display_.colorMode) {
    case ColorMode::Plain:
      return legend;
    case ColorMode::Height: {
      // The ramp spans the cloud's extent along the view's up (heightColorsAlong).
      const geom::Vec3 u = upDirectionVector(viewUp_);
      double lo = std::min(bounds_.min.dot(u), bounds_.max.dot(u)),
             hi = std::max(bounds_.min.dot(u), bounds_.max.dot(u));
      legend.title = std::string("height along ") + toString(viewUp_) + " above the lowest point";
      for (int i = 0; i < kStops; ++i) {
        double t = double(i) / (kStops - 1);
        legend.stops.push_back({lo + t * (hi - lo), render::viridis(t), metres(t * (hi - lo), 0.0)});
      }
      break;
    }
    case ColorMode::CircleDistance: {
      // circleDistanceColors: 0 -> ramp start, the scale or more -> ramp end.
      const double scale = options_.distanceColorScale * diag;
      legend.title = "distance to the nearest fitted circle (% of the cloud's diagonal)";
      for (int i = 0; i < kStops; ++i) {
        double t = double(i) / (kStops - 1);
        legend.stops.push_back({t * scale, render::viridis(t), metres(t * scale, diag)});
      }
      legend.note = fittedCount() == 0 ? "no fitted circle yet: every point is at the far end" : "and beyond";
      break;
    }
  }
  legend.shown = true;
  return legend;
}

}  // namespace treesketch::viewer
