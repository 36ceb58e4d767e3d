// `treesketch split CLOUD -o FOLDER`: a plot (or a clip holding a neighbour) cut into one cloud per
// stem at breast height (cloud/stems.h), so that `batch FOLDER` models each tree apart. The ground
// is set aside first (cloud/ground.h) and written only when asked (--ground FILE); the stems'
// positions and diameters go to FOLDER/stems.json; stems that join below breast height (a
// tree forked there) go to one tree's cloud.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "treesketch/cloud/ground.h"
#include "treesketch/cloud/stems.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/cloud/usable_extent.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"
#include "treesketch/util/text.h"

namespace treesketch::cli {

namespace {

struct SplitArgs {
  std::string cloud, folder, ground, up, format = "ply";
  double unitMetres = 1.0;
  double minDiameter = 0.05;
};

// A folder split before holds that run's trees, listed in its stems.json: they go, so that a batch
// of the folder sees only this run's (nothing else in the folder is touched).
void removeEarlierTrees(const std::filesystem::path& table) {
  std::ifstream in(table);
  if (!in) return;
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return;  // not a table this command wrote: left alone, and overwritten below
  }
  if (!doc.contains("trees") || !doc["trees"].is_array()) return;
  for (const nlohmann::json& t : doc["trees"]) {
    if (!t.contains("file") || !t["file"].is_string()) continue;
    const std::filesystem::path name = t["file"].get<std::string>();
    if (name.has_parent_path() || name.string().rfind("tree_", 0) != 0) continue;  // only our own names
    std::error_code ec;
    std::filesystem::remove(table.parent_path() / name, ec);
  }
}

void runSplit(const SplitArgs& a) {
  namespace fs = std::filesystem;
  if (a.format != "ply" && a.format != "xyz") throw OptionsError("--format is ply or xyz (got " + a.format + ")");
  if (!a.ground.empty()) {
    checkNotAnInput(a.ground, {a.cloud});
    checkOutputWritable(a.ground);
  }
  std::error_code ec;
  fs::create_directories(a.folder, ec);
  if (ec || !fs::is_directory(a.folder)) throw OutputError(a.folder + ": cannot create the output folder");
  const fs::path table = fs::path(a.folder) / "stems.json";
  checkOutputWritable(table);

  const geom::PointCloud cloud = io::readPointCloud(a.cloud);
  cloud::requireUsableExtent(cloud, a.cloud);
  const io::UpAxisChoice up = io::chooseUpAxis(a.up, cloud);
  const cloud::StrayPoints strays = cloud::findStrayAndGroundPoints(cloud, up.up);
  const std::vector<std::uint32_t> ground = cloud::setAsideFor(strays, cloud::StrayReason::Ground);
  cloud::StemOptions so;
  so.unitMetres = a.unitMetres;
  so.minDiameter = a.minDiameter;
  const cloud::Stems stems = cloud::findStems(cloud, up.up, ground, strays.spacing, so);
  std::printf("up axis: %s\n", up.reason.c_str());
  std::printf("%zu points, %zu ground; terrain from %s\n", cloud.size(), ground.size(),
              stems.terrainFromGround ? "the ground points" : "the cloud's lowest points (no ground found)");
  if (stems.stems.empty()) {
    char why[200];
    std::snprintf(why, sizeof why,
                  ": no stem found at breast height (%.2f m above the terrain, at least %.0f cm across): nothing to "
                  "split (check --units-metres and the up axis)",
                  so.breastHeight, 100.0 * so.minDiameter);
    throw DegenerateInputError(a.cloud + why);
  }
  const std::vector<std::int32_t> label = cloud::splitByTree(cloud, up.up, stems, ground, so);
  removeEarlierTrees(table);

  std::vector<std::vector<std::uint32_t>> members(stems.trees);
  for (std::uint32_t i = 0; i < label.size(); ++i)
    if (label[i] >= 0) members[static_cast<std::size_t>(label[i])].push_back(i);
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t t = 0; t < stems.trees; ++t) {
    char name[32];
    std::snprintf(name, sizeof name, "tree_%03zu.%s", t + 1, a.format.c_str());
    const fs::path out = fs::path(a.folder) / name;
    io::writePointCloud(out, cloud::selectPoints(cloud, members[t]));
    nlohmann::json its = nlohmann::json::array();
    std::string dbhs;
    for (const cloud::Stem& st : stems.stems) {
      if (st.tree != static_cast<std::int32_t>(t)) continue;
      its.push_back({{"x", st.centre.x()},
                     {"y", st.centre.y()},
                     {"z", st.centre.z()},
                     {"dbhM", st.diameter},
                     {"circleRmsM", st.rms},
                     {"pointsOnCircle", st.points}});
      char d[32];
      std::snprintf(d, sizeof d, "%s%.1f", dbhs.empty() ? "" : " + ", 100.0 * st.diameter);
      dbhs += d;
    }
    rows.push_back({{"file", name}, {"points", members[t].size()}, {"stems", its}});
    const cloud::Stem& first = *std::find_if(stems.stems.begin(), stems.stems.end(),
                                             [&](const cloud::Stem& st) { return st.tree == static_cast<std::int32_t>(t); });
    std::printf("  %s  stem at (%.2f, %.2f, %.2f), DBH %s cm, %zu points\n", name, first.centre.x(), first.centre.y(),
                first.centre.z(), dbhs.c_str(), members[t].size());
  }
  if (!a.ground.empty() && !ground.empty()) io::writePointCloud(a.ground, cloud::selectPoints(cloud, ground));
  if (!a.ground.empty() && ground.empty()) std::printf("no ground points: %s not written\n", a.ground.c_str());
  const nlohmann::json doc = {{"cloud", a.cloud},
                              {"up", up.up == geom::UpAxis::Y ? "y" : "z"},
                              {"unitMetres", a.unitMetres},
                              {"breastHeightM", so.breastHeight},
                              {"groundPoints", ground.size()},
                              {"terrainFromGround", stems.terrainFromGround},
                              {"trees", rows}};
  writeFileAtomically(table, [&](std::ostream& o) { o << doc.dump(2) << "\n"; });
  std::printf("%zu trees (%zu stems at breast height) -> %s (model them with: treesketch batch %s)\n", stems.trees,
              stems.stems.size(), a.folder.c_str(), a.folder.c_str());
}

}  // namespace

void registerSplit(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand(
      "split", "Cut a plot into one cloud per stem at breast height (ground set aside), for batch to model each tree");
  auto a = std::make_shared<SplitArgs>();
  sub->add_option("cloud", a->cloud, "Point cloud (.ply .xyz .txt .csv .pts .asc .las .laz)")->required();
  sub->add_option("-o,--output", a->folder, "Output folder: tree_001.ply, ... and stems.json")->required();
  sub->add_option("--ground", a->ground, "Also write the ground points to this cloud file (.ply, .xyz)");
  sub->add_option("--format", a->format, "Format of the trees' clouds: ply or xyz")->capture_default_str();
  sub->add_option("--up", a->up, "World up axis, y or z (default: what the file declares, else z)");
  sub->add_option("--units-metres", a->unitMetres, "Size of one cloud unit in metres (breast height is 1.3 m)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--min-dbh", a->minDiameter, "Smallest stem diameter counted, metres")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->callback([a, &action] { action = [a] { runSplit(*a); }; });
}

}  // namespace treesketch::cli
