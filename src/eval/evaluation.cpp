#include "treesketch/eval/evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "eval_methods.h"
#include "treesketch/classify/classify.h"
#include "treesketch/eval/mesh_distance.h"
#include "treesketch/io/view_camera.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/scan/tls_scan.h"
#include "treesketch/skeleton/option_table.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/sketch/auto_sketch.h"
#include "treesketch/sketch/polyline_sketch.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::eval {

namespace fs = std::filesystem;

namespace {

const geom::Viewport kViewport{0, 0, 1280, 800};

}  // namespace

namespace detail {

MethodOutput reconstructSketch(const sketch::Sketch& sk, const geom::PointCloud& cloud,
                               const recon::ReconstructionOptions& options, const Stopwatch& timer,
                               NodeResults* results) {
  recon::ReconstructionResult r = recon::reconstruct(cloud, sk, options);
  MethodOutput out;
  out.mesh = std::move(r.mesh);
  out.sketch = sk;
  out.nodes = static_cast<int>(sk.size());
  for (const auto& [id, res] : r.results)
    if (res.status == fit::NodeStatus::Fitted) ++out.fitted;
  if (sketch::NodeId root = sk.root(); root != sketch::kNoNode) {
    auto it = r.results.find(root);
    if (it != r.results.end() && it->second.status == fit::NodeStatus::Fitted)
      out.root = it->second.centre;
    else if (!sk.node(root).isScreenNode())
      out.root = sk.node(root).point;
  }
  out.ms = timer.ms();
  if (results) *results = std::move(r.results);
  return out;
}

geom::PointCloud pointsWhere(const geom::PointCloud& cloud, const std::vector<std::uint8_t>& flags) {
  geom::PointCloud out;
  out.up = cloud.up;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (flags[i]) out.positions.push_back(cloud.positions[i]);
  return out;
}

geom::Camera viewCamera(const MethodInput& in) {
  return io::cameraForView(in.options.view, in.cloud.bounds(), in.tree.up, kViewport, false);
}

}  // namespace detail

