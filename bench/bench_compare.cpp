// Closest-point throughput for the Hausdorff comparison: treesketch's BVH (Morton order + warm
// start) against Embree's rtcPointQuery with a plain closest-point callback, on the same ~100k-
// triangle target (a generated tree's branch mesh) and the same 1M queries: area-weighted samples
// of the target displaced by a smooth field of amplitude 0, 0.1 %, 1 % or 3 % of the diagonal, as a
// reconstruction at that distance from the original would give (thesis Table 5.1: backward RMS
// 0.76-3.68 % of the diagonal). The farther the queries, the more triangles lie within their
// distance and the slower any exact closest-point search is. Also the whole compareMeshes call.
//
//   build-xxx/bench_compare --benchmark_min_time=2
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <sys/resource.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <stdexcept>

#include "treesketch/accel/closest_point.h"
#if __has_include("treesketch/compare/hausdorff.h")
#include "treesketch/compare/hausdorff.h"
#define TS_HAVE_COMPARE 1
#endif
#include "treesketch/gen/tree_generator.h"

namespace {

using treesketch::geom::TriMesh;
using treesketch::geom::Vec3;

constexpr std::size_t kQueries = 1'000'000;

// Process CPU time (all threads), seconds. The machine is shared: wall-clock throughput depends on
// the load, so each benchmark also reports items per CPU-second ("per_core"): on two idle cores
// with perfect scaling the wall-clock rate would be twice that.
double processCpuSeconds() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return r.ru_utime.tv_sec + r.ru_stime.tv_sec + 1e-6 * (r.ru_utime.tv_usec + r.ru_stime.tv_usec);
}

struct CpuCounter {
  double start = processCpuSeconds();
  void report(benchmark::State& state, double items) {
    state.counters["per_core"] = benchmark::Counter(items / (processCpuSeconds() - start));
  }
};

const TriMesh& target() {
  static const TriMesh mesh = [] {
    // The default tree at detail 2 (~77k triangles), with more vertices per ring until it has
    // ~100k triangles.
    treesketch::gen::TreeOptions o = treesketch::gen::presetOptions("default");
    o.leaves = false;
    o.detail = 2;
    const std::vector<treesketch::gen::LevelOptions> base = o.levels;
    TriMesh m;
    for (double f = 1.0; f < 3.0; f += 0.05) {
      for (std::size_t l = 0; l < base.size(); ++l)
        o.levels[l].segments = std::max(3, static_cast<int>(std::lround(base[l].segments * f)));
      m = treesketch::gen::generateTree(o).branches.mesh;
      if (m.triangles.size() >= 95'000) break;
    }
    std::fprintf(stderr, "target: generated tree, detail %d, %zu triangles, %zu vertices, diagonal %.3f m\n", o.detail,
                 m.triangles.size(), m.vertices.size(), m.bounds().diagonal());
    return m;
  }();
  return mesh;
}

// Samples displaced by `perMille` thousandths of the target's diagonal.
std::vector<Vec3> makeQueries(int perMille) {
  {
    const TriMesh& m = target();
    std::vector<double> cdf;
    double total = 0;
    for (const auto& t : m.triangles) {
      total += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
      cdf.push_back(total);
    }
    const double amp = 0.001 * perMille * m.bounds().diagonal(), freq = 7.0 / m.bounds().diagonal();
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Vec3> q(kQueries);
    for (auto& p : q) {
      std::size_t t = std::lower_bound(cdf.begin(), cdf.end(), u(rng) * total) - cdf.begin();
      t = std::min(t, m.triangles.size() - 1);
      double a = u(rng), b = u(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const auto& tri = m.triangles[t];
      p = m.vertices[tri[0]] + a * (m.vertices[tri[1]] - m.vertices[tri[0]]) +
          b * (m.vertices[tri[2]] - m.vertices[tri[0]]);
      p += amp * Vec3(std::sin(freq * p.y() + 1), std::sin(freq * p.z() + 2), std::sin(freq * p.x() + 3));
    }
    return q;
  }
}

const std::vector<Vec3>& queries(int perMille) {
  static std::map<int, std::vector<Vec3>> cache;
  auto it = cache.find(perMille);
  if (it == cache.end()) it = cache.emplace(perMille, makeQueries(perMille)).first;
  return it->second;
}

void BM_BuildBvh(benchmark::State& state) {
  const TriMesh& m = target();
  for (auto _ : state) {
    treesketch::accel::MeshClosestPoint index(m);
    benchmark::DoNotOptimize(index.nodeCount());
  }
  state.SetItemsProcessed(state.iterations() * m.triangles.size());
}
BENCHMARK(BM_BuildBvh)->Unit(benchmark::kMillisecond)->UseRealTime();

// Arg 0: Morton order, arg 1: warm start.
void BM_TreesketchQueryAll(benchmark::State& state) {
  treesketch::accel::ClosestPointOptions o;
  o.mortonOrder = state.range(0) != 0;
  o.warmStart = state.range(1) != 0;
  treesketch::accel::MeshClosestPoint index(target(), o);
  const auto& q = queries(static_cast<int>(state.range(2)));
  double sum = 0;
  CpuCounter cpu;
  for (auto _ : state) {
    auto hits = index.queryAll(q);
    sum += hits[17].distance;
  }
  cpu.report(state, static_cast<double>(state.iterations() * q.size()));
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations() * q.size());
}
// Args: Morton order, warm start, displacement of the queries in thousandths of the diagonal.
BENCHMARK(BM_TreesketchQueryAll)
    ->Args({1, 1, 10})
    ->Args({1, 0, 10})
    ->Args({0, 1, 10})
    ->Args({0, 0, 10})
    ->Args({1, 1, 0})
    ->Args({1, 1, 1})
    ->Args({1, 1, 30})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// ---- raw Embree point query --------------------------------------------------------------------

struct EmbreeTarget {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  const TriMesh* mesh = nullptr;

  explicit EmbreeTarget(const TriMesh& m) : mesh(&m) {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("embree device");
    scene = rtcNewScene(device);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.vertices.size()));
    for (std::size_t i = 0; i < m.vertices.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(m.vertices[i][k]);
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), m.triangles.size()));
    for (std::size_t i = 0; i < m.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) idx[3 * i + k] = m.triangles[i][k];
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
  }
  ~EmbreeTarget() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

