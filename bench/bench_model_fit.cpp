// Model-fit throughput (compare/model_fit.h): signed distances of 1 M points to a published
// cylinder model through the pieces' bounding-volume hierarchy, against the brute force that
// measures every piece for every point. Target: rTwig's SimpleForest model (1,149 cylinders) and
// its scan (14,667 points, ../shared/data/real), the scan repeated with 1 cm Gaussian jitter to
// 1 M points (so ~1/3 of them are a few cm off the wood and some far). Skipped when the data are
// not there.
//
//   build/bench_model_fit --benchmark_min_time=2
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <filesystem>
#include <random>

#include "treesketch/compare/model_fit.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/point_cloud_io.h"

namespace {

using namespace treesketch;

constexpr std::size_t kPoints = 1'000'000;

struct Data {
  geom::CylinderModel model;
  geom::PointCloud cloud;
  bool ok = false;
};

const Data& data() {
  static const Data d = [] {
    Data out;
    const std::filesystem::path real = std::filesystem::path(TS_SHARED_DATA_DIR) / "real";
    if (!std::filesystem::exists(real / "rtwig_QSM_simpleforest.csv") ||
        !std::filesystem::exists(real / "rtwig_cloud.txt"))
      return out;
    out.model = io::readCylinderTable(real / "rtwig_QSM_simpleforest.csv").model;
    const geom::PointCloud scan = io::readPointCloud(real / "rtwig_cloud.txt");
    std::mt19937_64 rng(1);
    std::normal_distribution<double> jitter(0.0, 0.01);
    out.cloud.positions.reserve(kPoints);
    for (std::size_t i = 0; i < kPoints; ++i)
      out.cloud.positions.push_back(scan.positions[i % scan.size()] +
                                    geom::Vec3(jitter(rng), jitter(rng), jitter(rng)));
    out.ok = true;
    return out;
  }();
  return d;
}

// The whole measure: index build, parallel queries, shares and median.
void BM_MeasureModelFit(benchmark::State& state) {
  const Data& d = data();
  if (!d.ok) return state.SkipWithError("../shared/data/real not found");
  compare::ModelFitReport r;
  for (auto _ : state) {
    r = compare::measureModelFit(d.cloud, d.model);
    benchmark::DoNotOptimize(r.within2cm);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * d.cloud.size()));
  state.counters["within2cm_pct"] = 100.0 * r.within2cm;
}
BENCHMARK(BM_MeasureModelFit)->Unit(benchmark::kMillisecond)->UseRealTime();

// Index build alone.
void BM_BuildIndex(benchmark::State& state) {
  const Data& d = data();
  if (!d.ok) return state.SkipWithError("../shared/data/real not found");
  for (auto _ : state) {
    compare::CylinderModelIndex index(d.model);
    benchmark::DoNotOptimize(index.size());
  }
}
BENCHMARK(BM_BuildIndex)->Unit(benchmark::kMicrosecond);

// The reference: every piece for every point (closed caps, the same distance function), in
// parallel, on the first 20k points (the rate is what compares).
void BM_BruteForce(benchmark::State& state) {
  const Data& d = data();
  if (!d.ok) return state.SkipWithError("../shared/data/real not found");
  const std::size_t n = 20'000;
  std::vector<double> out(n);
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        double best = std::numeric_limits<double>::infinity();
        for (const auto& c : d.model.cylinders) best = std::min(best, compare::signedDistance(d.cloud.positions[i], c));
        out[i] = best;
      }
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}
BENCHMARK(BM_BruteForce)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
