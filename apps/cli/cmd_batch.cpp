// `treesketch batch INPUT --out DIR [--jobs N] [--index K] [--summarise]`: the automatic pipeline
// over every tree of a plot (a folder of clouds or a manifest, batch_plan.h). Each tree runs in
// its own process (this program with --index K), N at a time: a tree that fails or crashes is
// recorded and the rest go on, and memory is bounded by N trees. A rerun skips complete trees.
// `--index K` runs only the K-th tree (0-based; what a Slurm job array calls) and `--summarise`
// only gathers the summary. Exit code: 0 when every tree is done, 6 (kExitSomeFailed) otherwise.
#include <fcntl.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <new>
#include <string>
#include <thread>
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
  bool summarise = false, leafOn = false, woodOnly = false;
  double unitMetres = 1.0;
  std::uint64_t seed = 1;
  double treeTimeoutS = 0;  // --tree-timeout (0 = none)
  double treeMemoryMb = 0;  // --tree-memory (0 = none): the address space of each tree's process
  std::vector<std::string> settings;  // --set NAME=VALUE: the automatic model's settings
};

/// The options recorded in each tree's markers: those that shape the model.
BatchRunOptions runOptions(const BatchArgs& a) {
  BatchRunOptions o;
  o.model = {
      {"up", a.up.empty() ? "auto" : a.up}, {"leafOn", a.leafOn}, {"woodOnly", a.woodOnly}, {"unitMetres", a.unitMetres}, {"seed", a.seed}};
  if (!a.settings.empty()) o.model["settings"] = a.settings;  // absent when none: older markers stay valid
  o.treeTimeoutS = a.treeTimeoutS;
  o.treeMemoryMb = a.treeMemoryMb;
  return o;
}

