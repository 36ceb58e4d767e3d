// The one model at the end of every path, and every output written from it (see tree_model.h).
#include "treesketch/model/tree_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <numbers>

#include "treesketch/classify/classify.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/skeleton/skeleton_export.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::model {

namespace {

/// Branch orders from the shape (nodes parents first): at a node, the child with the largest
/// radius continues its branch (the first such on a tie); every other child starts a branch one
/// order up. Roots are order 0.
void assignBranchOrders(std::vector<geom::ModelNode>& nodes) {
  std::vector<std::int64_t> main(nodes.size(), -1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::int64_t p = nodes[i].parent;
    if (p < 0) continue;
    std::int64_t& m = main[static_cast<std::size_t>(p)];
    if (m < 0 || nodes[i].radius > nodes[static_cast<std::size_t>(m)].radius) m = static_cast<std::int64_t>(i);
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::int64_t p = nodes[i].parent;
    if (p < 0) {
      nodes[i].branchOrder = 0;
      continue;
    }
    const std::int32_t parentOrder = nodes[static_cast<std::size_t>(p)].branchOrder;
    nodes[i].branchOrder = main[static_cast<std::size_t>(p)] == static_cast<std::int64_t>(i) ? parentOrder
                                                                                              : parentOrder + 1;
  }
}

/// Ids (and measured flags) of the pieces geom::cylinderModelFromNodes makes: one per node with a
/// parent, in node order.
void pieceAttributes(const std::vector<geom::ModelNode>& nodes, const std::vector<std::int64_t>& nodeIds,
                     const std::vector<char>& nodeMeasured, TreeModel* out) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].parent < 0) continue;
    out->ids.push_back(nodeIds[i]);
    out->measured.push_back(nodeMeasured[i]);
  }
}

void writeJson(const std::string& path, const nlohmann::json& j) {
  const std::string text = j.dump(2) + "\n";
  writeFileAtomically(
      path, [&](std::ostream& os) { os << text; }, false);
}

}  // namespace

namespace {

/// Node `id`'s circle in the model: the reconstruction's (a fit, a kept circle or a radius
/// inferred from its limb), or its fit when the result has none (a result put together by hand).
recon::NodeRadius modelCircle(const recon::ReconstructionResult& r, sketch::NodeId id) {
  if (auto it = r.radii.find(id); it != r.radii.end()) return it->second;
  recon::NodeRadius c;
  const fit::NodeResult& n = r.results.at(id);
  if (n.status == fit::NodeStatus::Fitted && n.radius > 0 && n.centre.allFinite()) {
    c.source = n.kept ? recon::RadiusSource::Kept : recon::RadiusSource::Fitted;
    c.centre = n.centre;
    c.radius = n.radius;
  }
  return c;
}

}  // namespace

TreeModel fromReconstruction(const recon::ReconstructionResult& r, geom::UpAxis up) {
  std::vector<geom::ModelNode> nodes;
  std::vector<std::int64_t> ids;
  std::vector<char> measured;
  std::map<sketch::NodeId, std::int64_t> index;  // node with a circle → its place in `nodes`
  for (sketch::NodeId id : r.order) {
    const recon::NodeRadius c = modelCircle(r, id);
    if (c.source == recon::RadiusSource::None || !(c.radius > 0) || !c.centre.allFinite()) continue;
    geom::ModelNode m;
    m.position = c.centre;
    m.radius = c.radius;
    for (sketch::NodeId p = r.parents.at(id); p != sketch::kNoNode; p = r.parents.at(p)) {
      auto it = index.find(p);
      if (it != index.end()) {
        m.parent = it->second;
        break;
      }
    }
    index[id] = static_cast<std::int64_t>(nodes.size());
    nodes.push_back(m);
    ids.push_back(static_cast<std::int64_t>(id));
    measured.push_back(c.source != recon::RadiusSource::Inferred);
  }
  assignBranchOrders(nodes);
  TreeModel model;
  model.up = up;
  model.cylinders = geom::cylinderModelFromNodes(nodes);
  pieceAttributes(nodes, ids, measured, &model);
  model.mesh = r.mesh;
  return model;
}

