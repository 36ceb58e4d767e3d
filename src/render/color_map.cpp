// Colour maps. The ramp stops are sampled from matplotlib's viridis (van der Walt & Smith, 2015).
#include "treesketch/render/color_map.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace treesketch::render {

namespace {

std::uint8_t toByte(double v) { return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L)); }

}  // namespace

Rgb viridis(double t) {
  static constexpr std::array<std::array<double, 3>, 6> kStops = {
      {{68, 1, 84}, {65, 68, 135}, {42, 120, 142}, {34, 168, 132}, {122, 209, 81}, {253, 231, 37}}};
  if (std::isnan(t)) t = 0.0;
  t = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(t), kStops.size() - 2);
  double f = t - static_cast<double>(i);
  const auto& a = kStops[i];
  const auto& b = kStops[i + 1];
  return {toByte(a[0] + f * (b[0] - a[0])), toByte(a[1] + f * (b[1] - a[1])), toByte(a[2] + f * (b[2] - a[2]))};
}

std::vector<Rgb> heightColors(const std::vector<geom::Vec3>& points, geom::UpAxis up) {
  std::vector<Rgb> colors;
  if (points.empty()) return colors;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const auto& p : points) {
    double h = geom::height(p, up);
    if (std::isfinite(h)) {
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
  }
  colors.reserve(points.size());
  const double range = hi > lo ? hi - lo : 0.0;
  for (const auto& p : points) colors.push_back(viridis(range > 0 ? (geom::height(p, up) - lo) / range : 0.5));
  return colors;
}

Rgb distinctColor(int i) {
  static constexpr std::array<Rgb, 6> kCycle = {Rgb{150, 100, 60}, Rgb{70, 110, 180}, Rgb{80, 150, 80},
                                                Rgb{140, 90, 160}, Rgb{220, 130, 40}, Rgb{40, 150, 150}};
  return kCycle[static_cast<std::size_t>(std::abs(i)) % kCycle.size()];
}

Rgb blend(Rgb c, Rgb towards, double t) {
  t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
  return {toByte(c.r + t * (towards.r - c.r)), toByte(c.g + t * (towards.g - c.g)),
          toByte(c.b + t * (towards.b - c.b))};
}

}  // namespace treesketch::render
