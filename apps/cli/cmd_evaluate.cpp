// treesketch evaluate: the thesis's experiment (chapter 5) in one command, and the robustness
// matrix of scan conditions.
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "tree_job.h"
#include "treesketch/eval/correcting_user.h"
#include "treesketch/eval/evaluation.h"
#include "treesketch/eval/evaluation_report.h"
#include "treesketch/eval/tree_suite.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace {

struct EvaluateOpts {
  std::string trees;
  int builtin = 3;
  std::string out = "out/evaluate";
  std::vector<std::string> patterns{"sphere"};
  std::vector<std::string> methods;
  std::vector<int> sweep;
  bool noSweep = false;
  bool noLeafOn = false, noLeafOff = false;
  std::string matrix;
  std::vector<std::string> conditions;
  std::string split = "all";
  double metresPerUnit = eval::kEzTreeMetresPerUnit;
  bool list = false;
  bool correcting = false;
  eval::CorrectingUserOptions c;
  eval::EvalOptions e;
};

// Where the trees come from, the scan conditions and the report.
void addScanOptions(CLI::App& cmd, EvaluateOpts& o) {
  cmd.add_option("--trees", o.trees,
                 "Folder of third-party trees (<name>.branches.obj, <name>.leaves.obj, <name>.json), e.g. "
                 "../shared/data/trees; default: the built-in generator's trees");
  cmd.add_option("--builtin", o.builtin, "How many built-in trees when --trees is not given")
      ->capture_default_str()
      ->check(CLI::Range(1, 30));
  cmd.add_option("--out", o.out, "Output folder")->capture_default_str();
  cmd.add_option(
         "--matrix", o.matrix,
         "Scan-condition matrix: quick (a small subset, runs in the tests) or full (see docs/evaluation/README.md); "
         "replaces --pattern and the point and TLS options")
      ->check(CLI::IsMember({"quick", "full"}));
  cmd.add_option("--conditions", o.conditions, "With --matrix: run only these rows (names as --list shows)");
  cmd.add_flag("--list", o.list, "With --matrix: print the matrix's conditions and exit");
  cmd.add_option("--split", o.split,
                 "Trees to run: the tuning half, the held-out half or all (the report shows the halves apart)")
      ->capture_default_str()
      ->check(CLI::IsMember({"tune", "held-out", "all"}));
  cmd.add_option("--metres-per-unit", o.metresPerUnit,
                 "Scale of the --trees folder's meshes, metres per unit (ez-tree trees: decimetres); scan noise "
                 "and station height are converted with it")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("--pattern", o.patterns, "Scan patterns: sphere, tls (several allowed)")
      ->capture_default_str()
      ->check(CLI::IsMember({"sphere", "tls"}));
  cmd.add_option("--points", o.e.sphereTargetPoints,
                 "Sphere pattern: aim for about this many points (rays scaled from a pilot scan's hit rate)")
      ->capture_default_str();
  cmd.add_option("--rays", o.e.sphereRays, "Sphere pattern: cast exactly this many rays (overrides --points)");
  cmd.add_option("--tls-points", o.e.tlsTargetPoints, "TLS pattern: aim for about this many points")
      ->capture_default_str();
  cmd.add_option("--tls-stations", o.e.tlsStations, "TLS pattern: stations on a ring")->capture_default_str();
}

