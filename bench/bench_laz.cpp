// LAZ decoding speed: treesketch's decoder on the 400k-point LAS 1.4 plot (PDRF 6, layered,
// 9 chunks) and the 114k-point LAS 1.2 plot (PDRF 0, point-wise), on one thread and on all, and
// in the same run laz-perf (npm, WebAssembly) under node on the same file, one thread (it has no
// other). Counter "points_per_s": points decoded per wall-clock second (laz-perf: its fastest of
// three decodes, timed inside node, start-up excluded). Needs ../shared/data/real; the laz-perf
// row needs node and scripts/install_deps.sh's laz-perf, and is skipped without them.
//
//   build-xxx/bench_laz --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "treesketch/io/las.h"
#include "treesketch/io/laz.h"

namespace {

namespace fs = std::filesystem;

fs::path realFile(const char* name) { return fs::path(TS_SHARED_DATA_DIR) / "real" / name; }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void decode(benchmark::State& state, const char* name) {
  const fs::path path = realFile(name);
  if (!fs::exists(path)) {
    state.SkipWithError("no shared data");
    return;
  }
  const std::string bytes = slurp(path);
  const auto h = treesketch::io::parseLasHeader(bytes, path.string());
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    std::string records = treesketch::io::decompressLaz(bytes, h, path.string(), nullptr, threads);
    benchmark::DoNotOptimize(records.data());
  }
  state.counters["points_per_s"] =
      benchmark::Counter(static_cast<double>(h.pointCount), benchmark::Counter::kIsIterationInvariantRate);
}

void lazPerf(benchmark::State& state, const char* name) {
  const fs::path path = realFile(name);
  const std::string cmd = "node '" + std::string(TS_LAZ_ORACLE_SCRIPT) + "' '" + TS_LAZ_ORACLE_DIR + "' '" +
                          path.string() + "' --time 2>/dev/null";
  for (auto _ : state) {
    FILE* pipe = popen(cmd.c_str(), "r");
    double points = 0, seconds = 0;
    const bool ok = pipe && std::fscanf(pipe, "%lf %lf", &points, &seconds) == 2;
    if (pipe) pclose(pipe);
    if (!ok || seconds <= 0) {
      state.SkipWithError("node or laz-perf missing (scripts/install_deps.sh), or no shared data");
      return;
    }
    state.SetIterationTime(seconds);
    state.counters["points_per_s"] = points / seconds;
  }
}

void BM_LazDecodeLas14Plot(benchmark::State& state) { decode(state, "spanner_TLS_Clip.laz"); }
void BM_LazDecodeLas12Plot(benchmark::State& state) { decode(state, "treels_pine_plot.laz"); }
void BM_LazPerfNodeLas14Plot(benchmark::State& state) { lazPerf(state, "spanner_TLS_Clip.laz"); }
void BM_LazPerfNodeLas12Plot(benchmark::State& state) { lazPerf(state, "treels_pine_plot.laz"); }

}  // namespace

// Argument: threads (0 = all cores).
BENCHMARK(BM_LazDecodeLas14Plot)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LazPerfNodeLas14Plot)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LazDecodeLas12Plot)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LazPerfNodeLas12Plot)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
