// treesketch.Cloud and read_cloud: a point cloud whose positions and attributes are NumPy views
// of the library's storage (no copy), kept alive by the Cloud they come from; classify: the wood/leaf
// classification of a cloud as NumPy arrays.
#include <cstring>

#include "bindings.h"
#include "treesketch/classify/classify.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/util/error.h"

namespace treesketch::python {

namespace {

/// A 1-D (or N x width) view of an attribute array; None when the cloud has none.
template <typename T>
py::object attributeView(const std::vector<T>& values, py::handle owner, py::ssize_t width = 1) {
  if (values.empty()) return py::none();
  using Scalar = std::conditional_t<std::is_same_v<T, std::array<std::uint8_t, 3>>, std::uint8_t, T>;
  const auto n = static_cast<py::ssize_t>(values.size());
  const auto* data = reinterpret_cast<const Scalar*>(values.data());
  if (width == 1) return py::array_t<Scalar>({n}, {py::ssize_t{sizeof(T)}}, data, owner);
  return py::array_t<Scalar>({n, width}, {py::ssize_t{sizeof(T)}, py::ssize_t{sizeof(Scalar)}}, data, owner);
}

/// Copies a 1-D (or N x width) array into an attribute of `n` points; None leaves it empty.
template <typename Scalar, typename T>
void setAttribute(std::vector<T>& out, const py::object& value, std::size_t n, py::ssize_t width, const char* name) {
  if (value.is_none()) return;
  const auto a = value.cast<py::array_t<Scalar, py::array::c_style | py::array::forcecast>>();
  const bool shapeOk = width == 1 ? a.ndim() == 1 && a.shape(0) == static_cast<py::ssize_t>(n)
                                  : a.ndim() == 2 && a.shape(0) == static_cast<py::ssize_t>(n) && a.shape(1) == width;
  if (!shapeOk)
    throw OptionsError(std::string("from_numpy: ") + name + " must have one " + (width == 1 ? "value" : "row") +
                       " per point (" + std::to_string(n) + ")");
  out.resize(n);
  if (n) std::memcpy(out.data(), a.data(), n * sizeof(T));
}

}  // namespace

void bindCloud(py::module_& m) {
  py::class_<geom::PointCloud, CloudPtr>(m, "Cloud", py::dynamic_attr(),
                                         "A point cloud: positions (N x 3 float64) and the attributes its file has. "
                                         "The arrays are views of the cloud's own storage.")
      .def_static(
          "from_numpy",
          [](const py::array_t<double, py::array::c_style | py::array::forcecast>& xyz, const py::object& up,
             const py::object& intensity, const py::object& classification, const py::object& color) {
            auto cloud = std::make_shared<geom::PointCloud>();
            cloud->positions = vec3FromArray(xyz, "from_numpy: xyz");
            const std::size_t n = cloud->size();
            if (!up.is_none()) cloud->up = geom::parseUpAxis(up.cast<std::string>());
            setAttribute<float>(cloud->intensity, intensity, n, 1, "intensity");
            setAttribute<std::uint8_t>(cloud->classification, classification, n, 1, "classification");
            setAttribute<std::uint8_t>(cloud->color, color, n, 3, "color");
            return cloud;
          },
          py::arg("xyz"), py::kw_only(), py::arg("up") = py::none(), py::arg("intensity") = py::none(),
          py::arg("classification") = py::none(), py::arg("color") = py::none(),
          "A cloud from an N x 3 array of positions (copied once into the cloud; any float dtype). "
          "Optional: the up axis the data declares ('y' or 'z'), per-point intensity (float32), "
          "classification (uint8) and color (N x 3 uint8). Raises InputError for NaN or Inf (naming the row), "
          "OptionsError for a wrong shape.")
      .def_property_readonly(
          "xyz", [](py::object self) { return vec3View(self.cast<geom::PointCloud&>().positions, self); },
          "Positions, N x 3 float64, a view of the cloud's storage (kept alive by the array).")
      .def_property_readonly(
          "intensity", [](py::object self) { return attributeView(self.cast<geom::PointCloud&>().intensity, self); },
          "Per-point intensity (float32) as the file gives it, or None.")
      .def_property_readonly(
          "classification",
          [](py::object self) { return attributeView(self.cast<geom::PointCloud&>().classification, self); },
          "Per-point ASPRS classification (uint8), or None.")
      .def_property_readonly(
          "color", [](py::object self) { return attributeView(self.cast<geom::PointCloud&>().color, self, 3); },
          "Per-point colour, N x 3 uint8, or None.")
      .def_property_readonly(
          "station", [](py::object self) { return attributeView(self.cast<geom::PointCloud&>().station, self); },
          "Per-point scanner station (int32, synthetic scans), or None.")
      .def_property_readonly(
          "mesh_id", [](py::object self) { return attributeView(self.cast<geom::PointCloud&>().meshId, self); },
          "Per-point index of the scanned mesh (int32, synthetic scans), or None.")
      .def_property_readonly(
          "scanner",
          [](py::object self) -> py::object {
            const auto& c = self.cast<geom::PointCloud&>();
            if (c.scanner.empty()) return py::none();
            return vec3View(c.scanner, self);
          },
          "Per-point scanner position, N x 3 float64, or None.")
      .def_property_readonly(
          "up",
          [](const geom::PointCloud& c) -> py::object {
            if (!c.up) return py::none();
            return py::str(geom::toString(*c.up));
          },
          "The up axis the file declares ('y' or 'z'), or None.")
      .def_property_readonly(
          "attributes",
          [](const geom::PointCloud& c) {
            std::vector<std::string> names;
            if (!c.intensity.empty()) names.push_back("intensity");
            if (!c.classification.empty()) names.push_back("classification");
            if (!c.color.empty()) names.push_back("color");
            if (!c.station.empty()) names.push_back("station");
            if (!c.meshId.empty()) names.push_back("mesh_id");
            if (!c.scanner.empty()) names.push_back("scanner");
            return names;
          },
          "Names of the per-point attributes the cloud has.")
      .def("__len__", &geom::PointCloud::size)
      .def(
          "write",
          [](const geom::PointCloud& c, const std::string& path) {
            py::gil_scoped_release release;
            io::writePointCloud(path, c);
          },
          py::arg("path"),
          "Writes the cloud as binary PLY (.ply, with its attributes) or text (.xyz, .txt), atomically.")
      .def("__repr__",
           [](const geom::PointCloud& c) { return "<treesketch.Cloud of " + std::to_string(c.size()) + " points>"; });

  m.def(
      "read_cloud",
      [](const std::string& path) {
        CloudPtr cloud;
        {
          py::gil_scoped_release release;
          cloud = std::make_shared<geom::PointCloud>(io::readPointCloud(path));
        }
        py::object c = py::cast(cloud);
        c.attr("source") = path;  // names the cloud in the messages of later calls, as the CLI does
        return c;
      },
      py::arg("path"),
      "Reads a point cloud (.ply .xyz .txt .csv .pts .las; .obj vertices). Raises InputError naming the file "
      "and the line or byte offset for an unreadable file, NaN or Inf, fewer than 4 points, or .laz (with how to "
      "decompress it).");

  m.def(
      "classify",
      [](const CloudPtr& cloud, const py::object& up, const py::object& threshold) {
        if (!cloud) throw OptionsError("classify: cloud is None");
        const std::string upOption = up.is_none() ? std::string() : up.cast<std::string>();
        classify::ClassifyOptions options;
        if (!threshold.is_none()) {
          options.threshold = threshold.cast<double>();
          if (!(options.threshold >= 0.0 && options.threshold <= 1.0))
            throw OptionsError("classify: threshold must be between 0 and 1, got " + std::to_string(options.threshold));
        }
        classify::Classification c;
        {
          py::gil_scoped_release release;
          c = classify::classifyWood(*cloud, io::chooseUpAxis(upOption, *cloud).up, options);
        }
        const auto n = static_cast<py::ssize_t>(c.wood.size());
        py::array_t<float> probability(n);
        py::array_t<bool> wood(n);
        py::array_t<std::uint8_t> codes(n);
        const std::vector<std::uint8_t> classCodes = classify::classCodes(c);
        auto p = probability.mutable_unchecked<1>();
        auto w = wood.mutable_unchecked<1>();
        auto k = codes.mutable_unchecked<1>();
        for (py::ssize_t i = 0; i < n; ++i) {
          const auto u = static_cast<std::size_t>(i);
          p(i) = c.woodProbability[u];
          w(i) = c.wood[u] != 0;
          k(i) = classCodes[u];
        }
        py::dict d;
        d["wood_probability"] = probability;
        d["wood"] = wood;
        d["classification"] = codes;
        d["threshold"] = c.threshold;
        d["wood_points"] = c.woodPoints;
        return d;
      },
      py::arg("cloud"), py::kw_only(), py::arg("up") = py::none(), py::arg("threshold") = py::none(),
      "Tells wood from leaves, as `treesketch classify` does (the model built into the library): a dict of "
      "per-point NumPy arrays, 'wood_probability' (float32, the classifier's, 0..1), 'wood' (bool, the class "
      "after the graph step that keeps wood connected to the stem) and 'classification' (uint8, the file codes: "
      "64 wood, 65 leaf), with 'threshold' (the probability called wood) and 'wood_points'. up: 'y' or 'z' "
      "(None: what the file declares, else z); threshold: call wood at this probability and above (None: the "
      "model's own). The GIL is released while it works. Raises DegenerateInputError for a cloud too small to "
      "classify, OptionsError for a threshold outside 0..1.");
}

}  // namespace treesketch::python
