#include "treesketch/eval/evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>

#include "treesketch/eval/mesh_distance.h"
#include "treesketch/eval/svg_plot.h"
#include "treesketch/io/view_camera.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/scan/tls_scan.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/sketch/auto_sketch.h"
#include "treesketch/sketch/polyline_sketch.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::eval {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

const geom::Viewport kViewport{0, 0, 1280, 800};

double polylineLength(const sketch::BranchPolyline& b) {
  double l = 0;
  for (std::size_t i = 1; i < b.points.size(); ++i) l += (b.points[i] - b.points[i - 1]).norm();
  return l;
}

/// A careful user with a budget of about `nodeCount` nodes draws the trunk and the branches long
/// enough to deserve a node at the chosen spacing s: a branch (whose parent is drawn) is drawn when
/// its length is at least s, with max(1, round(length / s)) nodes (as sketchFromPolylines places
/// them). s is found by bisection so that the node count is as close to the budget as possible.
std::vector<bool> branchesAtSpacing(const std::vector<sketch::BranchPolyline>& axes, double s, int* nodes) {
  std::vector<bool> keep(axes.size(), false);
  int count = 0;
  for (std::size_t i = 0; i < axes.size(); ++i) {  // parents come before children in both sources
    bool isRoot = axes[i].parent < 0;
    double len = polylineLength(axes[i]);
    bool parentKept = isRoot || (axes[i].parent < static_cast<int>(i) && keep[axes[i].parent]);
    keep[i] = isRoot || (parentKept && len >= s);
    if (keep[i]) count += std::max(1, static_cast<int>(std::lround(len / s))) + (isRoot ? 1 : 0);
  }
  *nodes = count;
  return keep;
}

std::vector<sketch::BranchPolyline> branchesForBudget(const std::vector<sketch::BranchPolyline>& axes, int nodeCount,
                                                      double* spacingOut) {
  double total = 0;
  for (const auto& a : axes) total += polylineLength(a);
  double lo = total * 1e-4, hi = total;  // count(lo) >= budget >= count(hi), mostly
  int n = 0;
  for (int iter = 0; iter < 60; ++iter) {
    double mid = std::sqrt(lo * hi);
    branchesAtSpacing(axes, mid, &n);
    if (n > nodeCount)
      lo = mid;
    else
      hi = mid;
  }
  int nLo = 0, nHi = 0;
  auto keepLo = branchesAtSpacing(axes, lo, &nLo);
  auto keepHi = branchesAtSpacing(axes, hi, &nHi);
  bool useLo = std::abs(nLo - nodeCount) < std::abs(nHi - nodeCount);
  const std::vector<bool>& keep = useLo ? keepLo : keepHi;
  std::vector<int> newIndex(axes.size(), -1);
  std::vector<sketch::BranchPolyline> out;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (!keep[i]) continue;
    newIndex[i] = static_cast<int>(out.size());
    out.push_back(axes[i]);
  }
  for (auto& b : out)
    if (b.parent >= 0) b.parent = newIndex[b.parent];
  if (spacingOut) *spacingOut = useLo ? lo : hi;
  return out;
}

/// chooseDepth: a person's screen nodes choose their depth along the view ray; the
/// thesis's uniform baseline keeps the thesis's fit.
MethodOutput reconstructSketch(const sketch::Sketch& sk, const geom::PointCloud& cloud, std::uint64_t seed,
                               Clock::time_point t0, bool chooseDepth = false) {
  recon::ReconstructionOptions ro;
  ro.seed = seed;
  ro.fit.chooseDepth = chooseDepth;
  recon::ReconstructionResult r = recon::reconstruct(cloud, sk, ro);
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
  out.ms = msSince(t0);
  return out;
}

geom::Camera viewCamera(const MethodInput& in) {
  return io::cameraForView(in.options.view, in.cloud.bounds(), in.tree.up, kViewport, false);
}