std::string FittedShape::unfittedList() const {
  std::string s;
  for (std::size_t i = 0; i < unfitted.size() && i < 20; ++i) s += (i ? ", " : "") + std::to_string(unfitted[i]);
  return unfitted.size() > 20 ? s + ", ..." : s;
}

FittedShape fittedShape(const recon::ReconstructionResult& r) {
  FittedShape f;
  const auto fitted = [&](sketch::NodeId id) {
    const fit::NodeResult& n = r.results.at(id);
    return n.status == fit::NodeStatus::Fitted && n.radius > 0 && n.centre.allFinite();
  };
  for (sketch::NodeId id : r.order) {
    if (!fitted(id)) {
      if (r.results.at(id).status == fit::NodeStatus::Skipped) f.unfitted.push_back(id);
      continue;
    }
    bool joined = false;
    for (sketch::NodeId p = r.parents.at(id); p != sketch::kNoNode && !joined; p = r.parents.at(p)) joined = fitted(p);
    f.pieces += !joined;
  }
  return f;
}

void checkFittedShape(const FittedShape& shape, const std::string& sketch, const std::string& cloud) {
  if (shape.pieces <= 1) return;
  throw DegenerateInputError(sketch + ": the nodes fitted in " + cloud + " make " + std::to_string(shape.pieces) +
                             " separate pieces, no fitted node joins them (does the sketch belong to this cloud?); "
                             "nodes that did not fit: " +
                             shape.unfittedList() + "; no mesh written");
}

void checkAutoModel(const std::string& source, const geom::PointCloud& cloud, const skeleton::AutoSkeletonResult& r) {
  char what[512];
  std::snprintf(what, sizeof what, "%s (%zu points, bounding-box diagonal %.6g)", source.c_str(), cloud.size(),
                cloud.bounds().diagonal());
  if (r.mesh.empty() || r.model.size() < 2)
    throw DegenerateInputError(std::string(what) +
                               ": no skeleton found (points all equal, on a line, or too few?); no mesh written");
  const bool measured =
      std::any_of(r.fitAccepted.begin(), r.fitAccepted.end(), [](char c) { return c != 0; }) ||
      std::any_of(r.model.begin(), r.model.end(), [](const skeleton::SkeletonNode& n) { return n.stem; });
  if (!measured && !r.radiiFromCrown)
    throw DegenerateInputError(std::string(what) + ": no circle could be fitted at any of the " +
                               std::to_string(r.model.size()) +
                               " skeleton nodes and no crown to infer a stem from (points all equal, on a line, or "
                               "too few?); no mesh written");
  if (!(r.mesh.area() > 0))
    throw DegenerateInputError(std::string(what) + ": the model has zero area (points on a line?); no mesh written");
}

TreeModel fromSkeletonNodes(const std::vector<skeleton::SkeletonNode>& nodes, const std::vector<char>& accepted,
                            geom::UpAxis up) {
  TreeModel model;
  model.up = up;
  model.cylinders = skeleton::cylinderModelFromSkeleton(nodes);
  std::vector<geom::ModelNode> shape(nodes.size());
  std::vector<std::int64_t> ids(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    shape[i].parent = nodes[i].parent;
    ids[i] = static_cast<std::int64_t>(i);
  }
  pieceAttributes(shape, ids, accepted.size() == nodes.size() ? accepted : std::vector<char>(nodes.size(), 1),
                  &model);
  return model;
}

TreeModel fromAutoSkeleton(const skeleton::AutoSkeletonResult& r, geom::UpAxis up) {
  std::vector<char> measured = r.radiusMeasured;
  if (r.rangeNoise > 0)
    for (std::size_t i = 0; i < measured.size() && i < r.model.size(); ++i)
      if (r.model[i].radius < skeleton::kResolvableNoises * r.rangeNoise) measured[i] = 0;  // the noise's blob
  TreeModel model = fromSkeletonNodes(r.model, measured, up);
  model.mesh = r.mesh;
  return model;
}

