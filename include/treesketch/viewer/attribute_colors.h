// Colouring a cloud by the file's own attributes — intensity, RGB, classification — and the
// legends of every colouring the viewer offers (a colour scale with values, or a list of classes),
// as CloudCompare shows a scalar field's colour scale. Plain C++, no GL; RGB bytes, one per point.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/render/image.h"

namespace treesketch::viewer {

using render::Rgb;

/// The ASPRS name of a LAS classification code (LAS 1.4 R15, table 17: 0 "created, never
/// classified", 1 "unclassified", 2 "ground", 3–5 low/medium/high vegetation, 6 "building", 7 "low
/// point (noise)", 9 "water", ...); "reserved" / "user defined" for codes without a standard name.
std::string asprsClassName(int code);

/// A fixed colour per class (ground brown, vegetation greens, building red, noise magenta, water
/// blue, ...); other codes get distinct colours from render::distinctColor.
Rgb classificationColor(int code);

/// A value range for a colour scale.
struct ValueRange {
  double min = 0.0, max = 1.0;
};

/// The range from the `lowFraction` to the `highFraction` quantile of `values` (design choice for
/// intensity: 1 % and 99 %, so a few saturated returns do not grey out the rest). Empty input gives
/// [0, 1]; equal values give [v, v].
ValueRange quantileRange(const std::vector<float>& values, double lowFraction = 0.01, double highFraction = 0.99);

/// Intensity on a black -> white scale over `range` (clamped), as scanners' software shows it.
std::vector<Rgb> intensityColors(const std::vector<float>& intensity, const ValueRange& range);
/// Grey of `t` in [0, 1] on the intensity scale (clamped; NaN -> black).
Rgb intensityGrey(double t);
/// The file's colours as they are.
std::vector<Rgb> fileColors(const std::vector<std::array<std::uint8_t, 3>>& color);
/// classificationColor per point.
std::vector<Rgb> classificationColors(const std::vector<std::uint8_t>& classification);

/// The viewer's wood/leaf colours: wood brown, leaf green (as docs/classify.md's pictures), and a
/// ramp between them for the wood probability (0 leaf green, 1 wood brown; clamped, NaN grey).
Rgb woodClassColor(bool wood);
Rgb woodProbabilityColor(double t);
/// Per point: by `probability` on the ramp when it is not empty, else by class (`wood`: 1 wood).
std::vector<Rgb> woodColors(const std::vector<float>& probability, const std::vector<std::uint8_t>& wood);

struct LegendClass {
  int code = 0;
  std::string name;
  Rgb color{};
  std::size_t count = 0;  ///< points of this class
};

/// What the legend of a colouring shows.
struct Legend {
  enum class Kind { None, Scale, Classes };
  Kind kind = Kind::None;
  std::string title;                 ///< "height (m)", "intensity", "distance to circles (m)"
  ValueRange range;                  ///< Scale: the values at the bar's ends
  std::vector<Rgb> ramp;             ///< Scale: colours from range.min to range.max, evenly spaced
  std::vector<double> ticks;         ///< Scale: round values inside the range to label
  std::vector<LegendClass> classes;  ///< Classes: the codes present, ascending
  std::string note;                  ///< a line under it ("colours from the file", "clamped at 1–99 %")
};

/// Round tick values (1, 2 or 5 times a power of ten apart) inside [range.min, range.max], at most
/// `maxTicks` of them (at least the two ends' neighbours when the range is not empty). Empty for an
/// empty or reversed range.
std::vector<double> niceTicks(const ValueRange& range, int maxTicks = 5);

/// Legend of a continuous colouring: `sample(t)` gives the colour at t in [0, 1].
Legend scaleLegend(const std::string& title, const ValueRange& range, Rgb (*sample)(double), int rampSteps = 32);
/// Legend of the classes present in `classification` with their counts (ascending codes).
Legend classLegend(const std::vector<std::uint8_t>& classification);
/// Legend of the wood class: wood and leaf with their counts (`woodPoints` of `points`).
Legend woodClassLegend(std::size_t woodPoints, std::size_t points);

}  // namespace treesketch::viewer
