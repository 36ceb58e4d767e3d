// `treesketch batch INPUT --out DIR [--jobs N] [--index K] [--summarise]`: the automatic pipeline
// over every tree of a plot (a folder of clouds or a manifest, batch_plan.h). Each tree runs in
// its own process (this program with --index K), N at a time: a tree that fails or crashes is
// recorded and the rest go on, and memory is bounded by N trees. A rerun skips complete trees.
// `--index K` runs only the K-th tree (0-based; what a Slurm job array calls) and `--summarise`
// only gathers the summary. Exit code: 0 when every tree is done, 6 (kExitSomeFailed) otherwise.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "batch_plan.h"
#include "commands.h"
#include "tree_job.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

extern char** environ;

namespace treesketch::cli {

namespace fs = std::filesystem;

namespace {

/// The verdict's reasons as one field ("; " between them).
std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

struct BatchArgs {
  std::string input, out, up;
  int jobs = 1;
  int index = -1;
  bool summarise = false, leafOn = false;
  double unitMetres = 1.0;
  std::uint64_t seed = 1;
};

void writeMarker(const fs::path& path, const nlohmann::json& j) {
  const std::string text = j.dump(2) + "\n";
  writeFileAtomically(
      path, [&](std::ostream& os) { os << text; }, false);
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

void recordFailure(const fs::path& dir, const BatchTree& t, const std::string& error, int code) {
  writeMarker(dir / kFailedMarker, {{"tree", t.name},
                                    {"cloud", t.cloud.string()},
                                    {"status", "failed"},
                                    {"error", error},
                                    {"exitCode", code},
                                    {"input", inputStamp(t.cloud)}});
}

/// One tree in this process: its outputs, then done.json; on an error failed.json, rethrown.
void runOneTree(const BatchArgs& a, const BatchTree& t) {
  const fs::path dir = fs::path(a.out) / t.name;
  if (treeState(dir, t) == "done") {
    std::printf("batch: %s already done\n", t.name.c_str());
    return;
  }
  std::error_code ec;
  fs::remove(dir / kDoneMarker, ec);
  fs::remove(dir / kFailedMarker, ec);
  TreeJob job;
  job.cloud = t.cloud.string();
  job.out.mesh = (dir / "mesh.ply").string();
  job.out.cylinders = (dir / "cylinders.csv").string();
  job.out.qsm = (dir / "qsm.txt").string();
  job.out.metrics = (dir / "metrics.json").string();
  job.out.report = (dir / "report.json").string();
  job.up = a.up;
  job.leafOn = a.leafOn;
  job.seed = a.seed;
  job.unitMetres = a.unitMetres;
  try {
    const TreeJobResult r = runTreeJob(job);
    const compare::TreeMetrics& m = r.measures.metrics;
    writeMarker(dir / kDoneMarker, {{"tree", t.name},
                                    {"cloud", t.cloud.string()},
                                    {"status", "ok"},
                                    {"error", nullptr},
                                    {"points", r.points},
                                    {"strayPoints", r.strays.count()},
                                    {"warnings", joined(r.scale.warnings)},
                                    {"up", r.up},
                                    {"totalMs", r.totalMs},
                                    {"timings",
                                     {{"readMs", r.readMs},
                                      {"skeletonMs", r.skeletonMs},
                                      {"fitMs", r.fitMs},
                                      {"sweepMs", r.sweepMs},
                                      {"metricsMs", r.metricsMs}}},
                                    {"heightM", number(m.height)},
                                    {"dbhModelM", number(m.figures.trunkDiameter)},
                                    {"dbhCloudM", number(m.cloudDbh.diameter)},
                                    {"volumeM3", m.figures.volume},
                                    {"volumeLowM3", r.measures.volumeLow},
                                    {"volumeHighM3", r.measures.volumeHigh},
                                    {"measuredVolumeShare", r.measures.measuredVolumeShare},
                                    {"verdict", model::toString(r.measures.verdict.level)},
                                    {"verdictReasons", joined(r.measures.verdict.reasons)},
                                    {"stemVolumeM3", m.stemVolume},
                                    {"lengthM", m.figures.length},
                                    {"branches", m.branches},
                                    {"crownAreaM2", m.crownArea},
                                    {"input", inputStamp(t.cloud)}});
    std::printf("batch: %s: %zu points (%s), up %s, %.0f ms\n%s\n%s", t.name.c_str(), r.points,
                cloud::strayPointsLine(r.strays).c_str(), r.upReason.c_str(), r.totalMs,
                r.measures.verdictLine().c_str(), compare::metricsTable(m).c_str());
  } catch (const InputError& e) {
    recordFailure(dir, t, e.what(), kExitInput);
    throw;
  } catch (const OutputError& e) {
    recordFailure(dir, t, e.what(), kExitOutput);
    throw;
  } catch (const OptionsError& e) {
    recordFailure(dir, t, e.what(), kExitUsage);
    throw;
  } catch (const std::exception& e) {
    recordFailure(dir, t, std::string("internal error: ") + e.what(), kExitInternal);
    throw;
  }
}

/// The command line of a child that runs tree `k`.
std::vector<std::string> childArgs(const BatchArgs& a, std::size_t k) {
  std::vector<std::string> v = {fs::read_symlink("/proc/self/exe").string(),
                                "batch",
                                a.input,
                                "--out",
                                a.out,
                                "--index",
                                std::to_string(k),
                                "--seed",
                                std::to_string(a.seed)};
  if (!a.up.empty()) v.insert(v.end(), {"--up", a.up});
  if (a.leafOn) v.push_back("--leaf-on");
  char unit[64];
  std::snprintf(unit, sizeof unit, "%.17g", a.unitMetres);
  v.insert(v.end(), {"--units-metres", unit});
  return v;
}

pid_t spawnTree(const BatchArgs& a, std::size_t k, const fs::path& log) {
  fs::create_directories(log.parent_path());
  std::vector<std::string> args = childArgs(a, k);
  std::vector<char*> argv;
  for (auto& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw OutputError("batch: cannot start a process for tree " + std::to_string(k) + ": " + strerror(rc));
  return pid;
}

void runAll(const BatchArgs& a, const BatchPlan& plan) {
  const fs::path out = a.out;
  fs::create_directories(out);
  for (const auto& s : plan.skipped) std::printf("batch: skipped %s\n", s.c_str());
  std::vector<std::size_t> todo;
  std::size_t already = 0;
  for (std::size_t k = 0; k < plan.trees.size(); ++k) {
    const std::string state = treeState(out / plan.trees[k].name, plan.trees[k]);
    if (state.empty())
      todo.push_back(k);
    else
      ++already;
  }
  std::printf("batch: %zu trees, %zu to run (%zu already done or failed on the same input), %d at a time\n",
              plan.trees.size(), todo.size(), already, a.jobs);
  std::fflush(stdout);
  std::map<pid_t, std::pair<std::size_t, std::chrono::steady_clock::time_point>> running;
  std::size_t next = 0, finished = 0, failed = 0;
  while (next < todo.size() || !running.empty()) {
    while (next < todo.size() && running.size() < static_cast<std::size_t>(a.jobs)) {
      const std::size_t k = todo[next++];
      const pid_t pid = spawnTree(a, k, out / plan.trees[k].name / "log.txt");
      running[pid] = {k, std::chrono::steady_clock::now()};
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) break;
    auto it = running.find(pid);
    if (it == running.end()) continue;
    const auto [k, start] = it->second;
    running.erase(it);
    const BatchTree& t = plan.trees[k];
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string what = "ok";
    if (WIFSIGNALED(status)) {
      what = "crashed (signal " + std::to_string(WTERMSIG(status)) + ")";
      recordFailure(out / t.name, t, what + "; see log.txt", kExitInternal);
    } else if (WEXITSTATUS(status) != 0) {
      what =
          "failed (exit " + std::to_string(WEXITSTATUS(status)) + ", see " + (out / t.name / "log.txt").string() + ")";
    }
    failed += what != "ok";
    ++finished;
    std::printf("batch: [%zu/%zu] %s: %s in %.1f s\n", finished, todo.size(), t.name.c_str(), what.c_str(), s);
    std::fflush(stdout);
  }
}

void runBatch(const BatchArgs& a) {
  if (a.jobs < 1) throw OptionsError("--jobs must be >= 1, got " + std::to_string(a.jobs));
  const BatchPlan plan = planBatch(a.input);
  if (a.index >= 0) {
    if (a.summarise) throw OptionsError("--index and --summarise are separate steps");
    if (static_cast<std::size_t>(a.index) >= plan.trees.size())
      throw OptionsError("--index " + std::to_string(a.index) + ": " + a.input + " has " +
                         std::to_string(plan.trees.size()) + " trees (0-based)");
    return runOneTree(a, plan.trees[static_cast<std::size_t>(a.index)]);
  }
  if (!a.summarise) runAll(a, plan);
  const std::size_t notDone = writeBatchSummary(a.out, plan);
  std::printf("batch: %zu of %zu trees done -> %s, %s\n", plan.trees.size() - notDone, plan.trees.size(),
              (fs::path(a.out) / "summary.csv").c_str(), (fs::path(a.out) / "summary.json").c_str());
  if (notDone > 0)
    throw SomeFailed(std::to_string(notDone) + " of " + std::to_string(plan.trees.size()) +
                     " trees failed or did not run; see " + (fs::path(a.out) / "summary.csv").string());
}

}  // namespace

void registerBatch(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand("batch",
                                 "Reconstruct every tree of a folder or manifest (--auto): mesh, cylinder tables, "
                                 "metrics and report per tree, and a summary");
  auto a = std::make_shared<BatchArgs>();
  sub->add_option(
         "input", a->input,
         "A folder of clouds (.las .laz .ply .xyz .txt .csv .pts .asc; cylinder tables skipped) or a manifest (one "
         "cloud path per line)")
      ->required();
  sub->add_option("--out", a->out, "Output folder: OUT/<tree>/ per tree, OUT/summary.csv and .json")->required();
  sub->add_option("--jobs", a->jobs, "Trees processed at a time, each in its own process (default 1)");
  sub->add_option("--index", a->index, "Run only the K-th tree (0-based), e.g. $SLURM_ARRAY_TASK_ID")
      ->check(CLI::NonNegativeNumber);
  sub->add_flag("--summarise,--summarize", a->summarise, "Only gather the summary of the trees run so far");
  sub->add_option("--up", a->up, "Up axis, y or z (default: what each file declares, else z)")
      ->check(CLI::IsMember({"y", "z", "Y", "Z"}));
  sub->add_flag("--leaf-on", a->leafOn, "The trees were scanned in leaf");
  sub->add_option("--units-metres", a->unitMetres, "Metres per cloud unit (default 1)")->check(CLI::PositiveNumber);
  sub->add_option("--seed", a->seed, "Random seed of the circle fits (default 1)");
  sub->callback([a, &action] { action = [a] { runBatch(*a); }; });
}

}  // namespace treesketch::cli
