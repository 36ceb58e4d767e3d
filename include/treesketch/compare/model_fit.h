// How well a cylinder model explains a point cloud, for real scans that have no ground-truth
// surface: every cloud point's signed distance to the model's surface (negative inside), summed up
// as the share of points within ±1, ±2 and ±5 cm, the share deeper than 2 cm inside (a model too
// thick), the share farther than 5 cm outside (wood the model missed) and the median signed
// distance (the radius bias: > 0 when the model is too thin). Plus the figures by which QSMs are
// compared: volume, total length and the trunk diameter at breast height (1.3 m).
//
// The model's solid is the union of its pieces (geom/cylinder_model.h). A point outside it gets
// the smallest of its distances to the pieces, which is exact, also at a joint (a point just past
// one piece's end cap may lie on its neighbour's surface). A point inside gets minus its depth:
// the largest, over the pieces holding it, of its distance to that piece's surface without the
// caps at its joints — where a piece starts at its parent's end (the model's parent links), the
// two caps lie inside the union and are no surface; a point inside the trunk next to a joint is
// as deep as the trunk's side says, not a millimetre from a cap. That is exact where the pieces
// at a joint share its radius (a skeleton model's frustums) and off by at most the radius step
// where they do not (cylinder tables); without parent links every cap counts.
//
// Units: distances are computed in the cloud's (= the model's) units; ModelFitOptions::unitMetres
// says how many metres one unit is, and every length in the reports is in metres.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "treesketch/geom/cylinder_model.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"

namespace treesketch::compare {

/// Signed distance from `p` to the solid frustum `c` (model units; negative inside, 0 on the
/// surface). A piece of zero length has no surface of its own and gives +inf.
double signedDistance(const geom::Vec3& p, const geom::ModelCylinder& c);
/// Same, with the start and/or end cap open (joined to a neighbouring piece): for a point inside,
/// the depth is measured to the side and the closed caps only. Outside, caps always count.
double signedDistance(const geom::Vec3& p, const geom::ModelCylinder& c, bool openStart, bool openEnd);

/// Per piece of `model`, whether its start cap ([0]) and its end cap ([1]) are joints, open as
/// CylinderModelIndex treats them: a piece that starts within a tenth of its radius of its
/// parent's end opens its start cap and the parent's end cap. Parent indices out of range are
/// ignored (the index rejects them).
std::vector<std::array<bool, 2>> jointCaps(const geom::CylinderModel& model);

/// A bounding-volume hierarchy over the pieces' boxes, answering "signed distance to the union"
/// (as above; branch and bound: boxes are skipped only when they cannot hold a smaller value), so
/// a point far from the model costs about as little as one near it. Thread-safe for queries.
class CylinderModelIndex {
 public:
  /// Throws OptionsError when a piece has a non-finite coordinate, a negative or non-finite radius
  /// or a parent index out of range. Pieces of zero length are left out.
  ///
  /// With `cells` (and 16 pieces or more), cubes about the pieces remember, once a point in them is
  /// asked about, the few pieces that can be nearest to any point in them, and later queries there
  /// measure only those: the answers are the same, value and piece. Without, every query searches
  /// the hierarchy (an index asked about a few points saves setting the cells up).
  explicit CylinderModelIndex(const geom::CylinderModel& model, bool cells = true);
  ~CylinderModelIndex();
  CylinderModelIndex(CylinderModelIndex&&) noexcept;
  CylinderModelIndex& operator=(CylinderModelIndex&&) noexcept;

  /// Signed distance from `p` to the union of the pieces; +inf when the index holds none.
  /// `piece`, when given, receives the index (in the model) of the piece that gave it (-1 if none).
  double signedDistance(const geom::Vec3& p, std::int64_t* piece = nullptr) const;
  /// Pieces held (the model's pieces of non-zero length).
  std::size_t size() const;

