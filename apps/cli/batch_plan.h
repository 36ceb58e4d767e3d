// The plan and records of `treesketch batch`: which clouds make up a plot (a folder or a
// manifest), where each tree's outputs go, the per-tree markers that make a run resumable, and
// the summary of all trees.
//
// Which files of a folder are trees: regular files with a cloud extension (.las .laz .ply .xyz
// .txt .csv .pts .asc), sorted by name, except text tables whose first line names a `radius` column
// (a cylinder table such as a SimpleForest or TreeQSM model, not a cloud); those are listed as
// skipped. A manifest is a text file with one cloud path per line (blank lines and '#' comments
// skipped; relative paths are relative to the manifest's folder), taken in its order.
//
// Per tree, under OUT/<name>/ (name = the file's stem; file name with '.' → '_' when two stems
// clash; then _2, _3 for one file name in several folders): mesh.ply, cylinders.csv (treesketch), qsm.txt (TreeQSM
// layout), metrics.json, report.json, log.txt, and last a marker: done.json on success, failed.json on failure, each
// with the input's size and modification time. A tree is complete when done.json exists, names the
// same input size and time, and every output is there (atomic writes: present = complete); a
// failure is not retried while its input is unchanged.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace treesketch::cli {

struct BatchTree {
  std::string name;             ///< folder name under OUT
  std::filesystem::path cloud;  ///< the input
};

struct BatchPlan {
  std::vector<BatchTree> trees;
  std::vector<std::string> skipped;  ///< "path: why" for files of a folder that are not clouds
};

/// Lists the trees of a folder or a manifest. Throws InputError when `input` does not exist, a
/// manifest line names no file, or there is no tree at all.
BatchPlan planBatch(const std::filesystem::path& input);

/// The per-tree output files, in the order they are written; the marker files.
std::vector<std::string> batchOutputNames();
inline constexpr const char* kDoneMarker = "done.json";
inline constexpr const char* kFailedMarker = "failed.json";

/// The input's identity recorded in the markers: {"bytes": size, "mtime": nanoseconds}.
nlohmann::json inputStamp(const std::filesystem::path& cloud);
/// "done" when the tree is complete, "failed" when it failed on this very input, "" otherwise.
std::string treeState(const std::filesystem::path& treeDir, const BatchTree& tree);

/// Gathers every tree's marker into OUT/summary.csv and OUT/summary.json (atomically). Returns the
/// number of trees that are not done (failed or not run).
std::size_t writeBatchSummary(const std::filesystem::path& out, const BatchPlan& plan);

}  // namespace treesketch::cli
