// Automatic sketches: sampling sizes scaled to a cloud, and the thesis's baseline automatic
// sketch (evenly spaced nodes from the top of the view to the bottom with maximal sampling sizes,
// Leavenworth 2012 §3.2 and §5.4: "essentially this uses the entire point cloud").
#pragma once

#include "treesketch/geom/camera.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::sketch {

/// Sampling sizes as fractions of the cloud's bounding-box diagonal. The thesis gives absolute
/// numbers for its own models only (a constant EPSILON; lineEpsilon grown by one unit); these
/// fractions reproduce that scale on trees of any size. For a 15 m tree (diagonal ~ 18 m):
struct SamplingScale {
  /// Slice half-thickness: 0.4 % (~7 cm, a 14 cm slab). Thin enough that the slice of a branch
  /// leaning 45° off the node's normal still looks like a circle (the ellipse's extra width is
  /// the slab thickness), thick enough to hold a few dozen points of a 100k-point scan.
  double sliceHalfThicknessFraction = 0.004;
  /// Initial lineEpsilon: 2 % (~36 cm). Must exceed the branch radius plus the sketch's aim
  /// error, or the test points miss part of the circle: a trunk of 0.3-0.5 m diameter fits.
  double lineEpsilonFraction = 0.02;
  /// lineEpsilon growth after a failed fit: 2 % again, so about 50 steps reach the whole cloud.
  double lineEpsilonStepFraction = 0.02;
};

/// Sampling sizes for a cloud with bounds `cloudBounds` (world units): each field is the
/// matching SamplingScale fraction times the bbox diagonal. Throws OptionsError for an empty or
/// zero-size box or non-positive fractions.
SamplingParams defaultSamplingFor(const geom::BBox& cloudBounds, const SamplingScale& scale = {});

/// The thesis's automatic sketch (§5.4), under `camera`:
///  - the cloud's points in front of the camera (window depth in [0, 1]) are projected; their
///    screen bounding box [xmin, xmax] × [ymin, ymax] is "the tree display";
///  - the height ymax - ymin is cut into `nodeCount` equal bands; one screen node sits at the
///    centre of each band, at x = (xmin + xmax) / 2 (the horizontal centre of the projection);
///  - they form one chain: the root is the lowest node (largest y), each node's parent is the
///    node below it;
///  - "maximal sampling sizes": sliceHalfThickness = half the band height in world units (the
///    slices tile the height; the pixel size is taken at the depth of the cloud's bbox centre,
///    exact for an orthographic camera), lineEpsilon = the largest distance from the node's line
///    of a point in its slice, plus 1e-9 relative (the test points are the whole slice at once;
///    a slice without points takes the largest distance from the line to a bbox corner),
///    lineEpsilonStep = lineEpsilon.
/// sketch.defaults = defaultSamplingFor(cloud bounds), sketch.up = `up`; the camera is the
/// sketch's camera 0. Throws OptionsError for nodeCount < 1, an empty cloud, a degenerate
/// camera or no point in front of the camera. Cost: nodeCount + 1 passes over the cloud.
Sketch uniformAutoSketch(const geom::PointCloud& cloud, const geom::Camera& camera, int nodeCount, geom::UpAxis up);

}  // namespace treesketch::sketch
