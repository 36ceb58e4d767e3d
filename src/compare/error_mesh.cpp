// Error meshes coloured by distance (MeshLab's quality colour ramp as described in thesis §4.5).
#include "treesketch/compare/error_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::compare {

std::array<std::uint8_t, 3> rampColor(double t) {
  if (std::isnan(t)) t = 1;
  t = std::clamp(t, 0.0, 1.0);
  // Four equal legs: red -> yellow (G up), yellow -> green (R down), green -> cyan (B up),
  // cyan -> blue (G down).
  static constexpr double kStops[5][3] = {{255, 0, 0}, {255, 255, 0}, {0, 255, 0}, {0, 255, 255}, {0, 0, 255}};
  const double x = t * 4;
  const int leg = std::min(3, static_cast<int>(x));
  const double f = x - leg;
  std::array<std::uint8_t, 3> c{};
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<std::uint8_t>(std::lround(kStops[leg][k] + f * (kStops[leg + 1][k] - kStops[leg][k])));
  return c;
}

std::array<double, 2> colorRange(const std::vector<double>& distances, const ErrorMeshOptions& options) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double d : distances)
    if (std::isfinite(d)) {
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  if (!(lo <= hi)) lo = hi = 0;
  if (!std::isnan(options.rangeMin)) lo = options.rangeMin;
  if (!std::isnan(options.rangeMax)) hi = options.rangeMax;
  if (lo > hi)
    throw OptionsError("error mesh: colour range minimum " + std::to_string(lo) + " is above its maximum " +
                       std::to_string(hi));
  return {lo, hi};
}

geom::TriMesh makeErrorMesh(const geom::TriMesh& mesh, const std::vector<double>& vertexDistance,
                            const ErrorMeshOptions& options) {
  if (vertexDistance.size() != mesh.vertices.size())
    throw OptionsError("error mesh: " + std::to_string(vertexDistance.size()) + " distances for " +
                       std::to_string(mesh.vertices.size()) + " vertices");
  const auto [lo, hi] = colorRange(vertexDistance, options);
  geom::TriMesh out = mesh;
  out.quality = vertexDistance;
  out.colors.resize(mesh.vertices.size());
  for (std::size_t i = 0; i < vertexDistance.size(); ++i) {
    const double d = vertexDistance[i];
    double t;
    if (!std::isfinite(d))
      t = 1;
    else if (hi > lo)
      t = (d - lo) / (hi - lo);
    else
      t = d <= lo ? 0 : 1;
    out.colors[i] = rampColor(t);
  }
  return out;
}

}  // namespace treesketch::compare
