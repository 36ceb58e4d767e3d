// Error meshes: the sampled mesh with each vertex's distance to the other surface as its quality
// and a colour ramp red (near) -> yellow -> green -> cyan -> blue (far), as MeshLab's
// "colorize by vertex quality" after its Hausdorff filter (thesis §4.5: values below the range's
// minimum are red, above its maximum blue, in between interpolated).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "treesketch/geom/tri_mesh.h"

namespace treesketch::compare {

/// The ramp's colour at `t` (0 = red, 1/4 yellow, 1/2 green, 3/4 cyan, 1 blue, linear between);
/// t is clamped to [0, 1]; NaN gives blue (unknown counts as far).
std::array<std::uint8_t, 3> rampColor(double t);

struct ErrorMeshOptions {
  /// Colour range (metres). NaN = the minimum / maximum of the finite distances (thesis §4.5).
  double rangeMin = std::numeric_limits<double>::quiet_NaN();
  double rangeMax = std::numeric_limits<double>::quiet_NaN();
};

/// The range used for `distances` under `options`: given bounds as they are, missing ones from
/// the finite distances; {0, 0} when there are none. Throws OptionsError when min > max.
std::array<double, 2> colorRange(const std::vector<double>& distances, const ErrorMeshOptions& options);

/// A copy of `mesh` with per-vertex quality = `vertexDistance` (metres, one per vertex) and
/// colours from the ramp over colorRange(). Vertices with no distance (+inf: beyond the search
/// distance; NaN: not measured) keep that value as quality and are coloured blue. A zero-width
/// range colours values <= it red and values above it blue. Throws OptionsError when the sizes
/// differ or the range is inverted.
geom::TriMesh makeErrorMesh(const geom::TriMesh& mesh, const std::vector<double>& vertexDistance,
                            const ErrorMeshOptions& options = {});

}  // namespace treesketch::compare
