// `treesketch metrics MODEL.csv [MODEL2 ...] [--cloud C] [--up y|z] [--units-metres U] [--json OUT.json]`:
// the forestry figures of cylinder models (treesketch's CSV, TreeQSM or SimpleForest tables) —
// height, DBH from the model and, with --cloud, from a circle fit to the cloud's 1.3 m slice,
// crown projection, wood volume by stem, branches and order, branch counts and lengths, taper
// (compare/tree_metrics.h). Several models are put side by side (a published model beside
// treesketch's on the same scan).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "treesketch/compare/tree_metrics.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace {

struct MetricsArgs {
  std::vector<std::string> models;
  std::string cloud, json, up;  // up "" = io/up_axis.h
  double unitMetres = 1.0;
  double breastHeight = 1.3;
};

std::string cell(double v, double scale, const char* f) {
  if (!std::isfinite(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, f, v * scale);
  return buf;
}

/// One line per model: the figures QSMs are compared by.
void printSideBySide(const MetricsArgs& a, const std::vector<compare::TreeMetrics>& all) {
  int w = 5;
  for (const auto& m : a.models) w = std::max(w, static_cast<int>(m.size()));
  if (!a.cloud.empty()) w = std::max(w, static_cast<int>(a.cloud.size() + 6));
  std::printf("\n%-*s %10s %10s %10s %10s %10s %8s\n", w, "model", "volume L", "length m", "DBH cm", "height m",
              "crown m2", "branches");
  for (std::size_t i = 0; i < all.size(); ++i) {
    const compare::TreeMetrics& m = all[i];
    std::printf("%-*s %10s %10s %10s %10s %10s %8zu\n", w, a.models[i].c_str(),
                cell(m.figures.volume, 1000, "%.1f").c_str(), cell(m.figures.length, 1, "%.2f").c_str(),
                cell(m.figures.trunkDiameter, 100, "%.1f").c_str(), cell(m.height, 1, "%.2f").c_str(),
                cell(m.crownArea, 1, "%.2f").c_str(), m.branches);
  }
  if (!all.empty() && all[0].hasCloud && all[0].cloudDbh.ok)
    std::printf("%-*s %10s %10s %10s %10s %10s\n", w, ("cloud " + a.cloud).c_str(), "", "",
                cell(all[0].cloudDbh.diameter, 100, "%.1f").c_str(), cell(all[0].cloudHeight, 1, "%.2f").c_str(),
                cell(all[0].cloudCrownArea, 1, "%.2f").c_str());
}

void runMetrics(const MetricsArgs& a) {
  if (!a.json.empty()) {
    checkNotAnInput(a.json, {a.cloud});
    for (const auto& m : a.models) checkNotAnInput(a.json, {m});
  }
  if (!a.up.empty()) geom::parseUpAxis(a.up);
  std::vector<io::CylinderTable> tables;
  for (const auto& path : a.models) {
    tables.push_back(io::readCylinderTable(path));
    if (tables.back().model.empty()) throw InputError(path + ": the table has no cylinders");
  }
  geom::PointCloud cloud;
  if (!a.cloud.empty()) cloud = io::readPointCloud(a.cloud);
  const io::UpAxisChoice up = io::chooseUpAxis(a.up, cloud);
  std::printf("up axis: %s; 1 unit = %g m\n", up.reason.c_str(), a.unitMetres);

  compare::TreeMetricsOptions o;
  o.unitMetres = a.unitMetres;
  o.breastHeight = a.breastHeight;
  nlohmann::json j;
  j["cloud"] = a.cloud.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.cloud);
  j["up"] = geom::toString(up.up);
  j["upReason"] = up.reason;
  j["models"] = nlohmann::json::array();
  std::vector<compare::TreeMetrics> all;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    all.push_back(compare::treeMetrics(tables[i].model, up.up, o, a.cloud.empty() ? nullptr : &cloud));
    std::printf("\n%s (%s table, %zu cylinders):\n%s", a.models[i].c_str(), io::toString(tables[i].format),
                tables[i].model.size(), compare::metricsTable(all.back()).c_str());
    j["models"].push_back(
        {{"file", a.models[i]}, {"format", io::toString(tables[i].format)}, {"metrics", compare::toJson(all.back())}});
  }
  if (all.size() > 1) printSideBySide(a, all);
  if (!a.json.empty()) {
    const std::string text = j.dump(2) + "\n";
    writeFileAtomically(
        a.json, [&](std::ostream& out) { out << text; }, false);
    std::printf("-> %s\n", a.json.c_str());
  }
}

}  // namespace

void registerMetrics(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand(
      "metrics", "Forestry figures of cylinder models: height, DBH, crown, volume by order, branches, taper");
  auto a = std::make_shared<MetricsArgs>();
  sub->add_option("models", a->models,
                  "Cylinder tables: treesketch's --cylinders CSV, TreeQSM (text export or matrix), SimpleForest")
      ->required();
  sub->add_option("--cloud", a->cloud, "The tree's cloud: DBH from its 1.3 m slice, its height and crown");
  sub->add_option("--up", a->up, "Up axis, y or z (default: what the cloud file declares, else z)")
      ->check(CLI::IsMember({"y", "z", "Y", "Z"}));
  sub->add_option("--units-metres", a->unitMetres, "Metres per model/cloud unit (default 1)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--breast-height", a->breastHeight, "Breast height above the base, metres (default 1.3)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--json", a->json, "Write the metrics as JSON");
  sub->callback([a, &action] { action = [a] { runMetrics(*a); }; });
}

}  // namespace treesketch::cli
