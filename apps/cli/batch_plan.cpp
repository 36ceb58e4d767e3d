// `treesketch batch`: the plan, the markers and the summary (see batch_plan.h).
#include "batch_plan.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool isCloudExtension(const std::string& ext) {
  static const char* kExt[] = {".las", ".laz", ".ply", ".xyz", ".txt", ".csv", ".pts", ".asc"};
  return std::find_if(std::begin(kExt), std::end(kExt), [&](const char* e) { return ext == e; }) != std::end(kExt);
}

/// True for a text table whose first non-blank, non-comment line names a radius column.
bool isCylinderTable(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    return lower(line).find("radius") != std::string::npos;
  }
  return false;
}

/// Unique names: the stem, or the file name with '.' → '_' where stems clash, then "_2", "_3"...
/// for the same file name in different folders (a manifest).
void nameTrees(std::vector<BatchTree>& trees) {
  std::map<std::string, int> count, used;
  for (const auto& t : trees) ++count[t.cloud.stem().string()];
  for (auto& t : trees) {
    t.name = t.cloud.stem().string();
    if (count[t.name] > 1) {
      t.name = t.cloud.filename().string();
      std::replace(t.name.begin(), t.name.end(), '.', '_');
    }
    const int n = ++used[t.name];
    if (n > 1) {
      t.name += '_';
      t.name += std::to_string(n);
    }
  }
}

std::vector<BatchTree> readManifest(const fs::path& manifest) {
  std::ifstream in(manifest);
  if (!in) throw InputError(manifest.string() + ": cannot open the manifest");
  std::vector<BatchTree> trees;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto a = line.find_first_not_of(" \t\r"), b = line.find_last_not_of(" \t\r");
    if (a == std::string::npos || line[a] == '#') continue;
    fs::path p = line.substr(a, b - a + 1);
    if (p.is_relative()) p = manifest.parent_path() / p;
    if (!fs::is_regular_file(p))
      throw InputError(manifest.string() + ":" + std::to_string(n) + ": '" + p.string() +
                       "' is not a file, expected one cloud path per line");
    trees.push_back({"", p});
  }
  return trees;
}

}  // namespace

namespace {

/// Whether `file` is one of the batch's own outputs in `out` (its summary; the trees' files are in
/// folders, which a folder's listing does not enter): an --out that is the input folder must not
/// take its summary.csv for a tree on the next run.
bool isBatchOutput(const fs::path& file, const fs::path& out) {
  if (out.empty()) return false;
  const std::string name = file.filename().string();
  if (name != "summary.csv" && name != "summary.json") return false;
  std::error_code ec;
  return fs::equivalent(file.parent_path(), out, ec);
}

}  // namespace

BatchPlan planBatch(const fs::path& input, const fs::path& out) {
  BatchPlan plan;
  if (fs::is_directory(input)) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(input))
      if (e.is_regular_file() && !isBatchOutput(e.path(), out)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      const std::string ext = lower(f.extension().string());
      if (!isCloudExtension(ext)) continue;
      if ((ext == ".csv" || ext == ".txt") && isCylinderTable(f)) {
        plan.skipped.push_back(f.string() + ": a cylinder table (its header names a radius), not a cloud");
        continue;
      }
      plan.trees.push_back({"", f});
    }
  } else if (fs::is_regular_file(input)) {
    plan.trees = readManifest(input);
  } else {
    throw InputError(input.string() + ": no such folder or manifest");
  }
  if (plan.trees.empty())
    throw InputError(input.string() + ": no point clouds found (.las .laz .ply .xyz .txt .csv .pts .asc)");
  nameTrees(plan.trees);
  return plan;
}

std::vector<std::string> batchOutputNames() {
  return {"cylinders.csv", "qsm.txt", "mesh.ply", "metrics.json", "report.json"};
}

nlohmann::json inputStamp(const fs::path& cloud) {
  std::error_code ec;
  const auto bytes = fs::file_size(cloud, ec);
  const auto time = fs::last_write_time(cloud, ec);
  return {{"bytes", ec ? -1 : static_cast<std::int64_t>(bytes)},
          {"mtime", ec ? 0 : static_cast<std::int64_t>(time.time_since_epoch().count())}};
}

namespace {

bool readJson(const fs::path& p, nlohmann::json* j) {
  std::ifstream in(p);
  if (!in) return false;
  *j = nlohmann::json::parse(in, nullptr, false);
  return !j->is_discarded() && j->is_object();
}

}  // namespace

