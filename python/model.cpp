// treesketch.reconstruct and treesketch.Model: the automatic pipeline exactly as the CLI's
// `reconstruct --auto` runs it (apps/cli/tree_job.cpp: up axis, skeleton sketch, cylinder model,
// metrics with the cloud), its cylinders and mesh as NumPy arrays and its outputs written by the
// same library writers.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "bindings.h"
#include "treesketch/compare/model_fit.h"
#include "treesketch/compare/tree_metrics.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/skeleton/skeleton_export.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/cancel.h"
#include "treesketch/util/error.h"

namespace treesketch::python {

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// A tree model from the automatic pipeline, with what it was made from.
struct TreeModel {
  skeleton::AutoSkeletonResult result;
  geom::CylinderModel cylinders;  ///< cylinderModelFromSkeleton(result.model)
  geom::UpAxis up = geom::UpAxis::Z;
  std::string upReason;
  compare::TreeMetrics metrics;  ///< with the cloud, as the CLI's metrics and report
  std::string source;
  std::size_t points = 0;
  bool leafOn = false;
  std::uint64_t seed = 1;
  std::size_t forks = 0, fitsAccepted = 0, leafPieces = 0;
  double metricsMs = 0, libraryMs = 0;
};

/// The CLI's checks of an automatic model (tree_job.cpp), with the same messages.
void checkAutoModel(const std::string& source, const geom::PointCloud& cloud, const skeleton::AutoSkeletonResult& r) {
  std::size_t accepted = 0;
  for (char c : r.fitAccepted) accepted += c != 0;
  char what[512];
  std::snprintf(what, sizeof what, "%s (%zu points, bounding-box diagonal %.6g)", source.c_str(), cloud.size(),
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

std::string cloudSource(const py::object& cloud) {
  return py::hasattr(cloud, "source") ? cloud.attr("source").cast<std::string>() : std::string("cloud");
}

std::shared_ptr<TreeModel> reconstruct(const py::object& cloudObj, bool leafOn, const py::object& up,
                                       std::uint64_t seed, int ring, const py::object& inlierThreshold,
                                       double unitMetres, const py::object& progressFn) {
  const CloudPtr cloud = cloudObj.cast<CloudPtr>();
  if (!cloud) throw OptionsError("reconstruct: cloud is None");
  const std::string upOption = up.is_none() ? std::string() : up.cast<std::string>();
  const double threshold = inlierThreshold.is_none() ? -1.0 : inlierThreshold.cast<double>();
  auto model = std::make_shared<TreeModel>();
  model->source = cloudSource(cloudObj);
  model->leafOn = leafOn;
  model->seed = seed;
  Progress progress(progressFn);
  {
    py::gil_scoped_release release;
    const auto t0 = std::chrono::steady_clock::now();
    TreeModel& t = *model;
    t.points = cloud->size();
    const io::UpAxisChoice choice = io::chooseUpAxis(upOption, *cloud);
    t.up = choice.up;
    t.upReason = choice.reason;
    skeleton::AutoSkeletonOptions opt =
        skeleton::autoSkeletonPreset(leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, t.up);
    opt.seed = seed;
    opt.ringVertices = ring;
    if (threshold >= 0.0) opt.fit.circle.inlierThreshold = threshold;
    try {
      t.result = skeleton::autoSkeletonSketch(*cloud, opt, progress.function());
    } catch (const Cancelled&) {
      py::gil_scoped_acquire gil;
      progress.rethrowIfFailed();
      throw;
    }
    checkAutoModel(t.source, *cloud, t.result);
    t.forks = skeleton::countBranchPoints(t.result.model);
    for (char c : t.result.fitAccepted) t.fitsAccepted += c != 0;
    for (const auto& n : t.result.model) t.leafPieces += skeleton::isLeafPiece(n, opt);
    const auto tm = std::chrono::steady_clock::now();
    t.cylinders = skeleton::cylinderModelFromSkeleton(t.result.model);
    compare::TreeMetricsOptions mo;
    mo.unitMetres = unitMetres;
    t.metrics = compare::treeMetrics(t.cylinders, t.up, mo, cloud.get());
    t.metricsMs = msSince(tm);
    t.libraryMs = msSince(t0);
  }
  return model;
}

/// The cylinder table as columns, the rows and values of skeleton::writeCylinderCsv.
py::dict cylinderColumns(const TreeModel& t) {
  const auto& nodes = t.result.model;
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].parent >= 0) rows.push_back(i);
  const auto n = static_cast<py::ssize_t>(rows.size());
  py::array_t<std::int64_t> id(n), parent(n);
  py::array_t<double> start({n, py::ssize_t{3}}), end({n, py::ssize_t{3}}), radius(n), startRadius(n), length(n);
  py::array_t<std::int32_t> order(n);
  py::array_t<bool> measured(n);
  auto idW = id.mutable_unchecked<1>();
  auto parentW = parent.mutable_unchecked<1>();
  auto startW = start.mutable_unchecked<2>();
  auto endW = end.mutable_unchecked<2>();
  auto radiusW = radius.mutable_unchecked<1>();
  auto startRadiusW = startRadius.mutable_unchecked<1>();
  auto lengthW = length.mutable_unchecked<1>();
  auto orderW = order.mutable_unchecked<1>();
  auto measuredW = measured.mutable_unchecked<1>();
  for (py::ssize_t r = 0; r < n; ++r) {
    const std::size_t i = rows[static_cast<std::size_t>(r)];
    const auto& c = nodes[i];
    const auto& p = nodes[static_cast<std::size_t>(c.parent)];
    idW(r) = static_cast<std::int64_t>(i);
    parentW(r) = p.parent < 0 ? -1 : c.parent;
    for (int k = 0; k < 3; ++k) {
      startW(r, k) = p.position[k];
      endW(r, k) = c.position[k];
    }
    radiusW(r) = c.radius;
    startRadiusW(r) = t.cylinders.cylinders[static_cast<std::size_t>(r)].startRadius;
    lengthW(r) = (c.position - p.position).norm();
    orderW(r) = c.branchOrder;
    measuredW(r) = i < t.result.fitAccepted.size() && t.result.fitAccepted[i] != 0;
  }
  py::dict d;
  d["id"] = id;
  d["parent"] = parent;
  d["start"] = start;
  d["end"] = end;
  d["radius"] = radius;
  d["length"] = length;
  d["branch_order"] = order;
  d["start_radius"] = startRadius;
  d["measured"] = measured;
  return d;
}

void writeJsonFile(const std::string& path, const nlohmann::json& j) {
  const std::string text = j.dump(2) + "\n";
  writeFileAtomically(
      path, [&](std::ostream& os) { os << text; }, false);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// Writes one output of the model; `kind` "" = by the extension.
void writeOutput(const TreeModel& t, const std::string& path, std::string kind) {
  if (kind.empty()) {
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    if (ext == ".obj" || ext == ".ply")
      kind = "mesh";
    else if (ext == ".csv")
      kind = "cylinders";
    else if (ext == ".txt")
      kind = "qsm";
    else if (ext == ".json")
      kind = "sketch";
    else
      throw OptionsError(path + ": unknown output extension '" + ext +
                         "', expected .obj or .ply (mesh), .csv (cylinder table), .txt (TreeQSM table), .json "
                         "(sketch); or give kind=");
  }
  py::gil_scoped_release release;
  if (kind == "mesh")
    io::writeMesh(path, t.result.mesh);
  else if (kind == "cylinders")
    skeleton::writeCylinderCsv(path, t.result.model);
  else if (kind == "qsm")
    io::writeTreeQsmCylinders(path, t.cylinders, t.up);
  else if (kind == "sketch")
    io::writeSketch(std::filesystem::path(path), t.result.sketch);
  else if (kind == "metrics")
    writeJsonFile(path, compare::toJson(t.metrics));
  else
    throw OptionsError("write: kind '" + kind + "' unknown, expected mesh, cylinders, qsm, sketch or metrics");
}

}  // namespace

void bindModel(py::module_& m) {
  py::class_<TreeModel, std::shared_ptr<TreeModel>>(
      m, "Model", "A tree model made by reconstruct(): cylinders, mesh, editable sketch, metrics.")
      .def_property_readonly("cylinders", &cylinderColumns,
                             "The cylinder table as NumPy columns, the rows and values of the CLI's --cylinders CSV "
                             "(one per non-root skeleton node): id, parent (the parent row's id, -1 at the root), "
                             "start and end (M x 3), radius (at the end), start_radius, length, branch_order (0 = "
                             "stem), measured (True where a circle fit was accepted at the node, False where the "
                             "radius was inferred along the branch).")
      .def(
          "mesh", [](const TreeModel& t) { return meshToArrays(t.result.mesh); },
          "The swept tube mesh: (vertices N x 3 float64, faces M x 3 uint32).")
      .def(
          "metrics", [](const TreeModel& t) { return fromJson(compare::toJson(t.metrics)); },
          "The forestry metrics (height, DBH from the model and from the cloud, crown, volumes by order, taper) "
          "as the CLI's metrics JSON: metres, m², m³, None for NaN.")
      .def(
          "metrics_table", [](const TreeModel& t) { return compare::metricsTable(t.metrics); },
          "The metrics as the CLI prints them.")
      .def_property_readonly(
          "taper",
          [](const TreeModel& t) {
            const auto n = static_cast<py::ssize_t>(t.metrics.taper.size());
            py::array_t<double> h(n), d(n);
            for (py::ssize_t i = 0; i < n; ++i) {
              h.mutable_at(i) = t.metrics.taper[static_cast<std::size_t>(i)].height;
              d.mutable_at(i) = t.metrics.taper[static_cast<std::size_t>(i)].diameter;
            }
            return py::make_tuple(h, d);
          },
          "The stem's taper: (heights above the base, diameters), metres; a diameter is NaN where no stem piece "
          "crosses that height.")
      .def(
          "fit_report",
          [](const TreeModel& t, const CloudPtr& cloud, double unitMetres) {
            if (!cloud) throw OptionsError("fit_report: cloud is None");
            nlohmann::json j;
            {
              py::gil_scoped_release release;
              compare::ModelFitOptions fo;
              fo.unitMetres = unitMetres;
              const compare::ModelFitReport fit = compare::measureModelFit(*cloud, t.cylinders, fo);
              const compare::ModelFigures fig = compare::modelFigures(t.cylinders, t.up, unitMetres);
              j = {{"fit", compare::toJson(fit)},
                   {"figures", compare::toJson(fig)},
                   {"summary", compare::summaryLine(fit) + "; " + compare::summaryLine(fig)}};
            }
            return fromJson(j);
          },
          py::arg("cloud"), py::arg("unit_metres") = 1.0,
          "How well the model explains `cloud` (points within 1/2/5 cm, missed, median signed distance) and its "
          "figures (volume, length, trunk diameter): the 'model' part of the CLI's --report, and its summary line.")
      .def("write", &writeOutput, py::arg("path"), py::arg("kind") = "",
           "Writes one output, atomically, with the CLI's writers: by extension .obj/.ply the mesh, .csv the "
           "cylinder table, .txt the TreeQSM table, .json the editable sketch; kind= 'mesh', 'cylinders', 'qsm', "
           "'sketch' or 'metrics' (the metrics JSON) overrides the extension.")
      .def_property_readonly(
          "sketch", [](const TreeModel& t) { return t.result.sketch; },
          "The model as an editable Sketch (a copy): every node keeps its model circle; fit it again with "
          "Reconstruction.")
      .def_property_readonly(
          "up", [](const TreeModel& t) { return std::string(geom::toString(t.up)); }, "The up axis used.")
      .def_property_readonly(
          "up_reason", [](const TreeModel& t) { return t.upReason; }, "Why that up axis (as the CLI prints it).")
      .def_property_readonly(
          "summary",
          [](const TreeModel& t) {
            const auto& r = t.result;
            py::dict d;
            d["points"] = t.points;
            d["skeleton_nodes"] = r.model.size();
            d["forks"] = t.forks;
            d["fits_accepted"] = t.fitsAccepted;
            d["leaf_pieces"] = t.leafPieces;
            d["vertices"] = r.mesh.vertices.size();
            d["triangles"] = r.mesh.triangles.size();
            d["skeleton_ms"] = r.skeletonMs;
            d["fit_ms"] = r.fitMs;
            d["sweep_ms"] = r.sweepMs;
            d["completion_ms"] = r.completionMs;
            d["metrics_ms"] = t.metricsMs;
            d["library_ms"] = t.libraryMs;
            return d;
          },
          "Counts and wall times (ms) of the run; library_ms is the whole library call, measured in C++.")
      .def("__repr__", [](const TreeModel& t) {
        return "<treesketch.Model of " + t.source + ": " + std::to_string(t.cylinders.size()) + " cylinders>";
      });

  m.def("reconstruct", &reconstruct, py::arg("cloud"), py::kw_only(), py::arg("leaf_on") = false,
        py::arg("up") = py::none(), py::arg("seed") = 1, py::arg("ring") = 16, py::arg("inlier_threshold") = py::none(),
        py::arg("unit_metres") = 1.0, py::arg("progress") = py::none(),
        "The automatic model of a tree cloud, as `treesketch reconstruct CLOUD --auto` makes it: skeleton, a "
        "circle fit per node, regularised radii, tube mesh, metrics. up: 'y' or 'z' (None: what the file "
        "declares, else z); leaf_on: the tree was scanned in leaf; ring: vertices per ring; inlier_threshold: "
        "the fits' RANSAC band in cloud units (None: the library's); unit_metres: metres per cloud unit for the "
        "metrics. progress(done, total) is called during the work (from worker threads, with the GIL held); an "
        "exception it raises stops the work and is raised here. The GIL is released while the library works. "
        "Raises DegenerateInputError when no model can be made (no skeleton, no circle), OptionsError for bad "
        "options.");
}

}  // namespace treesketch::python
