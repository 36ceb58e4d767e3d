#include "treesketch/viewer/color_legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "treesketch/classify/classify.h"
#include "treesketch/render/color_map.h"
#include "treesketch/viewer/view_up.h"

namespace treesketch::viewer {

namespace {
constexpr ColorMode kMenuOrder[] = {ColorMode::Height,         ColorMode::CircleDistance, ColorMode::Plain,
                                    ColorMode::Intensity,      ColorMode::FileColor,      ColorMode::Classification,
                                    ColorMode::WoodProbability, ColorMode::WoodClass};
}

bool colorModeAvailable(ColorMode mode, const geom::PointCloud& cloud, bool classified) {
  const std::size_t n = cloud.size();
  switch (mode) {
    case ColorMode::WoodProbability:
    case ColorMode::WoodClass:
      return n > 0 && classified;
    case ColorMode::Intensity:
      return n > 0 && cloud.intensity.size() == n;
    case ColorMode::FileColor:
      return n > 0 && cloud.color.size() == n;
    case ColorMode::Classification:
      return n > 0 && cloud.classification.size() == n;
    default:
      return true;
  }
}

std::vector<ColorMode> availableColorModes(const geom::PointCloud& cloud, bool classified) {
  std::vector<ColorMode> out;
  for (ColorMode m : kMenuOrder)
    if (colorModeAvailable(m, cloud, classified)) out.push_back(m);
  return out;
}

ColorMode nextColorMode(ColorMode mode, const geom::PointCloud& cloud, bool classified) {
  std::vector<ColorMode> modes = availableColorModes(cloud, classified);
  auto it = std::find(modes.begin(), modes.end(), mode);
  if (it == modes.end() || ++it == modes.end()) return modes.front();
  return *it;
}

const char* colorModeLabel(ColorMode mode) {
  switch (mode) {
    case ColorMode::Height:
      return "height";
    case ColorMode::CircleDistance:
      return "distance to the model";
    case ColorMode::Plain:
      return "plain";
    case ColorMode::Intensity:
      return "intensity (file)";
    case ColorMode::FileColor:
      return "RGB (file)";
    case ColorMode::Classification:
      return "classification (file)";
    case ColorMode::WoodProbability:
      return "wood probability";
    case ColorMode::WoodClass:
      return "wood / leaf";
  }
  return "?";
}

std::vector<Rgb> attributeColors(const geom::PointCloud& cloud, ColorMode mode) {
  if (!colorModeAvailable(mode, cloud)) return {};
  switch (mode) {
    case ColorMode::Intensity:
      return intensityColors(cloud.intensity, quantileRange(cloud.intensity));
    case ColorMode::FileColor:
      return fileColors(cloud.color);
    case ColorMode::Classification:
      return classificationColors(cloud.classification);
    default:
      return {};
  }
}

Legend colorLegend(const ViewerState& state) {
  const geom::PointCloud& cloud = state.cloud();
  const ColorMode mode = state.view().display().colorMode;
  if (cloud.empty()) return {};
  if (!colorModeAvailable(mode, cloud, state.woodClasses() != nullptr)) {
    Legend l;
    l.note = mode == ColorMode::WoodProbability || mode == ColorMode::WoodClass
                 ? std::string("not classified yet (Tools > Classify wood/leaf, K): drawn plain")
                 : std::string("the file has no ") + toString(mode) + ": drawn plain";
    return l;
  }
  switch (mode) {
    case ColorMode::Height: {
      // The colours run along the view's up direction (heightColorsAlong), from the lowest point.
      const geom::Vec3 u = upDirectionVector(state.view().upDirection());
      const geom::BBox& b = state.bounds();
      const double span = std::abs((b.max - b.min).dot(u));
      return scaleLegend(
          std::string("height along ") + toString(state.view().upDirection()) + " above the lowest point (m)",
          {0.0, span}, render::viridis);
    }
    case ColorMode::CircleDistance: {
      const double diagonal = std::max(state.bounds().diagonal(), 1e-12);
      const double scale = state.options().distanceColorScale * diagonal;
      char title[96];
      std::snprintf(title, sizeof title, "distance to the model's surface (m; top: %.3g %% of the diagonal)",
                    100.0 * state.options().distanceColorScale);
      Legend l = scaleLegend(title, {0.0, scale}, render::viridis);
      char note[160];
      std::snprintf(note, sizeof note, "0 on the tubes; the top colour: %.3g m (%.3g %% of the cloud's %.3g m diagonal) "
                    "or farther", scale, 100.0 * state.options().distanceColorScale, diagonal);
      l.note = state.scene().fittedCount() == 0   ? "no fitted circle yet: every point is at the far end"
               : state.scene().fittedCount() == 1 ? "one fitted circle, no tube yet: the distance to the circle"
                                                  : std::string(note);
      return l;
    }
    case ColorMode::Intensity: {
      Legend l = scaleLegend("intensity", quantileRange(cloud.intensity), intensityGrey);
      l.note = "1-99 % of the returns; the rest clamped";
      return l;
    }
    case ColorMode::Classification:
      return classLegend(cloud.classification);
    case ColorMode::FileColor: {
      Legend l;
      l.title = "RGB";
      l.note = "the colours stored in the file";
      return l;
    }
    case ColorMode::WoodProbability: {
      Legend l = scaleLegend("wood probability (the classifier's)", {0.0, 1.0}, woodProbabilityColor);
      char note[128];
      std::snprintf(note, sizeof note, "wood at %.3g and above; the lassos change the class, not this",
                    state.woodClasses()->threshold);
      l.note = note;
      return l;
    }
    case ColorMode::WoodClass:
      return woodClassLegend(state.woodPointCount(), cloud.size());
    case ColorMode::Plain:
      return {};
  }
  return {};
}

}  // namespace treesketch::viewer
