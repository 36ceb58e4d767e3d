// One tree through the automatic pipeline (see tree_job.h).
#include "tree_job.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "treesketch/classify/classify.h"
#include "treesketch/cloud/usable_extent.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/skeleton/option_table.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::cli {

namespace {

/// What the report says first: the job, the cloud and the automatic model's counts and timings.
nlohmann::json reportHeader(const TreeJob& a, const TreeJobResult& r, const skeleton::AutoSkeletonResult& s) {
  nlohmann::json header;
  header["cloud"] = a.cloud;
  header["mesh"] = a.out.mesh;
  header["auto"] = true;
  header["leafOn"] = a.leafOn;
  header["woodOnly"] = a.woodOnly;
  if (a.woodOnly) header["woodPoints"] = r.woodPoints;
  header["up"] = r.up;
  header["upReason"] = r.upReason;
  header["points"] = r.points;
  header["strayPoints"] = model::strayPointsJson(s.strays);
  header["warnings"] = r.scale.warnings;
  header["seed"] = a.seed;
  header["settings"] = a.settings;
  header["skeletonNodes"] = r.skeletonNodes;
  header["forks"] = r.forks;
  header["thinnedBySurface"] = s.thinnedBySurface;
  header["thickenedBySurface"] = s.thickenedBySurface;
  header["vertices"] = r.vertices;
  header["triangles"] = r.triangles;
  header["timings"] = {{"readMs", r.readMs},
                       {"skeletonMs", r.skeletonMs},
                       {"fitMs", r.fitMs},
                       {"sweepMs", r.sweepMs},
                       {"metricsMs", r.metricsMs}};
  return header;
}

/// The automatic model's settings for `foliage`: the preset, then the job's seed, ring, inlier
/// threshold and --set changes.
skeleton::AutoSkeletonOptions jobOptions(const TreeJob& a, skeleton::Foliage foliage, geom::UpAxis up) {
  skeleton::AutoSkeletonOptions opt = skeleton::autoSkeletonPreset(foliage, up);
  opt.seed = a.seed;
  opt.ringVertices = a.ring;
  if (a.inlierThreshold >= 0.0) opt.fit.circle.inlierThreshold = a.inlierThreshold;
  for (const std::string& s : a.settings) skeleton::applySetting(opt, s);
  return opt;
}

}  // namespace

TreeJobResult runTreeJob(const TreeJob& a) {
  const Stopwatch t0;
  checkSettings(a.settings);
  model::checkOutputs(a.out, {a.cloud});
  if (!a.sketch.empty()) {
    checkNotAnInput(a.sketch, {a.cloud});
    checkOutputWritable(a.sketch);
  }
  if (!a.strays.empty()) {
    checkNotAnInput(a.strays, {a.cloud});
    checkOutputWritable(a.strays);
  }
  TreeJobResult r;
  const geom::PointCloud cloud = io::readPointCloud(a.cloud);
  cloud::requireUsableExtent(cloud, a.cloud);
  r.points = cloud.size();
  r.readMs = t0.ms();
  const io::UpAxisChoice up = io::chooseUpAxis(a.up, cloud);
  r.up = geom::toString(up.up);
  r.upReason = up.reason;

  // With --wood-only the wood points are modelled with the leaf-off settings (what is left is
  // meant to be wood), and the model is measured against every point.
  geom::PointCloud woodStore;
  if (a.woodOnly) woodStore = model::woodOnlyCloud(cloud, up.up, a.cloud);
  const geom::PointCloud& modelled = a.woodOnly ? woodStore : cloud;
  r.woodPoints = a.woodOnly ? woodStore.size() : 0;
  const skeleton::AutoSkeletonOptions opt =
      jobOptions(a, a.leafOn && !a.woodOnly ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, up.up);
  const skeleton::AutoSkeletonResult s = skeleton::autoSkeletonSketch(modelled, opt);
  // The model is made from, and measured against, the points kept (the strays are set aside);
  // with --wood-only, against every point.
  geom::PointCloud keptStore;
  const geom::PointCloud& kept =
      a.woodOnly || s.strays.empty() ? cloud : (keptStore = cloud::keptPoints(cloud, s.strays));
  r.strays = s.strays;
  r.scale = cloud::checkScale(modelled, s.strays, a.unitMetres);
  printScaleWarnings(r.scale);
  model::checkAutoModel(a.cloud, a.woodOnly ? modelled : kept, s);
  r.skeletonMs = s.skeletonMs;
  r.fitMs = s.fitMs;
  r.sweepMs = s.sweepMs;
  r.skeletonNodes = s.model.size();
  r.forks = skeleton::countBranchPoints(s.model);
  for (char c : s.fitAccepted) r.fitsAccepted += c != 0;
  for (const auto& n : s.model) r.leafPieces += skeleton::isLeafPiece(n, opt);
  r.vertices = s.mesh.vertices.size();
  r.triangles = s.mesh.triangles.size();

  const Stopwatch tm;
  const model::TreeModel tree = model::fromAutoSkeleton(s, up.up);
  model::MeasureOptions mo = model::autoMeasureOptions(s, opt, a.leafOn);
  mo.unitMetres = a.unitMetres;
  mo.woodOnly = a.woodOnly;
  // A wood-only model's wood may be as much as a model of every point holds (its range's upper end);
  // a model of every point of a tree in leaf may hold no more than the classified wood shows (its lower end).
  if (a.woodOnly)
    mo.everyPointVolume = model::everyPointVolume(cloud, jobOptions(a, skeleton::Foliage::LeafOn, up.up), up.up);
  if (a.leafOn && !a.woodOnly)
    mo.classifiedWoodVolume =
        model::classifiedWoodVolume(cloud, jobOptions(a, skeleton::Foliage::LeafOff, up.up), up.up);
  model::lookForStems(mo, modelled, up.up, s.strays);
  const model::ModelMeasures measures = model::measure(tree, kept, mo);
  r.metricsMs = tm.ms();

  const nlohmann::json header = reportHeader(a, r, s);
  // The sketch first; the model's outputs end with the report, after which a batch writes its
  // done marker, so their presence says the tree is complete.
  if (!a.sketch.empty()) io::writeSketch(std::filesystem::path(a.sketch), s.sketch);
  if (!a.strays.empty()) io::writePointCloud(a.strays, cloud::selectPoints(modelled, s.strays.setAside));
  model::writeOutputs(tree, measures, a.out, header);
  r.measures = measures;
  r.totalMs = t0.ms();
  return r;
}