MeasureOptions autoMeasureOptions(const skeleton::AutoSkeletonResult& r, const skeleton::AutoSkeletonOptions& options,
                                  bool leafOn) {
  MeasureOptions mo;
  mo.leafOn = leafOn;
  mo.noise = r.rangeNoise > 0 ? r.rangeNoise : r.noiseMeasured ? r.noise : -1.0;
  mo.contraction = r.contraction;
  std::size_t leafPieces = 0;
  for (const auto& n : r.model) leafPieces += skeleton::isLeafPiece(n, options);
  mo.leafPieceShare = r.model.empty() ? 0.0 : static_cast<double>(leafPieces) / static_cast<double>(r.model.size());
  return mo;
}

void lookForStems(MeasureOptions& options, const geom::PointCloud& scan, geom::UpAxis up,
                  const cloud::StrayPoints& strays) {
  const std::vector<std::uint32_t> ground = cloud::setAsideFor(strays, cloud::StrayReason::Ground);
  cloud::StemOptions so;
  so.unitMetres = options.unitMetres;
  options.stems = cloud::findStems(scan, up, ground, strays.spacing, so);
  options.stemsLookedFor = true;
}

namespace {

/// Relative radius spread of a piece on a fitted circle, and the factors of an inferred one.
constexpr double kMeasuredRadiusSpread = 0.10;
constexpr double kInferredRadiusLow = 2.0 / 3.0, kInferredRadiusHigh = 1.5;
/// The verdict's limits, each with its physical reading.
constexpr double kMaxInside = 0.05;          ///< points deeper than 2 cm inside: a scanner sees bark
constexpr double kMinMeasuredShare = 0.5;    ///< below: most of the volume is the pipe model's guess
constexpr double kMaxFormFactor = 4.0;       ///< above: more wood than a tree of that DBH and height holds
constexpr double kMaxMissed = 0.2;           ///< points > 5 cm outside: leaves, noise or other objects
constexpr double kMaxLeafPieceShare = 0.2;   ///< flat pieces in a leaf-off model: a tree in leaf
constexpr double kMinPointsPerMetre = 50.0;  ///< a circle fit needs a few dozen points per slice
/// The model's DBH and the circle the points show at breast height are two measurements of one
/// stem, each to about kMeasuredRadiusSpread: apart by more than both spreads together (√2 × 10 %),
/// one of them is off (the model's axis beside the bark, a circle on a stem seen from one side).
constexpr double kMaxDbhDisagreement = 0.14;
/// A tree's wood reaches up to within its crown's outer twigs and leaves of its top: a model whose
/// top lies more than a quarter of the tree's height below the cloud's has left wood out (a stem the
/// classification calls leaf above some height, a leader too sparse for the skeleton). Measured on
/// 28 models of real clouds: leaf-off and of every point 0.99–1.00 of their cloud's height, of the
/// classified wood of trees in leaf 0.81–0.95 (a broadleaf's crown, a palm's fronds); a drone scan
/// of a 25 m tree whose upper stem the classification called leaf, 0.49.
constexpr double kMinHeightShare = 0.75;
/// The verdict lists at most this many stems' diameters.
constexpr std::size_t kListedStems = 8;

std::string percent(double share) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * share);
  return buf;
}

/// Noise adds to a radius in quadrature: points scattered by σ about a circle of radius r lie at a
/// mean square distance r² + σ² from its centre, so a circle fitted to them is too thick, and a
/// circle round a twig thinner than the noise is the noise's own blob. A measured radius R may be
/// as thin as √(R² − (kσ)²), two noises for a 95 % allowance (a blob of R < 2σ: down to nothing).
constexpr double kNoiseRadiusAllowance = 2.0;