// The methods, the sweep, the leaf states, the view and the correcting user.
void addMethodOptions(CLI::App& cmd, EvaluateOpts& o) {
  cmd.add_option("--methods", o.methods,
                 "Methods: uniform, user, ideal, skeleton, skeleton-wood (the skeleton on the classified wood; "
                 "default: all but skeleton-wood)");
  cmd.add_option("--uniform-nodes", o.e.uniformNodes, "Nodes of the uniform automatic sketch (thesis: 18)")
      ->capture_default_str();
  cmd.add_option("--user-nodes", o.e.userNodes, "Node budget of the simulated user")->capture_default_str();
  cmd.add_option("--sweep", o.sweep, "Node counts for the RMS-vs-nodes sweep (default 5 10 20 40 80)");
  cmd.add_flag("--no-sweep", o.noSweep, "Skip the node-count sweep");
  cmd.add_flag("--no-leaf-on", o.noLeafOn, "Skip the leaf-on scans");
  cmd.add_flag("--no-leaf-off", o.noLeafOff, "Skip the leaf-off scans");
  cmd.add_option("--view", o.e.view, "View of the sketches: front, side, top")
      ->capture_default_str()
      ->check(CLI::IsMember({"front", "side", "top"}));
  cmd.add_option("--pixel-noise", o.e.pixelNoise, "Simulated user's hand jitter, pixels")->capture_default_str();
  cmd.add_option("--samples", o.e.samples, "Comparison samples per direction (0: MeshLab's default)")
      ->capture_default_str();
  cmd.add_option("--seed", o.e.seed, "Seed of scans, sketches and sampling")->capture_default_str();
  cmd.add_flag("--choose-depth", o.e.chooseDepth,
               "The simulated user's screen nodes choose their depth along the view ray from the parent's circle "
               "(as the viewer does) instead of the thesis's fit (the best-supported circle along the whole ray)");
  cmd.add_flag_function(
      "--user-every-point", [&o](std::int64_t) { o.e.userFitsOnWood = false; },
      "On leaf-on scans the simulated user's nodes are fitted to every point (the thesis) instead of "
      "the points the wood/leaf classification calls wood");
  cmd.add_flag_function(
      "--user-draws-hidden", [&o](std::int64_t) { o.e.userDrawsWhatItSees = false; },
      "The simulated user draws every true branch, also where the points it fits on do not show it "
      "(limbs hidden behind leaves); by default it draws only what they show");
  cmd.add_flag_function(
      "--user-no-growth", [&o](std::int64_t) { o.e.userGrowth = false; },
      "The simulated user's nodes keep to their first test region (no growth until a circle is found)");
  cmd.add_option(
         "--user-band-metres", o.e.userInlierBandMetres,
         "Inlier band of the simulated user's circle fits, metres, converted to the trees' units (0: the fit's default "
         "taken in scene units)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd.add_flag("--correcting-user", o.correcting,
               "Run only the simulated correcting user: from the automatic skeleton, one edit at a time "
               "on the worst visible error; writes correcting_user.{csv,md} and correcting_user_*.svg");
  cmd.add_flag_function(
      "--correcting-wood-only", [&o](std::int64_t) { o.c.leafOnWoodOnly = true; },
      "--correcting-user: leaf-on runs start from the automatic model of the points the wood/leaf "
      "classification calls wood (as reconstruct --auto --leaf-on --wood-only) instead of every point");
  cmd.add_option("--edits", o.c.maxEdits, "--correcting-user: edits per case")
      ->capture_default_str()
      ->check(CLI::Range(1, 500));
  cmd.add_option("--target", o.c.targetPct, "--correcting-user: RMS target both ways, % of the diagonal")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  // The automatic model's settings, over its leaf-off or leaf-on preset (eval::automaticModelOptions).
  addSettingOptions(&cmd, o.e.skeletonSettings);
}

// The simulated correcting user instead of the evaluation.
void runCorrecting(const EvaluateOpts& o, const eval::EvalOptions& e, const std::vector<eval::TreeCase>& trees) {
  eval::CorrectingUserOptions c = o.c;
  c.pixelNoise = e.pixelNoise;
  c.seed = e.seed;
  std::vector<eval::CorrectingRun> runs = eval::runCorrectingEvaluation(trees, e, c);
  eval::writeCorrectingReport(o.out, runs, c);
  std::cout << eval::correctingMarkdown(runs, c);
  std::cout << "wrote " << o.out << "/correcting_user.csv, correcting_user.md and correcting_user_*.svg\n";
}