void writeMarker(const fs::path& path, const nlohmann::json& j) {
  const std::string text = j.dump(2) + "\n";
  writeFileAtomically(
      path, [&](std::ostream& os) { os << text; }, false);
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

/// failed.json; `extra` adds how it ended ({"signal": n} or {"timedOutAfterS": s}).
void recordFailure(const fs::path& dir, const BatchTree& t, const BatchArgs& a, const std::string& error, int code,
                   const nlohmann::json& extra = nlohmann::json::object()) {
  nlohmann::json j = {
      {"tree", t.name},   {"cloud", t.cloud.string()},      {"status", "failed"},          {"error", error},
      {"exitCode", code}, {"options", runOptions(a).model}, {"input", inputStamp(t.cloud)}};
  j.update(extra);
  writeMarker(dir / kFailedMarker, j);
}

/// The job of one tree: its outputs in `dir`, the run's options.
TreeJob treeJob(const BatchArgs& a, const BatchTree& t, const fs::path& dir) {
  TreeJob job;
  job.cloud = t.cloud.string();
  job.out.mesh = (dir / "mesh.ply").string();
  job.out.cylinders = (dir / "cylinders.csv").string();
  job.out.qsm = (dir / "qsm.txt").string();
  job.out.metrics = (dir / "metrics.json").string();
  job.out.report = (dir / "report.json").string();
  job.up = a.up;
  job.leafOn = a.leafOn;
  job.woodOnly = a.woodOnly;
  job.seed = a.seed;
  job.unitMetres = a.unitMetres;
  job.settings = a.settings;
  return job;
}

/// One tree in this process: its outputs, then done.json; on an error failed.json, rethrown.
void runOneTree(const BatchArgs& a, const BatchTree& t) {
  const fs::path dir = fs::path(a.out) / t.name;
  if (treeState(dir, t, runOptions(a)) == "done") {
    std::printf("batch: %s already done\n", t.name.c_str());
    return;
  }
  if (a.treeMemoryMb > 0) {  // this process is the tree's own (--index): bound its address space
    rlimit limit{};
    limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(a.treeMemoryMb * 1024.0 * 1024.0);
    ::setrlimit(RLIMIT_AS, &limit);
  }
  std::error_code ec;
  fs::remove(dir / kDoneMarker, ec);
  fs::remove(dir / kFailedMarker, ec);
  const TreeJob job = treeJob(a, t, dir);
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
                                    {"options", runOptions(a).model},
                                    {"input", inputStamp(t.cloud)}});
    std::printf("batch: %s: %zu points (%s), up %s, %.0f ms\n%s\n%s", t.name.c_str(), r.points,
                cloud::strayPointsLine(r.strays).c_str(), r.upReason.c_str(), r.totalMs,
                r.measures.verdictLine().c_str(), compare::metricsTable(m).c_str());
  } catch (const DegenerateInputError& e) {
    recordFailure(dir, t, a, e.what(), kExitNoResult);
    throw;
  } catch (const InputError& e) {
    recordFailure(dir, t, a, e.what(), kExitInput);
    throw;
  } catch (const OutputError& e) {
    recordFailure(dir, t, a, e.what(), kExitOutput);
    throw;
  } catch (const OptionsError& e) {
    recordFailure(dir, t, a, e.what(), kExitUsage);
    throw;
  } catch (const std::bad_alloc&) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "out of memory: the tree needs more than %.6g MB (--tree-memory)", a.treeMemoryMb);
    recordFailure(dir, t, a, a.treeMemoryMb > 0 ? buf : "out of memory", kExitNoResult,
                  {{"outOfMemoryMb", a.treeMemoryMb}});
    throw;
  } catch (const std::exception& e) {
    recordFailure(dir, t, a, std::string("internal error: ") + e.what(), kExitInternal);
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
  if (a.woodOnly) v.push_back("--wood-only");
  for (const std::string& s : a.settings) v.insert(v.end(), {"--set", s});
  if (a.treeMemoryMb > 0) {
    char mb[64];
    std::snprintf(mb, sizeof mb, "%.17g", a.treeMemoryMb);
    v.insert(v.end(), {"--tree-memory", mb});
  }
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

/// An exclusive lock on OUT/.batch.lock for the life of the object (flock: released when the
/// process ends, however it ends). Throws OutputError when another run holds it.
class OutLock {
 public:
  explicit OutLock(const fs::path& out) {
    const fs::path path = out / ".batch.lock";
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw OutputError(path.string() + ": cannot create the lock file: " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw OutputError("--out " + out.string() +
                        ": another batch run is writing there (it holds .batch.lock); wait for it to finish or "
                        "choose another --out");
    }
  }
  ~OutLock() { ::close(fd_); }
  OutLock(const OutLock&) = delete;
  OutLock& operator=(const OutLock&) = delete;

 private:
  int fd_ = -1;
};

/// The trees to run, saying why a tree with a marker runs again.
std::vector<std::size_t> treesToRun(const BatchArgs& a, const BatchPlan& plan, std::size_t* already) {
  std::vector<std::size_t> todo;
  for (std::size_t k = 0; k < plan.trees.size(); ++k) {
    std::string why;
    const std::string state = treeState(fs::path(a.out) / plan.trees[k].name, plan.trees[k], runOptions(a), &why);
    if (!state.empty()) {
      ++*already;
      continue;
    }
    todo.push_back(k);
    if (!why.empty()) std::printf("batch: %s runs again: %s\n", plan.trees[k].name.c_str(), why.c_str());
  }
  return todo;
}

struct Running {
  std::size_t tree = 0;
  std::chrono::steady_clock::time_point start;
  bool stopped = false;  // killed by --tree-timeout
};

/// Kills the trees running longer than --tree-timeout.
void stopOverdue(const BatchArgs& a, std::map<pid_t, Running>& running) {
  if (a.treeTimeoutS <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  for (auto& [pid, r] : running)
    if (!r.stopped && std::chrono::duration<double>(now - r.start).count() > a.treeTimeoutS) {
      ::kill(pid, SIGKILL);
      r.stopped = true;
    }
}

/// Records how a child ended; returns "ok" or what went wrong.
std::string recordEnd(const BatchArgs& a, const BatchTree& t, const Running& r, int status) {
  const fs::path dir = fs::path(a.out) / t.name;
  if (r.stopped) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "stopped after the time limit of %.4g s (--tree-timeout)", a.treeTimeoutS);
    recordFailure(dir, t, a, buf, kExitNoResult, {{"timedOutAfterS", a.treeTimeoutS}});
    return buf;
  }
  if (WIFSIGNALED(status)) {
    const std::string what = "crashed (signal " + std::to_string(WTERMSIG(status)) + ")";
    recordFailure(dir, t, a, what + "; see log.txt", kExitInternal, {{"signal", WTERMSIG(status)}});
    return what;
  }
  if (WEXITSTATUS(status) != 0)
    return "failed (exit " + std::to_string(WEXITSTATUS(status)) + ", see " + (dir / "log.txt").string() + ")";
  return "ok";
}