/// `noise`: the scan's noise in model units, or < 0 when unknown. An inferred radius takes the same
/// allowance before its own factor: it is scaled from measured ones the noise thickens alike, and
/// where it is under two noises its points cannot tell the tube from none. `ceiling` (model units³,
/// MeasureOptions::everyPointVolume; <= 0: none) raises the upper end: a wood-only model's wood
/// may be as much as a model of every point holds (on the synthetic trees in leaf its range then
/// held the true volume in 90 of 98 scans, 64 without). `floor` (model units³, MeasureOptions::
/// classifiedWoodVolume; < 0: none) lowers the lower end: a model of every point of a tree in leaf
/// may hold no more wood than the points classified as wood show.
void volumeRange(const TreeModel& model, double unit3, double noise, double ceiling, double floor, ModelMeasures* m) {
  double low = 0, high = 0;
  const double allowance = noise > 0 ? kNoiseRadiusAllowance * noise : 0.0;
  auto lower = [&](double r, double factor) {
    const double r2 = r * r - allowance * allowance;
    return r2 > 0 ? factor * std::sqrt(r2) : 0.0;
  };
  for (std::size_t i = 0; i < model.cylinders.size(); ++i) {
    const geom::ModelCylinder& c = model.cylinders.cylinders[i];
    const double v = c.volume() * unit3;
    const bool measured = i < model.measured.size() && model.measured[i];
    const double hi = measured ? 1 + kMeasuredRadiusSpread : kInferredRadiusHigh;
    high += v * hi * hi;
    const double factor = measured ? 1 - kMeasuredRadiusSpread : kInferredRadiusLow;
    geom::ModelCylinder thin = c;
    thin.startRadius = lower(c.startRadius, factor);
    thin.endRadius = lower(c.endRadius, factor);
    low += thin.volume() * unit3;
  }
  m->volumeLow = floor >= 0 ? std::min(low, floor * unit3) : low;
  m->volumeHigh = std::max(high, ceiling > 0 ? ceiling * unit3 : 0.0);
}

/// "the cloud holds N trees: ..." with the stems' diameters.
std::string severalTrees(const cloud::Stems& stems) {
  std::string dbh;
  std::size_t listed = 0;
  for (const cloud::Stem& s : stems.stems) {
    if (listed == kListedStems) {
      dbh += ", ...";
      break;
    }
    char d[32];
    std::snprintf(d, sizeof d, "%s%.0f", listed ? ", " : "", 100.0 * s.diameter);
    dbh += d;
    ++listed;
  }
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "the cloud holds %zu trees: %zu stems at breast height (DBH %s cm) that do not join between stump "
                "height and 1.3 m; the model joins them into one tree",
                stems.trees, stems.stems.size(), dbh.c_str());
  return buf;
}

/// The verdict's reason and advice for a model whose top lies well below the cloud's (kMinHeightShare).
void shortOfTheTop(const ModelMeasures& m, const MeasureOptions& o,
                   const std::function<void(Verdict::Level, std::string, std::string)>& add) {
  const compare::TreeMetrics& t = m.metrics;
  if (!t.hasCloud || !(t.cloudHeight > 0) || !std::isfinite(t.height) || t.height >= kMinHeightShare * t.cloudHeight)
    return;
  char buf[200];
  std::snprintf(buf, sizeof buf, "the model reaches %.1f m of the cloud's %.1f m: the wood above is not modelled%s",
                t.height, t.cloudHeight, o.woodOnly ? " (the classification calls it leaf)" : "");
  if (o.woodOnly)
    add(Verdict::Level::Uncertain, buf,
        "check the classes (treesketch classify, or the gui coloured by class) or model every point (without "
        "--wood-only)");
  else
    add(Verdict::Level::NotTrusted, buf,
        "look at the model's top (treesketch gui): points of another object above the tree, or a leader too sparse "
        "to model");
}

/// The verdict's reason for a model of every point of a tree in leaf, with its classified wood's volume.
std::string everyPointReason(const ModelMeasures& m, const MeasureOptions& o) {
  std::string reason =
      "modelled from every point of a tree in leaf: its tubes run through the foliage, so its volume is not the "
      "wood's";
  if (o.classifiedWoodVolume >= 0) {
    char buf[160];
    const double u = o.unitMetres, wood = o.classifiedWoodVolume * (u * u * u);  // as volumeRange multiplies
    std::snprintf(buf, sizeof buf, "; a model of the points classified as wood holds %.3g m³%s", wood,
                  wood <= m.volumeLow ? ", the range's lower end" : "");
    reason += buf;
  }
  return reason;
}