MethodOutput methodUniform(const MethodInput& in) {
  auto t0 = Clock::now();
  sketch::Sketch sk = sketch::uniformAutoSketch(in.cloud, viewCamera(in), in.nodeCount, in.tree.up);
  return reconstructSketch(sk, in.cloud, in.options.seed, t0);
}

sketch::PolylineSketchOptions userOptions(const MethodInput& in, std::vector<sketch::BranchPolyline>& axes) {
  sketch::PolylineSketchOptions po;
  double spacing = 0;
  axes = branchesForBudget(in.tree.axes, in.nodeCount, &spacing);
  po.nodeSpacing = spacing;
  po.pixelNoise = in.options.pixelNoise;
  po.seed = in.options.seed;
  po.params = sketch::defaultSamplingFor(in.cloud.bounds());
  po.up = in.tree.up;
  return po;
}

MethodOutput methodUser(const MethodInput& in) {
  auto t0 = Clock::now();
  std::vector<sketch::BranchPolyline> axes;
  auto po = userOptions(in, axes);
  sketch::Sketch sk = sketch::sketchFromPolylines(axes, viewCamera(in), po);
  return reconstructSketch(sk, in.cloud, in.options.seed, t0, in.options.chooseDepth);
}

MethodOutput methodIdeal(const MethodInput& in) {
  auto t0 = Clock::now();
  std::vector<sketch::BranchPolyline> axes;
  auto po = userOptions(in, axes);
  sketch::Sketch sk = sketch::pointNodesFromPolylines(axes, po);
  return reconstructSketch(sk, in.cloud, in.options.seed, t0);
}

MethodOutput methodSkeleton(const MethodInput& in) {
  auto t0 = Clock::now();
  skeleton::AutoSkeletonOptions so =
      skeleton::autoSkeletonPreset(in.leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, in.tree.up);
  so.seed = in.options.seed;
  skeleton::AutoSkeletonResult r = skeleton::autoSkeletonSketch(in.cloud, so);
  MethodOutput out;
  out.model = model::fromAutoSkeleton(r, in.tree.up);
  out.mesh = std::move(r.mesh);
  out.sketch = std::move(r.sketch);
  out.nodes = static_cast<int>(out.sketch.size());
  for (char a : r.fitAccepted) out.fitted += a != 0;
  if (sketch::NodeId root = out.sketch.root(); root != sketch::kNoNode) {
    const sketch::Node& node = out.sketch.node(root);
    out.root = node.kept ? node.kept->centre : node.point;  // point nodes: the model's own position
  }
  out.ms = msSince(t0);
  return out;
}

