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
// with the input's size and modification time and the options that shape the model (up axis,
// leaf-on, units, seed). A tree is complete when done.json exists, names the same input size and
// time and the same options, and every output is there (atomic writes: present = complete): a
// rerun with other options runs the tree again. A failure is not retried while its input and
// options are unchanged, unless it may pass on a second try: a tree killed by a signal, one that
// could not write its outputs (a full disk) or met an internal error, one stopped by a time or
// memory limit that is now larger or gone. The batch's own summary is never taken for a tree.
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

/// Lists the trees of a folder or a manifest, leaving out the batch's own summary in `out` (when
/// --out is the input folder). Throws InputError when `input` does not
/// exist, a manifest line names no file, or there is no tree at all.
BatchPlan planBatch(const std::filesystem::path& input, const std::filesystem::path& out = {});

/// The per-tree output files, in the order they are written; the marker files.
std::vector<std::string> batchOutputNames();
inline constexpr const char* kDoneMarker = "done.json";
inline constexpr const char* kFailedMarker = "failed.json";

/// The input's identity recorded in the markers: {"bytes": size, "mtime": nanoseconds}.
nlohmann::json inputStamp(const std::filesystem::path& cloud);
/// How a run makes its trees: the options recorded in the markers, and the per-tree time limit.
struct BatchRunOptions {
  /// {"up", "leafOn", "unitMetres", "seed"}; null = any (the summary gathers whatever was run).
  nlohmann::json model;
  double treeTimeoutS = 0;  ///< 0 = none
  double treeMemoryMb = 0;  ///< 0 = none
};

/// "done" when the tree is complete with these options, "failed" when it failed on this very input
/// with these options and a second try would fail again, "" otherwise (to run). `why` (optional)
/// receives why a tree with a marker is to run again ("other options", "killed by a signal", ...).
std::string treeState(const std::filesystem::path& treeDir, const BatchTree& tree, const BatchRunOptions& options,
                      std::string* why = nullptr);

/// Gathers every tree's marker into OUT/summary.csv and OUT/summary.json (atomically). Returns the
/// number of trees that are not done (failed or not run).
std::size_t writeBatchSummary(const std::filesystem::path& out, const BatchPlan& plan,
                              const BatchRunOptions& options = {});

}  // namespace treesketch::cli