void runEvaluate(const EvaluateOpts& o, bool cmdRaysGiven, const std::string& legacyGiven) {
  if (!o.matrix.empty() && !legacyGiven.empty())
    throw OptionsError(legacyGiven + " sets the former single condition; it does not combine with --matrix");
  if (o.matrix.empty() && (!o.conditions.empty() || o.list))
    throw OptionsError("--conditions and --list need --matrix quick|full");
  if (!o.correcting && o.c.leafOnWoodOnly) throw OptionsError("--correcting-wood-only needs --correcting-user");
  checkSettings(o.e.skeletonSettings);  // before any scan
  eval::EvalOptions e = o.e;
  if (cmdRaysGiven) e.sphereTargetPoints = 0;
  e.patterns = o.patterns;
  if (!o.matrix.empty()) {
    e.conditions = eval::conditionMatrix(o.matrix);
    if (!o.conditions.empty()) e.conditions = eval::selectConditions(e.conditions, o.conditions);
    if (o.list) {
      std::cout << eval::conditionTable(e.conditions);
      return;
    }
  }
  if (!o.methods.empty())
    e.methods = o.methods;
  else
    e.methods = eval::defaultMethodNames();
  if (!o.sweep.empty()) e.nodeSweep = o.sweep;
  if (o.noSweep) e.nodeSweep.clear();
  e.leafOn = !o.noLeafOn;
  e.leafOff = !o.noLeafOff;
  if (!e.leafOn && !e.leafOff) throw OptionsError("--no-leaf-on and --no-leaf-off leave nothing to evaluate");
  e.log = [](const std::string& line) { std::cerr << line << "\n"; };
  checkOutputWritable(std::filesystem::path(o.out) / "results.csv");  // before hours of work
  std::vector<eval::TreeCase> all =
      o.trees.empty() ? eval::builtinTrees(o.builtin) : eval::loadTreeFolder(o.trees, o.metresPerUnit);
  std::vector<eval::TreeCase> trees;
  for (auto& t : all)
    if (eval::splitSelects(o.split, eval::treeHalf(t.name))) trees.push_back(std::move(t));
  if (trees.empty()) throw OptionsError("--split " + o.split + " selects none of the trees");
  const std::vector<eval::ScanCondition> conditions = eval::evaluationConditions(e);
  if (o.correcting) {
    runCorrecting(o, e, trees);
    return;
  }
  std::vector<eval::EvalRow> rows = eval::runEvaluation(trees, e);
  eval::writeReport(o.out, rows, conditions, e.skeletonSettings);
  std::cout << eval::markdownSummary(rows, conditions);
  std::cout << "wrote " << o.out
            << "/table.md, summary.md, results.csv, summary.csv and SVG plots (figures 5.12-5.14, RMS vs wood "
               "points and vs noise)\n";
}

}  // namespace

void registerEvaluate(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "evaluate",
      "Scan test trees (with and without leaves), reconstruct them with several sketch methods and compare each "
      "result with the branch mesh (Hausdorff, both directions) and the automatic model's wood volume with the "
      "tree's exact volume; writes table.md, summary.md, results.csv, "
      "summary.csv and SVG plots. --matrix runs the scan-condition matrix");
  auto o = std::make_shared<EvaluateOpts>();
  addScanOptions(*cmd, *o);
  addMethodOptions(*cmd, *o);
  cmd->callback([cmd, o, &action] {
    bool cmdRaysGiven = cmd->count("--rays") > 0;
    std::string legacyGiven;  // an option of the former single condition, checked when the action runs
    for (const char* opt : {"--pattern", "--points", "--rays", "--tls-points", "--tls-stations"})
      if (cmd->count(opt) > 0 && legacyGiven.empty()) legacyGiven = opt;
    action = [o, cmdRaysGiven, legacyGiven] { runEvaluate(*o, cmdRaysGiven, legacyGiven); };
  });
}

}  // namespace treesketch::cli
