// The project's colour maps, one module for the offline renderer (PNG pictures) and the viewer
// (point colours), so that a picture and the window colour a cloud alike: a viridis-like ramp,
// colours per point by height, distinct colours for several overlaid meshes, blending. Plain
// bytes (render::Rgb), no GL. (The error meshes' red-to-blue ramp follows MeshLab and stays in
// compare/error_mesh.h.)
#pragma once

#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"
#include "treesketch/render/image.h"

namespace treesketch::render {

/// Colour of `t` in [0, 1] on a dark-blue -> teal -> green -> yellow ramp (piecewise linear through
/// stops sampled from matplotlib's viridis). t is clamped; NaN maps to the start colour.
Rgb viridis(double t);

/// One colour per point by its height along `up`, the ramp spanning the cloud's height range.
/// A flat cloud (zero height range) gets the ramp's middle colour; an empty cloud gives {}.
std::vector<Rgb> heightColors(const std::vector<geom::Vec3>& points, geom::UpAxis up);

/// The i-th of a small cycle of distinct mid-tone colours (brown, blue, green, purple, orange, teal),
/// for telling overlaid meshes apart; any i >= 0 is valid (the cycle repeats).
Rgb distinctColor(int i);

/// `c` moved a fraction `t` (clamped to [0, 1]) towards `towards` (e.g. white, to fade a layer).
Rgb blend(Rgb c, Rgb towards, double t);

}  // namespace treesketch::render
