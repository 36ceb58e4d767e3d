// `treesketch reconstruct CLOUD --sketch SKETCH.json -o MESH.obj|.ply [--report REPORT.json]`:
// fits a circle at every sketch node and sweeps the tube mesh (thesis §3.1.3–3.1.4, §4.4).
// Prints a one-line summary; the optional JSON report lists every node's fit (or, with --auto,
// the automatic model's counts and timings) and how well the model explains the cloud
// (compare/model_fit.h: signed distances of the points to the model's frustums, QSM figures).
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.h"
#include "tree_job.h"
#include "treesketch/compare/model_fit.h"
#include "treesketch/compare/tree_metrics.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/skeleton/skeleton_export.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace {

struct ReconstructArgs {
  std::string cloud, sketch, output, report;
  int ring = 16;
  double inlierThreshold = -1.0;  // < 0: library default
  std::uint64_t seed = 1;
  bool autoSkeleton = false;        // --auto: sketch from the cloud's skeleton (skeleton module)
  bool leafOn = false;              // --leaf-on (with --auto): settings for trees in leaf
  bool refit = false;               // --refit: drop the sketch's kept circles, fit every node
  std::string up, cylinders, qsm;   // --up ("" = the rule of io/up_axis.h), --cylinders, --qsm (with --auto)
  double unitMetres = 0.0;          // --units-metres (with --report; 0 = not given: metres)
};