  /// A piece found by nearPieces: its slot in the index (for signedDistanceAmong), its index in
  /// the model and its own signed distance from the point asked about.
  struct NearPiece {
    std::uint32_t slot = 0;
    std::int64_t piece = -1;
    double distance = 0;
  };
  /// The pieces that can be nearest (give signedDistance) to some point q within `reach` of `p`
  /// (model units, >= 0): `near` receives, in no particular order, every piece whose own signed
  /// distance from p is at most max(d, 0) + 2 reach, where d = signedDistance(p) is returned.
  /// Why that suffices: outside the model signedDistance is the distance to the union and, piece
  /// by piece, to each solid, both 1-Lipschitz; a piece nearest to q lies within max(d, 0) + reach
  /// of q, so within max(d, 0) + 2 reach of p; inside, it holds q, so it lies within reach of p.
  /// An empty index gives +inf and no pieces.
  double nearPieces(const geom::Vec3& p, double reach, std::vector<NearPiece>& near) const;
  /// The smallest of the signed distances from `p` to the pieces `near` (from nearPieces), and in
  /// `piece` the model index of the first piece in `near` that gives it; `tied` says whether
  /// another piece in `near` gives exactly the same value (then signedDistance, which breaks ties
  /// by its own search order, may name the other). +inf and -1 when `near` is empty.
  double signedDistanceAmong(const geom::Vec3& p, const std::vector<NearPiece>& near, std::int64_t* piece,
                             bool* tied) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct ModelFitOptions {
  /// Metres per cloud unit (1 for a cloud in metres, 0.001 in millimetres); > 0.
  double unitMetres = 1.0;
  /// Keep every point's signed distance (cloud units) in ModelFitReport::distances.
  bool keepDistances = false;
};

struct ModelFitReport {
  std::uint64_t points = 0;  ///< cloud points measured
  double unitMetres = 1.0;
  /// Shares of the points (0-1); NaN for an empty cloud. |d| ≤ 1, 2, 5 cm:
  double within1cm = std::numeric_limits<double>::quiet_NaN();
  double within2cm = std::numeric_limits<double>::quiet_NaN();
  double within5cm = std::numeric_limits<double>::quiet_NaN();
  /// d < -2 cm: inside the model by more than 2 cm (the model is too thick there).
  double insideDeeper2cm = std::numeric_limits<double>::quiet_NaN();
  /// d > 5 cm: outside the model by more than 5 cm (wood the model missed).
  double outsideFarther5cm = std::numeric_limits<double>::quiet_NaN();
  /// Median signed distance, metres (mean of the two middle values for an even count): > 0 when
  /// the model sits inside the points (too thin), < 0 when too thick.
  double medianSigned = std::numeric_limits<double>::quiet_NaN();
  /// Per point, in cloud order, cloud units (only with ModelFitOptions::keepDistances).
  std::vector<double> distances;
};

/// Measures the cloud against the model (in parallel). An empty model leaves every point at +inf
/// (all missed). Throws OptionsError for unitMetres ≤ 0 or a NaN point.
ModelFitReport measureModelFit(const geom::PointCloud& cloud, const geom::CylinderModel& model,
                               const ModelFitOptions& options = {});
/// Same, from a prebuilt index.
ModelFitReport measureModelFit(const geom::PointCloud& cloud, const CylinderModelIndex& index,
                               const ModelFitOptions& options = {});

/// The figures QSMs are compared by, in metres.
struct ModelFigures {
  std::size_t cylinders = 0;
  double volume = 0;  ///< Σ frustum volumes, m³
  double length = 0;  ///< Σ piece lengths, m
  /// Height of the model's base along the up axis (its lowest piece end point), model units.
  double baseHeight = std::numeric_limits<double>::quiet_NaN();
  /// Breast height used, metres above the base.
  double breastHeight = 1.3;
  /// Trunk diameter at breast height, metres: twice the radius, at that height, of the piece whose
  /// axis crosses it (among the trunk's pieces, branch order 0, when the model gives orders; the
  /// thickest there if several cross). NaN when no piece crosses that height.
  double trunkDiameter = std::numeric_limits<double>::quiet_NaN();
  std::int64_t trunkPiece = -1;  ///< the piece it was taken from
};

/// Throws OptionsError for unitMetres ≤ 0 or breastHeightMetres < 0.
ModelFigures modelFigures(const geom::CylinderModel& model, geom::UpAxis up, double unitMetres = 1.0,
                          double breastHeightMetres = 1.3);

/// (A skeleton model becomes a CylinderModel with skeleton::cylinderModelFromSkeleton.)

/// JSON forms: shares as fractions (0-1), lengths in metres, NaN as null.
nlohmann::json toJson(const ModelFitReport& report);
nlohmann::json toJson(const ModelFigures& figures);

/// "98.7 % within ±2 cm (±1: 90.1 %, ±5: 99.9 %), 0.1 % missed (> 5 cm outside), 0.2 % > 2 cm
/// inside, median +0.12 cm" — the one-line summary the commands print.
std::string summaryLine(const ModelFitReport& report);
/// "volume 0.0300 m³, length 31.4 m, trunk diameter at 1.3 m 9.4 cm (1149 pieces)".
std::string summaryLine(const ModelFigures& figures);

}  // namespace treesketch::compare
