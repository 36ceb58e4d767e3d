// Point colours for the viewer: by height (a perceptual ramp from the lowest to the highest
// point), by distance to the nearest fitted circle (how well the reconstruction explains each
// point), or plain. Plain C++, no GL; RGB bytes, one per point.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"

namespace treesketch::viewer {

using Rgb = std::array<std::uint8_t, 3>;

/// A circle in 3D (a fitted cross-section): centre, unit normal of its plane, radius (world units).
struct Circle3 {
  geom::Vec3 centre = geom::Vec3::Zero();
  geom::Vec3 normal = geom::Vec3::UnitY();
  double radius = 0.0;
};

/// Colour of `t` in [0, 1] on the project's viridis-like ramp (render::viridis); t is clamped,
/// NaN maps to 0.
Rgb rampColor(double t);

/// One colour per point by its height along `up`, the ramp spanning the cloud's height range.
/// A flat cloud (zero height range) gets the ramp's middle colour; an empty cloud gives {}.
std::vector<Rgb> heightColors(const geom::PointCloud& cloud, geom::UpAxis up);

/// Euclidean distance from `p` to the circle (its curve, not its disc), world units.
double distanceToCircle(const geom::Vec3& p, const Circle3& circle);

/// One colour per point by its distance to the nearest of `circles`: 0 -> ramp start, `maxDistance`
/// (world units, > 0) or more -> ramp end. With no circles every point gets the ramp's end colour.
/// Runs in parallel (TBB); about 1 ms per million point-circle pairs on two cores.
std::vector<Rgb> circleDistanceColors(const geom::PointCloud& cloud, const std::vector<Circle3>& circles,
                                      double maxDistance);

/// The same colour for every point.
std::vector<Rgb> plainColors(const geom::PointCloud& cloud, const Rgb& color);

}  // namespace treesketch::viewer