namespace {

/// Why a failure recorded in `j` may pass on a second try ("" = it would fail again).
std::string retryReason(const nlohmann::json& j, double treeTimeoutS, double treeMemoryMb) {
  if (j.contains("signal")) return "killed by signal " + j["signal"].dump();
  if (j.contains("timedOutAfterS")) {
    const double limit = j["timedOutAfterS"].get<double>();
    return treeTimeoutS <= 0 || treeTimeoutS > limit ? "stopped by a shorter time limit" : "";
  }
  if (j.contains("outOfMemoryMb")) {
    const double limit = j["outOfMemoryMb"].get<double>();
    return treeMemoryMb <= 0 || treeMemoryMb > limit ? "running out of a smaller memory limit" : "";
  }
  const int code = j.value("exitCode", 0);
  if (code == 1) return "an internal error";
  if (code == 4) return "its outputs could not be written";
  return "";
}

}  // namespace

std::string treeState(const fs::path& dir, const BatchTree& tree, const BatchRunOptions& options, std::string* why) {
  nlohmann::json j;
  const nlohmann::json stamp = inputStamp(tree.cloud);
  const auto sameOptions = [&](const nlohmann::json& m) {
    return options.model.is_null() || m.value("options", nlohmann::json()) == options.model;
  };
  if (readJson(dir / kDoneMarker, &j) && j.value("input", nlohmann::json()) == stamp) {
    for (const auto& name : batchOutputNames())
      if (!fs::exists(dir / name)) return "";
    if (sameOptions(j)) return "done";
    if (why) *why = "made with other options (" + j.value("options", nlohmann::json()).dump() + ")";
    return "";
  }
  if (readJson(dir / kFailedMarker, &j) && j.value("input", nlohmann::json()) == stamp) {
    if (!sameOptions(j)) {
      if (why) *why = "failed with other options";
      return "";
    }
    const std::string retry = options.model.is_null() ? "" : retryReason(j, options.treeTimeoutS, options.treeMemoryMb);
    if (retry.empty()) return "failed";
    if (why) *why = "failed by " + retry;
    return "";
  }
  return "";
}

namespace {

std::string csvField(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) {
    std::string s = v.get<std::string>(), q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  }
  return v.dump();
}

}  // namespace

std::size_t writeBatchSummary(const fs::path& out, const BatchPlan& plan, const BatchRunOptions& options) {
  static const char* kColumns[] = {"tree",     "cloud",        "status",  "error",     "points", "strayPoints",
                                   "up",       "totalMs",      "heightM", "dbhModelM", "dbhCloudM",
                                   "volumeM3", "volumeLowM3", "volumeHighM3", "measuredVolumeShare", "stemVolumeM3",
                                   "lengthM", "branches", "crownAreaM2", "verdict", "verdictReasons", "warnings"};
  nlohmann::json rows = nlohmann::json::array();
  std::size_t notDone = 0;
  for (const auto& t : plan.trees) {
    nlohmann::json j;
    const fs::path dir = out / t.name;
    const std::string state = treeState(dir, t, options);
    if (state == "done" || state == "failed") {
      readJson(dir / (state == "done" ? kDoneMarker : kFailedMarker), &j);
    } else {
      j = {{"tree", t.name}, {"cloud", t.cloud.string()}, {"status", "not run"}};
    }
    notDone += state != "done";
    rows.push_back(j);
  }
  std::string csv;
  for (const char* c : kColumns) csv += std::string(csv.empty() ? "" : ",") + c;
  csv += "\n";
  for (const auto& r : rows) {
    std::string line;
    bool first = true;
    for (const char* c : kColumns) {
      if (!first) line += ',';
      line += csvField(r.value(c, nlohmann::json()));
      first = false;
    }
    csv += line + "\n";
  }
  const nlohmann::json summary = {{"trees", rows.size()},
                                  {"done", rows.size() - notDone},
                                  {"notDone", notDone},
                                  {"skipped", plan.skipped},
                                  {"results", rows}};
  const std::string text = summary.dump(2) + "\n";
  writeFileAtomically(
      out / "summary.csv", [&](std::ostream& os) { os << csv; }, false);
  writeFileAtomically(
      out / "summary.json", [&](std::ostream& os) { os << text; }, false);
  return notDone;
}

}  // namespace treesketch::cli
