// Virtual LIDAR throughput on a ~100k-triangle tree (a generated tree's branch mesh):
//   (a) raw Embree: rtcIntersect1 in a TBB loop over the very rays the sphere scanner casts
//       (precomputed, float, already in Embree's frame) — the ceiling;
//   (b) the scanner (scan::sphereScan on a prebuilt RayScene): ray generation + jitter +
//       rtcIntersect1 + double-precision hit refinement + cloud assembly, as rays/s;
//   (c) the thesis's largest scan, 1,179,648 rays (subdivision 8), wall time with and without
//       building the BVH; plus a TLS scan and the BVH build at each quality;
//   (d) the beam footprint's cost (7 sub-rays a beam, mixed returns) as a ratio to the same scan
//       with thin rays, both timed in the same iterations (BM_FootprintCost).
// Each runs with 1 and 2 threads (tbb::global_control). Targets: (b) >= 0.8 x (a); (c) < 1 s on
// 2 threads.
//
//   build-xxx/bench_scan --benchmark_min_time=1
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>
#include <stdexcept>

#include "treesketch/accel/ray_scene.h"
#include "treesketch/gen/tree_generator.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/scan/tls_scan.h"

namespace {

using treesketch::geom::TriMesh;
using treesketch::geom::Vec3;
namespace scan = treesketch::scan;
namespace accel = treesketch::accel;

constexpr int kThesisSubdiv = 8;  // 1,179,648 rays

const TriMesh& treeMesh() {
  static const TriMesh mesh = [] {
    treesketch::gen::TreeOptions o = treesketch::gen::presetOptions("default");
    o.leaves = false;
    TriMesh m;
    for (int detail = 1; detail <= 12; ++detail) {
      o.detail = detail;
      m = treesketch::gen::generateTree(o).branches.mesh;
      if (m.triangles.size() >= 90'000) break;
    }
    std::fprintf(stderr, "tree: generated (default preset), detail %d, %zu triangles, diagonal %.3f m\n", o.detail,
                 m.triangles.size(), m.bounds().diagonal());
    return m;
  }();
  return mesh;
}

scan::SphereScanOptions thesisOptions() {
  scan::SphereScanOptions o;
  o.subdivisions = kThesisSubdiv;
  return o;
}

// The sphere scanner's rays (scan::sphereScanRay: exactly what sphereScan casts), as float rays
// in the raw scene's frame.
std::vector<RTCRay> scannerRays(const Vec3& embreeOffset) {
  const TriMesh& m = treeMesh();
  const scan::SphereScanOptions o = thesisOptions();
  const std::uint64_t count = scan::sphereRayCount(o);
  const treesketch::geom::BBox bounds = m.bounds();
  std::vector<RTCRay> rays(count);
  for (std::uint64_t i = 0; i < count; ++i) {
    const accel::Ray a = scan::sphereScanRay(o, bounds, i);
    const Vec3 org = a.origin - embreeOffset;
    RTCRay& r = rays[i];
    r.org_x = static_cast<float>(org.x());
    r.org_y = static_cast<float>(org.y());
    r.org_z = static_cast<float>(org.z());
    r.dir_x = static_cast<float>(a.dir.x());
    r.dir_y = static_cast<float>(a.dir.y());
    r.dir_z = static_cast<float>(a.dir.z());
    r.tnear = 0.0f;
    r.tfar = INFINITY;
    r.time = 0.0f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
  }
  return rays;
}

// A raw Embree scene of the tree (translated to its bbox centre, as RayScene does).
struct RawScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Vec3 offset;
  explicit RawScene(RTCBuildQuality quality) {
    const TriMesh& m = treeMesh();
    offset = m.bounds().centre();
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("no Embree device");
    scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, quality);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, quality);
    auto* vb = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.vertices.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), m.triangles.size()));
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
      for (int k = 0; k < 3; ++k) vb[3 * v + k] = static_cast<float>(m.vertices[v][k] - offset[k]);
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) ib[3 * t + k] = m.triangles[t][k];
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("Embree build failed");
  }
  ~RawScene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

