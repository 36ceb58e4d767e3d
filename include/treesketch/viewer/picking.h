// Point picking and measuring in the desktop tool, as in CloudCompare's "point picking" and
// "distance between two points" tools: which cloud point a click means, what the tool says about
// it (coordinates and the file's attributes), and the distance between two picked points.
// Plain C++, no GL; the window draws the result (apps/viewer/overlays.cpp).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "treesketch/geom/camera.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"

namespace treesketch::viewer {

struct PickedPoint {
  bool found = false;
  std::size_t index = 0;  ///< into the cloud
  geom::Vec3 position = geom::Vec3::Zero();
  double screenDistancePx = 0.0;  ///< from the click to the point's projection
};

/// The cloud point a click at `screen` (window pixels, top-left origin) means under `camera`: of
/// the points in front of the camera (window depth in [0, 1]) whose projection lies within
/// `radiusPx` of the click, the nearest to the camera — the one the person sees there, not one
/// hidden behind it. Ties in depth go to the nearer projection. `found` is false when no point is
/// that close, or for an empty cloud or a non-positive radius. One pass over the cloud (10.6 ms CPU
/// for 2 M points, bench/bench_picking.cpp).
PickedPoint pickPoint(const geom::PointCloud& cloud, const geom::Camera& camera, const geom::Vec2& screen,
                      double radiusPx);

/// A measured segment between two picked points (world units, usually metres).
struct Measurement {
  geom::Vec3 a = geom::Vec3::Zero(), b = geom::Vec3::Zero();
  double distance = 0.0;                  ///< |b - a|
  geom::Vec3 delta = geom::Vec3::Zero();  ///< b - a
  double vertical = 0.0;                  ///< |Δ| along the up axis (a height difference)
  double horizontal = 0.0;                ///< across the up axis
};

/// The distance from `a` to `b` and its split along and across `up`.
Measurement measure(const geom::Vec3& a, const geom::Vec3& b, geom::UpAxis up);

/// What the tool shows for cloud point `index`: "x y z" first, then one line per attribute the
/// cloud has (intensity, RGB, classification with its ASPRS name, station, mesh). An index out of
/// range gives {}.
std::vector<std::string> describePoint(const geom::PointCloud& cloud, std::size_t index);

/// The picks of the tool's pick mode: the first click sets A, the second B (and the measurement
/// A–B), the third starts again at A.
class PickSession {
 public:
  /// Adds a pick; returns false (nothing changes) when `p` was not found.
  bool add(const PickedPoint& p);
  void clear() { count_ = 0; }
  /// 0, 1 or 2 picks.
  int count() const { return count_; }
  const PickedPoint& first() const { return picks_[0]; }
  const PickedPoint& second() const { return picks_[1]; }
  /// The latest pick (valid when count() > 0).
  const PickedPoint& last() const { return picks_[count_ > 0 ? count_ - 1 : 0]; }
  bool hasMeasurement() const { return count_ == 2; }
  Measurement measurement(geom::UpAxis up) const { return measure(picks_[0].position, picks_[1].position, up); }

 private:
  PickedPoint picks_[2];
  int count_ = 0;
};

}  // namespace treesketch::viewer
