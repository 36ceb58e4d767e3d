// Automatic sketches: sampling sizes from the cloud's size, and the thesis's uniform baseline
// (Leavenworth 2012, §3.2 and §5.4).
#include "treesketch/sketch/auto_sketch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "treesketch/util/error.h"

namespace treesketch::sketch {

using geom::Vec2;
using geom::Vec3;

SamplingParams defaultSamplingFor(const geom::BBox& cloudBounds, const SamplingScale& scale) {
  double d = cloudBounds.diagonal();
  if (cloudBounds.empty() || !(d > 0) || !std::isfinite(d))
    throw OptionsError("sampling sizes: the cloud's bounding box is empty or has zero size");
  if (!(scale.sliceHalfThicknessFraction > 0) || !(scale.lineEpsilonFraction > 0) ||
      !(scale.lineEpsilonStepFraction > 0))
    throw OptionsError("sampling sizes: the fractions of the bbox diagonal must be > 0");
  SamplingParams p;
  p.sliceHalfThickness = scale.sliceHalfThicknessFraction * d;
  p.lineEpsilon = scale.lineEpsilonFraction * d;
  p.lineEpsilonStep = scale.lineEpsilonStepFraction * d;
  return p;
}

namespace {

double distanceToLine(const Vec3& p, const Vec3& linePoint, const Vec3& unitDir) {
  Vec3 r = p - linePoint;
  return (r - unitDir * unitDir.dot(r)).norm();
}

/// Largest distance from the line to a corner of the box: distance to a line is convex, so this
/// bounds the distance of every point inside the box.
double maxDistanceToBox(const geom::BBox& box, const Vec3& linePoint, const Vec3& unitDir) {
  double best = 0;
  for (int c = 0; c < 8; ++c) {
    Vec3 corner((c & 1) ? box.max.x() : box.min.x(), (c & 2) ? box.max.y() : box.min.y(),
                (c & 4) ? box.max.z() : box.min.z());
    best = std::max(best, distanceToLine(corner, linePoint, unitDir));
  }
  return best;
}

}  // namespace

Sketch uniformAutoSketch(const geom::PointCloud& cloud, const geom::Camera& camera, int nodeCount, geom::UpAxis up) {
  if (nodeCount < 1) throw OptionsError("uniform auto sketch: the node count must be >= 1, got " + std::to_string(nodeCount));
  if (cloud.empty()) throw OptionsError("uniform auto sketch: the point cloud is empty");
  camera.validate("uniform auto sketch");
  geom::BBox bounds = cloud.bounds();

  // The tree display: screen bounding box of the points in front of the camera.
  double inf = std::numeric_limits<double>::infinity();
  double xMin = inf, xMax = -inf, yMin = inf, yMax = -inf;
  std::size_t seen = 0;
  for (const Vec3& p : cloud.positions) {
    Vec3 s = camera.project(p);
    if (!s.allFinite() || s.z() < 0.0 || s.z() > 1.0) continue;
    xMin = std::min(xMin, s.x());
    xMax = std::max(xMax, s.x());
    yMin = std::min(yMin, s.y());
    yMax = std::max(yMax, s.y());
    ++seen;
  }
  if (seen == 0) throw OptionsError("uniform auto sketch: no point of the cloud is in front of the camera");

  Sketch sk;
  sk.up = up;
  sk.defaults = defaultSamplingFor(bounds);
  int cam = sk.addCamera(camera);
  double x = 0.5 * (xMin + xMax);
  double band = (yMax - yMin) / nodeCount;  // pixels

  // World size of one pixel at the depth of the cloud's centre (exact for orthographic cameras).
  Vec3 c = camera.project(bounds.centre());
  double depth = (c.allFinite() && c.z() >= 0.0 && c.z() <= 1.0) ? c.z() : 0.5;
  Vec2 cs(x, 0.5 * (yMin + yMax));
  double pixel = (camera.unproject(cs + Vec2(0, 1), depth) - camera.unproject(cs, depth)).norm();
  double halfThickness = 0.5 * band * pixel;
  if (!(halfThickness > 0) || !std::isfinite(halfThickness)) halfThickness = sk.defaults.sliceHalfThickness;

  NodeId parent = kNoNode;
  for (int i = nodeCount - 1; i >= 0; --i) {  // bottom (root) to top
    Vec2 screen(x, yMin + (i + 0.5) * band);
    SamplingParams params = sk.defaults;
    params.sliceHalfThickness = halfThickness;
    parent = sk.addScreenNode(parent, cam, screen, params);
  }

  // Maximal lineEpsilon: the farthest point of the node's slice from its line (so the test
  // points are the whole slice at once); a slice without points gets the bound from the box.
  double margin = 1e-9 * bounds.diagonal();
  for (NodeId id : sk.ids()) {
    NodeGeometry g = sk.geometry(id);
    SamplingParams params = sk.node(id).params;
    double farthest = -1;
    for (const Vec3& p : cloud.positions) {
      Vec3 r = p - g.planePoint;
      if (std::abs(r.dot(g.planeNormal)) > params.sliceHalfThickness) continue;
      farthest = std::max(farthest, (r - g.lineDir * g.lineDir.dot(r)).norm());
    }
    if (farthest < 0) farthest = maxDistanceToBox(bounds, g.linePoint, g.lineDir);
    params.lineEpsilon = farthest * (1 + 1e-9) + margin;
    params.lineEpsilonStep = params.lineEpsilon;
    sk.setParams(id, params);
  }
  return sk;
}

}  // namespace treesketch::sketch