RTCBuildQuality embreeQuality(int q) {
  return q == 0 ? RTC_BUILD_QUALITY_LOW : q == 1 ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_HIGH;
}
const char* qualityName(int q) { return q == 0 ? "low" : q == 1 ? "medium" : "high"; }

// (a) raw rtcIntersect1 over the scanner's rays. Args: threads, build quality (0 low .. 2 high).
void BM_RawEmbreeIntersect1(benchmark::State& state) {
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, state.range(0));
  const RawScene raw(embreeQuality(static_cast<int>(state.range(1))));
  const std::vector<RTCRay> rays = scannerRays(raw.offset);
  std::atomic<std::uint64_t> hits{0};
  for (auto _ : state) {
    hits = 0;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        RTCIntersectContext ctx;
                        rtcInitIntersectContext(&ctx);
                        std::uint64_t h = 0;
                        for (std::size_t i = r.begin(); i != r.end(); ++i) {
                          RTCRayHit rh;
                          rh.ray = rays[i];
                          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                          rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                          rtcIntersect1(raw.scene, &ctx, &rh);
                          h += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
                        }
                        hits += h;
                      });
    benchmark::DoNotOptimize(hits.load());
  }
  state.SetLabel(qualityName(static_cast<int>(state.range(1))));
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(rays.size()) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["hit_frac"] = static_cast<double>(hits.load()) / static_cast<double>(rays.size());
}
BENCHMARK(BM_RawEmbreeIntersect1)
    ->ArgsProduct({{1, 2}, {0, 1, 2}})
    ->ArgNames({"threads", "quality"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// RayScene::intersectAll over the same rays (precomputed, double): the cost of the accel layer
// (frame change, double-precision refinement) without the scanner's ray generation. Arg: threads.
void BM_RaySceneIntersectAll(benchmark::State& state) {
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, state.range(0));
  const accel::RayScene scene(treeMesh());
  const Vec3 offset = treeMesh().bounds().centre();
  std::vector<accel::Ray> rays;
  for (const RTCRay& r : scannerRays(offset)) {
    accel::Ray a;
    a.origin = Vec3(r.org_x, r.org_y, r.org_z) + offset;
    a.dir = Vec3(r.dir_x, r.dir_y, r.dir_z);
    rays.push_back(a);
  }
  for (auto _ : state) {
    const std::vector<accel::RayHit> hits = scene.intersectAll(rays);
    benchmark::DoNotOptimize(hits.data());
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(rays.size()) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RaySceneIntersectAll)->Arg(1)->Arg(2)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond);

// (b)+(c) the scanner on a prebuilt RayScene: 1,179,648-ray sphere scan. Args: threads, quality.
void BM_SphereScanScanner(benchmark::State& state) {
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, state.range(0));
  const accel::RayScene scene(treeMesh(), {static_cast<accel::BuildQuality>(state.range(1))});
  std::uint64_t rays = 0, points = 0;
  for (auto _ : state) {
    const scan::ScanResult r = scan::sphereScan(scene, thesisOptions());
    rays = r.stats.raysCast;
    points = r.cloud.size();
    benchmark::DoNotOptimize(r.cloud.positions.data());
  }
  state.SetLabel(qualityName(static_cast<int>(state.range(1))));
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(rays) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_SphereScanScanner)
    ->ArgsProduct({{1, 2}, {0, 1, 2}})
    ->ArgNames({"threads", "quality"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// (c) the whole call from meshes: BVH build (default quality) + 1,179,648-ray sphere scan.
void BM_SphereScanWithBuild(benchmark::State& state) {
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, state.range(0));
  const std::vector<TriMesh> meshes = {treeMesh()};
  for (auto _ : state) {
    const scan::ScanResult r = scan::sphereScan(meshes, thesisOptions());
    benchmark::DoNotOptimize(r.cloud.positions.data());
  }
}
BENCHMARK(BM_SphereScanWithBuild)->Arg(1)->Arg(2)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond);

