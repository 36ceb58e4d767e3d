// `treesketch fit-report CLOUD MODEL.csv [--units-metres U] [--up z] [--json R.json]`: how well a
// cylinder model (treesketch's cylinder CSV, a TreeQSM or a SimpleForest table) explains a
// cloud — each point's signed distance to the model's surface summed up as shares within ±1, ±2,
// ±5 cm, too deep inside, missed — and the model's volume, length and trunk diameter at 1.3 m,
// so that a published model and treesketch's can be put side by side on a real scan.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "treesketch/compare/model_fit.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace {

struct FitReportArgs {
  std::string cloud, model, json, up;  // up "" = io/up_axis.h
  double unitMetres = 1.0;
};

void runFitReport(const FitReportArgs& a) {
  if (!a.json.empty()) checkNotAnInput(a.json, {a.cloud, a.model});
  checkOutputWritable(a.json);
  const io::CylinderTable table = io::readCylinderTable(a.model);
  if (table.model.empty()) throw InputError(a.model + ": the table has no cylinders");
  const geom::PointCloud cloud = io::readPointCloud(a.cloud);
  if (cloud.empty()) throw InputError(a.cloud + ": the cloud has no points");

  const io::UpAxisChoice up = io::chooseUpAxis(a.up, cloud);
  compare::ModelFitOptions o;
  o.unitMetres = a.unitMetres;
  const compare::ModelFitReport fit = compare::measureModelFit(cloud, table.model, o);
  const compare::ModelFigures fig = compare::modelFigures(table.model, up.up, a.unitMetres);

  std::printf("fit-report: %s (%zu points) against %s (%s table, %zu cylinders); 1 unit = %g m, up %s\n",
              a.cloud.c_str(), cloud.size(), a.model.c_str(), io::toString(table.format), table.model.size(),
              a.unitMetres, up.reason.c_str());
  std::printf("fit: %s\n", compare::summaryLine(fit).c_str());
  std::printf("model: %s\n", compare::summaryLine(fig).c_str());
  if (!a.json.empty()) {
    nlohmann::json j;
    j["cloud"] = a.cloud;
    j["model"] = a.model;
    j["format"] = io::toString(table.format);
    j["up"] = geom::toString(up.up);
    j["fit"] = compare::toJson(fit);
    j["figures"] = compare::toJson(fig);
    const std::string text = j.dump(2) + "\n";
    writeFileAtomically(
        a.json, [&](std::ostream& out) { out << text; }, false);
  }
}

}  // namespace

void registerFitReport(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand(
      "fit-report",
      "How well a cylinder model (treesketch, TreeQSM or SimpleForest table) explains a cloud, and its volume, "
      "length, trunk diameter");
  auto a = std::make_shared<FitReportArgs>();
  sub->add_option("cloud", a->cloud, "Point cloud (.ply .xyz .txt .csv .pts .asc .las .laz)")->required();
  sub->add_option("model", a->model, "Cylinder table: treesketch's --cylinders CSV, TreeQSM or SimpleForest")
      ->required();
  sub->add_option("--units-metres", a->unitMetres, "Metres per cloud unit (default 1: the cloud is in metres)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--up", a->up,
                  "Up axis for the trunk diameter at 1.3 m, y or z (default: what the cloud file declares, else z)")
      ->check(CLI::IsMember({"y", "z", "Y", "Z"}));
  sub->add_option("--json", a->json, "Write the report as JSON");
  sub->callback([a, &action] { action = [a] { runFitReport(*a); }; });
}

}  // namespace treesketch::cli
