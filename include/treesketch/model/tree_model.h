// The tree model at the end of every path: a person's sketch fitted by recon, the automatic model
// of the skeleton module, a sketch corrected in the desktop tool, a batch job. Each becomes one
// TreeModel (frustums, which of them rest on a fitted circle, the swept mesh, the up axis), and
// every output — mesh, cylinder table, TreeQSM text, metrics JSON, fit report — is measured and
// written from it here, by one code path, so the same model gives the same files whichever
// command or window made it.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <limits>
#include <string>
#include <vector>

#include "treesketch/cloud/stems.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/compare/model_fit.h"
#include "treesketch/compare/tree_metrics.h"
#include "treesketch/geom/cylinder_model.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/skeleton_sketch.h"

namespace treesketch::model {

struct TreeModel {
  geom::CylinderModel cylinders;  ///< one frustum per parent→child link, parents first
  /// Per piece: its id in the cylinder table (the node it ends at).
  std::vector<std::int64_t> ids;
  /// Per piece: its end radius rests on a circle fitted to the points (1), or was inferred from
  /// the tree's allometry and its neighbours (0).
  std::vector<char> measured;
  geom::TriMesh mesh;  ///< the swept tubes
  geom::UpAxis up = geom::UpAxis::Z;
  bool empty() const { return cylinders.empty(); }
};

/// A fitted sketch's model: each node with a circle in the reconstruction's model (its accepted
/// fit, its kept circle, or a radius inferred from its limb: recon/radius_inference.h) joined to
/// its nearest ancestor with one (nodes with none are bridged, as the sweep bridges them); a piece
/// ending at an inferred radius is not measured.
/// Branch orders follow the tree's shape (at a node the child with the largest radius continues
/// the branch, every other child starts one of the next order), so a branch's first piece starts
/// with the branch's own radius, as the automatic model's do. The mesh is the reconstruction's.
TreeModel fromReconstruction(const recon::ReconstructionResult& result, geom::UpAxis up);

/// How a fitted sketch's nodes hold together: the nodes that did not fit (skipped; disabled nodes
/// are off by choice) and how many separate pieces the fitted ones make (a fitted node with no
/// fitted ancestor starts one; fromReconstruction bridges unfitted nodes inside a piece).
struct FittedShape {
  std::vector<sketch::NodeId> unfitted;
  std::size_t pieces = 0;
  /// "3, 7, 12" (the first 20, then "...").
  std::string unfittedList() const;
};
FittedShape fittedShape(const recon::ReconstructionResult& result);

/// Refuses a fitted sketch whose fitted nodes make more than one piece (floating discs and tubes:
/// a sketch of another tree, or one whose trunk missed the cloud) with DegenerateInputError naming
/// `sketch`, `cloud` and the nodes that did not fit.
void checkFittedShape(const FittedShape& shape, const std::string& sketch, const std::string& cloud);

/// Refuses an automatic result that is no model, with DegenerateInputError naming `source` (the
/// cloud's path), its point count and its diagonal: no skeleton, no radius measured or inferred
/// (no fit, no measured stem, no crown to infer a stem from: points all equal or on a line), or a
/// tube of zero area. A model whose radii were all inferred from the crown passes (its verdict
/// says so).
void checkAutoModel(const std::string& source, const geom::PointCloud& cloud, const skeleton::AutoSkeletonResult& result);

/// A skeleton model's frustums (parents first; ids = node indices; measured = `accepted`, or all
/// when it is empty). The mesh is left empty.
TreeModel fromSkeletonNodes(const std::vector<skeleton::SkeletonNode>& nodes, const std::vector<char>& accepted,
                            geom::UpAxis up);

/// The automatic model (AutoSkeletonResult::model, its accepted fits and its mesh).
TreeModel fromAutoSkeleton(const skeleton::AutoSkeletonResult& result, geom::UpAxis up);

/// The points of `cloud` the wood/leaf classification (classify::classifyWood, `up` its up axis)
/// calls wood: what `--wood-only` models. Fewer than a hundred is no tree's wood:
/// DegenerateInputError naming `source`.
geom::PointCloud woodOnlyCloud(const geom::PointCloud& cloud, geom::UpAxis up, const std::string& source);

/// Share of the model's volume whose pieces rest on a fitted circle, in [0, 1] (0 for no volume).
double measuredVolumeShare(const TreeModel& model);

struct MeasureOptions {
  double unitMetres = 1.0;  ///< metres per cloud unit (> 0)
  bool fit = true;          ///< measure the cloud's points against the model (the report and the verdict need it)
  bool leafOn = false;      ///< the model was made with the leaf-on settings (the verdict's advice)
  /// The model was made from the points classified as wood only (the verdict's advice; the points
  /// far outside it are then the leaves, not a fault of the model).
  bool woodOnly = false;
  /// Share of the automatic skeleton's pieces that looked like leaves (flat), or < 0 when unknown.
  double leafPieceShare = -1;
  /// The scan's noise measured while modelling (cloud units; the points' spread about the stem or
  /// the circles, AutoSkeletonResult::noise), or < 0 when not measured.
  double noise = -1;
  /// The radius the automatic skeleton's points were drawn together by (AutoSkeletonResult::
  /// contraction; cloud units), 0 when not.
  double contraction = 0;
  /// The stems at breast height in the scan (lookForStems), when looked for: a cloud of two trees
  /// or more is a plot, which one model joins into one tree.
  bool stemsLookedFor = false;
  cloud::Stems stems;
  /// With woodOnly: the volume of the automatic model of every point with the leaf-on settings
  /// (everyPointVolume(); cloud units³), or < 0 when not made. It is the upper end of the volume's
  /// range when above it: the points the classification calls leaf may hold wood, and a model of
  /// every point is the wood with what the foliage adds to it.
  double everyPointVolume = -1;
  /// With leafOn and not woodOnly: the volume of the automatic model of the points the wood/leaf
  /// classification calls wood (classifiedWoodVolume(); cloud units³), or < 0 when not made. It is
  /// the lower end of the volume's range when below it: a model of every point of a tree in leaf
  /// takes its foliage for wood.
  double classifiedWoodVolume = -1;
};

/// The volume (cloud units³) of the automatic model of every point of `cloud` made with `options`
/// (the leaf-on settings, for MeasureOptions::everyPointVolume).
double everyPointVolume(const geom::PointCloud& cloud, const skeleton::AutoSkeletonOptions& options, geom::UpAxis up);

/// The volume (cloud units³) of the automatic model, made with `options` (the leaf-off settings),
/// of the points of `cloud` the wood/leaf classification calls wood (as woodOnlyCloud chooses
/// them), for MeasureOptions::classifiedWoodVolume; -1 when it calls too few wood to model.
double classifiedWoodVolume(const geom::PointCloud& cloud, const skeleton::AutoSkeletonOptions& options,
                            geom::UpAxis up);

/// Looks for the stems at breast height in `scan` (cloud/stems.h; `strays`: the points set aside
/// before modelling, the ground among them), in `options.unitMetres`, for the verdict and the report.
void lookForStems(MeasureOptions& options, const geom::PointCloud& scan, geom::UpAxis up,
                  const cloud::StrayPoints& strays);

/// What the automatic model knows of its scan, for measure(): the noise it measured (when it
/// measured one), whether it ran with the leaf-on settings (`options`'s foliage is not recorded),
/// and the share of its pieces that looked like leaves. unitMetres and woodOnly are the caller's.
MeasureOptions autoMeasureOptions(const skeleton::AutoSkeletonResult& result,
                                  const skeleton::AutoSkeletonOptions& options, bool leafOn);

/// Whether the model's figures can be trusted, with the measured reasons and what to do.
struct Verdict {
  enum class Level { Trusted, Uncertain, NotTrusted };
  Level level = Level::Trusted;
  std::vector<std::string> reasons;  ///< each with its measured figure
  std::vector<std::string> advice;
};

/// "trusted", "uncertain", "not trusted".
const char* toString(Verdict::Level level);

/// What is known of a model against its cloud.
struct ModelMeasures {
  compare::TreeMetrics metrics;  ///< height, DBH, volumes, orders, crown, taper
  bool hasFit = false;
  compare::ModelFitReport fit;    ///< shares of the points by signed distance (when hasFit)
  compare::ModelFigures figures;  ///< volume, length, trunk diameter
  double measuredVolumeShare = 0;
  /// The volume's range, m³: pieces on fitted circles with their radii ±10 % (a circle fitted to a
  /// scanned arc), the lower end also allowing for the scan's noise σ (MeasureOptions::noise: a
  /// radius R down to √(R² − 4σ²), noise adding to a radius in quadrature), inferred pieces ×2/3
  /// to ×1.5 (the pipe model's spread between trees), their lower end after the same allowance.
  double volumeLow = 0, volumeHigh = 0;
  /// Volume over the cylinder of the stem's DBH and the tree's height (a tree's form factor,
  /// branches included: about 0.5–2.5); NaN without a DBH.
  double formFactor = 0;
  /// The scan's noise in metres (MeasureOptions::noise), NaN when not measured.
  double noiseMetres = std::numeric_limits<double>::quiet_NaN();
  /// The radius the skeleton's points were drawn together by, metres (MeasureOptions::contraction);
  /// 0 when the skeleton is the scan's own.
  double contractionMetres = 0;
  /// The stems at breast height (MeasureOptions::stems; empty when not looked for).
  bool stemsLookedFor = false;
  cloud::Stems stems;
  Verdict verdict;
  /// One line: the fit's shares (when measured) and the model's figures.
  std::string summary() const;
  /// One line: the volume with its range and measured share, and the verdict with its reasons.
  std::string verdictLine() const;
};

ModelMeasures measure(const TreeModel& model, const geom::PointCloud& cloud, const MeasureOptions& options = {});

/// Where to write a model's outputs ("" = not wanted).
struct OutputPaths {
  std::string mesh;       ///< .obj or .ply
  std::string cylinders;  ///< treesketch's cylinder table (.csv)
  std::string qsm;        ///< TreeQSM's cylinder text layout (.txt)
  std::string metrics;    ///< tree metrics (.json)
  std::string report;     ///< fit report (.json)
  std::vector<const std::string*> all() const { return {&mesh, &cylinders, &qsm, &metrics, &report}; }
};

/// Refuses outputs before any work: an output that is one of `inputs`, or two outputs on one
/// path, or a folder that cannot be written, or a mesh path with an extension other than .obj or
/// .ply (OptionsError / OutputError naming the path).
void checkOutputs(const OutputPaths& paths, const std::vector<std::string>& inputs);

/// {"setAside", "far", "isolated", "spacing", "linkDistance"}: what the automatic model set aside.
nlohmann::json strayPointsJson(const cloud::StrayPoints& strays);

/// {"level", "reasons", "advice"}.
nlohmann::json verdictJson(const Verdict& verdict);

/// The report: `header` (what the path knows: its nodes' fits, or the automatic model's counts
/// and timings) with "model" ({"fit", "figures", "measuredVolumeShare", "volumeRangeM3",
/// "formFactor", "noiseM"}), "verdict" ({"level", "reasons", "advice"}) and "metrics" added.
nlohmann::json reportJson(const ModelMeasures& measures, nlohmann::json header);

/// Writes every wanted output, each atomically, in this order: cylinder table, TreeQSM text, mesh,
/// metrics, report (a batch's done marker follows the report, so a complete set says a complete
/// tree). The report needs `measures.hasFit`. Throws OutputError (nothing partial is left).
void writeOutputs(const TreeModel& model, const ModelMeasures& measures, const OutputPaths& paths,
                  const nlohmann::json& reportHeader = nlohmann::json::object());

}  // namespace treesketch::model