// BVH build alone, per quality. Args: threads, quality.
void BM_RaySceneBuild(benchmark::State& state) {
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, state.range(0));
  const TriMesh& m = treeMesh();
  for (auto _ : state) {
    const accel::RayScene scene(m, {static_cast<accel::BuildQuality>(state.range(1))});
    benchmark::DoNotOptimize(&scene);
  }
  state.SetLabel(qualityName(static_cast<int>(state.range(1))));
}
BENCHMARK(BM_RaySceneBuild)
    ->ArgsProduct({{1, 2}, {0, 1, 2}})
    ->ArgNames({"threads", "quality"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// A TLS survey of the same tree: 4 stations, 0.2 degree step (4 x 1800 x 751 = 5.4 M rays).
void BM_TlsScan(benchmark::State& state) {
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, state.range(0));
  const accel::RayScene scene(treeMesh());
  scan::TlsScanOptions o;  // defaults: Y up like the generated tree
  std::uint64_t rays = 0, points = 0;
  for (auto _ : state) {
    const scan::ScanResult r = scan::tlsScan(scene, o);
    rays = r.stats.raysCast;
    points = r.cloud.size();
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(rays) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_TlsScan)->Arg(1)->Arg(2)->ArgName("threads")->UseRealTime()->Unit(benchmark::kMillisecond);

// (d) The beam footprint (defaults: 0.3 mrad, 3 mm exit, a ring of 6 sub-rays) against thin rays,
// on the same scene and rays. Each iteration times the thin scan and then the footprint scan, so
// both see the same machine load; the counters are their mean wall times and process CPU times
// (std::clock: all threads; the figure to trust on a loaded machine) and both ratios.
// Args: pattern (0 = sphere, subdivision 8, 1.18 M rays; 1 = TLS, 4 stations at 0.2 degrees,
// 5.4 M rays), threads.
void BM_FootprintCost(benchmark::State& state) {
  const bool tls = state.range(0) == 1;
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, state.range(1));
  const accel::RayScene scene(treeMesh());
  auto run = [&](bool footprint) {
    if (tls) {
      scan::TlsScanOptions o;  // defaults: Y up like the generated tree
      o.beam.enabled = footprint;
      return scan::tlsScan(scene, o);
    }
    scan::SphereScanOptions o = thesisOptions();
    o.beam.enabled = footprint;
    return scan::sphereScan(scene, o);
  };
  using Clock = std::chrono::steady_clock;
  double thinMs = 0.0, wideMs = 0.0, thinCpuMs = 0.0, wideCpuMs = 0.0;
  auto cpuMs = [](std::clock_t a, std::clock_t b) { return 1000.0 * static_cast<double>(b - a) / CLOCKS_PER_SEC; };
  std::uint64_t thinPoints = 0, widePoints = 0, mixed = 0, rays = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    const std::clock_t c0 = std::clock();
    const scan::ScanResult thin = run(false);
    const auto t1 = Clock::now();
    const std::clock_t c1 = std::clock();
    const scan::ScanResult wide = run(true);
    const auto t2 = Clock::now();
    const std::clock_t c2 = std::clock();
    thinMs += std::chrono::duration<double, std::milli>(t1 - t0).count();
    wideMs += std::chrono::duration<double, std::milli>(t2 - t1).count();
    thinCpuMs += cpuMs(c0, c1);
    wideCpuMs += cpuMs(c1, c2);
    thinPoints = thin.cloud.size();
    widePoints = wide.cloud.size();
    mixed = wide.stats.mixed;
    rays = thin.stats.raysCast;
  }
  const double n = static_cast<double>(state.iterations());
  state.SetLabel(tls ? "tls" : "sphere");
  state.counters["rays"] = static_cast<double>(rays);
  state.counters["thin_ms"] = thinMs / n;
  state.counters["footprint_ms"] = wideMs / n;
  state.counters["ratio"] = wideMs / thinMs;
  state.counters["thin_cpu_ms"] = thinCpuMs / n;
  state.counters["footprint_cpu_ms"] = wideCpuMs / n;
  state.counters["cpu_ratio"] = wideCpuMs / thinCpuMs;
  state.counters["thin_points"] = static_cast<double>(thinPoints);
  state.counters["footprint_points"] = static_cast<double>(widePoints);
  state.counters["mixed_frac"] = widePoints ? static_cast<double>(mixed) / static_cast<double>(widePoints) : 0.0;
}
BENCHMARK(BM_FootprintCost)
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->ArgNames({"pattern", "threads"})
    ->Iterations(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
