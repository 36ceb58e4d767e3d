// One tree through the automatic pipeline (see tree_job.h).
#include "tree_job.h"

#include <chrono>
#include <cstdio>

#include "treesketch/compare/model_fit.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/skeleton/skeleton_export.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void writeJson(const std::string& path, const nlohmann::json& j) {
  const std::string text = j.dump(2) + "\n";
  writeFileAtomically(
      path, [&](std::ostream& os) { os << text; }, false);
}

/// A model is made only from a fitted circle: a cloud whose points are all equal, on one line or
/// too few for a circle gives none, and a tube swept without one (or of zero area) is no success.
void checkAutoModel(const TreeJob& a, const geom::PointCloud& cloud, const skeleton::AutoSkeletonResult& r) {
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

}  // namespace

TreeJobResult runTreeJob(const TreeJob& a) {
  const auto t0 = std::chrono::steady_clock::now();
  for (const std::string* out : {&a.mesh, &a.sketch, &a.cylinders, &a.qsm, &a.metrics, &a.report})
    if (!out->empty()) checkNotAnInput(*out, {a.cloud});
  for (const std::string* out : {&a.mesh, &a.sketch, &a.cylinders, &a.qsm, &a.metrics, &a.report})
    if (!out->empty()) checkOutputWritable(*out);
  try {
    io::meshFormatFromPath(a.mesh);
  } catch (const InputError& e) {
    throw OptionsError(std::string("-o: ") + e.what());
  }
  TreeJobResult r;
  const geom::PointCloud cloud = io::readPointCloud(a.cloud);
  r.points = cloud.size();
  r.readMs = msSince(t0);
  const io::UpAxisChoice up = io::chooseUpAxis(a.up, cloud);
  r.up = geom::toString(up.up);
  r.upReason = up.reason;

  skeleton::AutoSkeletonOptions opt =
      skeleton::autoSkeletonPreset(a.leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, up.up);
  opt.seed = a.seed;
  opt.ringVertices = a.ring;
  if (a.inlierThreshold >= 0.0) opt.fit.circle.inlierThreshold = a.inlierThreshold;
  const skeleton::AutoSkeletonResult s = skeleton::autoSkeletonSketch(cloud, opt);
  checkAutoModel(a, cloud, s);
  r.skeletonMs = s.skeletonMs;
  r.fitMs = s.fitMs;
  r.sweepMs = s.sweepMs;
  r.skeletonNodes = s.model.size();
  r.forks = skeleton::countBranchPoints(s.model);
  for (char c : s.fitAccepted) r.fitsAccepted += c != 0;
  for (const auto& n : s.model) r.leafPieces += skeleton::isLeafPiece(n, opt);
  r.vertices = s.mesh.vertices.size();
  r.triangles = s.mesh.triangles.size();

  const auto tm = std::chrono::steady_clock::now();
  const geom::CylinderModel model = skeleton::cylinderModelFromSkeleton(s.model);
  compare::TreeMetricsOptions mo;
  mo.unitMetres = a.unitMetres;
  r.metrics = compare::treeMetrics(model, up.up, mo, &cloud);
  r.metricsMs = msSince(tm);

  // The mesh is written last of the model files, the report last of all: a batch's done marker
  // comes after them, so their presence says the tree is complete.
  if (!a.sketch.empty()) io::writeSketch(std::filesystem::path(a.sketch), s.sketch);
  if (!a.cylinders.empty()) skeleton::writeCylinderCsv(a.cylinders, s.model);
  if (!a.qsm.empty()) io::writeTreeQsmCylinders(a.qsm, model, up.up);
  io::writeMesh(a.mesh, s.mesh);
  if (!a.metrics.empty()) writeJson(a.metrics, compare::toJson(r.metrics));
  if (!a.report.empty()) {
    compare::ModelFitOptions fo;
    fo.unitMetres = a.unitMetres;
    const compare::ModelFitReport fit = compare::measureModelFit(cloud, model, fo);
    const compare::ModelFigures fig = compare::modelFigures(model, up.up, a.unitMetres);
    r.fitSummary = compare::summaryLine(fit) + "; " + compare::summaryLine(fig);
    nlohmann::json j;
    j["cloud"] = a.cloud;
    j["mesh"] = a.mesh;
    j["auto"] = true;
    j["leafOn"] = a.leafOn;
    j["up"] = r.up;
    j["upReason"] = r.upReason;
    j["points"] = r.points;
    j["seed"] = a.seed;
    j["skeletonNodes"] = r.skeletonNodes;
    j["forks"] = r.forks;
    j["vertices"] = r.vertices;
    j["triangles"] = r.triangles;
    j["timings"] = {{"readMs", r.readMs},
                    {"skeletonMs", r.skeletonMs},
                    {"fitMs", r.fitMs},
                    {"sweepMs", r.sweepMs},
                    {"metricsMs", r.metricsMs}};
    j["model"] = {{"fit", compare::toJson(fit)}, {"figures", compare::toJson(fig)}};
    j["metrics"] = compare::toJson(r.metrics);
    writeJson(a.report, j);
  }
  r.totalMs = msSince(t0);
  return r;
}

}  // namespace treesketch::cli