namespace {

// The thesis's fit, as the uniform baseline and the ideal user's point nodes keep it.
recon::ReconstructionOptions thesisOptions(std::uint64_t seed) {
  recon::ReconstructionOptions ro;
  ro.seed = seed;
  return ro;
}

using detail::reconstructSketch;
using detail::viewCamera;

MethodOutput methodUniform(const MethodInput& in) {
  const Stopwatch timer;
  sketch::Sketch sk = sketch::uniformAutoSketch(in.cloud, viewCamera(in), in.nodeCount, in.tree.up);
  return reconstructSketch(sk, in.cloud, thesisOptions(in.options.seed), timer);
}

/// The points of `cloud` the wood/leaf classification calls wood (empty when it finds none).
geom::PointCloud classifiedWood(const geom::PointCloud& cloud, geom::UpAxis up) {
  return detail::pointsWhere(cloud, classify::classifyWood(cloud, up, classify::woodModellingOptions()).wood);
}

// The careful user's nodes (the branches it draws, detail::carefulUserPlan) as point nodes on the
// true axes, fitted on every point with the thesis's fit.
MethodOutput methodIdeal(const MethodInput& in) {
  const Stopwatch timer;
  std::vector<sketch::BranchPolyline> axes;
  geom::PointCloud storage;
  const geom::PointCloud& seen = detail::pointsKept(in.cloud, detail::carefulUserPoints(in), storage);
  const int minPoints = carefulUserFitOptions(in.options, in.tree.metresPerUnit).fit.circle.minInliers;
  auto po = detail::carefulUserPlan(in, seen, minPoints, axes);
  sketch::Sketch sk = sketch::pointNodesFromPolylines(axes, po);
  return reconstructSketch(sk, in.cloud, thesisOptions(in.options.seed), timer);
}

MethodOutput methodSkeleton(const MethodInput& in) {
  const Stopwatch timer;
  const skeleton::AutoSkeletonOptions so = automaticModelOptions(in.leafOn, in.tree.up, in.options);
  skeleton::AutoSkeletonResult r = skeleton::autoSkeletonSketch(in.cloud, so);
  MethodOutput out;
  out.model = model::fromAutoSkeleton(r, in.tree.up);
  out.measure = model::autoMeasureOptions(r, so, in.leafOn);
  out.setAside = std::move(r.strays);
  out.mesh = std::move(r.mesh);
  out.sketch = std::move(r.sketch);
  out.nodes = static_cast<int>(out.sketch.size());
  for (char a : r.fitAccepted) out.fitted += a != 0;
  if (sketch::NodeId root = out.sketch.root(); root != sketch::kNoNode) {
    const sketch::Node& node = out.sketch.node(root);
    out.root = node.kept ? node.kept->centre : node.point;  // point nodes: the model's own position
  }
  out.ms = timer.ms();
  if (in.leafOn)  // the range's lower end, as --leaf-on makes it (not timed: the model's time is its own)
    out.measure->classifiedWoodVolume =
        model::classifiedWoodVolume(in.cloud, automaticModelOptions(false, in.tree.up, in.options), in.tree.up);
  return out;
}

// The automatic skeleton on the points the wood/leaf classification calls wood (leaf-off settings:
// what is left is meant to be wood); on a leaf-off scan the same as "skeleton".
MethodOutput methodSkeletonWood(const MethodInput& in) {
  if (!in.leafOn) return methodSkeleton(in);
  const Stopwatch timer;
  const geom::PointCloud wood = classifiedWood(in.cloud, in.tree.up);
  if (wood.size() < detail::kMinWoodPoints) return methodSkeleton(in);  // nothing to model as wood: as before
  MethodInput woodInput{in.tree, wood, in.options, in.nodeCount, false};
  MethodOutput out = methodSkeleton(woodInput);
  out.setAside = {};  // indices into the wood, not the scan: measured against every point, as the CLI does
  out.ms = timer.ms();
  if (!out.measure) return out;
  out.measure->woodOnly = true;  // and the range's upper end, as --wood-only makes it (not timed)
  out.measure->everyPointVolume =
      model::everyPointVolume(in.cloud, automaticModelOptions(true, in.tree.up, in.options), in.tree.up);
  return out;
}

const std::map<std::string, Method>& registry() {
  static const std::map<std::string, Method> methods = [] {
    std::map<std::string, Method> m;
    m["uniform"] = methodUniform;
    m["user"] = detail::methodUser;
    m["ideal"] = methodIdeal;
    m["skeleton"] = methodSkeleton;
    m["skeleton-wood"] = methodSkeletonWood;
    return m;
  }();
  return methods;
}

}  // namespace

skeleton::AutoSkeletonOptions automaticModelOptions(bool leafOn, geom::UpAxis up, const EvalOptions& options) {
  skeleton::AutoSkeletonOptions so =
      skeleton::autoSkeletonPreset(leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, up);
  so.seed = options.seed;
  for (const std::string& s : options.skeletonSettings) skeleton::applySetting(so, s);
  return so;
}

skeleton::AutoSkeletonResult automaticModel(const geom::PointCloud& cloud, bool leafOn, bool woodOnly, geom::UpAxis up,
                                            const EvalOptions& options, bool* onWood) {
  if (onWood) *onWood = false;
  if (leafOn && woodOnly && !cloud.empty()) {
    const geom::PointCloud wood = classifiedWood(cloud, up);
    if (wood.size() >= detail::kMinWoodPoints) {  // else no tree's wood: every point, as "skeleton-wood"
      if (onWood) *onWood = true;
      return skeleton::autoSkeletonSketch(wood, automaticModelOptions(false, up, options));
    }
  }
  return skeleton::autoSkeletonSketch(cloud, automaticModelOptions(leafOn, up, options));
}

