#include "treesketch/viewer/view_overlays.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace treesketch::viewer {

double roundLengthAtMost(double maxLength) {
  if (!(maxLength > 0.0) || !std::isfinite(maxLength)) return 0.0;
  double p = std::pow(10.0, std::floor(std::log10(maxLength)));
  // Guard against log10 rounding (log10(1000) = 2.9999...).
  while (p * 10.0 <= maxLength) p *= 10.0;
  while (p > maxLength) p /= 10.0;
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= maxLength * (1.0 + 1e-12)) return m * p;
  return p;
}

std::string formatLength(double metres) {
  struct Unit {
    double size;
    const char* name;
  };
  static const Unit units[] = {{1000.0, "km"}, {1.0, "m"}, {0.01, "cm"}, {0.001, "mm"}};
  double a = std::abs(metres);
  const Unit* u = &units[3];
  for (const Unit& c : units)
    if (a >= c.size * (1.0 - 1e-9)) {
      u = &c;
      break;
    }
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g %s", metres / u->size, u->name);
  return buf;
}

ScaleBar scaleBarFor(double worldPerPixel, double maxPixels, double unitsMetres) {
  ScaleBar bar;
  if (!(worldPerPixel > 0.0) || !std::isfinite(worldPerPixel) || !(maxPixels > 0.0) || !(unitsMetres > 0.0)) return bar;
  double maxMetres = worldPerPixel * maxPixels * unitsMetres;
  double metres = roundLengthAtMost(maxMetres);
  if (metres <= 0.0) return bar;
  bar.length = metres / unitsMetres;
  bar.pixels = bar.length / worldPerPixel;
  bar.label = formatLength(metres);
  return bar;
}

std::array<GizmoAxis, 3> axisGizmo(const geom::Camera& camera) {
  geom::Vec3 right = camera.right(), up = camera.up(), back = -camera.forward();
  std::array<GizmoAxis, 3> out;
  for (int k = 0; k < 3; ++k) {
    geom::Vec3 e = geom::Vec3::Unit(k);
    out[static_cast<std::size_t>(k)] = {k, geom::Vec2(e.dot(right), -e.dot(up)), e.dot(back)};
  }
  std::sort(out.begin(), out.end(),
            [](const GizmoAxis& a, const GizmoAxis& b) { return a.towardsViewer < b.towardsViewer; });
  return out;
}

}  // namespace treesketch::viewer
