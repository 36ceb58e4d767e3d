// `treesketch reconstruct CLOUD (--sketch SKETCH.json | --auto) -o MESH.obj|.ply [--cylinders C.csv]
// [--qsm Q.txt] [--metrics M.json] [--report REPORT.json]`: fits a circle at every sketch node and
// sweeps the tube mesh (thesis §3.1.3–3.1.4, §4.4), or makes the automatic model. Either way the
// result is one model (model/tree_model.h) and every output is written from it. Prints a one-line
// summary; the optional JSON report lists every node's fit (or, with --auto, the automatic model's
// counts and timings) and how well the model explains the cloud.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.h"
#include "tree_job.h"
#include "treesketch/cloud/usable_extent.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace {

struct ReconstructArgs {
  std::string cloud, sketch;
  std::string outliers;             // --outliers (with --auto): the stray points set aside
  model::OutputPaths out;  // -o, --cylinders, --qsm, --metrics, --report
  int ring = 16;
  double inlierThreshold = -1.0;  // < 0: library default
  std::uint64_t seed = 1;
  bool autoSkeleton = false;        // --auto: sketch from the cloud's skeleton (skeleton module)
  bool leafOn = false;              // --leaf-on (with --auto): settings for trees in leaf
  bool woodOnly = false;            // --wood-only (with --auto): model the points classified as wood
  bool refit = false;               // --refit: drop the sketch's kept circles, fit every node
  std::string up;                   // --up ("" = the rule of io/up_axis.h; with --auto)
  double unitMetres = 0.0;          // --units-metres (with --report; 0 = not given: metres)
  std::vector<std::string> settings;  // --set NAME=VALUE (with --auto)
};

nlohmann::json vec(const geom::Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

/// The sketch path's part of the report: every node's fit.
nlohmann::json reportHeader(const ReconstructArgs& a, const recon::ReconstructionResult& r, std::size_t cloudSize) {
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
    // The model's circle: the fit, the kept circle or a radius inferred from the limb, and why.
    if (auto c = r.radii.find(id); c != r.radii.end()) {
      j["modelRadiusSource"] = recon::toString(c->second.source);
      j["modelRadius"] = c->second.radius;
      if (!c->second.why.empty()) j["modelRadiusWhy"] = c->second.why;
    }
    nodes.push_back(j);
  }
  nlohmann::json root;
  root["cloud"] = a.cloud;
  root["sketch"] = a.sketch;
  root["mesh"] = a.out.mesh;
  root["points"] = cloudSize;
  root["seed"] = a.seed;
  root["ringVertices"] = a.ring;
  root["nodes"] = nodes;
  const recon::FitSummary summary = recon::summarizeFits(r.results, r.radii);
  root["fitSummary"] = {{"nodes", summary.nodes},       {"fitted", summary.fitted},
                        {"kept", summary.kept},         {"disabled", summary.disabled},
                        {"inferred", summary.inferred}, {"notFitted", summary.notFitted}};
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
  job.out = a.out;
  job.sketch = a.sketch;
  job.strays = a.outliers;
  job.up = a.up;
  job.leafOn = a.leafOn;
  job.woodOnly = a.woodOnly;
  job.seed = a.seed;
  job.ring = a.ring;
  job.inlierThreshold = a.inlierThreshold;
  job.unitMetres = a.unitMetres == 0.0 ? 1.0 : a.unitMetres;
  job.settings = a.settings;
  const TreeJobResult r = runTreeJob(job);
  std::printf("up axis: %s\n", r.upReason.c_str());
  std::printf("%s of %zu%s\n", cloud::strayPointsLine(r.strays).c_str(), r.points,
              a.outliers.empty() ? "" : (" -> " + a.outliers).c_str());
  std::printf(
      "reconstruct --auto: %zu skeleton nodes (%zu forks), %zu fits accepted, %zu leaf pieces not fitted; "
      "%zu vertices, %zu triangles; skeleton %.1f ms, fit %.1f ms, sweep %.1f ms -> %s\n",
      r.skeletonNodes, r.forks, r.fitsAccepted, r.leafPieces, r.vertices, r.triangles, r.skeletonMs, r.fitMs, r.sweepMs,
      a.out.mesh.c_str());
  printModelSummary(r.measures, a.out);
}