std::vector<std::string> defaultMethodNames() {
  std::vector<std::string> names;
  for (const auto& name : methodNames())
    if (name != "skeleton-wood") names.push_back(name);
  return names;
}

std::vector<std::string> methodNames() {
  std::vector<std::string> names;
  for (const auto& [name, m] : registry()) names.push_back(name);
  return names;
}

MethodOutput runMethod(const std::string& name, const MethodInput& input) {
  auto it = registry().find(name);
  if (it == registry().end()) {
    std::string known;
    for (const auto& n : methodNames()) known += (known.empty() ? "" : ", ") + n;
    throw OptionsError("unknown evaluation method '" + name + "' (known: " + known + ")");
  }
  return it->second(input);
}

std::vector<ScanCondition> evaluationConditions(const EvalOptions& o) {
  std::vector<ScanCondition> out = o.conditions;
  if (out.empty()) {
    for (const auto& pattern : o.patterns) {
      if (pattern == "sphere") {
        ScanCondition c = referenceCondition();
        c.targetPoints = o.sphereTargetPoints;
        c.sphereRays = o.sphereRays;
        c.sphereJitterDeg = o.sphereJitterDeg;
        out.push_back(c);
      } else if (pattern == "tls") {
        // The former TLS setting: no physical scale, so height and noise follow the tree's size.
        ScanCondition c;
        c.name = "reference-tls";
        c.factor = "reference";
        c.pattern = "tls";
        c.stations = o.tlsStations;
        c.stepDeg = o.tlsStepDeg;
        c.targetPoints = o.tlsTargetPoints;
        c.stationHeightDiagonal = 0.02;
        c.rangeNoiseDiagonal = 0.0005;
        c.sweep = true;
        out.push_back(c);
      } else {
        throw OptionsError("unknown scan pattern '" + pattern + "' (known: sphere, tls)");
      }
    }
  }
  std::set<std::string> names;
  for (const auto& c : out) {
    if (c.pattern != "sphere" && c.pattern != "tls")
      throw OptionsError("condition '" + c.name + "': unknown scan pattern '" + c.pattern + "' (known: sphere, tls)");
    if (!names.insert(c.name).second) throw OptionsError("condition name '" + c.name + "' given twice");
  }
  return out;
}

namespace {

/// Half-angle of the sphere pattern's cone that covers the model's bounding box from the origins.
double wideConeDeg(double radiusFactor) { return std::atan(0.5 / radiusFactor) * 180.0 / M_PI; }

}  // namespace