/// The verdict's reason for a model of the classified wood, with the volume of every point's model.
std::string woodOnlyReason(const ModelMeasures& m, const MeasureOptions& o) {
  std::string reason =
      "modelled from the points classified as wood only: twigs and limbs the classification calls leaf are "
      "missing, so the volume is a lower figure";
  if (o.everyPointVolume > 0) {
    char buf[160];
    const double u = o.unitMetres, every = o.everyPointVolume * (u * u * u);  // as volumeRange multiplies
    std::snprintf(buf, sizeof buf, "; a model of every point holds %.3g m³%s", every,
                  every >= m.volumeHigh ? ", the range's upper end" : "");
    reason += buf;
  }
  return reason;
}

/// The verdict's reason for a model on points drawn together (AutoSkeletonResult::contraction).
std::string drawnTogetherReason(const ModelMeasures& m) {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "the scan's noise (%.1f mm) blurs its thinner branches: the skeleton was grown on the points drawn "
                "together by %.1f mm",
                1000.0 * m.noiseMetres, 1000.0 * m.contractionMetres);
  return buf;
}

Verdict assess(const ModelMeasures& m, std::size_t points, const MeasureOptions& o) {
  Verdict v;
  auto add = [&](Verdict::Level level, std::string reason, std::string advice) {
    v.level = std::max(v.level, level);
    v.reasons.push_back(std::move(reason));
    if (!advice.empty() && std::find(v.advice.begin(), v.advice.end(), advice) == v.advice.end())
      v.advice.push_back(std::move(advice));
  };
  using L = Verdict::Level;
  const std::string leafOn =
      !o.leafOn ? "if the tree was in leaf, run with --leaf-on"
                : (o.woodOnly ? "" : "for the wood's volume, run with --wood-only (models the points classified as wood)");
  if (o.stemsLookedFor && o.stems.trees > 1)
    add(L::NotTrusted, severalTrees(o.stems),
        "cut the cloud into trees first: treesketch split CLOUD -o FOLDER, then treesketch batch FOLDER");
  if (m.hasFit && m.fit.insideDeeper2cm > kMaxInside)
    add(L::NotTrusted,
        percent(m.fit.insideDeeper2cm) + " of the points lie deeper than 2 cm inside the model: its tubes are "
                                         "thicker than the wood the scanner saw",
        leafOn);
  if (m.formFactor > kMaxFormFactor) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "the volume is %.1f× a cylinder of the stem's DBH and the tree's height (trees: about 0.5–2.5)",
                  m.formFactor);
    add(L::NotTrusted, buf, leafOn);
  }
  if (m.figures.volume > 0 && m.measuredVolumeShare < kMinMeasuredShare)
    add(L::Uncertain,
        "only " + percent(m.measuredVolumeShare) +
            " of the volume rests on circles fitted to the points; the rest follows the pipe model from the stem",
        "a denser or less noisy scan of the crown measures more of it");
  if (m.hasFit && m.fit.outsideFarther5cm > kMaxMissed && !o.woodOnly)
    add(L::Uncertain,
        percent(m.fit.outsideFarther5cm) +
            " of the points lie more than 5 cm outside the model (leaves, noise, other objects or branches it "
            "missed)",
        leafOn.empty() ? "remove ground, neighbours and outliers from the cloud" : leafOn);
  if (!o.leafOn && o.leafPieceShare > kMaxLeafPieceShare)
    add(L::Uncertain, percent(o.leafPieceShare) + " of the skeleton's pieces are flat, as leaves are", leafOn);
  if (o.leafOn && !o.woodOnly) add(L::Uncertain, everyPointReason(m, o), leafOn);
  if (o.woodOnly)
    add(L::Uncertain, woodOnlyReason(m, o), "");
  if (m.contractionMetres > 0)
    add(L::Uncertain, drawnTogetherReason(m), "a less noisy scan of the crown measures more of it");
  shortOfTheTop(m, o, add);
  const compare::CloudDbh& cloudDbh = m.metrics.cloudDbh;
  const double modelDbh = m.metrics.figures.trunkDiameter;
  if (m.metrics.hasCloud && cloudDbh.ok && modelDbh > 0 && cloudDbh.diameter > 0 &&
      std::abs(modelDbh - cloudDbh.diameter) > kMaxDbhDisagreement * cloudDbh.diameter) {
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "the model's stem is %.1f cm across at breast height and a circle through the points there %.1f cm "
                  "(%zu points): one of the two is off (the model's axis beside the bark, or a circle on a stem seen "
                  "from one side)",
                  100.0 * modelDbh, 100.0 * cloudDbh.diameter, cloudDbh.inliers);
    add(L::Uncertain, buf, "check the stem at breast height (treesketch gui) before using the DBH");
  }
  const double length = m.figures.length;
  if (length > 0 && static_cast<double>(points) / length < kMinPointsPerMetre) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.0f points per metre of branch: too few to measure branch radii",
                  static_cast<double>(points) / length);
    add(L::Uncertain, buf, "");
  }
  return v;
}

}  // namespace

