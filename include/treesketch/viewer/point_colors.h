// Point colours for the viewer: by distance to the model's surface, or to the nearest fitted
// circle before there is a surface (how well the reconstruction explains each point), on the
// project's ramp, or plain; the ramp and the height
// colouring are render/color_map.h's (one colour module for pictures and the window). Plain C++,
// no GL; RGB bytes, one per point.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "treesketch/geom/cylinder_model.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"
#include "treesketch/render/image.h"

namespace treesketch::compare {
class CylinderModelIndex;
}

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

/// circleDistanceColors for repeated calls on one cloud (the viewer recolours after every edit):
/// the points are binned once into a grid of cells `maxDistance` wide, and each circle visits only
/// the cells within `maxDistance` of it; every other point is at least that far from all circles,
/// so it gets the ramp's end colour, as in circleDistanceColors. Same colours, in time that grows
/// with the points near the circles rather than points x circles.
class DistanceColorGrid {
 public:
  /// Bins `cloud` (which must outlive the grid and not change) for distances up to `maxDistance`.
  void build(const geom::PointCloud& cloud, double maxDistance);
  bool builtFor(const geom::PointCloud& cloud, double maxDistance) const {
    return cloud_ == &cloud && size_ == cloud.size() && maxDistance == maxDistance_;
  }
  /// The colours (as circleDistanceColors(cloud, circles, maxDistance)) into `out`.
  void colors(const std::vector<Circle3>& circles, std::vector<Rgb>& out);
  /// The colours of surfaceDistanceColors(cloud, model, maxDistance) into `out`. The grid keeps the
  /// colours of the model it was given last, and measures again only the points within
  /// maxDistance of the box of a piece that differs between the two models (added, removed, moved,
  /// resized, or joined to its parent differently; a piece is compared by its exact values). Any
  /// other point's distance is the minimum over the same pieces in both models, or is at least
  /// maxDistance in both (the ramp's end colour): its colour cannot change. A cell whose centroid
  /// lies farther than maxDistance plus the cell's spread (its farthest point from the centroid)
  /// from the surface is wholly beyond the ramp: its points are not measured one by one. The
  /// first call after build() measures near every piece. Throws OptionsError (as
  /// compare::CylinderModelIndex) for a piece with non-finite values, leaving the grid as it was.
  void surfaceColors(const geom::CylinderModel& model, std::vector<Rgb>& out);
  /// Drops the kept surface colours: the next surfaceColors measures near every piece, as the
  /// first after build() (the reference the kept colours are compared with).
  void forgetSurface() { surfaceKept_ = false; }
  /// Points whose distance the last surfaceColors call measured one by one, and cells it decided
  /// as a whole (beyond the ramp's end); for tests and benchmarks.
  std::size_t lastPointsMeasured() const { return lastMeasured_; }
  std::size_t lastCellsDecided() const { return lastCellsDecided_; }

 private:
  /// A piece as the distance sees it: start, end, radii, open start and end caps.
  using PieceKey = std::array<double, 10>;
  void markCellsNear(const geom::BBox& box);
  void measureMarkedCells(const compare::CylinderModelIndex& index, const std::vector<geom::BBox>& changed);

  const geom::PointCloud* cloud_ = nullptr;
  std::size_t size_ = 0;
  double maxDistance_ = 0, cell_ = 1;
  geom::Vec3 origin_ = geom::Vec3::Zero();
  int dims_[3] = {0, 0, 0};
  std::vector<std::uint32_t> start_, points_;  ///< CSR: cell c holds points_[start_[c] .. start_[c+1])
  std::vector<double> best_;
  std::vector<std::uint32_t> touched_;
  // The surface colouring kept between calls: the last model's pieces (sorted) and colours.
  bool surfaceKept_ = false;
  std::vector<PieceKey> surfacePieces_;
  std::vector<Rgb> surface_;
  std::vector<char> cellMarked_;
  std::vector<std::uint32_t> markedCells_;
  std::size_t lastMeasured_ = 0, lastCellsDecided_ = 0;
};

/// One colour per point by its distance to the surface of a cylinder model (the union of its
/// frustums, compare::CylinderModelIndex: the distance fit-report measures, here unsigned: a point
/// inside the model is as far from the surface as it is deep) on render::viridis: 0 (on the
/// surface) -> ramp start, `maxDistance` (world units, > 0) or more -> ramp end. Points farther
/// than `maxDistance` from the model's box are not queried. An empty model gives every point the
/// ramp's end colour. Runs in parallel (TBB).
std::vector<Rgb> surfaceDistanceColors(const geom::PointCloud& cloud, const geom::CylinderModel& model,
                                       double maxDistance);

/// The same colour for every point.
std::vector<Rgb> plainColors(const geom::PointCloud& cloud, const Rgb& color);

}  // namespace treesketch::viewer