TreeScan scanTree(const TreeCase& tree, const ScanCondition& c, bool leafOn, std::uint64_t seed) {
  std::vector<geom::TriMesh> meshes{tree.branches};
  if (leafOn && !tree.leaves.empty()) meshes.push_back(tree.leaves);
  const double diag = tree.branches.bounds().diagonal();
  // The terrain a clip of the tree out of a plot's scan keeps: under its crown and a little past it.
  if (c.terrainSlopeDeg >= 0) {
    const geom::Vec3 extent = tree.branches.bounds().extent();
    const double crown =
        tree.up == geom::UpAxis::Y ? std::max(extent.x(), extent.z()) : std::max(extent.x(), extent.y());
    meshes.push_back(terrainUnder(tree.branches.bounds(), tree.up, tree.metresPerUnit, 0.6 * crown, c.terrainSlopeDeg));
  }
  const double noise =
      c.rangeNoiseDiagonal > 0 ? c.rangeNoiseDiagonal * diag : mmToUnits(c.rangeNoiseMm, tree.metresPerUnit);
  TreeScan out;
  if (c.pattern == "sphere") {
    scan::SphereScanOptions s;
    s.rays = c.sphereRays;
    s.seed = seed;
    if (c.sphereSubdivisions > 0) {
      s.subdivisions = c.sphereSubdivisions;
      s.rays = 0;
    }
    const double jitter = c.sphereJitterDeg > 0 ? c.sphereJitterDeg : wideConeDeg(s.radiusFactor);
    const std::uint64_t target = c.targetWoodPoints > 0 ? c.targetWoodPoints : c.targetPoints;
    if (target > 0) {
      // Scale the ray count from a pilot scan's hit rate (on the wood, for a wood target).
      scan::SphereScanOptions pilot = s;
      pilot.rays = 100000;
      pilot.subdivisions = 6;
      pilot.seed = seed + 7919;
      pilot.jitterDeg = jitter;
      scan::ScanResult p = scan::sphereScan(meshes, pilot);
      double hits = c.targetWoodPoints > 0
                        ? static_cast<double>(p.stats.hitsPerMesh.empty() ? 0 : p.stats.hitsPerMesh[0])
                        : static_cast<double>(p.cloud.size());
      double hitRate = std::max(hits, 1.0) / static_cast<double>(scan::sphereRayCount(pilot));
      s.rays = static_cast<std::uint64_t>(std::min(static_cast<double>(target) / hitRate, 5e7));
    }
    s.jitterDeg = jitter;
    s.rangeNoise = noise;
    s.recordMesh = true;
    out.rays = scan::sphereRayCount(s);
    out.cloud = scan::sphereScan(meshes, s).cloud;
    return out;
  }
  if (c.pattern == "tls") {
    scan::TlsScanOptions t;
    t.stationCount = c.stations;
    t.up = tree.up;
    t.seed = seed;
    t.stationHeight = c.stationHeightDiagonal > 0 ? c.stationHeightDiagonal * diag
                                                  : metresToUnits(c.stationHeightM, tree.metresPerUnit);
    t.rangeNoise = noise;
    double step = c.stepDeg;
    if (step <= 0) {
      // Pilot scan at a coarse step; hits scale as 1/step^2.
      if (c.targetPoints == 0) throw OptionsError("condition '" + c.name + "': TLS needs a step or a point target");
      scan::TlsScanOptions pilot = t;
      pilot.stepDeg = 1.0;
      std::uint64_t hits = std::max<std::uint64_t>(scan::tlsScan(meshes, pilot).cloud.size(), 1);
      step = pilot.stepDeg * std::sqrt(static_cast<double>(hits) / static_cast<double>(c.targetPoints));
      step = std::clamp(step, 0.005, 1.0);
    }
    t.stepDeg = step;
    t.recordMesh = true;
    // On terrain, the stations stand where they would round the tree alone (the terrain's wider
    // box would move them out and down).
    if (c.terrainSlopeDeg >= 0) t.stations = scan::tlsStationPositions(t, tree.branches.bounds());
    out.stepDeg = step;
    out.rays = scan::tlsRayCount(t);
    out.cloud = scan::tlsScan(meshes, t).cloud;
    return out;
  }
  throw OptionsError("unknown scan pattern '" + c.pattern + "' (known: sphere, tls)");
}

geom::Vec3 trunkBase(const TreeCase& tree) {
  for (const auto& a : tree.axes)
    if (a.parent < 0 && !a.points.empty()) return a.points.front();
  throw OptionsError("tree '" + tree.name + "' has no root axis (no trunk base to check the root against)");
}