nlohmann::json vec(const geom::Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

/// The sketch model as frustums: each fitted node joined to its nearest fitted ancestor (the
/// bands the sweep makes; skipped and disabled nodes are bridged).
geom::CylinderModel sketchModel(const recon::ReconstructionResult& r) {
  std::vector<geom::ModelNode> nodes;
  std::map<sketch::NodeId, std::int64_t> index;  // fitted node → its place in `nodes`
  for (sketch::NodeId id : r.order) {
    const fit::NodeResult& n = r.results.at(id);
    if (n.status != fit::NodeStatus::Fitted || !(n.radius > 0) || !n.centre.allFinite()) continue;
    geom::ModelNode m;
    m.position = n.centre;
    m.radius = n.radius;
    for (sketch::NodeId p = r.parents.at(id); p != sketch::kNoNode; p = r.parents.at(p)) {
      auto it = index.find(p);
      if (it != index.end()) {
        m.parent = it->second;
        break;
      }
    }
    index[id] = static_cast<std::int64_t>(nodes.size());
    nodes.push_back(m);
  }
  return geom::cylinderModelFromNodes(nodes);
}

/// The model-fit part of a report: "fit" (shares, median) and "figures" (volume, length, trunk
/// diameter), and the one-line summary printed.
nlohmann::json measureModel(const geom::PointCloud& cloud, const geom::CylinderModel& model, geom::UpAxis up,
                            double unitMetres, std::string* summary) {
  if (unitMetres == 0.0) unitMetres = 1.0;
  compare::ModelFitOptions o;
  o.unitMetres = unitMetres;
  const compare::ModelFitReport fit = compare::measureModelFit(cloud, model, o);
  const compare::ModelFigures fig = compare::modelFigures(model, up, unitMetres);
  *summary = compare::summaryLine(fit) + "; " + compare::summaryLine(fig);
  return {{"fit", compare::toJson(fit)}, {"figures", compare::toJson(fig)}};
}

nlohmann::json reportJson(const ReconstructArgs& a, const recon::ReconstructionResult& r, std::size_t cloudSize) {
  nlohmann::json nodes = nlohmann::json::array();
  for (sketch::NodeId id : r.order) {
    const fit::NodeResult& n = r.results.at(id);
    nlohmann::json j;
    j["id"] = id;
    j["parent"] = r.parents.at(id);
    j["status"] = fit::toString(n.status);
    j["kept"] = n.kept;  // the sketch's kept circle, not a fit
    j["reason"] = n.reason;
    j["centre"] = vec(n.centre);
    j["normal"] = vec(n.normal);
    j["radius"] = n.radius;
    j["rms"] = n.rms;
    if (n.sliceComputed)
      j["sliceCount"] = n.sliceIndices.size();
    else
      j["sliceCount"] = nullptr;  // not computed: the first fit succeeded
    j["testCount"] = n.testIndices.size();
    j["inlierCount"] = n.inlierIndices.size();
    j["iterations"] = n.iterations;
    j["lineEpsilon"] = n.lineEpsilon;
    j["growthSteps"] = n.growthSteps;
    j["ms"] = n.ms;
    nodes.push_back(j);
  }
  nlohmann::json root;
  root["cloud"] = a.cloud;
  root["sketch"] = a.sketch;
  root["mesh"] = a.output;
  root["points"] = cloudSize;
  root["seed"] = a.seed;
  root["ringVertices"] = a.ring;
  root["nodes"] = nodes;
  root["vertices"] = r.mesh.vertices.size();
  root["triangles"] = r.mesh.triangles.size();
  root["timings"] = {{"indexMs", r.timings.indexMs},
                     {"fitMs", r.timings.fitMs},
                     {"sweepMs", r.timings.sweepMs},
                     {"totalMs", r.timings.totalMs}};
  return root;
}

/// --auto: skeleton → sketch → fits → regularised radii → mesh (tree_job.h); the sketch is saved
/// to --sketch (when given) for refining, the cylinder tables to --cylinders and --qsm.
void runAutoReconstruct(const ReconstructArgs& a) {
  if (a.refit) throw OptionsError("--refit applies to a sketch file (--sketch without --auto)");
  TreeJob job;
  job.cloud = a.cloud;
  job.mesh = a.output;
  job.sketch = a.sketch;
  job.cylinders = a.cylinders;
  job.qsm = a.qsm;
  job.report = a.report;
  job.up = a.up;
  job.leafOn = a.leafOn;
  job.seed = a.seed;
  job.ring = a.ring;
  job.inlierThreshold = a.inlierThreshold;
  job.unitMetres = a.unitMetres == 0.0 ? 1.0 : a.unitMetres;
  const TreeJobResult r = runTreeJob(job);
  std::printf("up axis: %s\n", r.upReason.c_str());
  std::printf(
      "reconstruct --auto: %zu skeleton nodes (%zu forks), %zu fits accepted, %zu leaf pieces not fitted; "
      "%zu vertices, %zu triangles; skeleton %.1f ms, fit %.1f ms, sweep %.1f ms -> %s\n",
      r.skeletonNodes, r.forks, r.fitsAccepted, r.leafPieces, r.vertices, r.triangles, r.skeletonMs, r.fitMs, r.sweepMs,
      a.output.c_str());
  if (!a.report.empty()) {
    std::printf("model fit: %s -> %s\n", r.fitSummary.c_str(), a.report.c_str());
    std::printf("tree metrics:\n%s", compare::metricsTable(r.metrics).c_str());
  }
}

void runReconstruct(const ReconstructArgs& a) {
  if (a.unitMetres != 0.0 && a.report.empty())
    throw OptionsError("--units-metres applies to the report's figures: it needs --report");
  if (a.autoSkeleton) return runAutoReconstruct(a);
  if (a.sketch.empty()) throw OptionsError("--sketch is required (or --auto)");
  if (!a.up.empty() || !a.qsm.empty())
    throw OptionsError("--up and --qsm need --auto (a sketch file carries its own up axis)");
  if (a.leafOn) throw OptionsError("--leaf-on needs --auto (it sets the automatic skeleton's options)");
  checkNotAnInput(a.output, {a.cloud, a.sketch});
  if (!a.report.empty()) checkNotAnInput(a.report, {a.cloud, a.sketch});
  for (const std::string& out : {a.output, a.report}) checkOutputWritable(out);
  try {
    io::meshFormatFromPath(a.output);  // reject a bad extension before the work
  } catch (const InputError& e) {
    throw OptionsError(std::string("-o: ") + e.what());
  }
  recon::ReconstructionOptions opt;
  opt.seed = a.seed;
  opt.sweep.ringVertices = a.ring;
  if (a.inlierThreshold >= 0.0) opt.fit.circle.inlierThreshold = a.inlierThreshold;

  geom::PointCloud cloud = io::readPointCloud(a.cloud);
  sketch::Sketch sk = io::readSketch(a.sketch);
  if (sk.empty()) throw InputError(a.sketch + ": the sketch has no nodes, expected at least one");
  if (a.refit) sk.clearKeptCircles();

  recon::ReconstructionResult r = recon::reconstruct(cloud, sk, opt);
  std::size_t fitted = 0, skipped = 0, disabled = 0, kept = 0;
  for (const auto& [id, n] : r.results) {
    fitted += n.status == fit::NodeStatus::Fitted && !n.kept;
    kept += n.kept;
    skipped += n.status == fit::NodeStatus::Skipped;
    disabled += n.status == fit::NodeStatus::Disabled;
  }
  std::string fitSummary;
  if (!a.report.empty()) {
    nlohmann::json j = reportJson(a, r, cloud.size());
    const geom::CylinderModel model = sketchModel(r);
    j["model"] = measureModel(cloud, model, sk.up, a.unitMetres, &fitSummary);  // the sketch's up
    compare::TreeMetricsOptions mo;
    mo.unitMetres = a.unitMetres == 0.0 ? 1.0 : a.unitMetres;
    j["metrics"] = compare::toJson(compare::treeMetrics(model, sk.up, mo, &cloud));
    std::string text = j.dump(2) + "\n";
    writeFileAtomically(
        a.report, [&](std::ostream& os) { os << text; }, false);
  }
  if (fitted + kept > 0 && !(r.mesh.area() > 0))
    throw DegenerateInputError(a.sketch + ": the model made in " + a.cloud + " has zero area (" +
                               std::to_string(fitted + kept) + " circles, all of radius 0?); no mesh written");
  if (fitted + kept == 0)
    throw DegenerateInputError(a.sketch + ": no node could be fitted in " + a.cloud + " (" + std::to_string(skipped) +
                               " skipped, " + std::to_string(disabled) + " disabled); no mesh written" +
                               (a.report.empty() ? "" : ", see " + a.report));
  io::writeMesh(a.output, r.mesh);
  std::printf(
      "reconstruct: %zu nodes: %zu fitted, %zu skipped, %zu disabled, %zu kept circles; %zu vertices, %zu "
      "triangles; index %.1f ms, fit %.1f ms, sweep %.1f ms -> %s\n",
      r.results.size(), fitted, skipped, disabled, kept, r.mesh.vertices.size(), r.mesh.triangles.size(),
      r.timings.indexMs, r.timings.fitMs, r.timings.sweepMs, a.output.c_str());
  if (!a.report.empty()) std::printf("model fit: %s -> %s\n", fitSummary.c_str(), a.report.c_str());
}

}  // namespace