void runAll(const BatchArgs& a, const BatchPlan& plan) {
  const fs::path out = a.out;
  fs::create_directories(out);
  const OutLock lock(out);
  for (const auto& s : plan.skipped) std::printf("batch: skipped %s\n", s.c_str());
  std::size_t already = 0;
  const std::vector<std::size_t> todo = treesToRun(a, plan, &already);
  std::printf("batch: %zu trees, %zu to run (%zu already done or failed on the same input and options), %d at a time\n",
              plan.trees.size(), todo.size(), already, a.jobs);
  std::fflush(stdout);
  std::map<pid_t, Running> running;
  std::size_t next = 0, finished = 0;
  while (next < todo.size() || !running.empty()) {
    while (next < todo.size() && running.size() < static_cast<std::size_t>(a.jobs)) {
      const std::size_t k = todo[next++];
      const pid_t pid = spawnTree(a, k, out / plan.trees[k].name / "log.txt");
      running[pid] = {k, std::chrono::steady_clock::now(), false};
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, a.treeTimeoutS > 0 ? WNOHANG : 0);
    if (pid == 0) {  // none ended yet: the time limit, then a short wait
      stopOverdue(a, running);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    if (pid < 0) break;
    auto it = running.find(pid);
    if (it == running.end()) continue;
    const Running r = it->second;
    running.erase(it);
    const BatchTree& t = plan.trees[r.tree];
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - r.start).count();
    const std::string what = recordEnd(a, t, r, status);
    ++finished;
    std::printf("batch: [%zu/%zu] %s: %s in %.1f s\n", finished, todo.size(), t.name.c_str(), what.c_str(), s);
    std::fflush(stdout);
  }
}

void runBatch(const BatchArgs& a) {
  if (a.jobs < 1) throw OptionsError("--jobs must be >= 1, got " + std::to_string(a.jobs));
  if (!(a.treeMemoryMb >= 0) || !std::isfinite(a.treeMemoryMb))
    throw OptionsError("--tree-memory must be a number of megabytes >= 0 (0 = no limit)");
  if (!(a.treeTimeoutS >= 0) || !std::isfinite(a.treeTimeoutS))
    throw OptionsError("--tree-timeout must be a number of seconds >= 0 (0 = no limit)");
  checkSettings(a.settings);
  if (a.index < 0) checkOutputWritable((fs::path(a.out) / "summary.csv").string());  // exit 4 before any work
  const BatchPlan plan = planBatch(a.input, a.out);
  if (a.index >= 0) {
    if (a.summarise) throw OptionsError("--index and --summarise are separate steps");
    if (static_cast<std::size_t>(a.index) >= plan.trees.size())
      throw OptionsError("--index " + std::to_string(a.index) + ": " + a.input + " has " +
                         std::to_string(plan.trees.size()) + " trees (0-based)");
    return runOneTree(a, plan.trees[static_cast<std::size_t>(a.index)]);
  }
  if (!a.summarise) runAll(a, plan);
  BatchRunOptions gather = runOptions(a);
  if (a.summarise) gather.model = nullptr;  // whatever the runs recorded
  const std::size_t notDone = writeBatchSummary(a.out, plan, gather);
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
  sub->add_flag("--wood-only", a->woodOnly,
                "Model only the points the wood/leaf classification calls wood (see reconstruct --wood-only)");
  sub->add_option("--units-metres", a->unitMetres, "Metres per cloud unit (default 1)")->check(CLI::PositiveNumber);
  sub->add_option("--seed", a->seed, "Random seed of the circle fits (default 1)");
  sub->add_option("--tree-timeout", a->treeTimeoutS,
                  "Stop a tree that runs longer than this many seconds and record it in failed.json (default 0: no "
                  "limit; a rerun with a longer limit runs it again)");
  sub->add_option("--tree-memory", a->treeMemoryMb,
                  "Limit each tree's process to this many MB of address space and record a tree that needs more in "
                  "failed.json (default 0: no limit; a rerun with a larger limit runs it again)");
  addSettingOptions(sub, a->settings);
  sub->callback([a, &action] { action = [a] { runBatch(*a); }; });
}

}  // namespace treesketch::cli
