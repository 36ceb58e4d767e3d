// One tree through the automatic pipeline, as `reconstruct --auto` and `batch` run it: read the
// cloud, choose the up axis (io/up_axis.h), skeleton → sketch → fits → mesh, then write the
// requested outputs through the one model writer (model/tree_model.h), each atomically.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "treesketch/cloud/scale_check.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/model/tree_model.h"

namespace treesketch::cli {

struct TreeJob {
  std::string cloud;
  model::OutputPaths out;  ///< the model's files: the mesh is required, the others optional ("" = none)
  std::string sketch;      ///< the automatic sketch (optional)
  std::string strays;      ///< the points set aside as strays, a cloud file (optional; written even when none)
  std::string up;                 ///< --up ("" = the rule of io/up_axis.h)
  bool leafOn = false;
  /// Model only the points the wood/leaf classification calls wood (classify/classify.h), with the
  /// leaf-off settings (what is left is meant to be wood); the model is measured against every
  /// point. For a tree in leaf whose volume matters more than its finest twigs.
  bool woodOnly = false;
  std::uint64_t seed = 1;
  int ring = 16;
  double inlierThreshold = -1;  ///< < 0: library default
  double unitMetres = 1.0;
  /// --set NAME=VALUE assignments (skeleton/option_table.h), applied over the preset in order.
  std::vector<std::string> settings;
};

struct TreeJobResult {
  std::size_t points = 0;
  std::size_t woodPoints = 0;  ///< with woodOnly: the points classified as wood (the ones modelled)
  cloud::StrayPoints strays;  ///< indices into the points modelled  ///< the points set aside before modelling
  cloud::ScaleCheck scale;    ///< the cloud's size and precision, with warnings and their fixes
  std::string up, upReason;
  std::size_t skeletonNodes = 0, forks = 0, fitsAccepted = 0, leafPieces = 0, vertices = 0, triangles = 0;
  double readMs = 0, skeletonMs = 0, fitMs = 0, sweepMs = 0, metricsMs = 0, totalMs = 0;
  model::ModelMeasures measures;  ///< metrics, the fit against the cloud, the volume's range, the verdict
};

/// Runs the job. Throws InputError (unreadable cloud, no skeleton), OptionsError, OutputError.
TreeJobResult runTreeJob(const TreeJob& job);

/// The lines every command that makes a model prints after it: the fit summary (with the report's
/// path), the volume's range and the verdict, and the metrics table (when a report or metrics file
/// was written).
/// Prints each warning of `scale` on stderr ("warning: ...").
void printScaleWarnings(const cloud::ScaleCheck& scale);

/// Adds `--set NAME=VALUE` (repeatable, into `settings`) and `--list-settings` to a command that
/// makes the automatic model. `--set help` and `--list-settings` print the settings table with the
/// leaf-off defaults and the leaf-on preset's differences, and end the command (exit 0).
void addSettingOptions(CLI::App* command, std::vector<std::string>& settings);

/// Checks `settings` against the settings table before any file is read: an unknown name, a value
/// of the wrong type or out of range throws OptionsError naming the setting.
void checkSettings(const std::vector<std::string>& settings);

void printModelSummary(const model::ModelMeasures& measures, const model::OutputPaths& outputs);

}  // namespace treesketch::cli
