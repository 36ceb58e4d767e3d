// treesketch.reconstruct and treesketch.Model: the automatic pipeline exactly as the CLI's
// `reconstruct --auto` runs it (apps/cli/tree_job.cpp: up axis, skeleton sketch, the library's
// tree model and its measures), its cylinders and mesh as NumPy arrays, and its outputs written by
// the library's one writer (model/tree_model.h). A fitted sketch (sketch.cpp) gives the same Model.
#include "model.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "bindings.h"
#include "treesketch/classify/classify.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/cancel.h"
#include "treesketch/util/error.h"

namespace treesketch::python {

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::shared_ptr<PyModel> reconstruct(const py::object& cloudObj, bool leafOn, bool woodOnly, const py::object& up,
                                     std::uint64_t seed, int ring, const py::object& inlierThreshold, double unitMetres,
                                     const py::object& progressFn) {
  const CloudPtr cloud = cloudObj.cast<CloudPtr>();
  if (!cloud) throw OptionsError("reconstruct: cloud is None");
  const std::string upOption = up.is_none() ? std::string() : up.cast<std::string>();
  const double threshold = inlierThreshold.is_none() ? -1.0 : inlierThreshold.cast<double>();
  auto result = std::make_shared<PyModel>();
  result->source = cloudSource(cloudObj);
  result->unitMetres = unitMetres;
  Progress progress(progressFn);
  {
    py::gil_scoped_release release;
    const auto t0 = std::chrono::steady_clock::now();
    PyModel& t = *result;
    t.points = cloud->size();
    const io::UpAxisChoice choice = io::chooseUpAxis(upOption, *cloud);
    t.upReason = choice.reason;
    // With wood_only the wood points are modelled with the leaf-off settings and the model is
    // measured against every point, as `reconstruct --auto --wood-only`.
    geom::PointCloud woodStore;
    if (woodOnly) woodStore = model::woodOnlyCloud(*cloud, choice.up, t.source);
    const geom::PointCloud& modelled = woodOnly ? woodStore : *cloud;
    auto options = [&](skeleton::Foliage foliage) {
      skeleton::AutoSkeletonOptions o = skeleton::autoSkeletonPreset(foliage, choice.up);
      o.seed = seed;
      o.ringVertices = ring;
      if (threshold >= 0.0) o.fit.circle.inlierThreshold = threshold;
      return o;
    };
    const skeleton::AutoSkeletonOptions opt =
        options(leafOn && !woodOnly ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff);
    skeleton::AutoSkeletonResult s;
    try {
      s = skeleton::autoSkeletonSketch(modelled, opt, progress.function());
    } catch (const Cancelled&) {
      py::gil_scoped_acquire gil;
      progress.rethrowIfFailed();
      throw;
    }
    // The model is made from, and measured against, the points kept (the strays are set aside).
    geom::PointCloud keptStore;
    const geom::PointCloud& kept =
        woodOnly || s.strays.empty() ? *cloud : (keptStore = cloud::keptPoints(*cloud, s.strays));
    model::checkAutoModel(t.source, woodOnly ? modelled : kept, s);
    std::size_t accepted = 0, leafPieces = 0;
    for (char c : s.fitAccepted) accepted += c != 0;
    for (const auto& n : s.model) leafPieces += skeleton::isLeafPiece(n, opt);
    t.counts = {{"points", t.points},
                {"wood_points", woodOnly ? woodStore.size() : 0},
                {"skeleton_nodes", s.model.size()},
                {"forks", skeleton::countBranchPoints(s.model)},
                {"fits_accepted", accepted},
                {"leaf_pieces", leafPieces},
                {"stray_points", s.strays.count()},
                {"ground_points", s.strays.ground},
                {"marked_noise_points", s.strays.markedNoise},
                {"repeated_points", s.strays.repeated},
                {"vertices", s.mesh.vertices.size()},
                {"triangles", s.mesh.triangles.size()}};
    t.reportHeader = {{"cloud", t.source},
                      {"auto", true},
                      {"leafOn", leafOn},
                      {"woodOnly", woodOnly},
                      {"up", geom::toString(choice.up)},
                      {"upReason", t.upReason},
                      {"points", t.points},
                      {"strayPoints", model::strayPointsJson(s.strays)},
                      {"seed", seed},
                      {"skeletonNodes", t.counts["skeleton_nodes"]},
                      {"forks", t.counts["forks"]},
                      {"vertices", t.counts["vertices"]},
                      {"triangles", t.counts["triangles"]}};
    t.timings = {
        {"skeleton_ms", s.skeletonMs}, {"fit_ms", s.fitMs}, {"sweep_ms", s.sweepMs}, {"completion_ms", s.completionMs}};
    const auto tm = std::chrono::steady_clock::now();
    t.tree = model::fromAutoSkeleton(s, choice.up);
    // As the CLI measures it: the fit, the volume's range and the verdict.
    model::MeasureOptions mo = model::autoMeasureOptions(s, opt, leafOn);
    mo.unitMetres = unitMetres;
    mo.woodOnly = woodOnly;
    // The range's ends, as the CLI makes them: a model of every point (wood-only), of the wood (leaf-on).
    if (woodOnly) mo.everyPointVolume = model::everyPointVolume(*cloud, options(skeleton::Foliage::LeafOn), choice.up);
    if (leafOn && !woodOnly)
      mo.classifiedWoodVolume = model::classifiedWoodVolume(*cloud, options(skeleton::Foliage::LeafOff), choice.up);
    model::lookForStems(mo, modelled, choice.up, s.strays);
    t.measures = model::measure(t.tree, kept, mo);
    t.measureOptions = mo;
    t.timings["metrics_ms"] = msSince(tm);
    t.timings["library_ms"] = msSince(t0);
    t.sketch = std::move(s.sketch);
    t.strays = std::move(s.strays);
  }
  return result;
}

/// The cylinder table as columns: the rows and values io::writeCylinderCsv writes.
py::dict cylinderColumns(const PyModel& t) {
  const auto& pieces = t.tree.cylinders.cylinders;
  const auto n = static_cast<py::ssize_t>(pieces.size());
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
  const auto idOf = [&](std::int64_t piece) {
    return static_cast<std::size_t>(piece) < t.tree.ids.size() ? t.tree.ids[static_cast<std::size_t>(piece)] : piece;
  };
  for (py::ssize_t r = 0; r < n; ++r) {
    const auto i = static_cast<std::size_t>(r);
    const geom::ModelCylinder& c = pieces[i];
    idW(r) = idOf(r);
    parentW(r) = c.parent < 0 ? -1 : idOf(c.parent);
    for (int k = 0; k < 3; ++k) {
      startW(r, k) = c.start[k];
      endW(r, k) = c.end[k];
    }
    radiusW(r) = c.endRadius;
    startRadiusW(r) = c.startRadius;
    lengthW(r) = c.length();
    orderW(r) = c.branchOrder;
    measuredW(r) = i < t.tree.measured.size() && t.tree.measured[i] != 0;
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

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// The fit against `cloud` (what a report holds), measured on demand; on the model's own cloud
/// (as many points) without the points it set aside as strays, as the CLI's report measures it.
model::ModelMeasures measuredWithFit(const PyModel& t, const geom::PointCloud& cloud, double unitMetres) {
  model::MeasureOptions mo = t.measureOptions;
  mo.unitMetres = unitMetres;
  mo.fit = true;
  if (!t.strays.empty() && cloud.size() == t.points) return model::measure(t.tree, cloud::keptPoints(cloud, t.strays), mo);
  return model::measure(t.tree, cloud, mo);
}

/// Writes one output through the library's writer; `kind` "" = by the extension.
void writeOutput(const PyModel& t, const std::string& path, std::string kind, const CloudPtr& cloud) {
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
  model::OutputPaths paths;
  if (kind == "mesh")
    paths.mesh = path;
  else if (kind == "cylinders")
    paths.cylinders = path;
  else if (kind == "qsm")
    paths.qsm = path;
  else if (kind == "metrics")
    paths.metrics = path;
  else if (kind == "report")
    paths.report = path;
  else if (kind != "sketch")
    throw OptionsError("write: kind '" + kind + "' unknown, expected mesh, cylinders, qsm, sketch, metrics or report");
  if (kind == "report" && !cloud) throw OptionsError("write: a report needs the cloud (cloud=)");
  py::gil_scoped_release release;
  if (kind == "sketch") return io::writeSketch(std::filesystem::path(path), t.sketch);
  model::checkOutputs(paths, {});
  if (kind == "report") {
    return model::writeOutputs(t.tree, measuredWithFit(t, *cloud, t.unitMetres), paths, t.reportHeader);
  }
  model::writeOutputs(t.tree, t.measures, paths);
}

}  // namespace

std::string cloudSource(const py::object& cloud) {
  return py::hasattr(cloud, "source") ? cloud.attr("source").cast<std::string>() : std::string("cloud");
}

void bindModel(py::module_& m) {
  py::class_<PyModel, std::shared_ptr<PyModel>>(
      m, "Model",
      "A tree model (the library's model::TreeModel): cylinders, mesh, editable sketch, metrics. Made by "
      "reconstruct() or Reconstruction.model().")
      .def_property_readonly("cylinders", &cylinderColumns,
                             "The cylinder table as NumPy columns, the rows and values of the CLI's --cylinders CSV "
                             "(one per piece, parents first): id, parent (the parent piece's id, -1 for none), "
                             "start and end (M x 3), radius (at the end), start_radius, length, branch_order (0 = "
                             "stem), measured (True where the piece's end rests on a fitted circle, False where its "
                             "radius was inferred).")
      .def(
          "mesh", [](const PyModel& t) { return meshToArrays(t.tree.mesh); },
          "The swept tube mesh: (vertices N x 3 float64, faces M x 3 uint32).")
      .def(
          "metrics", [](const PyModel& t) { return fromJson(compare::toJson(t.measures.metrics)); },
          "The forestry metrics (height, DBH from the model and from the cloud, crown, volumes by order, taper) "
          "as the CLI's --metrics JSON: metres, m², m³, None for NaN.")
      .def(
          "metrics_table", [](const PyModel& t) { return compare::metricsTable(t.measures.metrics); },
          "The metrics as the CLI prints them.")
      .def_property_readonly(
          "taper",
          [](const PyModel& t) {
            const auto& taper = t.measures.metrics.taper;
            const auto n = static_cast<py::ssize_t>(taper.size());
            py::array_t<double> h(n), d(n);
            for (py::ssize_t i = 0; i < n; ++i) {
              h.mutable_at(i) = taper[static_cast<std::size_t>(i)].height;
              d.mutable_at(i) = taper[static_cast<std::size_t>(i)].diameter;
            }
            return py::make_tuple(h, d);
          },
          "The stem's taper: (heights above the base, diameters), metres; a diameter is NaN where no stem piece "
          "crosses that height.")
      .def(
          "fit_report",
          [](const PyModel& t, const CloudPtr& cloud, const py::object& unitMetres) {
            if (!cloud) throw OptionsError("fit_report: cloud is None");
            const double u = unitMetres.is_none() ? t.unitMetres : unitMetres.cast<double>();
            nlohmann::json j;
            {
              py::gil_scoped_release release;
              const model::ModelMeasures mm = measuredWithFit(t, *cloud, u);
              j = model::reportJson(mm, nlohmann::json::object())["model"];
              j["summary"] = mm.summary();
            }
            return fromJson(j);
          },
          py::arg("cloud"), py::arg("unit_metres") = py::none(),
          "How well the model explains `cloud` (points within 1/2/5 cm, missed, median signed distance), its "
          "figures (volume, length, trunk diameter) and the measured share of its volume: the 'model' part of "
          "the CLI's --report, and its summary line. unit_metres: None = the model's.")
      .def("write", &writeOutput, py::arg("path"), py::arg("kind") = "", py::arg("cloud") = nullptr,
           "Writes one output, atomically, with the library's writer (the CLI's): by extension .obj/.ply the "
           "mesh, .csv the cylinder table, .txt the TreeQSM table, .json the editable sketch; kind= 'mesh', "
           "'cylinders', 'qsm', 'sketch', 'metrics' (the --metrics JSON) or 'report' (the --report JSON, with "
           "cloud=) overrides the extension.")
      .def_property_readonly(
          "sketch", [](const PyModel& t) { return t.sketch; },
          "The model's sketch (a copy): the automatic model's keeps every node's model circle; edit it and fit "
          "it again with Reconstruction.")
      .def_property_readonly(
          "up", [](const PyModel& t) { return std::string(geom::toString(t.tree.up)); }, "The up axis used.")
      .def_property_readonly(
          "up_reason", [](const PyModel& t) { return t.upReason; }, "Why that up axis (as the CLI prints it).")
      .def_property_readonly(
          "summary",
          [](const PyModel& t) {
            nlohmann::json j = t.counts;
            for (const auto& [k, v] : t.timings.items()) j[k] = v;
            return fromJson(j);
          },
          "Counts and wall times (ms) of the run; library_ms is the whole library call, measured in C++.")
      .def("__repr__", [](const PyModel& t) {
        return "<treesketch.Model of " + t.source + ": " + std::to_string(t.tree.cylinders.size()) + " cylinders>";
      });

  m.def("reconstruct", &reconstruct, py::arg("cloud"), py::kw_only(), py::arg("leaf_on") = false,
        py::arg("wood_only") = false, py::arg("up") = py::none(), py::arg("seed") = 1, py::arg("ring") = 16,
        py::arg("inlier_threshold") = py::none(), py::arg("unit_metres") = 1.0, py::arg("progress") = py::none(),
        "The automatic model of a tree cloud, as `treesketch reconstruct CLOUD --auto` makes it: skeleton, a "
        "circle fit per node, regularised radii, tube mesh, metrics. up: 'y' or 'z' (None: what the file "
        "declares, else z); leaf_on: the tree was scanned in leaf; wood_only: model only the points the wood/leaf "
        "classification calls wood, with the leaf-off settings, measured against every point (as --wood-only); "
        "ring: vertices per ring; inlier_threshold: the fits' RANSAC band in cloud units (None: the library's); unit_metres: metres per cloud unit for the "
        "metrics. progress(done, total) is called during the work (from worker threads, with the GIL held); an "
        "exception it raises stops the work and is raised here. The GIL is released while the library works. "
        "Raises DegenerateInputError when no model can be made (no skeleton, no circle), OptionsError for bad "
        "options.");
}

}  // namespace treesketch::python