void printScaleWarnings(const cloud::ScaleCheck& scale) {
  for (const std::string& w : scale.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  std::fflush(stderr);
}

void checkSettings(const std::vector<std::string>& settings) {
  skeleton::AutoSkeletonOptions probe = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOff);
  for (const std::string& s : settings) skeleton::applySetting(probe, s);
}

namespace {

void printSettingTable() {
  using skeleton::Foliage;
  const skeleton::AutoSkeletonOptions off = skeleton::autoSkeletonPreset(Foliage::LeafOff);
  const skeleton::AutoSkeletonOptions on = skeleton::autoSkeletonPreset(Foliage::LeafOn);
  std::printf("settings of the automatic model (--set NAME=VALUE), with the leaf-off defaults:\n%s",
              skeleton::formatSettingTable(off).c_str());
  std::string diff;
  for (const skeleton::SettingInfo& s : skeleton::settingTable()) {
    const double v = skeleton::settingValue(on, s.name);
    if (v == skeleton::settingValue(off, s.name)) continue;
    diff += "\n  " + s.name + "=" + skeleton::formatSettingValue(s, v);
  }
  std::printf("--leaf-on starts from these instead:%s\n", diff.c_str());
  std::fflush(stdout);
}

}  // namespace

void addSettingOptions(CLI::App* command, std::vector<std::string>& settings) {
  command->add_option_function<std::vector<std::string>>(
      "--set",
      [&settings](const std::vector<std::string>& values) {
        for (const std::string& v : values) {
          if (v == "help") {
            printSettingTable();
            throw CLI::Success();
          }
          settings.push_back(v);
        }
      },
      "Change one setting of the automatic model, NAME=VALUE (repeatable; --set help lists them with their "
      "defaults and ranges)");
  command->add_flag_callback(
      "--list-settings",
      [] {
        printSettingTable();
        throw CLI::Success();
      },
      "Print the automatic model's settings (names, types, ranges, defaults) and exit");
}

void printModelSummary(const model::ModelMeasures& m, const model::OutputPaths& outputs) {
  if (m.hasFit)
    std::printf("model fit: %s%s\n", m.summary().c_str(),
                outputs.report.empty() ? "" : (" -> " + outputs.report).c_str());
  std::printf("%s\n", m.verdictLine().c_str());
  if (!outputs.report.empty() || !outputs.metrics.empty())
    std::printf("tree metrics:\n%s", compare::metricsTable(m.metrics).c_str());
}

}  // namespace treesketch::cli