namespace {

// One tree scanned under one condition and leaf state: what every method's row shares.
struct EvalCase {
  const TreeCase& tree;
  const ScanCondition& c;
  const TreeScan& scan;
  bool leafOn;
  std::size_t wood;  // points on the wood (mesh id 0)
  std::string half;
  double diag;
  geom::Vec3 base;
};

// The row's description of the case: tree, condition, scan.
EvalRow caseRow(const EvalCase& k, const std::string& method, bool sweep) {
  const ScanCondition& c = k.c;
  const geom::PointCloud& cloud = k.scan.cloud;
  EvalRow row;
  row.tree = k.tree.name;
  row.half = k.half;
  row.condition = c.name;
  row.factor = c.factor;
  row.leaf = k.leafOn ? "leaf-on" : "leaf-off";
  row.pattern = c.pattern;
  row.method = method;
  row.sweep = sweep;
  row.points = cloud.size();
  row.woodPoints = k.wood;
  row.woodFraction = cloud.size() ? static_cast<double>(k.wood) / cloud.size() : 0.0;
  row.rays = k.scan.rays;
  row.stations = c.pattern == "tls" ? c.stations : 0;
  row.stepDeg = k.scan.stepDeg;
  row.metresPerUnit = k.tree.metresPerUnit;
  row.rangeNoiseMm =
      c.rangeNoiseDiagonal > 0 ? c.rangeNoiseDiagonal * k.diag * k.tree.metresPerUnit * 1e3 : c.rangeNoiseMm;
  row.sparse = k.wood < kSparseWoodPoints;
  row.backwardOnly = c.backwardOnly();
  row.bboxDiagonal = k.diag;
  return row;
}

// The model's volume against the tree's (a method with no cylinder model leaves them NaN).
// With measure options, also its range and verdict as `reconstruct --report` gives them, measured
// against the scan at the tree's scale (so the verdict's figures in metres mean what they say).
void setVolumes(EvalRow& row, const TreeCase& tree, const MethodOutput& out, const geom::PointCloud& cloud) {
  const model::TreeModel& m = out.model;
  row.trueVolume = tree.woodVolume;
  if (m.empty()) return;
  double volume = 0;
  for (const auto& c : m.cylinders.cylinders) volume += c.volume();
  row.modelVolume = volume;
  row.measuredVolumeShare = model::measuredVolumeShare(m);
  if (row.trueVolume > 0) row.volumeError = row.modelVolume / row.trueVolume - 1.0;
  if (!out.measure || !(tree.metresPerUnit > 0)) return;
  model::MeasureOptions mo = *out.measure;
  mo.unitMetres = tree.metresPerUnit;
  model::lookForStems(mo, cloud, m.up, out.setAside);
  const model::ModelMeasures measures =
      model::measure(m, out.setAside.empty() ? cloud : cloud::keptPoints(cloud, out.setAside), mo);
  const double cubic = tree.metresPerUnit * tree.metresPerUnit * tree.metresPerUnit;
  row.volumeLow = measures.volumeLow / cubic;
  row.volumeHigh = measures.volumeHigh / cubic;
  row.verdict = model::toString(measures.verdict.level);
}

// "  volume +3.2 % (81 % measured)" for the log, or nothing without a volume error.
std::string volumeText(const EvalRow& row) {
  if (!std::isfinite(row.volumeError)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "  volume %+6.1f %% (%.0f %% measured)", 100.0 * row.volumeError,
                100.0 * row.measuredVolumeShare);
  return buf;
}

// Runs one method on the case and measures its model against the reference.
EvalRow evaluateMethod(const EvalCase& k, const EvalOptions& o, const std::string& method, int nodes, bool sweep) {
  const TreeCase& tree = k.tree;
  const double diag = k.diag;
  EvalRow row = caseRow(k, method, sweep);
  MethodOutput out = runMethod(method, MethodInput{tree, k.scan.cloud, o, nodes, k.leafOn});
  row.nodes = out.nodes;
  row.fitted = out.fitted;
  for (const auto& [id, node] : out.sketch.nodes()) row.tips += node.children.empty();
  row.referenceLimbs = static_cast<int>(tree.axes.size());
  row.reconstructMs = out.ms;
  row.meshTriangles = out.mesh.triangles.size();
  auto pct = [&](double v) { return diag > 0 ? 100.0 * v / diag : NAN; };
  row.rootOffsetPct = out.root ? pct((*out.root - k.base).norm()) : NAN;
  row.rootAtBase = std::isfinite(row.rootOffsetPct) && row.rootOffsetPct <= kRootAtBasePct;
  DistanceOptions dopt;
  dopt.minSamples = o.minSamples;
  dopt.samples = o.samples;
  dopt.seed = o.seed;
  DirectionStats fwd = oneWayDistance(tree.branches, out.mesh, dopt);
  DirectionStats bwd = oneWayDistance(out.mesh, tree.branches, dopt);
  row.samples = fwd.samples;
  row.forwardMax = pct(fwd.max);
  row.forwardMean = pct(fwd.mean);
  row.forwardRms = pct(fwd.rms);
  row.backwardMax = pct(bwd.max);
  row.backwardMean = pct(bwd.mean);
  row.backwardRms = pct(bwd.rms);
  setVolumes(row, tree, out, k.scan.cloud);
  if (out.causes) detail::setCauses(row, *out.causes);
  if (o.log) {
    char buf[360];
    std::snprintf(buf, sizeof buf,
                  "%s %s %s %-8s nodes %3d/%3d  back RMS %6.3f %%  fwd RMS %6.3f %%  root %6.2f %%  %7.0f ms%s",
                  tree.name.c_str(), k.c.name.c_str(), row.leaf.c_str(), method.c_str(), row.fitted, row.nodes,
                  row.backwardRms, row.forwardRms, row.rootOffsetPct, row.reconstructMs, volumeText(row).c_str());
    o.log(buf);
    if (out.causes) o.log("  " + out.causes->text());
  }
  return row;
}

}  // namespace

