#include "treesketch/viewer/attribute_colors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "treesketch/render/color_map.h"
#include "treesketch/viewer/view_overlays.h"

namespace treesketch::viewer {

std::string asprsClassName(int code) {
  static const char* names[] = {"created, never classified",
                                "unclassified",
                                "ground",
                                "low vegetation",
                                "medium vegetation",
                                "high vegetation",
                                "building",
                                "low point (noise)",
                                "reserved (model key-point)",
                                "water",
                                "rail",
                                "road surface",
                                "reserved (overlap)",
                                "wire - guard (shield)",
                                "wire - conductor (phase)",
                                "transmission tower",
                                "wire-structure connector",
                                "bridge deck",
                                "high noise"};
  if (code >= 0 && code < static_cast<int>(sizeof names / sizeof names[0])) return names[code];
  if (code >= 19 && code <= 63) return "reserved";
  if (code >= 64 && code <= 255) return "user defined";
  return "invalid";
}

Rgb classificationColor(int code) {
  switch (code) {
    case 0:
      return {150, 150, 150};
    case 1:
      return {200, 200, 200};
    case 2:
      return {150, 105, 60};  // ground
    case 3:
      return {170, 230, 110};  // low vegetation
    case 4:
      return {80, 190, 70};
    case 5:
      return {20, 120, 40};  // high vegetation
    case 6:
      return {220, 60, 50};  // building
    case 7:
    case 18:
      return {240, 40, 240};  // noise
    case 9:
      return {50, 110, 230};  // water
    default:
      return render::distinctColor(code);
  }
}

ValueRange quantileRange(const std::vector<float>& values, double lowFraction, double highFraction) {
  std::vector<float> v;
  v.reserve(values.size());
  for (float x : values)
    if (std::isfinite(x)) v.push_back(x);
  if (v.empty()) return {};
  auto at = [&](double f) {
    f = std::clamp(f, 0.0, 1.0);
    auto k = static_cast<std::size_t>(std::llround(f * static_cast<double>(v.size() - 1)));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return static_cast<double>(v[k]);
  };
  double lo = at(lowFraction), hi = at(highFraction);
  if (hi < lo) std::swap(lo, hi);
  return {lo, hi};
}

Rgb intensityGrey(double t) {
  if (!(t > 0.0)) return {0, 0, 0};
  auto g = static_cast<std::uint8_t>(std::lround(std::min(t, 1.0) * 255.0));
  return {g, g, g};
}

std::vector<Rgb> intensityColors(const std::vector<float>& intensity, const ValueRange& range) {
  std::vector<Rgb> out(intensity.size());
  double span = range.max - range.min;
  for (std::size_t i = 0; i < intensity.size(); ++i)
    out[i] = span > 0.0 ? intensityGrey((intensity[i] - range.min) / span) : intensityGrey(0.5);
  return out;
}

std::vector<Rgb> fileColors(const std::vector<std::array<std::uint8_t, 3>>& color) {
  std::vector<Rgb> out(color.size());
  for (std::size_t i = 0; i < color.size(); ++i) out[i] = {color[i][0], color[i][1], color[i][2]};
  return out;
}

std::vector<Rgb> classificationColors(const std::vector<std::uint8_t>& classification) {
  std::array<Rgb, 256> table;
  for (int c = 0; c < 256; ++c) table[static_cast<std::size_t>(c)] = classificationColor(c);
  std::vector<Rgb> out(classification.size());
  for (std::size_t i = 0; i < classification.size(); ++i) out[i] = table[classification[i]];
  return out;
}

std::vector<double> niceTicks(const ValueRange& range, int maxTicks) {
  std::vector<double> ticks;
  double span = range.max - range.min;
  if (!(span > 0.0) || !std::isfinite(span) || maxTicks < 2) return ticks;
  // Start at the largest round step giving about maxTicks ticks and go up (1 -> 2 -> 5 -> 10) until
  // at most maxTicks fit.
  double step = roundLengthAtMost(span / (maxTicks - 1));
  if (step <= 0.0) return ticks;
  auto count = [&](double s) { return std::floor(range.max / s) - std::ceil(range.min / s) + 1.0; };
  while (count(step) > maxTicks) step = roundLengthAtMost(step * 2.5 * (1 + 1e-9)) * (1 + 1e-12);
  step = roundLengthAtMost(step);
  for (double k = std::ceil(range.min / step); k <= std::floor(range.max / step); k += 1.0) {
    // k * step carries binary noise (3 * 0.05 = 0.15000000000000002): keep the decimal value.
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", k * step);
    double t = std::strtod(buf, nullptr);
    ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
  }
  return ticks;
}

Legend scaleLegend(const std::string& title, const ValueRange& range, Rgb (*sample)(double), int rampSteps) {
  Legend l;
  l.kind = Legend::Kind::Scale;
  l.title = title;
  l.range = range;
  rampSteps = std::max(rampSteps, 2);
  for (int i = 0; i < rampSteps; ++i) l.ramp.push_back(sample(static_cast<double>(i) / (rampSteps - 1)));
  l.ticks = niceTicks(range);
  return l;
}

Legend classLegend(const std::vector<std::uint8_t>& classification) {
  Legend l;
  l.kind = Legend::Kind::Classes;
  l.title = "classification (ASPRS)";
  std::array<std::size_t, 256> counts{};
  for (std::uint8_t c : classification) ++counts[c];
  for (int c = 0; c < 256; ++c)
    if (counts[static_cast<std::size_t>(c)] > 0)
      l.classes.push_back({c, asprsClassName(c), classificationColor(c), counts[static_cast<std::size_t>(c)]});
  return l;
}

namespace {
constexpr Rgb kWoodBrown{140, 90, 50};
constexpr Rgb kLeafGreen{90, 170, 70};
}  // namespace

Rgb woodClassColor(bool wood) { return wood ? kWoodBrown : kLeafGreen; }

Rgb woodProbabilityColor(double t) {
  if (std::isnan(t)) return Rgb{128, 128, 128};
  t = std::clamp(t, 0.0, 1.0);
  auto mix = [t](std::uint8_t a, std::uint8_t b) { return static_cast<std::uint8_t>(std::lround(a + t * (b - a))); };
  return Rgb{mix(kLeafGreen.r, kWoodBrown.r), mix(kLeafGreen.g, kWoodBrown.g), mix(kLeafGreen.b, kWoodBrown.b)};
}

std::vector<Rgb> woodColors(const std::vector<float>& probability, const std::vector<std::uint8_t>& wood) {
  std::vector<Rgb> out;
  if (!probability.empty()) {
    out.reserve(probability.size());
    for (float p : probability) out.push_back(woodProbabilityColor(p));
    return out;
  }
  out.reserve(wood.size());
  for (std::uint8_t w : wood) out.push_back(woodClassColor(w != 0));
  return out;
}

Legend woodClassLegend(std::size_t woodPoints, std::size_t points) {
  Legend l;
  l.kind = Legend::Kind::Classes;
  l.title = "wood / leaf (the classification, then the lassos)";
  l.classes.push_back({64, "wood", woodClassColor(true), woodPoints});
  l.classes.push_back({65, "leaf", woodClassColor(false), points - std::min(points, woodPoints)});
  l.note = "the fits and strokes use the wood points only";
  return l;
}

}  // namespace treesketch::viewer
