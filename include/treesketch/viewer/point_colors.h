// Point colours for the viewer: by distance to the nearest fitted circle (how well the
// reconstruction explains each point) on the project's ramp, or plain; the ramp and the height
// colouring are render/color_map.h's (one colour module for pictures and the window). Plain C++,
// no GL; RGB bytes, one per point.
#pragma once

#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"
#include "treesketch/render/image.h"

namespace treesketch::viewer {

using render::Rgb;

/// A circle in 3D (a fitted cross-section): centre, unit normal of its plane, radius (world units).
struct Circle3 {
  geom::Vec3 centre = geom::Vec3::Zero();
  geom::Vec3 normal = geom::Vec3::UnitY();
  double radius = 0.0;
};

/// Euclidean distance from `p` to the circle (its curve, not its disc), world units.
double distanceToCircle(const geom::Vec3& p, const Circle3& circle);

/// One colour per point by its distance to the nearest of `circles` on render::viridis: 0 -> ramp
/// start, `maxDistance` (world units, > 0) or more -> ramp end. With no circles every point gets
/// the ramp's end colour.
/// Runs in parallel (TBB); about 1 ms per million point-circle pairs on two cores.
std::vector<Rgb> circleDistanceColors(const geom::PointCloud& cloud, const std::vector<Circle3>& circles,
                                      double maxDistance);

/// The same colour for every point.
std::vector<Rgb> plainColors(const geom::PointCloud& cloud, const Rgb& color);

}  // namespace treesketch::viewer
