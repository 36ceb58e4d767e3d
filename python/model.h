// The Python module's Model: the library's tree model with its measures and where it came from,
// shared by the automatic path (model.cpp) and the sketch path (sketch.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bindings.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::python {

struct PyModel {
  model::TreeModel tree;
  model::ModelMeasures measures;  ///< with the cloud it was made from; the fit only on demand
  /// What `measures` was measured with (leaf state, noise, leaf pieces): a report re-measures with
  /// the same, plus the fit.
  model::MeasureOptions measureOptions;
  sketch::Sketch sketch;          ///< the editable sketch behind the model
  std::string source;             ///< names the cloud in messages and reports
  std::string upReason;
  std::size_t points = 0;
  cloud::StrayPoints strays;  ///< the points of its cloud set aside before modelling
  double unitMetres = 1.0;
  nlohmann::json counts = nlohmann::json::object();        ///< e.g. skeleton_nodes, forks, vertices
  nlohmann::json timings = nlohmann::json::object();       ///< *_ms, library_ms
  nlohmann::json reportHeader = nlohmann::json::object();  ///< what a written report says first
};

/// The name a Cloud carries (its file), or "cloud".
std::string cloudSource(const py::object& cloud);

}  // namespace treesketch::python