const char* toString(Verdict::Level level) {
  switch (level) {
    case Verdict::Level::Trusted:
      return "trusted";
    case Verdict::Level::Uncertain:
      return "uncertain";
    case Verdict::Level::NotTrusted:
      return "not trusted";
  }
  return "?";
}

double measuredVolumeShare(const TreeModel& model) {
  double all = 0, measured = 0;
  for (std::size_t i = 0; i < model.cylinders.size(); ++i) {
    const double v = model.cylinders.cylinders[i].volume();
    all += v;
    if (i < model.measured.size() && model.measured[i]) measured += v;
  }
  return all > 0 ? measured / all : 0.0;
}

std::string ModelMeasures::summary() const {
  std::string line =
      hasFit ? compare::summaryLine(fit) + "; " + compare::summaryLine(figures) : compare::summaryLine(figures);
  if (std::isfinite(noiseMetres)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "; scan noise %.1f mm", 1000.0 * noiseMetres);
    line += buf;
  }
  if (contractionMetres > 0) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " (skeleton on the points drawn together by %.1f mm)", 1000.0 * contractionMetres);
    line += buf;
  }
  return line;
}

ModelMeasures measure(const TreeModel& model, const geom::PointCloud& cloud, const MeasureOptions& options) {
  ModelMeasures m;
  compare::TreeMetricsOptions mo;
  mo.unitMetres = options.unitMetres;
  m.metrics = compare::treeMetrics(model.cylinders, model.up, mo, &cloud);
  m.figures = compare::modelFigures(model.cylinders, model.up, options.unitMetres);
  m.measuredVolumeShare = measuredVolumeShare(model);
  if (options.fit) {
    compare::ModelFitOptions fo;
    fo.unitMetres = options.unitMetres;
    m.fit = compare::measureModelFit(cloud, model.cylinders, fo);
    m.hasFit = true;
  }
  const double u = options.unitMetres;
  volumeRange(model, u * u * u, std::isfinite(options.noise) ? options.noise : -1.0,
              options.woodOnly ? options.everyPointVolume : -1.0,
              options.leafOn && !options.woodOnly ? options.classifiedWoodVolume : -1.0, &m);
  const double dbh = m.metrics.figures.trunkDiameter, height = m.metrics.height;
  const double cylinder = std::numbers::pi / 4 * dbh * dbh * height;
  m.formFactor = cylinder > 0 ? m.figures.volume / cylinder : std::numeric_limits<double>::quiet_NaN();
  if (options.noise >= 0 && std::isfinite(options.noise)) m.noiseMetres = options.noise * u;
  if (options.contraction > 0 && std::isfinite(options.contraction)) m.contractionMetres = options.contraction * u;
  m.stemsLookedFor = options.stemsLookedFor;
  m.stems = options.stems;
  m.verdict = assess(m, cloud.size(), options);
  return m;
}