const std::map<std::string, Method>& registry() {
  static const std::map<std::string, Method> methods = [] {
    std::map<std::string, Method> m;
    m["uniform"] = methodUniform;
    m["user"] = methodUser;
    m["ideal"] = methodIdeal;
    m["skeleton"] = methodSkeleton;
    return m;
  }();
  return methods;
}

}  // namespace

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
        const geom::PointCloud& cloud = scan.cloud;
        std::size_t wood = 0;
        for (auto id : cloud.meshId) wood += id == 0;
        auto runOne = [&](const std::string& method, int nodes, bool sweep) {
          EvalRow row;
          row.tree = tree.name;
          row.half = half;
          row.condition = c.name;
          row.factor = c.factor;
          row.leaf = leafOn ? "leaf-on" : "leaf-off";
          row.pattern = c.pattern;
          row.method = method;
          row.sweep = sweep;
          row.points = cloud.size();
          row.woodPoints = wood;
          row.woodFraction = cloud.size() ? static_cast<double>(wood) / cloud.size() : 0.0;
          row.rays = scan.rays;
          row.stations = c.pattern == "tls" ? c.stations : 0;
          row.stepDeg = scan.stepDeg;
          row.metresPerUnit = tree.metresPerUnit;
          row.rangeNoiseMm =
              c.rangeNoiseDiagonal > 0 ? c.rangeNoiseDiagonal * diag * tree.metresPerUnit * 1e3 : c.rangeNoiseMm;
          row.sparse = wood < kSparseWoodPoints;
          row.backwardOnly = c.backwardOnly();
          row.bboxDiagonal = diag;
          MethodOutput out = runMethod(method, MethodInput{tree, cloud, o, nodes, leafOn});
          row.nodes = out.nodes;
          row.fitted = out.fitted;
          for (const auto& [id, node] : out.sketch.nodes()) row.tips += node.children.empty();
          row.referenceLimbs = static_cast<int>(tree.axes.size());
          row.reconstructMs = out.ms;
          row.meshTriangles = out.mesh.triangles.size();
          auto pct = [&](double v) { return diag > 0 ? 100.0 * v / diag : NAN; };
          row.rootOffsetPct = out.root ? pct((*out.root - base).norm()) : NAN;
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
          if (o.log) {
            char buf[320];
            std::snprintf(buf, sizeof buf,
                          "%s %s %s %-8s nodes %3d/%3d  back RMS %6.3f %%  fwd RMS %6.3f %%  root %6.2f %%  %7.0f ms",
                          tree.name.c_str(), c.name.c_str(), row.leaf.c_str(), method.c_str(), row.fitted, row.nodes,
                          row.backwardRms, row.forwardRms, row.rootOffsetPct, row.reconstructMs);
            o.log(buf);
          }
          rows.push_back(row);
        };
        for (const auto& method : o.methods) {
          int nodes = method == "uniform" ? o.uniformNodes : o.userNodes;
          runOne(method, nodes, false);
        }
        // The sweep runs once per tree and condition: leaf-on, or leaf-off when leaf-on is not run.
        if (c.sweep && (leafOn || !(o.leafOn && c.leafOn))) {
          for (int n : o.nodeSweep) runOne("user", n, true);
        }
      }
    }
  }
  return rows;
}

// -- summaries -------------------------------------------------------------------------------------

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
      double bSum = 0, fSum = 0;
      for (const auto& r : rows) {
        if (r.sweep || r.condition != condition || r.leaf != leaf || r.method != method) continue;
        if (half != "all" && r.half != half) continue;
        s.factor = r.factor;
        if (r.backwardOnly) s.forwardJudged = false;
        s.woodPointsMin = s.cases == 0 ? r.woodPoints : std::min(s.woodPointsMin, r.woodPoints);
        s.woodPointsMax = std::max(s.woodPointsMax, r.woodPoints);
        ++s.cases;
        if (r.sparse) {
          ++s.sparse;
          continue;
        }
        if (!std::isfinite(r.backwardRms) || !std::isfinite(r.forwardRms)) {
          ++s.noMesh;
          continue;
        }
        ++s.judged;
        bSum += r.backwardRms;
        fSum += r.forwardRms;
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
      }
      if (s.judged > 0) {
        s.backwardMean = bSum / s.judged;
        s.forwardMean = fSum / s.judged;
      }
      out.push_back(s);
    }
  }
  return out;
}

namespace {

std::string f2(double v) {
  if (!std::isfinite(v)) return std::isinf(v) ? "∞" : "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}
std::string f3(double v) {
  if (!std::isfinite(v)) return std::isinf(v) ? "∞" : "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

std::string flagsOf(const EvalRow& r) {
  std::string f;
  if (r.sparse) f = "sparse";
  if (r.backwardOnly) f += std::string(f.empty() ? "" : ", ") + "backward only";
  return f;
}

/// (condition, leaf) groups of the main rows, in first-seen order.
std::vector<std::pair<std::string, std::string>> conditionGroups(const std::vector<EvalRow>& rows) {
  std::vector<std::pair<std::string, std::string>> groups;
  for (const auto& r : rows) {
    auto key = std::make_pair(r.condition, r.leaf);
    if (std::find(groups.begin(), groups.end(), key) == groups.end()) groups.push_back(key);
  }
  return groups;
}

/// The rows' scales as text ("1 unit = 0.1 m (14 trees)").
std::string scaleText(const std::vector<EvalRow>& rows) {
  std::map<double, std::set<std::string>> trees;
  for (const auto& r : rows) trees[r.metresPerUnit].insert(r.tree);
  std::string s;
  for (const auto& [mpu, names] : trees) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "1 scene unit = %g m (%zu tree%s)", mpu, names.size(), names.size() == 1 ? "" : "s");
    s += (s.empty() ? "" : "; ") + std::string(buf);
  }
  return s;
}

}  // namespace