void registerReconstruct(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand("reconstruct", "Fit a circle at every sketch node and sweep the tube mesh");
  auto a = std::make_shared<ReconstructArgs>();
  sub->add_option("cloud", a->cloud, "Point cloud (.ply .xyz .txt .csv .pts .asc .las .laz)")->required();
  sub->add_option("--sketch", a->sketch, "Sketch file (.json); with --auto, where to save the automatic sketch");
  sub->add_flag("--auto", a->autoSkeleton, "Sketch automatically from the cloud's branching skeleton");
  sub->add_option("--up", a->up,
                  "With --auto: world up axis, y or z (default: what the file declares — LAS is z, a treesketch PLY "
                  "says its own — else z)")
      ->check(CLI::IsMember({"y", "z", "Y", "Z"}));
  sub->add_flag("--leaf-on", a->leafOn,
                "With --auto: the tree was scanned in leaf (finer voxels, weaker foliage rule)");
  sub->add_option("--cylinders", a->cylinders, "With --auto: also write the cylinder table (.csv)");
  sub->add_option("--qsm", a->qsm, "With --auto: also write the cylinder table in TreeQSM's text layout (.txt)");
  sub->add_option("-o,--output", a->output, "Output mesh (.obj or .ply)")->required();
  sub->add_option("--report", a->report,
                  "Write a JSON report: every node's fit (or the automatic model's counts), and how well the model "
                  "explains the cloud (points within 1/2/5 cm, missed, median signed distance, volume, length, "
                  "trunk diameter at 1.3 m)");
  sub->add_option("--units-metres", a->unitMetres,
                  "With --report: metres per cloud unit, for the centimetre figures (default 1)")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--refit", a->refit,
                "Fit every node from the cloud, ignoring the circles the sketch keeps (an automatic sketch's model)");
  sub->add_option("--ring", a->ring, "Vertices per ring (default 16)")->check(CLI::Range(3, 4096));
  sub->add_option("--inlier-threshold", a->inlierThreshold,
                  "RANSAC inlier threshold on |distance to centre - radius|, cloud units (default 0.01)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--seed", a->seed, "Random seed of the circle fits (default 1)");
  sub->callback([a, &action] { action = [a] { runReconstruct(*a); }; });
}

}  // namespace treesketch::cli