void runReconstruct(const ReconstructArgs& a) {
  if (a.unitMetres != 0.0 && a.out.report.empty() && a.out.metrics.empty())
    throw OptionsError(
        "--units-metres applies to the report's and the metrics' figures: it needs --report or --metrics");
  if (a.autoSkeleton) return runAutoReconstruct(a);
  if (a.sketch.empty()) throw OptionsError("--sketch is required (or --auto)");
  if (!a.up.empty()) throw OptionsError("--up needs --auto (a sketch file carries its own up axis)");
  if (a.leafOn) throw OptionsError("--leaf-on needs --auto (it sets the automatic skeleton's options)");
  if (a.woodOnly) throw OptionsError("--wood-only needs --auto (it chooses the points the automatic model uses)");
  if (!a.settings.empty()) throw OptionsError("--set needs --auto (it changes the automatic model's settings)");
  if (!a.outliers.empty()) throw OptionsError("--outliers needs --auto (a sketch is fitted to every point)");
  const model::OutputPaths& outputs = a.out;
  model::checkOutputs(outputs, {a.cloud, a.sketch});
  recon::ReconstructionOptions opt = recon::sketchReconstructionOptions();  // as the desktop tool fits it
  opt.seed = a.seed;
  opt.sweep.ringVertices = a.ring;
  if (a.inlierThreshold >= 0.0) opt.fit.circle.inlierThreshold = a.inlierThreshold;

  geom::PointCloud cloud = io::readPointCloud(a.cloud);
  cloud::requireUsableExtent(cloud, a.cloud);
  sketch::Sketch sk = io::readSketch(a.sketch);
  if (sk.empty()) throw InputError(a.sketch + ": the sketch has no nodes, expected at least one");
  if (a.refit) sk.clearKeptCircles();

  const recon::ReconstructionResult r = recon::reconstruct(cloud, sk, opt);
  std::size_t fitted = 0, skipped = 0, disabled = 0, kept = 0;
  for (const auto& [id, n] : r.results) {
    fitted += n.status == fit::NodeStatus::Fitted && !n.kept;
    kept += n.kept;
    skipped += n.status == fit::NodeStatus::Skipped;
    disabled += n.status == fit::NodeStatus::Disabled;
  }
  const model::TreeModel tree = model::fromReconstruction(r, sk.up);  // the sketch's up axis
  model::MeasureOptions mo;
  mo.unitMetres = a.unitMetres == 0.0 ? 1.0 : a.unitMetres;
  const model::ModelMeasures measures = model::measure(tree, cloud, mo);
  const bool wantsModel = !a.out.cylinders.empty() || !a.out.qsm.empty() || !a.out.metrics.empty();
  if (fitted + kept > 0 && !(r.mesh.area() > 0))
    throw DegenerateInputError(a.sketch + ": the model made in " + a.cloud + " has zero area (" +
                               std::to_string(fitted + kept) + " circles, all of radius 0?); no mesh written");
  if (fitted + kept == 0) {
    // The report still says why each node failed; no model file is written.
    if (!a.out.report.empty()) {
      model::OutputPaths reportOnly;
      reportOnly.report = a.out.report;
      model::writeOutputs(tree, measures, reportOnly, reportHeader(a, r, cloud.size()));
    }
    throw DegenerateInputError(a.sketch + ": no node could be fitted in " + a.cloud + " (" + std::to_string(skipped) +
                               " skipped, " + std::to_string(disabled) + " disabled); no mesh written" +
                               (a.out.report.empty() ? "" : ", see " + a.out.report));
  }
  const model::FittedShape shape = model::fittedShape(r);
  model::checkFittedShape(shape, a.sketch, a.cloud);
  if (wantsModel && tree.cylinders.empty())
    throw DegenerateInputError(a.sketch + ": only " + std::to_string(fitted + kept) +
                               " node(s) fitted in " + a.cloud +
                               ", no parent-child pair: no cylinder to write; no output written");
  model::writeOutputs(tree, measures, outputs, reportHeader(a, r, cloud.size()));
  std::printf(
      "reconstruct: %zu nodes: %zu fitted, %zu skipped, %zu disabled, %zu kept circles; %zu vertices, %zu "
      "triangles; index %.1f ms, fit %.1f ms, sweep %.1f ms -> %s\n",
      r.results.size(), fitted, skipped, disabled, kept, r.mesh.vertices.size(), r.mesh.triangles.size(),
      r.timings.indexMs, r.timings.fitMs, r.timings.sweepMs, a.out.mesh.c_str());
  if (!shape.unfitted.empty()) {
    std::printf("nodes that did not fit: %s\n", shape.unfittedList().c_str());
    std::printf("fits: %s\n", recon::summarizeFits(r.results, r.radii).text().c_str());
  }
  printModelSummary(measures, outputs);
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
  sub->add_flag("--wood-only", a->woodOnly,
                "With --auto: model only the points the wood/leaf classification calls wood (as `classify` "
                "does), with the leaf-off settings; for the volume of a tree in leaf (its range reaches up to a "
                "model of every point)");
  sub->add_option("--outliers", a->outliers,
                  "With --auto: write the stray points set aside before modelling (far from the tree or isolated) "
                  "to this cloud file (.ply, .xyz)");
  sub->add_option("--cylinders", a->out.cylinders, "Also write the model's cylinder table (.csv)");
  sub->add_option("--qsm", a->out.qsm, "Also write the model's cylinders in TreeQSM's text layout (.txt)");
  sub->add_option("--metrics", a->out.metrics,
                  "Also write the tree metrics (.json: height, DBH, volumes by order, crown, taper)");
  sub->add_option("-o,--output", a->out.mesh, "Output mesh (.obj or .ply)")->required();
  sub->add_option("--report", a->out.report,
                  "Write a JSON report: every node's fit (or the automatic model's counts), and how well the model "
                  "explains the cloud (points within 1/2/5 cm, missed, median signed distance, volume, length, "
                  "trunk diameter at 1.3 m)");
  sub->add_option("--units-metres", a->unitMetres,
                  "With --report or --metrics: metres per cloud unit (default 1)")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--refit", a->refit,
                "Fit every node from the cloud, ignoring the circles the sketch keeps (an automatic sketch's model)");
  sub->add_option("--ring", a->ring, "Vertices per ring (default 16)")->check(CLI::Range(3, 4096));
  sub->add_option("--inlier-threshold", a->inlierThreshold,
                  "RANSAC inlier threshold on |distance to centre - radius|, cloud units (default 0.01)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--seed", a->seed, "Random seed of the circle fits (default 1)");
  addSettingOptions(sub, a->settings);
  sub->callback([a, &action] { action = [a] { runReconstruct(*a); }; });
}

}  // namespace treesketch::cli