std::string markdownTable(const std::vector<EvalRow>& rows) {
  std::ostringstream s;
  const auto summaries = summarize(rows);
  if (!rows.empty()) s << "Scale: " << scaleText(rows) << ".\n\n";
  for (const auto& [condition, leaf] : conditionGroups(rows)) {
    s << "### " << condition << ", " << leaf << "\n\n";
    s << "| tree | half | method | nodes (fitted) | tips (limbs) | root offset % | reconstruct ms | points | wood "
         "points "
         "| wood % | samples | bbox diag | back max % | back mean % | back RMS % | fwd max % | fwd mean % | fwd RMS % "
         "| flags |\n";
    s << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const auto& r : rows) {
      if (r.condition != condition || r.leaf != leaf || r.sweep) continue;
      s << "| " << r.tree << " | " << r.half << " | " << r.method << " | " << r.nodes << " (" << r.fitted << ") | "
        << r.tips << " (" << r.referenceLimbs << ") | " << f2(r.rootOffsetPct) << " | " << f2(r.reconstructMs) << " | "
        << r.points << " | " << r.woodPoints << " | " << f2(100.0 * r.woodFraction) << " | " << r.samples << " | "
        << f2(r.bboxDiagonal) << " | " << f3(r.backwardMax) << " | " << f3(r.backwardMean) << " | " << f3(r.backwardRms)
        << " | " << f3(r.forwardMax) << " | " << f3(r.forwardMean) << " | " << f3(r.forwardRms) << " | " << flagsOf(r)
        << " |\n";
    }
    s << "\nMean and worst case over the judged trees of each half (sparse cases and cases without a mesh left out, "
         "counted):\n\n| method | half | judged (sparse, no mesh) | back RMS mean % | back RMS worst % | fwd RMS mean "
         "% "
         "| fwd RMS worst % |\n|---|---|---:|---:|---:|---:|---:|\n";
    for (const auto& m : summaries) {
      if (m.condition != condition || m.leaf != leaf) continue;
      std::string open = m.forwardJudged ? "" : "(", close = m.forwardJudged ? "" : ")";
      s << "| " << m.method << " | " << m.half << " | " << m.judged << " of " << m.cases << " (" << m.sparse << ", "
        << m.noMesh << ") | " << f3(m.backwardMean) << " | " << f3(m.backwardWorst) << " | " << open
        << f3(m.forwardMean) << close << " | " << open << f3(m.forwardWorst) << close << " |\n";
    }
    s << "\n";
  }
  return s.str();
}

