#include "treesketch/eval/evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

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

MethodOutput reconstructSketch(const sketch::Sketch& sk, const geom::PointCloud& cloud, std::uint64_t seed,
                               Clock::time_point t0) {
  recon::ReconstructionOptions ro;
  ro.seed = seed;
  recon::ReconstructionResult r = recon::reconstruct(cloud, sk, ro);
  MethodOutput out;
  out.mesh = std::move(r.mesh);
  out.sketch = sk;
  out.nodes = static_cast<int>(sk.size());
  for (const auto& [id, res] : r.results)
    if (res.status == fit::NodeStatus::Fitted) ++out.fitted;
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
  return reconstructSketch(sk, in.cloud, in.options.seed, t0);
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
  out.mesh = std::move(r.mesh);
  out.sketch = std::move(r.sketch);
  out.nodes = static_cast<int>(out.sketch.size());
  for (char a : r.fitAccepted) out.fitted += a != 0;
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

std::uint64_t tlsCount(const TreeCase& tree, const std::vector<geom::TriMesh>& meshes, const EvalOptions& o,
                       double step) {
  scan::TlsScanOptions t;
  t.stationCount = o.tlsStations;
  t.stepDeg = step;
  t.up = tree.up;
  t.seed = o.seed;
  t.stationHeight = 0.02 * tree.branches.bounds().diagonal();
  return scan::tlsScan(meshes, t).cloud.size();
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

geom::PointCloud scanTree(const TreeCase& tree, const std::string& pattern, bool leafOn, const EvalOptions& o) {
  std::vector<geom::TriMesh> meshes{tree.branches};
  if (leafOn && !tree.leaves.empty()) meshes.push_back(tree.leaves);
  if (pattern == "sphere") {
    scan::SphereScanOptions s;
    s.rays = o.sphereRays;
    s.seed = o.seed;
    if (o.sphereTargetPoints > 0) {
      scan::SphereScanOptions pilot = s;
      pilot.rays = 100000;
      pilot.seed = o.seed + 7919;
      pilot.jitterDeg = o.sphereJitterDeg > 0 ? o.sphereJitterDeg : std::atan(0.5 / s.radiusFactor) * 180.0 / M_PI;
      double hitRate = std::max<double>(scan::sphereScan(meshes, pilot).cloud.size(), 1.0) /
                       static_cast<double>(scan::sphereRayCount(pilot));
      s.rays = static_cast<std::uint64_t>(std::min(static_cast<double>(o.sphereTargetPoints) / hitRate, 5e7));
    }
    s.jitterDeg = o.sphereJitterDeg > 0 ? o.sphereJitterDeg
                                        : std::atan(0.5 / s.radiusFactor) * 180.0 / M_PI;  // cone over the bbox
    s.recordMesh = true;
    return scan::sphereScan(meshes, s).cloud;
  }
  if (pattern == "tls") {
    double step = o.tlsStepDeg;
    if (step <= 0) {
      // Pilot scan at a coarse step; hits scale as 1/step^2.
      const double pilot = 1.0;
      std::uint64_t hits = std::max<std::uint64_t>(tlsCount(tree, meshes, o, pilot), 1);
      step = pilot * std::sqrt(static_cast<double>(hits) / static_cast<double>(o.tlsTargetPoints));
      step = std::clamp(step, 0.005, 1.0);
    }
    scan::TlsScanOptions t;
    t.stationCount = o.tlsStations;
    t.stepDeg = step;
    t.up = tree.up;
    t.seed = o.seed;
    t.recordMesh = true;
    t.stationHeight = 0.02 * tree.branches.bounds().diagonal();
    t.rangeNoise = 0.0005 * tree.branches.bounds().diagonal();
    return scan::tlsScan(meshes, t).cloud;
  }
  throw OptionsError("unknown scan pattern '" + pattern + "' (known: sphere, tls)");
}

std::vector<EvalRow> runEvaluation(const std::vector<TreeCase>& trees, const EvalOptions& o) {
  for (const auto& m : o.methods) {
    if (!registry().count(m)) runMethod(m, MethodInput{trees.front(), geom::PointCloud{}, o, 0});  // throws
  }
  std::vector<EvalRow> rows;
  for (const auto& tree : trees) {
    const double diag = tree.branches.bounds().diagonal();
    for (const auto& pattern : o.patterns) {
      for (int cond = 0; cond < 2; ++cond) {
        bool leafOn = cond == 0;
        if ((leafOn && !o.leafOn) || (!leafOn && !o.leafOff)) continue;
        geom::PointCloud cloud = scanTree(tree, pattern, leafOn, o);
        std::size_t wood = 0;
        for (auto id : cloud.meshId) wood += id == 0;
        auto runOne = [&](const std::string& method, int nodes, bool sweep) {
          EvalRow row;
          row.tree = tree.name;
          row.condition = leafOn ? "leaf-on" : "leaf-off";
          row.pattern = pattern;
          row.method = method;
          row.sweep = sweep;
          row.points = cloud.size();
          row.woodFraction = cloud.size() ? static_cast<double>(wood) / cloud.size() : 0.0;
          row.bboxDiagonal = diag;
          MethodOutput out = runMethod(method, MethodInput{tree, cloud, o, nodes, leafOn});
          row.nodes = out.nodes;
          row.fitted = out.fitted;
          for (const auto& [id, node] : out.sketch.nodes()) row.tips += node.children.empty();
          row.referenceLimbs = static_cast<int>(tree.axes.size());
          row.reconstructMs = out.ms;
          row.meshTriangles = out.mesh.triangles.size();
          DistanceOptions dopt;
          dopt.minSamples = o.minSamples;
          dopt.samples = o.samples;
          dopt.seed = o.seed;
          DirectionStats fwd = oneWayDistance(tree.branches, out.mesh, dopt);
          DirectionStats bwd = oneWayDistance(out.mesh, tree.branches, dopt);
          auto pct = [&](double v) { return diag > 0 ? 100.0 * v / diag : NAN; };
          row.samples = fwd.samples;
          row.forwardMax = pct(fwd.max);
          row.forwardMean = pct(fwd.mean);
          row.forwardRms = pct(fwd.rms);
          row.backwardMax = pct(bwd.max);
          row.backwardMean = pct(bwd.mean);
          row.backwardRms = pct(bwd.rms);
          if (o.log) {
            char buf[256];
            std::snprintf(buf, sizeof buf, "%s %s %s %-8s nodes %3d/%3d  back RMS %6.3f %%  fwd RMS %6.3f %%  %7.0f ms",
                          tree.name.c_str(), pattern.c_str(), row.condition.c_str(), method.c_str(), row.fitted,
                          row.nodes, row.backwardRms, row.forwardRms, row.reconstructMs);
            o.log(buf);
          }
          rows.push_back(row);
        };
        for (const auto& method : o.methods) {
          int nodes = method == "uniform" ? o.uniformNodes : o.userNodes;
          runOne(method, nodes, false);
        }
        if (leafOn || !o.leafOn) {
          for (int n : o.nodeSweep) runOne("user", n, true);
        }
      }
    }
  }
  return rows;
}

namespace {

std::string f2(double v) {
  if (!std::isfinite(v)) return "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}
std::string f3(double v) {
  if (!std::isfinite(v)) return "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace

std::string markdownTable(const std::vector<EvalRow>& rows) {
  std::ostringstream s;
  std::vector<std::pair<std::string, std::string>> groups;
  for (const auto& r : rows) {
    auto key = std::make_pair(r.pattern, r.condition);
    if (std::find(groups.begin(), groups.end(), key) == groups.end()) groups.push_back(key);
  }
  for (const auto& [pattern, condition] : groups) {
    s << "### " << pattern << " scan, " << condition << "\n\n";
    s << "| tree | method | nodes (fitted) | tips (limbs) | reconstruct ms | points | wood % | samples | bbox diag | "
         "back max % | back mean % | back RMS % | fwd max % | fwd mean % | fwd RMS % |\n";
    s << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    std::map<std::string, std::vector<const EvalRow*>> byMethod;
    for (const auto& r : rows) {
      if (r.pattern != pattern || r.condition != condition || r.sweep) continue;
      byMethod[r.method].push_back(&r);
      s << "| " << r.tree << " | " << r.method << " | " << r.nodes << " (" << r.fitted << ") | " << r.tips << " ("
        << r.referenceLimbs << ") | " << f2(r.reconstructMs) << " | " << r.points << " | " << f2(100.0 * r.woodFraction)
        << " | " << r.samples << " | " << f2(r.bboxDiagonal) << " | " << f3(r.backwardMax) << " | "
        << f3(r.backwardMean) << " | " << f3(r.backwardRms) << " | " << f3(r.forwardMax) << " | " << f3(r.forwardMean)
        << " | " << f3(r.forwardRms) << " |\n";
    }
    s << "\nMean over trees (a method that fitted no node on a tree has no mesh: that tree is left out of its "
         "mean and counted in the last column):\n\n| method | back RMS % | fwd RMS % | reconstruct ms | trees "
         "without a mesh |\n|---|---:|---:|---:|---:|\n";
    for (const auto& [method, list] : byMethod) {
      double b = 0, f = 0, ms = 0;
      int n = 0, failed = 0;
      for (const auto* r : list) {
        ms += r->reconstructMs;
        if (!std::isfinite(r->backwardRms) || !std::isfinite(r->forwardRms)) {
          ++failed;
          continue;
        }
        b += r->backwardRms;
        f += r->forwardRms;
        ++n;
      }
      s << "| " << method << " | " << f3(n ? b / n : NAN) << " | " << f3(n ? f / n : NAN) << " | "
        << f2(ms / list.size()) << " | " << failed << " of " << list.size() << " |\n";
    }
    s << "\n";
  }
  return s.str();
}

std::string csvTable(const std::vector<EvalRow>& rows) {
  std::ostringstream s;
  s << "tree,pattern,condition,method,sweep,nodes,fitted,points,wood_fraction,reconstruct_ms,samples,bbox_diagonal,"
       "backward_max_pct,backward_mean_pct,backward_rms_pct,forward_max_pct,forward_mean_pct,forward_rms_pct,"
       "mesh_triangles,tips,reference_limbs\n";
  s.precision(9);
  for (const auto& r : rows) {
    s << r.tree << "," << r.pattern << "," << r.condition << "," << r.method << "," << (r.sweep ? 1 : 0) << ","
      << r.nodes << "," << r.fitted << "," << r.points << "," << r.woodFraction << "," << r.reconstructMs << ","
      << r.samples << "," << r.bboxDiagonal << "," << r.backwardMax << "," << r.backwardMean << "," << r.backwardRms
      << "," << r.forwardMax << "," << r.forwardMean << "," << r.forwardRms << "," << r.meshTriangles << "," << r.tips
      << "," << r.referenceLimbs << "\n";
  }
  return s.str();
}

void writeReport(const fs::path& folder, const std::vector<EvalRow>& rows) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder)) throw OutputError(folder.string() + ": cannot create the directory");
  writeFileAtomically(
      folder / "table.md", [&](std::ostream& o) { o << markdownTable(rows); }, false);
  writeFileAtomically(
      folder / "results.csv", [&](std::ostream& o) { o << csvTable(rows); }, false);
  if (rows.empty()) return;

  // The main condition of the plots: the first pattern, leaf-on when present.
  std::string pattern = rows.front().pattern;
  std::string condition = "leaf-off";
  for (const auto& r : rows)
    if (r.pattern == pattern && r.condition == "leaf-on") condition = "leaf-on";
  std::vector<std::string> trees, methods;
  for (const auto& r : rows) {
    if (std::find(trees.begin(), trees.end(), r.tree) == trees.end()) trees.push_back(r.tree);
    if (!r.sweep && std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
  }
  auto find = [&](const std::string& tree, const std::string& method) -> const EvalRow* {
    for (const auto& r : rows)
      if (!r.sweep && r.tree == tree && r.method == method && r.pattern == pattern && r.condition == condition)
        return &r;
    return nullptr;
  };
  std::string userMethod = std::find(methods.begin(), methods.end(), "user") != methods.end() ? "user" : methods[0];

  BarChart f12;
  f12.title = "Backward vs forward RMS per tree (" + userMethod + ", " + pattern + ", " + condition + ")";
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
  f13.title = "Backward RMS per tree and method (" + pattern + ", " + condition + ")";
  f13.yLabel = "backward RMS, % of bbox diagonal";
  f13.groups = trees;
  f13.series = methods;
  f13.values.assign(methods.size(), std::vector<double>(trees.size(), NAN));
  for (std::size_t m = 0; m < methods.size(); ++m)
    for (std::size_t t = 0; t < trees.size(); ++t)
      if (const EvalRow* r = find(trees[t], methods[m])) f13.values[m][t] = r->backwardRms;
  writeSvg(folder / "fig_5_13_user_vs_auto.svg", renderSvg(f13));

  LineChart f14;
  f14.title = "Backward RMS vs sketch nodes (simulated user, " + pattern + ", " + condition + ")";
  f14.xLabel = "sketch nodes";
  f14.yLabel = "backward RMS, % of bbox diagonal";
  for (const auto& tree : trees) {
    std::vector<std::pair<double, double>> pts;
    for (const auto& r : rows)
      if (r.sweep && r.tree == tree && r.pattern == pattern && r.condition == condition)
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

}  // namespace treesketch::eval
