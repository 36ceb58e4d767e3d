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
#include "treesketch/compare/model_fit.h"
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
  std::string up = "y", cylinders;  // --up, --cylinders (with --auto)
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

/// A model is made only from a fitted circle: a cloud whose points are all equal, on one line or
/// too few for a circle gives none, and a tube swept without one (or of zero area) is no success.
void checkAutoModel(const ReconstructArgs& a, const geom::PointCloud& cloud, const skeleton::AutoSkeletonResult& r) {
  std::size_t accepted = 0;
  for (char c : r.fitAccepted) accepted += c != 0;
  char what[512];
  std::snprintf(what, sizeof what, "%s (%zu points, bounding-box diagonal %.6g)", a.cloud.c_str(), cloud.size(),
                cloud.bounds().diagonal());
  if (r.mesh.empty() || r.model.empty())
    throw DegenerateInputError(std::string(what) + ": no skeleton found; no mesh written");
  if (accepted == 0)
    throw DegenerateInputError(std::string(what) + ": no circle could be fitted at any of the " +
                               std::to_string(r.model.size()) +
                               " skeleton nodes (points all equal, on a line, or too few?); no mesh written");
  if (!(r.mesh.area() > 0))
    throw DegenerateInputError(std::string(what) + ": the model has zero area; no mesh written");
}

/// --auto: skeleton → sketch → fits → regularised radii → mesh; the sketch is saved to --sketch
/// (when given) for refining, the cylinder table to --cylinders.
void runAutoReconstruct(const ReconstructArgs& a) {
  checkNotAnInput(a.output, {a.cloud});
  if (!a.sketch.empty()) checkNotAnInput(a.sketch, {a.cloud});
  if (!a.report.empty()) checkNotAnInput(a.report, {a.cloud});
  for (const std::string& out : {a.output, a.sketch, a.report, a.cylinders}) checkOutputWritable(out);
  if (a.refit) throw OptionsError("--refit applies to a sketch file (--sketch without --auto)");
  try {
    io::meshFormatFromPath(a.output);
  } catch (const InputError& e) {
    throw OptionsError(std::string("-o: ") + e.what());
  }
  skeleton::AutoSkeletonOptions opt = skeleton::autoSkeletonPreset(
      a.leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, geom::parseUpAxis(a.up));
  opt.seed = a.seed;
  opt.ringVertices = a.ring;
  if (a.inlierThreshold >= 0.0) opt.fit.circle.inlierThreshold = a.inlierThreshold;
  geom::PointCloud cloud = io::readPointCloud(a.cloud);
  if (cloud.empty()) throw InputError(a.cloud + ": the cloud has no points");
  skeleton::AutoSkeletonResult r = skeleton::autoSkeletonSketch(cloud, opt);
  checkAutoModel(a, cloud, r);
  io::writeMesh(a.output, r.mesh);
  if (!a.sketch.empty()) io::writeSketch(std::filesystem::path(a.sketch), r.sketch);
  if (!a.cylinders.empty()) skeleton::writeCylinderCsv(a.cylinders, r.model);
  std::string fitSummary;
  if (!a.report.empty()) {
    const geom::CylinderModel model = skeleton::cylinderModelFromSkeleton(r.model);
    nlohmann::json j;
    j["cloud"] = a.cloud;
    j["mesh"] = a.output;
    j["auto"] = true;
    j["leafOn"] = a.leafOn;
    j["up"] = geom::toString(opt.skeleton.up);
    j["points"] = cloud.size();
    j["seed"] = a.seed;
    j["skeletonNodes"] = r.model.size();
    j["forks"] = skeleton::countBranchPoints(r.model);
    j["vertices"] = r.mesh.vertices.size();
    j["triangles"] = r.mesh.triangles.size();
    j["timings"] = {{"skeletonMs", r.skeletonMs}, {"fitMs", r.fitMs}, {"sweepMs", r.sweepMs}};
    j["model"] = measureModel(cloud, model, opt.skeleton.up, a.unitMetres, &fitSummary);
    const std::string text = j.dump(2) + "\n";
    writeFileAtomically(
        a.report, [&](std::ostream& os) { os << text; }, false);
  }
  std::size_t accepted = 0, leaf = 0;
  for (char c : r.fitAccepted) accepted += c != 0;
  for (const auto& n : r.model) leaf += skeleton::isLeafPiece(n, opt);
  std::printf(
      "reconstruct --auto: %zu skeleton nodes (%zu forks), %zu fits accepted, %zu leaf pieces not fitted; "
      "%zu vertices, %zu triangles; skeleton %.1f ms, fit %.1f ms, sweep %.1f ms -> %s\n",
      r.model.size(), skeleton::countBranchPoints(r.model), accepted, leaf, r.mesh.vertices.size(),
      r.mesh.triangles.size(), r.skeletonMs, r.fitMs, r.sweepMs, a.output.c_str());
  if (!a.report.empty()) std::printf("model fit: %s -> %s\n", fitSummary.c_str(), a.report.c_str());
}

void runReconstruct(const ReconstructArgs& a) {
  if (a.unitMetres != 0.0 && a.report.empty())
    throw OptionsError("--units-metres applies to the report's figures: it needs --report");
  if (a.autoSkeleton) return runAutoReconstruct(a);
  if (a.sketch.empty()) throw OptionsError("--sketch is required (or --auto)");
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
    j["model"] = measureModel(cloud, sketchModel(r), sk.up, a.unitMetres, &fitSummary);  // the sketch's up
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
  sub->add_option("cloud", a->cloud, "Point cloud (.ply .xyz .txt .csv .pts .las)")->required();
  sub->add_option("--sketch", a->sketch, "Sketch file (.json); with --auto, where to save the automatic sketch");
  sub->add_flag("--auto", a->autoSkeleton, "Sketch automatically from the cloud's branching skeleton");
  sub->add_option("--up", a->up, "With --auto: world up axis, y or z (default y)")
      ->check(CLI::IsMember({"y", "z", "Y", "Z"}));
  sub->add_flag("--leaf-on", a->leafOn,
                "With --auto: the tree was scanned in leaf (finer voxels, weaker foliage rule)");
  sub->add_option("--cylinders", a->cylinders, "With --auto: also write the cylinder table (.csv)");
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