struct EmbreeResult {
  const TriMesh* mesh;
  Vec3 q;
  double best2;
  unsigned prim;
};

bool closestCallback(RTCPointQueryFunctionArguments* args) {
  auto* r = static_cast<EmbreeResult*>(args->userPtr);
  const auto& t = r->mesh->triangles[args->primID];
  Vec3 c = treesketch::accel::closestPointOnTriangle(r->q, r->mesh->vertices[t[0]], r->mesh->vertices[t[1]],
                                                     r->mesh->vertices[t[2]]);
  double d2 = (c - r->q).squaredNorm();
  if (d2 < r->best2) {
    r->best2 = d2;
    r->prim = args->primID;
    args->query->radius = static_cast<float>(std::sqrt(d2));
    return true;
  }
  return false;
}

// Arg 0: queries in Morton order (the sort is timed too).
void BM_EmbreePointQuery(benchmark::State& state) {
  EmbreeTarget et(target());
  const auto& q = queries(static_cast<int>(state.range(1)));
  std::vector<double> out(q.size());
  CpuCounter cpu;
  for (auto _ : state) {
    std::vector<std::uint32_t> order;
    if (state.range(0)) order = treesketch::accel::mortonOrder(q);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, q.size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
      RTCPointQueryContext ctx;
      for (std::size_t i = r.begin(); i < r.end(); ++i) {
        std::size_t qi = order.empty() ? i : order[i];
        rtcInitPointQueryContext(&ctx);
        RTCPointQuery pq;
        pq.x = static_cast<float>(q[qi].x());
        pq.y = static_cast<float>(q[qi].y());
        pq.z = static_cast<float>(q[qi].z());
        pq.time = 0;
        pq.radius = std::numeric_limits<float>::infinity();
        EmbreeResult res{et.mesh, q[qi], std::numeric_limits<double>::infinity(), RTC_INVALID_GEOMETRY_ID};
        rtcPointQuery(et.scene, &pq, &ctx, closestCallback, &res);
        out[qi] = std::sqrt(res.best2);
      }
    });
  }
  cpu.report(state, static_cast<double>(state.iterations() * q.size()));
  benchmark::DoNotOptimize(out.data());
  state.SetItemsProcessed(state.iterations() * q.size());
}
// Args: Morton order, displacement of the queries in thousandths of the diagonal.
BENCHMARK(BM_EmbreePointQuery)
    ->Args({0, 10})
    ->Args({1, 10})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({1, 30})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

#ifdef TS_HAVE_COMPARE
// The whole one-direction comparison (sampling + queries + statistics) of the displaced samples'
// source mesh against itself shifted: samples = vertex count per kind (MeshLab default), 3 kinds.
void BM_CompareMeshes(benchmark::State& state) {
  const TriMesh& m = target();
  TriMesh shifted = m;
  const double d = 0.005 * m.bounds().diagonal();
  for (auto& v : shifted.vertices) v += Vec3(d, 0, 0);
  treesketch::compare::CompareOptions o;
  std::size_t samples = 0;
  for (auto _ : state) {
    auto report = treesketch::compare::compareMeshes(m, shifted, o);
    samples = report.samplesUsed + report.samplesDropped;
  }
  state.SetItemsProcessed(state.iterations() * samples);
  state.counters["samples"] = static_cast<double>(samples);
}
BENCHMARK(BM_CompareMeshes)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

}  // namespace

BENCHMARK_MAIN();