std::vector<EvalRow> runEvaluation(const std::vector<TreeCase>& trees, const EvalOptions& o) {
  for (const auto& m : o.methods)
    if (!registry().count(m)) runMethod(m, MethodInput{TreeCase{}, geom::PointCloud{}, o, 0});  // throws
  const std::vector<ScanCondition> conditions = evaluationConditions(o);
  std::vector<EvalRow> rows;
  for (const auto& tree : trees) {
    const double diag = tree.branches.bounds().diagonal();
    const geom::Vec3 base = trunkBase(tree);
    const std::string half = halfName(treeHalf(tree.name));
    for (const auto& c : conditions) {
      for (int cond = 0; cond < 2; ++cond) {
        bool leafOn = cond == 0;
        if ((leafOn && !(o.leafOn && c.leafOn)) || (!leafOn && !(o.leafOff && c.leafOff))) continue;
        TreeScan scan = scanTree(tree, c, leafOn, o.seed);
        std::size_t wood = 0;
        for (auto id : scan.cloud.meshId) wood += id == 0;
        const EvalCase k{tree, c, scan, leafOn, wood, half, diag, base};
        for (const auto& method : o.methods) {
          int nodes = method == "uniform" ? o.uniformNodes : o.userNodes;
          rows.push_back(evaluateMethod(k, o, method, nodes, false));
        }
        // The sweep runs once per tree and condition: leaf-on, or leaf-off when leaf-on is not run.
        if (c.sweep && (leafOn || !(o.leafOn && c.leafOn))) {
          for (int n : o.nodeSweep) rows.push_back(evaluateMethod(k, o, "user", n, true));
        }
      }
    }
  }
  return rows;
}

// -- summaries -------------------------------------------------------------------------------------

