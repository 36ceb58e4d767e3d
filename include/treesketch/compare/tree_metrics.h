// The figures foresters read off a tree model (a QSM) and its cloud: height, diameter at breast
// height (DBH) from the model and measured in the cloud, crown projection area and diameter, wood
// volume split by stem, branches and branch order, branch counts and lengths per order, and the
// stem's taper. Builds on modelFigures (compare/model_fit.h) for volume, length and the model's DBH.
//
// Conventions: heights are measured along the up axis from the base; the model's base is its
// lowest piece end, the cloud's its lowest point (the ground in a segmented single-tree scan).
// Every length is in metres, areas in m², volumes in m³: TreeMetricsOptions::unitMetres says how
// many metres one model/cloud unit is (the CLI's --units-metres). The cloud DBH is measured the
// way foresters do it with a scan: the points within ±sliceHalfWidth of 1.3 m above the cloud's
// base, projected on the ground plane, and a robust RANSAC circle fit to them (fit/circle_fit.h).
#pragma once

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "treesketch/compare/model_fit.h"
#include "treesketch/fit/circle_fit.h"
#include "treesketch/geom/cylinder_model.h"
#include "treesketch/geom/point_cloud.h"

namespace treesketch::compare {

struct TreeMetricsOptions {
  /// Metres per model/cloud unit (> 0).
  double unitMetres = 1.0;
  /// Breast height above the base, metres: 1.3 m, the usual forestry convention.
  double breastHeight = 1.3;
  /// Half the thickness of the cloud slice at breast height, metres: ±3 cm holds a few hundred
  /// points of a TLS stem scan and keeps the stem's taper across the slice under a millimetre.
  double sliceHalfWidth = 0.03;
  /// Step of the taper table along the stem, metres (1 m, as in taper tables).
  double taperStep = 1.0;
  /// Cloud slice: only points within this many model DBH radii (plus 5 cm) of the model's stem
  /// axis at breast height are fitted, when the model has a stem there; low branches and
  /// understorey in the slice are left out. 0 = use every slice point.
  double stemRegionRadii = 3.0;
  /// The circle fit; its inlierThreshold and radius bounds are in metres here (converted to
  /// cloud units). Defaults: 1 cm band (the scanner noise), at most 3 m radius.
  fit::CircleFitOptions circle = [] {
    fit::CircleFitOptions c;
    c.inlierThreshold = 0.01;
    c.maxRadius = 3.0;
    return c;
  }();
};

/// Per branch order: how many branches, pieces, their total length (m) and volume (m³).
struct OrderMetrics {
  std::int32_t order = 0;  ///< 0 = the stem
  std::size_t branches = 0;
  std::size_t pieces = 0;
  double length = 0;  ///< m
  double volume = 0;  ///< m³
};

/// The stem's diameter at one height above the model's base.
struct TaperSample {
  double height = 0;    ///< m above the model's base
  double diameter = 0;  ///< m; NaN when no stem piece crosses that height
};

/// DBH from the cloud slice, with the fit's quality.
struct CloudDbh {
  bool ok = false;
  std::string reason;                                          ///< why no circle (empty when ok)
  double sliceHeight = 0;                                      ///< m above the cloud's base
  std::size_t slicePoints = 0;                                 ///< points in the slice (after the stem region)
  std::size_t inliers = 0;                                     ///< points within the inlier band of the circle
  double diameter = std::numeric_limits<double>::quiet_NaN();  ///< m
  double rms = std::numeric_limits<double>::quiet_NaN();       ///< RMS residual of the inliers, m
  geom::Vec3 centre = geom::Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  ///< cloud units
};

struct TreeMetrics {
  double unitMetres = 1.0;
  ModelFigures figures;  ///< volume, length, model DBH (trunkDiameter), base height
  /// Model height: highest piece end minus the base, m.
  double height = std::numeric_limits<double>::quiet_NaN();
  double stemVolume = 0;             ///< order-0 pieces, m³
  double branchVolume = 0;           ///< every other piece, m³
  double stemLength = 0;             ///< m
  std::size_t branches = 0;          ///< branches of order >= 1
  std::vector<OrderMetrics> orders;  ///< by increasing order
  /// Crown projection of the model: convex hull of the pieces' end discs on the ground plane.
  double crownArea = 0;            ///< m²
  double crownDiameter = 0;        ///< diameter of the circle of the same area, m
  double crownSpread = 0;          ///< largest width of the hull, m
  std::vector<TaperSample> taper;  ///< at 0, step, 2 step... up to the stem's top

  /// From the cloud (hasCloud): height (highest minus lowest point), crown projection of all
  /// points, and the DBH fit.
  bool hasCloud = false;
  std::size_t cloudPoints = 0;
  double cloudHeight = std::numeric_limits<double>::quiet_NaN();
  double cloudCrownArea = std::numeric_limits<double>::quiet_NaN();
  double cloudCrownDiameter = std::numeric_limits<double>::quiet_NaN();
  double cloudCrownSpread = std::numeric_limits<double>::quiet_NaN();
  CloudDbh cloudDbh;
};

/// The metrics of `model` (and, when `cloud` is given, of the cloud) with `up` as the vertical.
/// Branch orders come from geom::branchStructure (the model's own when it gives them). An empty
/// model gives zeros and NaNs; an empty cloud gives hasCloud with no DBH (reason said). Throws
/// OptionsError for unitMetres <= 0, negative heights or steps, or bad parent links.
TreeMetrics treeMetrics(const geom::CylinderModel& model, geom::UpAxis up, const TreeMetricsOptions& options = {},
                        const geom::PointCloud* cloud = nullptr);

/// Area (m² when the points are in metres) and largest width of the convex hull of 2D points.
/// Fewer than 3 distinct points: area 0 (the width of two points is their distance).
void convexHullFigures(std::vector<geom::Vec2> points, double* area, double* spread);

/// JSON: metres, m², m³; NaN as null. Keys documented in docs/formats.md, "Forestry figures".
nlohmann::json toJson(const TreeMetrics& metrics);
/// A readable table (several lines, units in each row), for the terminal.
std::string metricsTable(const TreeMetrics& metrics);

}  // namespace treesketch::compare
