// `treesketch classify CLOUD -o OUT.ply|.las`: wood/leaf classification of a tree's points
// (classify/classify.h), written with the class code and the wood probability of every point
// (io/classified_cloud.h). Two more modes on labelled virtual scans of a tree folder
// (eval/classify_eval.h): --evaluate REPORT.md scores the built-in classifier per scan, --train
// OUT.json trains a new one on the tuning half (docs/classify.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>

#include "commands.h"
#include "treesketch/classify/classify.h"
#include "treesketch/cloud/usable_extent.h"
#include "treesketch/eval/classify_eval.h"
#include "treesketch/eval/condition_matrix.h"
#include "treesketch/io/classified_cloud.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"
#include "treesketch/util/text.h"

namespace treesketch::cli {

namespace {

struct ClassifyArgs {
  std::string cloud, output, up;
  double threshold = NAN;
  double promote = 1.0;
  bool noGraph = false;
  bool noSmoothing = false;
  bool context = false;  // the context pass, as the wood-only model classifies
  std::string model;  // a trained JSON instead of the built-in model
  // labelled scans
  std::string train, trainContext, evaluate, trees, split = "held-out";
  std::vector<std::string> moreTrees;  // --train: folders of further trees, every one trained on
  std::vector<std::string> conditions;
  double metresPerUnit = eval::kEzTreeMetresPerUnit;
  int leafVariants = 2;
  bool noPosition = false;
  bool noNormal = false;
  int rounds = 0, depth = 0;  // 0: the library's defaults (classify::BoostOptions)
  double learningRate = 0;
  std::size_t rowsPerScan = 0;  // 0: eval::ClassifierTraining's default
};

classify::ClassifyOptions classifyOptions(const ClassifyArgs& a) {
  classify::ClassifyOptions o = a.context ? classify::woodModellingOptions() : classify::ClassifyOptions{};
  if (!std::isnan(a.threshold)) o.threshold = a.threshold;
  o.connect = !a.noGraph;
  o.smoothing = !a.noSmoothing;
  o.graph.promoteProbability = a.promote;
  return o;
}

std::vector<eval::TreeCase> labelledTrees(const ClassifyArgs& a, bool tuning) {
  if (a.trees.empty()) throw OptionsError("--train, --train-context and --evaluate need --trees FOLDER (e.g. ../shared/data/trees)");
  std::vector<eval::TreeCase> out;
  for (auto& t : eval::loadTreeFolder(a.trees, a.metresPerUnit))
    if (tuning ? eval::treeHalf(t.name) == eval::TreeHalf::Tune : eval::splitSelects(a.split, eval::treeHalf(t.name)))
      out.push_back(std::move(t));
  if (out.empty()) throw OptionsError("the split selects none of the trees in " + a.trees);
  return out;
}

std::vector<eval::ScanCondition> conditions(const ClassifyArgs& a) {
  const auto all = eval::leafOnConditions();
  return a.conditions.empty() ? all : eval::selectConditions(all, a.conditions);
}

/// The training trees: the tuning half of --trees and every tree of the --more-trees folders. A
/// tree named as one of the held-out developer trees is refused: it would be scored on its own scans.
std::vector<eval::TreeCase> trainingTrees(const ClassifyArgs& a) {
  std::vector<eval::TreeCase> trees = labelledTrees(a, true);
  const auto& heldOut = eval::developerHeldOutTrees();
  for (const auto& folder : a.moreTrees)
    for (auto& t : eval::loadTreeFolder(folder, a.metresPerUnit)) {
      if (std::find(heldOut.begin(), heldOut.end(), t.name) != heldOut.end())
        throw OptionsError(folder + ": " + t.name + " is a held-out developer tree; it cannot be trained on");
      trees.push_back(std::move(t));
    }
  return trees;
}

void runTrain(const ClassifyArgs& a) {
  const std::string& out = a.train.empty() ? a.trainContext : a.train;
  checkOutputWritable(out);
  eval::ClassifierTraining t;
  t.conditions = conditions(a);
  t.leafVariants = a.leafVariants;
  t.features.positionFeatures = !a.noPosition;
  t.features.normalFeatures = !a.noNormal;
  if (a.rounds > 0) t.boost.rounds = a.rounds;
  if (a.depth > 0) t.boost.depth = a.depth;
  if (a.learningRate > 0) t.boost.learningRate = a.learningRate;
  if (a.rowsPerScan > 0) t.rowsPerScan = a.rowsPerScan;
  t.log = [](const std::string& line) { std::cerr << line << "\n"; };
  const classify::BoostedTrees m =
      a.train.empty() ? eval::trainContextClassifier(trainingTrees(a), t) : eval::trainClassifier(trainingTrees(a), t);
  writeFileAtomically(out, [&](std::ostream& o) { o << classify::toJson(m); });
  std::printf("wrote %s (%zu trees, threshold %.3f)\n", out.c_str(), m.trees.size(), m.threshold);
}

void runEvaluate(const ClassifyArgs& a, const classify::BoostedTrees* model) {
  checkOutputWritable(a.evaluate);
  eval::ClassifyEvalOptions o;
  o.conditions = conditions(a);
  o.classify = classifyOptions(a);
  o.log = [](const std::string& line) { std::cerr << line << "\n"; };
  const auto rows = eval::evaluateClassifier(labelledTrees(a, false), o, model);
  const std::string report = eval::classifyReport(rows);
  writeFileAtomically(a.evaluate, [&](std::ostream& out) { out << report; });
  std::cout << report.substr(0, report.find("\n\n") + 1) << "wrote " << a.evaluate << "\n";
}

void runClassifyCloud(const ClassifyArgs& a, const classify::BoostedTrees* model) {
  if (a.cloud.empty() || a.output.empty()) throw OptionsError("classify needs a CLOUD and -o OUT.ply|.las");
  checkNotAnInput(a.output, {a.cloud});
  checkOutputWritable(a.output);
  const std::string ext = lowercase(std::filesystem::path(a.output).extension().string());
  if (ext != ".ply" && ext != ".las") throw OptionsError(a.output + ": the output is .ply or .las");
  Stopwatch clock;
  const geom::PointCloud cloud = io::readPointCloud(a.cloud);
  cloud::requireUsableExtent(cloud, a.cloud);
  const double readMs = clock.ms();
  const io::UpAxisChoice up = io::chooseUpAxis(a.up, cloud);
  const classify::Classification c = [&] {
    try {
      return classify::classifyWood(cloud, up.up, classifyOptions(a), model);
    } catch (const DegenerateInputError& e) {  // the stage does not know the file: name it
      throw DegenerateInputError(a.cloud + ": " + e.what());
    }
  }();
  io::writeClassifiedCloud(a.output, cloud, classify::classCodes(c), c.woodProbability);
  std::printf("up axis: %s\n", up.reason.c_str());
  std::printf("%zu points (%zu core points), spacing %.4g (features at %.4g): %zu wood (%.1f %%), %zu leaf; "
              "threshold %.3f%s\n",
              cloud.size(), c.cores, c.measuredSpacing, c.spacing, c.woodPoints, 100.0 * c.woodPoints / cloud.size(),
              cloud.size() - c.woodPoints, c.threshold,
              c.contextPass ? " (context pass)" : c.smoothed ? " (probabilities smoothed over the graph)" : "");
  if (!a.noGraph)
    std::printf("graph step: %zu wood points reached from %zu at the base, %zu in pieces of their own, %zu demoted\n",
                c.graph.reached, c.graph.seeds, c.graph.kept, c.graph.demoted);
  std::printf("time: read %.0f ms, features %.0f ms, classifier %.0f ms, graph %.0f ms\n", readMs, c.featuresMs,
              c.predictMs, c.graphMs);
  std::printf("wrote %s (classification %d = wood, %d = leaf; wood_probability)\n", a.output.c_str(),
              classify::kWoodClass, classify::kLeafClass);
}

void runClassify(const ClassifyArgs& a) {
  if ((!a.train.empty()) + (!a.trainContext.empty()) + (!a.evaluate.empty()) > 1)
    throw OptionsError("--train, --train-context and --evaluate are separate runs");
  if (!a.train.empty() || !a.trainContext.empty()) return runTrain(a);
  std::unique_ptr<classify::BoostedTrees> model;
  if (!a.model.empty()) {
    std::ifstream in(a.model, std::ios::binary);
    if (!in) throw InputError(a.model + ": cannot open the model");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    model = std::make_unique<classify::BoostedTrees>(classify::boostedTreesFromJson(text, a.model));
  }
  if (!a.evaluate.empty()) return runEvaluate(a, model.get());
  runClassifyCloud(a, model.get());
}

}  // namespace

void registerClassify(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("classify",
                                 "Tell wood from leaves: write every point with its class (LAS/PLY classification 64 "
                                 "= wood, 65 = leaf) and its wood probability");
  auto a = std::make_shared<ClassifyArgs>();
  cmd->add_option("cloud", a->cloud, "Input cloud (.ply .xyz .txt .csv .pts .asc .las .laz .obj)");
  cmd->add_option("-o,--output", a->output, "Output cloud (.ply or .las)");
  cmd->add_option("--up", a->up, "Up axis, y or z (default: the file's, else z)")->check(CLI::IsMember({"y", "z"}));
  cmd->add_option("--threshold", a->threshold, "Wood at and above this probability (default: the model's)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--promote", a->promote,
                  "Points at least this probable become wood where the growth from the base reaches them")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--context", a->context,
                "Classify as --wood-only does: with the context pass (the first pass's wood around each point) at the "
                "modelling threshold 0.75 (--threshold changes it)");
  cmd->add_flag("--no-graph", a->noGraph, "The classifier's call alone, without keeping wood connected to the stem");
  cmd->add_flag("--no-smoothing", a->noSmoothing,
                "The built-in model's probabilities as they come, not averaged with their neighbours' (wood then at "
                "the model's own threshold)");
  cmd->add_option("--model", a->model, "A model trained with --train instead of the built-in one");
  cmd->add_option("--evaluate", a->evaluate,
                  "Score the classifier on labelled leaf-on scans of --trees and write a Markdown report here");
  cmd->add_option("--train", a->train, "Train a classifier on the tuning half of --trees and write it here (JSON)");
  cmd->add_option("--train-context", a->trainContext,
                  "Train the context model (the second pass the wood-only model classifies with) on the tuning half "
                  "of --trees and write it here (JSON)");
  cmd->add_option("--trees", a->trees, "Folder of test trees (ez-tree layout), e.g. ../shared/data/trees");
  cmd->add_option("--more-trees", a->moreTrees,
                  "--train, --train-context: also train on every tree of these folders (ez-tree layout, e.g. made by "
                  "scripts/test_trees/make_trees.sh; never the held-out developer trees)");
  cmd->add_option("--split", a->split, "--evaluate: tune, held-out or all")
      ->capture_default_str()
      ->check(CLI::IsMember({"tune", "held-out", "all"}));
  cmd->add_option("--conditions", a->conditions, "Leaf-on rows of the scan matrix (default: all of them)");
  cmd->add_option("--leaf-variants", a->leafVariants, "--train: scans per tree and condition (1 = leaves as given)")
      ->capture_default_str()
      ->check(CLI::Range(1, 8));
  cmd->add_flag("--no-position-features", a->noPosition,
                "--train: leave out the height and distance from the stem (shape and paths only)");
  cmd->add_flag("--no-normal-features", a->noNormal,
                "--train: leave out how the surface normals turn over each neighbourhood");
  cmd->add_option("--rounds", a->rounds, "--train, --train-context: boosted trees (default: the library's, 150)")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--depth", a->depth, "--train, --train-context: depth of each tree (default: the library's, 3)")
      ->check(CLI::Range(1, 12));
  cmd->add_option("--learning-rate", a->learningRate,
                  "--train, --train-context: each tree's learning rate (default: the library's, 0.15)")
      ->check(CLI::Range(1e-4, 1.0));
  cmd->add_option("--rows-per-scan", a->rowsPerScan,
                  "--train, --train-context: core points sampled per scan (default: 20000)")
      ->check(CLI::Range(std::size_t{100}, std::size_t{10000000}));
  cmd->add_option("--metres-per-unit", a->metresPerUnit, "Scale of the --trees meshes")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->callback([a, &action] { action = [a] { runClassify(*a); }; });
}

}  // namespace treesketch::cli