namespace {

// Running sums of one summary's judged cases.
struct SummarySums {
  double backward = 0, forward = 0, volumeAbs = 0, measuredShare = 0;
};

// One judged case (not sparse, with a mesh) into its summary.
void addJudgedRow(ConditionSummary& s, const EvalRow& r, SummarySums& sums) {
  ++s.judged;
  sums.backward += r.backwardRms;
  sums.forward += r.forwardRms;
  if (!(r.backwardRms <= s.backwardWorst)) {  // also replaces the initial NaN
    s.backwardWorst = r.backwardRms;
    s.backwardWorstTree = r.tree;
  }
  if (!(r.forwardRms <= s.forwardWorst)) {
    s.forwardWorst = r.forwardRms;
    s.forwardWorstTree = r.tree;
  }
  if (r.referenceLimbs > 0) {
    double ratio = static_cast<double>(r.tips) / r.referenceLimbs;
    s.tipsRatioMin = std::isfinite(s.tipsRatioMin) ? std::min(s.tipsRatioMin, ratio) : ratio;
    s.tipsRatioMax = std::isfinite(s.tipsRatioMax) ? std::max(s.tipsRatioMax, ratio) : ratio;
    s.tipsRatioInBand += ratio >= kTipsRatioMin && ratio <= kTipsRatioMax;
  }
  s.rootAtBase += r.rootAtBase;
  double offset = std::isfinite(r.rootOffsetPct) ? r.rootOffsetPct : INFINITY;
  s.rootOffsetWorst = std::isnan(s.rootOffsetWorst) ? offset : std::max(s.rootOffsetWorst, offset);
  if (std::isfinite(r.volumeError)) {
    ++s.volumeJudged;
    sums.volumeAbs += std::abs(r.volumeError);
    sums.measuredShare += r.measuredVolumeShare;
    if (!(std::abs(r.volumeError) <= std::abs(s.volumeErrorWorst))) {
      s.volumeErrorWorst = r.volumeError;
      s.volumeWorstTree = r.tree;
    }
    if (std::isfinite(r.volumeLow) && std::isfinite(r.volumeHigh)) {
      ++s.volumeRanged;
      s.volumeRangeHolds += r.volumeLow <= r.trueVolume && r.trueVolume <= r.volumeHigh;
    }
    if (r.verdict == "trusted") {
      ++s.verdictTrusted;
      if (!(std::abs(r.volumeError) <= std::abs(s.volumeErrorWorstTrusted))) {
        s.volumeErrorWorstTrusted = r.volumeError;
        s.volumeWorstTrustedTree = r.tree;
      }
    }
  }
}

// The means, once every case is in.
void finishSummary(ConditionSummary& s, const SummarySums& sums) {
  if (s.judged > 0) {
    s.backwardMean = sums.backward / s.judged;
    s.forwardMean = sums.forward / s.judged;
  }
  if (s.volumeJudged > 0) {
    s.volumeErrorMeanAbs = sums.volumeAbs / s.volumeJudged;
    s.measuredVolumeShareMean = sums.measuredShare / s.volumeJudged;
  }
}

}  // namespace

std::vector<ConditionSummary> summarize(const std::vector<EvalRow>& rows) {
  // Groups (condition, leaf, method) in first-seen order.
  std::vector<std::tuple<std::string, std::string, std::string>> keys;
  for (const auto& r : rows) {
    if (r.sweep) continue;
    auto k = std::make_tuple(r.condition, r.leaf, r.method);
    if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
  }
  std::vector<ConditionSummary> out;
  for (const auto& [condition, leaf, method] : keys) {
    std::vector<std::string> halves;
    for (const char* h : {"tune", "held-out"})
      for (const auto& r : rows)
        if (!r.sweep && r.condition == condition && r.leaf == leaf && r.method == method && r.half == h) {
          halves.push_back(h);
          break;
        }
    halves.push_back("all");
    for (const auto& half : halves) {
      ConditionSummary s;
      s.condition = condition;
      s.leaf = leaf;
      s.method = method;
      s.half = half;
      SummarySums sums;
      for (const auto& r : rows) {
        if (r.sweep || r.condition != condition || r.leaf != leaf || r.method != method) continue;
        if (half != "all" && r.half != half) continue;
        s.factor = r.factor;
        if (r.backwardOnly) s.forwardJudged = false;
        s.woodPointsMin = s.cases == 0 ? r.woodPoints : std::min(s.woodPointsMin, r.woodPoints);
        s.woodPointsMax = std::max(s.woodPointsMax, r.woodPoints);
        ++s.cases;
        if (r.sparse)
          ++s.sparse;
        else if (!std::isfinite(r.backwardRms) || !std::isfinite(r.forwardRms))
          ++s.noMesh;
        else
          addJudgedRow(s, r, sums);
      }
      finishSummary(s, sums);
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace treesketch::eval
