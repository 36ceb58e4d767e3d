// What the Python module's files share: the pieces that turn library data into NumPy arrays and
// Python objects, and the progress callback that crosses the released GIL.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/util/progress.h"

namespace treesketch::python {

namespace py = pybind11;

static_assert(sizeof(geom::Vec3) == 3 * sizeof(double), "Vec3 arrays are read as N x 3 doubles");

/// A cloud shared between Python objects: a Cloud and the arrays viewing its storage.
using CloudPtr = std::shared_ptr<geom::PointCloud>;

/// An N x 3 float64 array viewing `points` (no copy); `owner` is kept alive by the array.
py::array_t<double> vec3View(const std::vector<geom::Vec3>& points, py::handle owner);
/// An N x 3 float64 array holding a copy of `points`.
py::array_t<double> vec3Copy(const std::vector<geom::Vec3>& points);
/// The rows of an N x 3 array as points; `what` names the argument in errors (OptionsError for
/// another shape, InputError naming the row for NaN or Inf).
std::vector<geom::Vec3> vec3FromArray(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                                      const std::string& what);

/// A mesh from (vertices N x 3, faces M x 3 integer) arrays; OptionsError for bad shapes or
/// indices out of range.
geom::TriMesh meshFromArrays(const py::handle& mesh, const std::string& what);
/// (vertices, faces) as new arrays: float64 N x 3 and uint32 M x 3.
py::tuple meshToArrays(const geom::TriMesh& mesh);

/// A JSON value as Python data (dict, list, float, int, str, bool, None).
py::object fromJson(const nlohmann::json& j);

/// A Python progress callback, callable from the library's worker threads while the GIL is
/// released. An exception the callback raises stops the work (as treesketch::Cancelled does) and is
/// raised again by rethrowIfFailed(). Without a callback, the reports that come on the main thread
/// check for Ctrl-C (Python's signal handlers), so a KeyboardInterrupt stops the work too.
class Progress {
 public:
  explicit Progress(py::object callback) : callback_(std::move(callback)) {}
  ProgressFn function();
  /// Raises the callback's exception, if it raised one. Call with the GIL held.
  void rethrowIfFailed();

 private:
  py::object callback_;
  std::mutex mutex_;
  std::exception_ptr error_;
};

// Each file's part of the module.
void bindCloud(py::module_& m);
void bindModel(py::module_& m);
void bindSketch(py::module_& m);
void bindEvaluation(py::module_& m);

}  // namespace treesketch::python
