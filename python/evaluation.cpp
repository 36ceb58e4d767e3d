// Evaluation from Python: meshes in and out, the built-in tree generator, the virtual scanner
// (scan) and the two-way surface comparison (compare), as the CLI's scan and compare run them.
#include <cmath>
#include <limits>

#include "bindings.h"
#include "treesketch/compare/hausdorff.h"
#include "treesketch/gen/tree_generator.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/scan/tls_scan.h"
#include "treesketch/util/cancel.h"
#include "treesketch/util/error.h"

namespace treesketch::python {

namespace {

/// One mesh (a (vertices, faces) pair) or a list of them.
std::vector<geom::TriMesh> meshList(const py::handle& meshes) {
  std::vector<geom::TriMesh> out;
  const bool one = py::isinstance<py::tuple>(meshes) && py::len(meshes) == 2 &&
                   py::isinstance<py::array>(py::reinterpret_borrow<py::tuple>(meshes)[0]);
  if (one) {
    out.push_back(meshFromArrays(meshes, "mesh"));
  } else {
    for (const py::handle& m : meshes) out.push_back(meshFromArrays(m, "mesh " + std::to_string(out.size())));
  }
  if (out.empty()) throw OptionsError("scan: no mesh given");
  return out;
}

void checkHasArea(const geom::TriMesh& mesh, const std::string& what) {
  if (!(mesh.area() > 0))
    throw DegenerateInputError(what + ": zero area (every triangle has repeated or collinear corners)");
}

CloudPtr scanMeshes(const py::handle& meshesObj, const std::string& pattern, std::uint64_t seed, int subdivisions,
                    std::uint64_t rays, const py::object& noise, const std::string& up, int stations,
                    double stationHeight, double stepDeg, double unitMetres, bool recordMesh, bool recordScanner,
                    const py::object& progressFn) {
  if (pattern != "sphere" && pattern != "tls")
    throw OptionsError("scan: pattern '" + pattern + "' unknown, expected sphere or tls");
  const std::vector<geom::TriMesh> meshes = meshList(meshesObj);
  double area = 0;
  for (const auto& m : meshes) area += m.area();
  if (!(area > 0))
    throw DegenerateInputError(
        "scan: the meshes have zero area (every triangle has repeated or collinear corners); "
        "nothing a ray can hit");
  const geom::UpAxis upAxis = geom::parseUpAxis(up);
  Progress progress(progressFn);
  auto cloud = std::make_shared<geom::PointCloud>();
  try {
    py::gil_scoped_release release;
    scan::ScanResult result;
    if (pattern == "sphere") {
      scan::SphereScanOptions o;
      o.subdivisions = subdivisions;
      o.rays = rays;
      if (!noise.is_none()) o.rangeNoise = noise.cast<double>();
      o.unitMetres = unitMetres;
      o.seed = seed;
      o.recordMesh = recordMesh;
      o.recordScanner = recordScanner;
      result = scan::sphereScan(meshes, o, progress.function());
    } else {
      scan::TlsScanOptions o;
      o.stationCount = stations;
      o.stationHeight = stationHeight;
      o.stepDeg = stepDeg;
      if (!noise.is_none()) o.rangeNoise = noise.cast<double>();
      o.up = upAxis;
      o.unitMetres = unitMetres;
      o.seed = seed;
      o.recordMesh = recordMesh;
      o.recordScanner = recordScanner;
      result = scan::tlsScan(meshes, o, progress.function());
    }
    if (result.cloud.empty())
      throw DegenerateInputError("scan: none of the " + std::to_string(result.stats.raysCast) +
                                 " rays hit the meshes (scanner inside the mesh, range too short?)");
    *cloud = std::move(result.cloud);
    cloud->up = upAxis;
  } catch (const Cancelled&) {
    progress.rethrowIfFailed();
    throw;
  }
  return cloud;
}

py::object compareSurfaces(const py::handle& a, const py::handle& b, std::size_t samples, std::uint64_t seed,
                           bool oneWay, double maxDistance, int bins, const py::object& progressFn) {
  const geom::TriMesh meshA = meshFromArrays(a, "compare: a");
  checkHasArea(meshA, "compare: a");
  const bool bIsCloud = py::isinstance<geom::PointCloud>(b);
  geom::TriMesh meshB;
  CloudPtr cloudB;
  if (bIsCloud) {
    cloudB = b.cast<CloudPtr>();
  } else {
    meshB = meshFromArrays(b, "compare: b");
    checkHasArea(meshB, "compare: b");
  }
  compare::CompareOptions o;  // the CLI's defaults
  o.sampling.count = samples;
  o.sampling.seed = seed;
  o.maxDistance = maxDistance;
  o.histogramBins = bins;
  Progress progress(progressFn);
  o.progress = progress.function();
  nlohmann::json j;
  try {
    py::gil_scoped_release release;
    compare::BothReport both;
    both.forward = bIsCloud ? compare::compareMeshToCloud(meshA, *cloudB, o) : compare::compareMeshes(meshA, meshB, o);
    if (oneWay) {
      j = {{"forward", compare::toJson(both.forward)}};
    } else {
      both.backward =
          bIsCloud ? compare::compareCloudToMesh(*cloudB, meshA, o) : compare::compareMeshes(meshB, meshA, o);
      compare::finishBoth(both);
      j = compare::toJson(both);
    }
  } catch (const Cancelled&) {
    progress.rethrowIfFailed();
    throw;
  }
  return fromJson(j);
}

}  // namespace

void bindEvaluation(py::module_& m) {
  m.def(
      "read_mesh",
      [](const std::string& path) {
        geom::TriMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = io::readMesh(path);
        }
        return meshToArrays(mesh);
      },
      py::arg("path"), "Reads a mesh (.obj, .ply) as (vertices N x 3 float64, faces M x 3 uint32).");
  m.def(
      "write_mesh",
      [](const std::string& path, const py::handle& mesh) {
        const geom::TriMesh t = meshFromArrays(mesh, "write_mesh");
        py::gil_scoped_release release;
        io::writeMesh(path, t);
      },
      py::arg("path"), py::arg("mesh"), "Writes a (vertices, faces) mesh as .obj or binary .ply, atomically.");
  m.def(
      "generate_tree",
      [](const std::string& preset, std::uint64_t seed, const std::string& up) {
        gen::TreeOptions o = gen::presetOptions(preset);
        o.seed = seed;
        o.up = geom::parseUpAxis(up);
        o.leaves = false;
        geom::TriMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = gen::generateTree(o).branches.mesh;
        }
        return meshToArrays(mesh);
      },
      py::arg("preset") = "default", py::kw_only(), py::arg("seed") = 1, py::arg("up") = "y",
      "The built-in tree generator's branch mesh (no leaves) as (vertices, faces): presets 'default', 'conifer', "
      "'sparse'; metres.");
  m.def("scan", &scanMeshes, py::arg("meshes"), py::kw_only(), py::arg("pattern") = "sphere", py::arg("seed") = 1,
        py::arg("subdivisions") = scan::SphereScanOptions{}.subdivisions, py::arg("rays") = 0,
        py::arg("noise") = py::none(), py::arg("up") = "y", py::arg("stations") = scan::TlsScanOptions{}.stationCount,
        py::arg("station_height") = scan::TlsScanOptions{}.stationHeight,
        py::arg("step_deg") = scan::TlsScanOptions{}.stepDeg, py::arg("unit_metres") = 1.0,
        py::arg("record_mesh") = false, py::arg("record_scanner") = false, py::arg("progress") = py::none(),
        "Virtual LIDAR, as `treesketch scan`: casts the thesis's sphere pattern (subdivisions k: 18*4^k rays, or "
        "about `rays`) or TLS stations (pattern='tls') at one (vertices, faces) mesh or a list of them and returns "
        "the hits as a Cloud (TLS: with station ids; record_mesh, record_scanner: each point's mesh index and "
        "scanner position). noise: range noise sigma in metres (None: the pattern's "
        "default). DegenerateInputError when nothing is hit.");
  m.def("compare", &compareSurfaces, py::arg("a"), py::arg("b"), py::kw_only(), py::arg("samples") = 0,
        py::arg("seed") = 1, py::arg("one_way") = false,
        py::arg("max_distance") = std::numeric_limits<double>::infinity(), py::arg("bins") = 10,
        py::arg("progress") = py::none(),
        "Surface distances between mesh `a` (vertices, faces) and `b` (a mesh or a Cloud), as `treesketch "
        "compare`: forward (a sampled against b) and backward, Hausdorff distance; a dict as its --json. samples: "
        "per direction (0: each sampled mesh's vertex count).");
}

}  // namespace treesketch::python
