// The Python module `treesketch`: the library's errors as Python exceptions, the helpers of
// bindings.h, and the module itself (each file binds one part: cloud, model, sketch, evaluation).
#include <cmath>
#include <cstring>

#include "bindings.h"
#include "treesketch/util/cancel.h"
#include "treesketch/util/error.h"

namespace treesketch::python {

py::array_t<double> vec3View(const std::vector<geom::Vec3>& points, py::handle owner) {
  const auto n = static_cast<py::ssize_t>(points.size());
  static const double kEmpty[3] = {0, 0, 0};  // a valid pointer for an empty view
  const double* data = points.empty() ? kEmpty : points.data()->data();
  return py::array_t<double>({n, py::ssize_t{3}}, {py::ssize_t{sizeof(geom::Vec3)}, py::ssize_t{sizeof(double)}}, data,
                             owner);
}

py::array_t<double> vec3Copy(const std::vector<geom::Vec3>& points) {
  py::array_t<double> a({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
  if (!points.empty()) std::memcpy(a.mutable_data(), points.data()->data(), points.size() * sizeof(geom::Vec3));
  return a;
}

std::vector<geom::Vec3> vec3FromArray(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                                      const std::string& what) {
  if (a.ndim() != 2 || a.shape(1) != 3) {
    std::string shape;
    for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? " x " : "") + std::to_string(a.shape(i));
    throw OptionsError(what + ": expected an N x 3 array, got shape (" + shape + ")");
  }
  std::vector<geom::Vec3> points(static_cast<std::size_t>(a.shape(0)));
  if (!points.empty()) std::memcpy(points.data()->data(), a.data(), points.size() * sizeof(geom::Vec3));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw InputError(what + ": row " + std::to_string(i) + " has a NaN or infinite coordinate");
  return points;
}

geom::TriMesh meshFromArrays(const py::handle& mesh, const std::string& what) {
  py::tuple t;
  try {
    t = py::tuple(py::reinterpret_borrow<py::object>(mesh));
  } catch (const py::error_already_set&) {
    throw OptionsError(what + ": expected a (vertices, faces) pair of arrays");
  }
  if (t.size() != 2) throw OptionsError(what + ": expected a (vertices, faces) pair of arrays");
  geom::TriMesh m;
  m.vertices =
      vec3FromArray(t[0].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(), what + " vertices");
  const auto f = t[1].cast<py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>>();
  if (f.ndim() != 2 || f.shape(1) != 3) throw OptionsError(what + " faces: expected an M x 3 integer array");
  const std::int64_t* p = f.data();
  m.triangles.resize(static_cast<std::size_t>(f.shape(0)));
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = p[3 * i + k];
      if (v < 0 || v >= static_cast<std::int64_t>(m.vertices.size()))
        throw OptionsError(what + " faces: row " + std::to_string(i) + " names vertex " + std::to_string(v) +
                           ", expected 0 to " + std::to_string(m.vertices.size()) + " - 1");
      m.triangles[i][k] = static_cast<std::uint32_t>(v);
    }
  return m;
}

py::tuple meshToArrays(const geom::TriMesh& mesh) {
  py::array_t<std::uint32_t> f({static_cast<py::ssize_t>(mesh.triangles.size()), py::ssize_t{3}});
  if (!mesh.triangles.empty())
    std::memcpy(f.mutable_data(), mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
  return py::make_tuple(vec3Copy(mesh.vertices), f);
}

py::object fromJson(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(j.get<double>());
    case nlohmann::json::value_t::string:
      return py::str(j.get<std::string>());
    case nlohmann::json::value_t::array: {
      py::list l;
      for (const auto& v : j) l.append(fromJson(v));
      return l;
    }
    case nlohmann::json::value_t::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = fromJson(v);
      return d;
    }
    default:
      return py::none();
  }
}

namespace {

unsigned long mainThread = 0;  // Python's main thread (the only one that runs signal handlers)

}  // namespace

ProgressFn Progress::function() {
  if (callback_.is_none()) {
    return [this](std::uint64_t, std::uint64_t) {
      if (PyThread_get_thread_ident() != mainThread) return;
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() == 0) return;
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::make_exception_ptr(py::error_already_set());
      throw Cancelled();
    };
  }
  return [this](std::uint64_t done, std::uint64_t total) {
    py::gil_scoped_acquire gil;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (error_) throw Cancelled();
    }
    try {
      callback_(done, total);
    } catch (py::error_already_set&) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      throw Cancelled();
    }
  };
}

void Progress::rethrowIfFailed() {
  std::exception_ptr e;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    e = error_;
  }
  if (e) std::rethrow_exception(e);
}

namespace {

/// The exception classes: treesketch.Error and one subclass per library error type.
struct Exceptions {
  PyObject* error = nullptr;
  PyObject* input = nullptr;
  PyObject* output = nullptr;
  PyObject* options = nullptr;
  PyObject* degenerate = nullptr;
};

PyObject* newException(py::module_& m, const char* name, PyObject* bases, const char* doc) {
  const std::string qualified = std::string("treesketch.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases, nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

void bindErrors(py::module_& m) {
  static Exceptions ex;
  ex.error = newException(m, "Error", PyExc_Exception, "Base of the errors treesketch raises.");
  ex.input = newException(m, "InputError", ex.error,
                          "A file or array that cannot be read as what was expected (the message names it, and the "
                          "line or byte offset when known).");
  ex.output = newException(m, "OutputError", ex.error, "An output that could not be written.");
  py::tuple optionBases = py::make_tuple(py::handle(ex.error), py::handle(PyExc_ValueError));
  ex.options = newException(m, "OptionsError", optionBases.ptr(),
                            "Options or arguments out of range or inconsistent (also a ValueError).");
  ex.degenerate = newException(m, "DegenerateInputError", ex.error,
                               "Input read correctly from which no result can be made (no skeleton, zero area...).");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(ex.input, e.what());
    } catch (const OutputError& e) {
      PyErr_SetString(ex.output, e.what());
    } catch (const OptionsError& e) {
      PyErr_SetString(ex.options, e.what());
    } catch (const DegenerateInputError& e) {
      PyErr_SetString(ex.degenerate, e.what());
    } catch (const Cancelled& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    }
  });
}

}  // namespace

}  // namespace treesketch::python

PYBIND11_MODULE(treesketch, m) {
  using namespace treesketch::python;
  m.doc() =
      "treesketch: tree models from LIDAR point clouds. Clouds, cylinder models and meshes as NumPy arrays; "
      "the same library as the treesketch command.";
  m.attr("__version__") = TREESKETCH_VERSION;
  mainThread = py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
  bindErrors(m);
  bindCloud(m);
  bindModel(m);
  bindSketch(m);
  bindEvaluation(m);
}
