// The desktop tool's per-click and per-mode-switch work on large clouds, without a GPU: picking a
// point under the mouse (one pass projecting every point), and recolouring by a file attribute
// with its legend (intensity: two quantiles; classification: a table lookup and class counts).
// Clouds: a random box of N points with intensity and classes; the camera frames it from the front.
//
//   build/bench_picking --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <random>

#include "treesketch/geom/camera.h"
#include "treesketch/viewer/attribute_colors.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/picking.h"

namespace {

using treesketch::geom::Vec2;
using treesketch::geom::Vec3;
namespace geom = treesketch::geom;
namespace viewer = treesketch::viewer;

geom::PointCloud randomCloud(std::size_t n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  geom::PointCloud c;
  c.positions.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    c.positions.emplace_back(u(rng), 4.0 + 4.0 * u(rng), u(rng));
    c.intensity.push_back(static_cast<float>(30000.0 + 20000.0 * u(rng)));
    c.classification.push_back(static_cast<std::uint8_t>(i % 7 == 0 ? 2 : 5));
  }
  return c;
}

const geom::PointCloud& cloudOf(std::size_t n) {
  static std::size_t cachedN = 0;
  static geom::PointCloud cached;
  if (cachedN != n) {
    cached = randomCloud(n);
    cachedN = n;
  }
  return cached;
}

geom::Camera frontCamera() {
  geom::Camera cam;
  cam.viewport = geom::Viewport{340, 0, 940, 774};
  cam.view = geom::lookAt(Vec3(0, 4, 20), Vec3(0, 4, 0), Vec3(0, 1, 0));
  cam.projection = geom::perspective(30, 940.0 / 774.0, 0.1, 100);
  return cam;
}

void BM_PickPoint(benchmark::State& state) {
  const geom::PointCloud& c = cloudOf(static_cast<std::size_t>(state.range(0)));
  geom::Camera cam = frontCamera();
  Vec3 centre = cam.project(Vec3(0, 4, 0));
  for (auto _ : state) {
    viewer::PickedPoint p = viewer::pickPoint(c, cam, Vec2(centre.x(), centre.y()), 6.0);
    benchmark::DoNotOptimize(p);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_PickPoint)->Arg(100'000)->Arg(1'000'000)->Arg(2'000'000)->Unit(benchmark::kMillisecond);

void BM_IntensityColoursAndLegend(benchmark::State& state) {
  const geom::PointCloud& c = cloudOf(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    auto colours = viewer::attributeColors(c, viewer::ColorMode::Intensity);
    viewer::ValueRange r = viewer::quantileRange(c.intensity);  // the legend's range
    benchmark::DoNotOptimize(colours);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_IntensityColoursAndLegend)->Arg(1'000'000)->Arg(2'000'000)->Unit(benchmark::kMillisecond);

void BM_ClassColoursAndLegend(benchmark::State& state) {
  const geom::PointCloud& c = cloudOf(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    auto colours = viewer::attributeColors(c, viewer::ColorMode::Classification);
    viewer::Legend l = viewer::classLegend(c.classification);
    benchmark::DoNotOptimize(colours);
    benchmark::DoNotOptimize(l);
  }
}
BENCHMARK(BM_ClassColoursAndLegend)->Arg(1'000'000)->Arg(2'000'000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