std::string markdownSummary(const std::vector<EvalRow>& rows, const std::vector<ScanCondition>& conditions) {
  std::ostringstream s;
  const auto summaries = summarize(rows);
  std::vector<std::string> halves, methods, tune, held;
  for (const char* h : {"tune", "held-out"})
    if (std::any_of(rows.begin(), rows.end(), [&](const EvalRow& r) { return r.half == h; })) halves.push_back(h);
  if (std::any_of(rows.begin(), rows.end(), [](const EvalRow& r) { return r.method == "skeleton"; }))
    methods.push_back("skeleton");
  for (const auto& r : rows) {
    if (std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
    auto& list = r.half == "tune" ? tune : held;
    if (std::find(list.begin(), list.end(), r.tree) == list.end()) list.push_back(r.tree);
  }
  std::string cellHalves;
  for (const auto& h : halves) cellHalves += (cellHalves.empty() ? "" : " / ") + h;

  s << "# Evaluation summary\n\n";
  const bool ezTree =
      std::any_of(rows.begin(), rows.end(), [](const EvalRow& r) { return r.metresPerUnit == kEzTreeMetresPerUnit; });
  s << "- Scale: " << (rows.empty() ? std::string("no rows") : scaleText(rows))
    << ". Physical scan settings (station height, range noise in mm) are converted with it"
    << (ezTree ? "; the ez-tree trees are taken as decimetres (a tree 25-65 units tall is 2.5-6.5 m)" : "") << ".\n";
  s << "- Split: tuning half (" << tune.size() << "): " << (tune.empty() ? "—" : "");
  for (std::size_t i = 0; i < tune.size(); ++i) s << (i ? ", " : "") << tune[i];
  s << "; held-out half (" << held.size() << "): " << (held.empty() ? "—" : "");
  for (std::size_t i = 0; i < held.size(); ++i) s << (i ? ", " : "") << held[i];
  s << ". Every cell below is `" << cellHalves << "`.\n";
  s << "- RMS distances are % of the reference (branch mesh) bounding-box diagonal; backward: the reconstruction "
       "sampled against the branch mesh, forward: the branch mesh against the reconstruction. Worst = max over "
       "the trees of the half.\n";
  s << "- Judged cases: a case with fewer than " << kSparseWoodPoints
    << " wood points is flagged sparse and left out (counted); so is a case without a mesh. One-station TLS cannot "
       "see the far side: its forward RMS and tips ratio are shown in parentheses, not judged.\n";
  s << "- Tips / limbs: the method's sketch tips over the reference's limbs, min–max over the judged trees (target "
    << kTipsRatioMin << "–" << kTipsRatioMax << ").\n";
  s << "- Root at base: judged trees whose sketch root lies within " << kRootAtBasePct
    << " % of the diagonal of the reference trunk base (the first centre of the reference skeleton's root limb), "
       "and the largest such distance (∞: no root located).\n\n";
  if (!conditions.empty()) s << "## Conditions\n\n" << conditionTable(conditions) << "\n";

  auto cell = [&](const std::string& condition, const std::string& leaf, const std::string& method,
                  const std::function<std::string(const ConditionSummary&)>& f) {
    std::string out;
    for (const auto& h : halves) {
      std::string v = "—";
      for (const auto& m : summaries)
        if (m.condition == condition && m.leaf == leaf && m.method == method && m.half == h) v = f(m);
      out += (out.empty() ? "" : " / ") + v;
    }
    return out;
  };
  for (const auto& leaf : {std::string("leaf-off"), std::string("leaf-on")}) {
    for (const auto& method : methods) {
      std::vector<std::string> conds;
      for (const auto& m : summaries)
        if (m.leaf == leaf && m.method == method && std::find(conds.begin(), conds.end(), m.condition) == conds.end())
          conds.push_back(m.condition);
      if (conds.empty()) continue;
      s << "## " << method << ", " << leaf << "\n\n";
      s << "| condition | factor | wood points | judged (sparse, no mesh) | back RMS mean % | back RMS worst % | fwd "
           "RMS "
           "mean % | fwd RMS worst % | tips / limbs | root at base (max offset %) |\n";
      s << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
      for (const auto& cond : conds) {
        std::string factor;
        for (const auto& m : summaries)
          if (m.condition == cond) factor = m.factor;
        s << "| " << cond << " | " << factor << " | "
          << cell(cond, leaf, method,
                  [](const ConditionSummary& m) {
                    return m.woodPointsMin == m.woodPointsMax
                               ? std::to_string(m.woodPointsMin)
                               : std::to_string(m.woodPointsMin) + "–" + std::to_string(m.woodPointsMax);
                  })
          << " | "
          << cell(cond, leaf, method,
                  [](const ConditionSummary& m) {
                    return std::to_string(m.judged) + " (" + std::to_string(m.sparse) + ", " +
                           std::to_string(m.noMesh) + ")";
                  })
          << " | " << cell(cond, leaf, method, [](const ConditionSummary& m) { return f3(m.backwardMean); }) << " | "
          << cell(cond, leaf, method, [](const ConditionSummary& m) { return f3(m.backwardWorst); }) << " | "
          << cell(cond, leaf, method,
                  [](const ConditionSummary& m) {
                    return m.forwardJudged || m.judged == 0 ? f3(m.forwardMean) : "(" + f3(m.forwardMean) + ")";
                  })
          << " | "
          << cell(cond, leaf, method,
                  [](const ConditionSummary& m) {
                    return m.forwardJudged || m.judged == 0 ? f3(m.forwardWorst) : "(" + f3(m.forwardWorst) + ")";
                  })
          << " | "
          << cell(cond, leaf, method,
                  [](const ConditionSummary& m) {
                    if (m.judged == 0) return std::string("—");
                    std::string v = m.tipsRatioMin == m.tipsRatioMax ? f2(m.tipsRatioMin)
                                                                     : f2(m.tipsRatioMin) + "–" + f2(m.tipsRatioMax);
                    return m.forwardJudged ? v : "(" + v + ")";
                  })
          << " | "
          << cell(cond, leaf, method,
                  [](const ConditionSummary& m) {
                    if (m.judged == 0) return std::string("—");
                    return std::to_string(m.rootAtBase) + "/" + std::to_string(m.judged) + " (" +
                           f2(m.rootOffsetWorst) + ")";
                  })
          << " |\n";
      }
      s << "\n";
    }
  }
  return s.str();
}

std::string csvTable(const std::vector<EvalRow>& rows) {
  std::ostringstream s;
  s << "tree,half,condition,factor,pattern,leaf,method,sweep,nodes,fitted,points,wood_points,wood_fraction,rays,"
       "stations,step_deg,range_noise_mm,metres_per_unit,reconstruct_ms,samples,bbox_diagonal,backward_max_pct,"
       "backward_mean_pct,backward_rms_pct,forward_max_pct,forward_mean_pct,forward_rms_pct,mesh_triangles,tips,"
       "reference_limbs,root_offset_pct,root_at_base,sparse,backward_only\n";
  s.precision(9);
  for (const auto& r : rows) {
    s << r.tree << "," << r.half << "," << r.condition << "," << r.factor << "," << r.pattern << "," << r.leaf << ","
      << r.method << "," << (r.sweep ? 1 : 0) << "," << r.nodes << "," << r.fitted << "," << r.points << ","
      << r.woodPoints << "," << r.woodFraction << "," << r.rays << "," << r.stations << "," << r.stepDeg << ","
      << r.rangeNoiseMm << "," << r.metresPerUnit << "," << r.reconstructMs << "," << r.samples << "," << r.bboxDiagonal
      << "," << r.backwardMax << "," << r.backwardMean << "," << r.backwardRms << "," << r.forwardMax << ","
      << r.forwardMean << "," << r.forwardRms << "," << r.meshTriangles << "," << r.tips << "," << r.referenceLimbs
      << "," << r.rootOffsetPct << "," << (r.rootAtBase ? 1 : 0) << "," << (r.sparse ? 1 : 0) << ","
      << (r.backwardOnly ? 1 : 0) << "\n";
  }
  return s.str();
}

std::string csvSummary(const std::vector<ConditionSummary>& summaries) {
  std::ostringstream s;
  s << "condition,factor,leaf,method,half,cases,sparse,no_mesh,judged,forward_judged,wood_points_min,wood_points_max,"
       "backward_rms_mean_pct,backward_rms_worst_pct,backward_worst_tree,forward_rms_mean_pct,forward_rms_worst_pct,"
       "forward_worst_tree,tips_ratio_min,tips_ratio_max,tips_ratio_in_band,root_at_base,root_offset_worst_pct\n";
  s.precision(9);
  for (const auto& m : summaries) {
    s << m.condition << "," << m.factor << "," << m.leaf << "," << m.method << "," << m.half << "," << m.cases << ","
      << m.sparse << "," << m.noMesh << "," << m.judged << "," << (m.forwardJudged ? 1 : 0) << "," << m.woodPointsMin
      << "," << m.woodPointsMax << "," << m.backwardMean << "," << m.backwardWorst << "," << m.backwardWorstTree << ","
      << m.forwardMean << "," << m.forwardWorst << "," << m.forwardWorstTree << "," << m.tipsRatioMin << ","
      << m.tipsRatioMax << "," << m.tipsRatioInBand << "," << m.rootAtBase << "," << m.rootOffsetWorst << "\n";
  }
  return s.str();
}

namespace {

/// The thesis's figures 5.12-5.14 from the first condition (leaf-on when it has it).
void writeThesisPlots(const fs::path& folder, const std::vector<EvalRow>& rows) {
  const std::string condition = rows.front().condition;
  std::string leaf = "leaf-off";
  for (const auto& r : rows)
    if (r.condition == condition && r.leaf == "leaf-on") leaf = "leaf-on";
  const std::string label = condition + ", " + leaf;
  std::vector<std::string> trees, methods;
  for (const auto& r : rows) {
    if (std::find(trees.begin(), trees.end(), r.tree) == trees.end()) trees.push_back(r.tree);
    if (!r.sweep && std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
  }
  auto find = [&](const std::string& tree, const std::string& method) -> const EvalRow* {
    for (const auto& r : rows)
      if (!r.sweep && r.tree == tree && r.method == method && r.condition == condition && r.leaf == leaf) return &r;
    return nullptr;
  };
  std::string userMethod = std::find(methods.begin(), methods.end(), "user") != methods.end() ? "user" : methods[0];

  BarChart f12;
  f12.title = "Backward vs forward RMS per tree (" + userMethod + ", " + label + ")";
  f12.yLabel = "RMS, % of bbox diagonal";
  f12.groups = trees;
  f12.series = {"backward", "forward"};
  f12.values.assign(2, std::vector<double>(trees.size(), NAN));
  for (std::size_t t = 0; t < trees.size(); ++t) {
    if (const EvalRow* r = find(trees[t], userMethod)) {
      f12.values[0][t] = r->backwardRms;
      f12.values[1][t] = r->forwardRms;
    }
  }
  writeSvg(folder / "fig_5_12_backward_vs_forward.svg", renderSvg(f12));

  BarChart f13;
  f13.title = "Backward RMS per tree and method (" + label + ")";
  f13.yLabel = "backward RMS, % of bbox diagonal";
  f13.groups = trees;
  f13.series = methods;
  f13.values.assign(methods.size(), std::vector<double>(trees.size(), NAN));
  for (std::size_t m = 0; m < methods.size(); ++m)
    for (std::size_t t = 0; t < trees.size(); ++t)
      if (const EvalRow* r = find(trees[t], methods[m])) f13.values[m][t] = r->backwardRms;
  writeSvg(folder / "fig_5_13_user_vs_auto.svg", renderSvg(f13));

  LineChart f14;
  f14.title = "Backward RMS vs sketch nodes (simulated user, " + label + ")";
  f14.xLabel = "sketch nodes";
  f14.yLabel = "backward RMS, % of bbox diagonal";
  for (const auto& tree : trees) {
    std::vector<std::pair<double, double>> pts;
    for (const auto& r : rows)
      if (r.sweep && r.tree == tree && r.condition == condition && r.leaf == leaf)
        pts.emplace_back(r.nodes, r.backwardRms);
    if (pts.empty()) continue;
    std::sort(pts.begin(), pts.end());
    f14.series.push_back(tree);
    f14.xs.emplace_back();
    f14.ys.emplace_back();
    for (auto [x, y] : pts) {
      f14.xs.back().push_back(x);
      f14.ys.back().push_back(y);
    }
  }
  writeSvg(folder / "fig_5_14_rms_vs_nodes.svg", renderSvg(f14));
}

/// The robustness plots: RMS against wood points (every case) and against range noise (means).
void writeRobustnessPlots(const fs::path& folder, const std::vector<EvalRow>& rows) {
  std::string leaf = "leaf-on";
  for (const auto& r : rows)
    if (r.leaf == "leaf-off") leaf = "leaf-off";
  std::vector<std::string> methods;
  for (const auto& r : rows)
    if (!r.sweep && std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
  const std::vector<std::string> halves = {"tune", "held-out"};

  for (bool backward : {true, false}) {
    const std::string dir = backward ? "backward" : "forward";
    LineChart c;
    c.title = dir + " RMS vs wood points, every case (" + leaf + "; hollow: held-out trees)";
    c.xLabel = "wood points in the scan";
    c.yLabel = dir + " RMS, % of bbox diagonal";
    c.logX = c.logY = true;
    for (std::size_t m = 0; m < methods.size(); ++m) {
      for (std::size_t h = 0; h < halves.size(); ++h) {
        std::vector<double> xs, ys;
        for (const auto& r : rows) {
          if (r.sweep || r.leaf != leaf || r.method != methods[m] || r.half != halves[h]) continue;
          if (!backward && r.backwardOnly) continue;  // not judged
          xs.push_back(static_cast<double>(r.woodPoints));
          ys.push_back(backward ? r.backwardRms : r.forwardRms);
        }
        if (xs.empty()) continue;
        c.series.push_back(methods[m] + " (" + halves[h] + ")");
        c.xs.push_back(xs);
        c.ys.push_back(ys);
        c.styles.push_back(SeriesStyle{static_cast<int>(m), false, false, h == 1});
      }
    }
    writeSvg(folder / ("fig_" + dir + "_vs_wood_points.svg"), renderSvg(c));
  }

  // Noise: the TLS base and its noise variants, mean over the judged trees of each half.
  std::map<std::string, double> noiseOf;
  for (const auto& r : rows)
    if (r.pattern == "tls" && (r.factor == "noise" || r.factor == "base")) noiseOf[r.condition] = r.rangeNoiseMm;
  if (noiseOf.size() < 2) return;
  const auto summaries = summarize(rows);
  for (bool backward : {true, false}) {
    const std::string dir = backward ? "backward" : "forward";
    LineChart c;
    c.title = dir + " RMS vs range noise, mean over trees (TLS base, " + leaf + "; dashed: held-out trees)";
    c.xLabel = "range noise sigma, mm";
    c.yLabel = dir + " RMS, % of bbox diagonal";
    c.logY = true;
    for (std::size_t m = 0; m < methods.size(); ++m) {
      for (std::size_t h = 0; h < halves.size(); ++h) {
        std::vector<std::pair<double, double>> pts;
        for (const auto& s : summaries) {
          auto it = noiseOf.find(s.condition);
          if (it == noiseOf.end() || s.leaf != leaf || s.method != methods[m] || s.half != halves[h]) continue;
          pts.emplace_back(it->second, backward ? s.backwardMean : s.forwardMean);
        }
        if (pts.empty()) continue;
        std::sort(pts.begin(), pts.end());
        c.series.push_back(methods[m] + " (" + halves[h] + ")");
        c.xs.emplace_back();
        c.ys.emplace_back();
        for (auto [x, y] : pts) {
          c.xs.back().push_back(x);
          c.ys.back().push_back(y);
        }
        c.styles.push_back(SeriesStyle{static_cast<int>(m), true, h == 1, false});
      }
    }
    writeSvg(folder / ("fig_" + dir + "_vs_noise.svg"), renderSvg(c));
  }
}

}  // namespace

void writeReport(const fs::path& folder, const std::vector<EvalRow>& rows,
                 const std::vector<ScanCondition>& conditions) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder)) throw OutputError(folder.string() + ": cannot create the directory");
  writeFileAtomically(
      folder / "table.md", [&](std::ostream& o) { o << markdownTable(rows); }, false);
  writeFileAtomically(
      folder / "summary.md", [&](std::ostream& o) { o << markdownSummary(rows, conditions); }, false);
  writeFileAtomically(
      folder / "results.csv", [&](std::ostream& o) { o << csvTable(rows); }, false);
  writeFileAtomically(
      folder / "summary.csv", [&](std::ostream& o) { o << csvSummary(summarize(rows)); }, false);
  if (rows.empty()) return;
  writeThesisPlots(folder, rows);
  writeRobustnessPlots(folder, rows);
}

}  // namespace treesketch::eval
