// The sketch path from Python: a Sketch (read, edited, written) and a Reconstruction that fits it
// to a cloud and, after an edit, re-fits only the nodes the edit touched (recon/reconstruction.h).
#include "treesketch/sketch/sketch.h"

#include <optional>

#include "bindings.h"
#include "model.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/util/cancel.h"
#include "treesketch/util/error.h"

namespace treesketch::python {

namespace {

geom::Vec3 toVec3(const py::handle& v, const std::string& what) {
  const auto a = v.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
  if (a.size() != 3) throw OptionsError(what + ": expected 3 numbers");
  const geom::Vec3 p(a.data()[0], a.data()[1], a.data()[2]);
  if (!p.allFinite()) throw OptionsError(what + ": NaN or infinite coordinate");
  return p;
}

py::array_t<double> fromVec3(const geom::Vec3& v) {
  py::array_t<double> a(3);
  for (int k = 0; k < 3; ++k) a.mutable_at(k) = v[k];
  return a;
}

py::dict nodeDict(const sketch::Node& n) {
  py::dict d;
  d["id"] = n.id;
  d["parent"] = n.parent;
  d["children"] = n.children;
  d["point_node"] = !n.isScreenNode();
  if (!n.isScreenNode()) {
    d["point"] = fromVec3(n.point);
    d["normal"] = fromVec3(n.normal);
  }
  d["enabled"] = n.params.enabled;
  d["slice_half_thickness"] = n.params.sliceHalfThickness;
  d["line_epsilon"] = n.params.lineEpsilon;
  if (n.kept) {
    d["kept_centre"] = fromVec3(n.kept->centre);
    d["kept_radius"] = n.kept->radius;
  } else {
    d["kept_centre"] = py::none();
    d["kept_radius"] = py::none();
  }
  return d;
}

recon::ReconstructionOptions reconstructionOptions(std::uint64_t seed, int ring, const py::object& inlierThreshold) {
  recon::ReconstructionOptions o = recon::sketchReconstructionOptions();  // as `reconstruct --sketch`
  o.seed = seed;
  o.sweep.ringVertices = ring;
  if (!inlierThreshold.is_none()) o.fit.circle.inlierThreshold = inlierThreshold.cast<double>();
  return o;
}

/// A Reconstruction bound to Python: the library's, the cloud (for the model's measures) and the
/// sketch last given to update.
struct PyReconstruction {
  std::unique_ptr<recon::Reconstruction> recon;
  CloudPtr cloud;
  std::string source;
  sketch::Sketch sketch;
  bool updated = false;
};

std::unique_ptr<PyReconstruction> makeReconstruction(const py::object& cloudObj, std::uint64_t seed, int ring,
                                                     const py::object& inlierThreshold) {
  const CloudPtr cloud = cloudObj.cast<CloudPtr>();
  if (!cloud) throw OptionsError("Reconstruction: cloud is None");
  const recon::ReconstructionOptions o = reconstructionOptions(seed, ring, inlierThreshold);
  auto r = std::make_unique<PyReconstruction>();
  r->cloud = cloud;
  r->source = cloudSource(cloudObj);
  py::gil_scoped_release release;
  r->recon = std::make_unique<recon::Reconstruction>(*cloud, o);
  return r;
}

std::vector<sketch::NodeId> update(PyReconstruction& r, const sketch::Sketch& sk, const py::object& progressFn) {
  Progress progress(progressFn);
  try {
    py::gil_scoped_release release;
    std::vector<sketch::NodeId> changed = r.recon->update(sk, progress.function());
    r.sketch = sk;
    r.updated = true;
    return changed;
  } catch (const Cancelled&) {
    progress.rethrowIfFailed();
    throw;
  }
}

/// The fitted sketch as a Model, as `reconstruct --sketch` makes it (model::fromReconstruction,
/// measured with the cloud).
std::shared_ptr<PyModel> sketchModel(const PyReconstruction& r, double unitMetres) {
  if (!r.updated) throw OptionsError("Reconstruction.model: no sketch yet (call update first)");
  auto m = std::make_shared<PyModel>();
  py::gil_scoped_release release;
  const recon::ReconstructionResult res = r.recon->result(r.sketch);
  std::size_t fitted = 0, skipped = 0, disabled = 0;
  for (const auto& [id, n] : res.results) {
    fitted += n.status == fit::NodeStatus::Fitted;
    skipped += n.status == fit::NodeStatus::Skipped;
    disabled += n.status == fit::NodeStatus::Disabled;
  }
  if (fitted == 0)
    throw DegenerateInputError("the sketch: no node could be fitted in " + r.source + " (" + std::to_string(skipped) +
                               " skipped, " + std::to_string(disabled) + " disabled); no model");
  model::checkFittedShape(model::fittedShape(res), "the sketch", r.source);  // as `reconstruct --sketch`
  m->tree = model::fromReconstruction(res, r.sketch.up);  // the sketch's up axis
  model::MeasureOptions mo;
  mo.unitMetres = unitMetres;
  mo.fit = false;
  m->measures = model::measure(m->tree, *r.cloud, mo);
  m->measureOptions = mo;
  m->sketch = r.sketch;
  m->source = r.source;
  m->upReason = std::string("the sketch's up axis, ") + geom::toString(r.sketch.up);
  m->points = r.cloud->size();
  m->unitMetres = unitMetres;
  m->counts = {{"points", m->points},
               {"nodes", res.results.size()},
               {"fitted", fitted},
               {"skipped", skipped},
               {"disabled", disabled},
               {"vertices", res.mesh.vertices.size()},
               {"triangles", res.mesh.triangles.size()}};
  m->reportHeader = {{"cloud", r.source},
                     {"points", m->points},
                     {"nodes", res.results.size()},
                     {"vertices", res.mesh.vertices.size()},
                     {"triangles", res.mesh.triangles.size()}};
  return m;
}

/// Every node's fit as columns, by increasing id.
py::dict fitColumns(const PyReconstruction& r) {
  const auto results = r.recon->results();
  const auto n = static_cast<py::ssize_t>(results.size());
  py::array_t<std::int64_t> id(n);
  py::array_t<double> centre({n, py::ssize_t{3}}), normal({n, py::ssize_t{3}}), radius(n), rms(n);
  py::array_t<bool> fitted(n), kept(n);
  py::list status, reason;
  py::ssize_t i = 0;
  for (const auto& [nodeId, res] : results) {
    id.mutable_at(i) = nodeId;
    for (int k = 0; k < 3; ++k) {
      centre.mutable_at(i, k) = res->centre[k];
      normal.mutable_at(i, k) = res->normal[k];
    }
    radius.mutable_at(i) = res->radius;
    rms.mutable_at(i) = res->rms;
    fitted.mutable_at(i) = res->status == fit::NodeStatus::Fitted;
    kept.mutable_at(i) = res->kept;
    status.append(fit::toString(res->status));
    reason.append(res->reason);
    ++i;
  }
  py::dict d;
  d["id"] = id;
  d["centre"] = centre;
  d["normal"] = normal;
  d["radius"] = radius;
  d["rms"] = rms;
  d["fitted"] = fitted;
  d["kept"] = kept;
  d["status"] = status;
  d["reason"] = reason;
  return d;
}

}  // namespace

void bindSketch(py::module_& m) {
  py::class_<sketch::Sketch>(m, "Sketch",
                             "A sketch: a tree of nodes, each a slice plane through a branch where a circle is "
                             "fitted (or a kept circle is used). Read from a sketch file or taken from a Model.")
      .def(py::init<>())
      .def_static(
          "read",
          [](const std::string& path) {
            py::gil_scoped_release release;
            return io::readSketch(std::filesystem::path(path));
          },
          py::arg("path"), "Reads a sketch file (.json); InputError naming the file and the node for a bad one.")
      .def(
          "write",
          [](const sketch::Sketch& s, const std::string& path) { io::writeSketch(std::filesystem::path(path), s); },
          py::arg("path"), "Writes the sketch file, atomically.")
      .def("__len__", &sketch::Sketch::size)
      .def_property_readonly("ids", &sketch::Sketch::ids, "Node ids, increasing.")
      .def_property_readonly("root", &sketch::Sketch::root, "The root's id (-1 when empty).")
      .def_property_readonly(
          "up", [](const sketch::Sketch& s) { return std::string(geom::toString(s.up)); }, "The sketch's up axis.")
      .def(
          "node", [](const sketch::Sketch& s, sketch::NodeId id) { return nodeDict(s.node(id)); }, py::arg("id"),
          "One node as a dict (id, parent, children, point, normal, enabled, kept circle). OptionsError for an "
          "unknown id.")
      .def(
          "add_point_node",
          [](sketch::Sketch& s, sketch::NodeId parent, const py::handle& point, const py::handle& normal) {
            return s.addPointNode(parent, toVec3(point, "point"), toVec3(normal, "normal"));
          },
          py::arg("parent"), py::arg("point"), py::arg("normal"),
          "Adds a node at `point` (world) slicing along `normal`, under `parent` (-1 for the root); returns its id.")
      .def(
          "move_node",
          [](sketch::Sketch& s, sketch::NodeId id, const py::handle& point, const py::handle& normal) {
            s.movePointNode(id, toVec3(point, "point"), toVec3(normal, "normal"));
          },
          py::arg("id"), py::arg("point"), py::arg("normal"),
          "Moves a point node (its kept circle is dropped: the node is fitted again).")
      .def("remove_node", &sketch::Sketch::removeNode, py::arg("id"), py::arg("with_subtree") = true,
           "Removes a node, with its subtree or re-attaching its children to its parent.")
      .def(
          "set_enabled",
          [](sketch::Sketch& s, sketch::NodeId id, bool enabled) {
            sketch::SamplingParams p = s.node(id).params;
            p.enabled = enabled;
            s.setParams(id, p);
          },
          py::arg("id"), py::arg("enabled"), "Enables or disables a node (a disabled node is bridged).")
      .def(
          "set_kept_circle",
          [](sketch::Sketch& s, sketch::NodeId id, const py::object& centre, const py::object& radius) {
            if (centre.is_none()) return s.setKeptCircle(id, std::nullopt);
            sketch::KeptCircle c;
            c.centre = toVec3(centre, "centre");
            c.radius = radius.cast<double>();
            s.setKeptCircle(id, c);
          },
          py::arg("id"), py::arg("centre"), py::arg("radius") = py::none(),
          "Sets the circle a node keeps instead of a fit (centre None: drop it, so the node is fitted).")
      .def("clear_kept_circles", &sketch::Sketch::clearKeptCircles,
           "Drops every kept circle (every node is fitted, as `reconstruct --refit`); returns how many.")
      .def("__repr__",
           [](const sketch::Sketch& s) { return "<treesketch.Sketch of " + std::to_string(s.size()) + " nodes>"; });

  m.def(
      "read_sketch",
      [](const std::string& path) {
        py::gil_scoped_release release;
        return io::readSketch(std::filesystem::path(path));
      },
      py::arg("path"), "Reads a sketch file (the same as Sketch.read).");

  py::class_<PyReconstruction>(m, "Reconstruction",
                               "A sketch fitted to a cloud, kept up to date: update() after an edit re-fits only "
                               "the nodes whose inputs changed and re-sweeps the bands they touch.")
      .def(py::init(&makeReconstruction), py::arg("cloud"), py::kw_only(), py::arg("seed") = 1, py::arg("ring") = 16,
           py::arg("inlier_threshold") = py::none(),
           "Builds the cloud's slice index (the Reconstruction keeps the cloud for its model's measures). Options "
           "as `treesketch reconstruct --sketch` (and the desktop tool).")
      .def("update", &update, py::arg("sketch"), py::arg("progress") = py::none(),
           "Brings the fits and the mesh up to date with `sketch`; returns the ids re-fitted. progress(done, "
           "total) is told as the fits finish. OptionsError for an invalid sketch.")
      .def(
          "mesh", [](const PyReconstruction& r) { return meshToArrays(r.recon->mesh()); },
          "The tube mesh: (vertices N x 3 float64, faces M x 3 uint32).")
      .def("model", &sketchModel, py::arg("unit_metres") = 1.0,
           "The fitted sketch as a Model (cylinders, mesh, metrics, writers), as `treesketch reconstruct --sketch` "
           "makes it: each node with a circle joined to its nearest ancestor with one. DegenerateInputError when "
           "no node could be fitted.")
      .def_property_readonly("fits", &fitColumns,
                             "Every node's fit as columns by increasing id: id, centre, normal (N x 3), radius, "
                             "rms, fitted, kept (bool), status and reason (lists of str).")
      .def_property_readonly(
          "fit_count", [](const PyReconstruction& r) { return r.recon->fitCount(); },
          "Node fits performed since construction.")
      .def_property_readonly(
          "timings",
          [](const PyReconstruction& r) {
            const recon::Timings& t = r.recon->timings();
            py::dict d;
            d["index_ms"] = t.indexMs;
            d["fit_ms"] = t.fitMs;
            d["sweep_ms"] = t.sweepMs;
            d["total_ms"] = t.totalMs;
            return d;
          },
          "Wall times of the index build and of the last update, ms.");

  m.def(
      "fit",
      [](const py::object& cloud, const sketch::Sketch& sk, std::uint64_t seed, int ring,
         const py::object& inlierThreshold) {
        auto r = makeReconstruction(cloud, seed, ring, inlierThreshold);
        update(*r, sk, py::none());
        return r;
      },
      py::arg("cloud"), py::arg("sketch"), py::kw_only(), py::arg("seed") = 1, py::arg("ring") = 16,
      py::arg("inlier_threshold") = py::none(),
      "Fits `sketch` to `cloud`: a Reconstruction after its first update (edit the sketch, then call update).");
}

}  // namespace treesketch::python