std::string ModelMeasures::verdictLine() const {
  char buf[400];
  std::snprintf(buf, sizeof buf, "volume %.4g m³ (range %.4g–%.4g, %.0f %% on fitted circles); verdict: %s",
                figures.volume, volumeLow, volumeHigh, 100.0 * measuredVolumeShare, toString(verdict.level));
  std::string line = buf;
  for (const std::string& r : verdict.reasons) line += "\n  - " + r;
  for (const std::string& a : verdict.advice) line += "\n  what to do: " + a;
  return line;
}

void checkOutputs(const OutputPaths& paths, const std::vector<std::string>& inputs) {
  const std::vector<const std::string*> outs = paths.all();
  for (const std::string* out : outs) {
    if (out->empty()) continue;
    for (const std::string& in : inputs)
      if (!in.empty()) checkNotAnInput(*out, {in});
    for (const std::string* other : outs)
      if (other != out && !other->empty() && *other == *out)
        throw OptionsError("the same path is given for two outputs: " + *out);
  }
  for (const std::string* out : outs)
    if (!out->empty()) checkOutputWritable(*out);
  if (!paths.mesh.empty()) {
    try {
      io::meshFormatFromPath(paths.mesh);
    } catch (const InputError& e) {
      throw OptionsError(std::string("mesh output: ") + e.what());
    }
  }
}

nlohmann::json strayPointsJson(const cloud::StrayPoints& s) {
  return {{"setAside", s.count()},
          {"far", s.far},
          {"isolated", s.isolated},
          {"ground", s.ground},
          {"markedNoise", s.markedNoise},
          {"repeated", s.repeated},
          {"spacing", s.spacing},
          {"linkDistance", s.linkDistance},
          {"tooSparse", s.tooSparse}};
}

nlohmann::json verdictJson(const Verdict& v) {
  return {{"level", toString(v.level)}, {"reasons", v.reasons}, {"advice", v.advice}};
}

nlohmann::json reportJson(const ModelMeasures& m, nlohmann::json header) {
  if (!m.hasFit) throw OptionsError("a report needs the model measured against its cloud");
  header["model"] = {{"fit", compare::toJson(m.fit)},
                     {"figures", compare::toJson(m.figures)},
                     {"measuredVolumeShare", m.measuredVolumeShare},
                     {"volumeRangeM3", {m.volumeLow, m.volumeHigh}},
                     {"formFactor", std::isfinite(m.formFactor) ? nlohmann::json(m.formFactor) : nlohmann::json()},
                     {"noiseM", std::isfinite(m.noiseMetres) ? nlohmann::json(m.noiseMetres) : nlohmann::json()},
                     {"contractionM", m.contractionMetres}};
  if (m.stemsLookedFor) {
    nlohmann::json stems = nlohmann::json::array();
    for (const cloud::Stem& s : m.stems.stems)
      stems.push_back({{"centre", {s.centre.x(), s.centre.y(), s.centre.z()}},
                       {"dbhM", s.diameter},
                       {"circleRmsM", s.rms},
                       {"pointsOnCircle", s.points},
                       {"tree", s.tree}});
    header["stemsAtBreastHeight"] = {{"trees", m.stems.trees}, {"stems", stems}};
  }
  header["verdict"] = verdictJson(m.verdict);
  header["metrics"] = compare::toJson(m.metrics);
  return header;
}

void writeOutputs(const TreeModel& model, const ModelMeasures& measures, const OutputPaths& paths,
                  const nlohmann::json& reportHeader) {
  if (!paths.cylinders.empty()) io::writeCylinderCsv(paths.cylinders, model.cylinders, model.ids, model.measured);
  if (!paths.qsm.empty()) io::writeTreeQsmCylinders(paths.qsm, model.cylinders, model.up);
  if (!paths.mesh.empty()) io::writeMesh(paths.mesh, model.mesh);
  if (!paths.metrics.empty()) writeJson(paths.metrics, compare::toJson(measures.metrics));
  if (!paths.report.empty()) writeJson(paths.report, reportJson(measures, reportHeader));
}

}  // namespace treesketch::model
