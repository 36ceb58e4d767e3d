// Skeleton sketch speed: a 1M-point cloud of a synthetic branching tree (noisy cylinder surfaces,
// trunk + 8 limbs + 4 twigs each, ~10 m tall) → extractSkeleton, and → autoSkeletonSketch
// (skeleton, sketch, every node's slice + RANSAC fit, radius rules, sweep). Target: ≤ 2 s on 2 cores.
// Also: a leafy cloud (the built-in generator's default tree with leaves, sphere-scanned to about
// 1M points, ~90 % leaf points) through autoSkeletonSketch with the leaf-on settings.
//   build-*/bench_skeleton --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "treesketch/cloud/ground.h"
#include "treesketch/cloud/stems.h"
#include "treesketch/gen/tree_generator.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/skeleton/skeleton_sketch.h"

using namespace treesketch;
using geom::Vec3;

namespace {

struct Cyl {
  Vec3 a, b;
  double r;
};

std::vector<Cyl> benchTree() {
  std::vector<Cyl> cyls;
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  cyls.push_back({Vec3(0, 0, 0), Vec3(0, 10, 0), 0.3});
  for (int i = 0; i < 8; ++i) {
    const double h = 3.0 + 0.8 * i, phi = 2.4 * i;
    const Vec3 base(0, h, 0);
    const Vec3 dir = Vec3(std::cos(phi), 0.8, std::sin(phi)).normalized();
    const double len = 4.0 - 0.3 * i;
    cyls.push_back({base, base + len * dir, 0.15 - 0.01 * i});
    for (int k = 0; k < 4; ++k) {
      const Vec3 tb = base + (0.35 + 0.15 * k) * len * dir;
      const Vec3 tdir = (dir + Vec3(uni(rng) - 0.5, 0.6, uni(rng) - 0.5)).normalized();
      cyls.push_back({tb, tb + 1.2 * tdir, 0.05});
    }
  }
  return cyls;
}

geom::PointCloud benchCloud(std::size_t target) {
  const auto cyls = benchTree();
  double area = 0;
  for (const auto& c : cyls) area += 2 * M_PI * c.r * (c.b - c.a).norm();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 0.005);
  geom::PointCloud cloud;
  cloud.positions.reserve(target + cyls.size());
  for (const auto& c : cyls) {
    const double len = (c.b - c.a).norm();
    const Vec3 axis = (c.b - c.a) / len, u = geom::anyPerpendicular(axis), v = axis.cross(u);
    const auto count = static_cast<std::size_t>(target * 2 * M_PI * c.r * len / area);
    for (std::size_t i = 0; i < count; ++i) {
      const double t = uni(rng) * len, a = uni(rng) * 2 * M_PI, r = c.r + gauss(rng);
      cloud.positions.push_back(c.a + t * axis + r * (std::cos(a) * u + std::sin(a) * v));
    }
  }
  return cloud;
}

const geom::PointCloud& cloud1M() {
  static const geom::PointCloud cloud = benchCloud(1000000);
  return cloud;
}

/// An earlier leaf-off skeleton (no sparse links, bridges within 8 voxels along a piece's axis):
/// the reference path for same-run ratios. (It also had a cross-section rule, since removed.)
void earlierLeafOffSkeleton(skeleton::SkeletonOptions& o) {
  o.graph.sparseLinkNeighbours = 0;
  o.graph.maxGapVoxels = 8;
  o.graph.coneAngleDeg = 45;
  o.graph.minBridgeLinearity = 0.4;
}

void BM_ExtractSkeleton1M(benchmark::State& state) {
  const auto& cloud = cloud1M();
  std::size_t nodes = 0;
  double voxel = 0;
  // Arg 0: defaults. Arg 1: the earlier leaf-off skeleton (earlierLeafOffSkeleton).
  skeleton::SkeletonOptions o;
  if (state.range(0) == 1) earlierLeafOffSkeleton(o);
  for (auto _ : state) {
    auto s = skeleton::extractSkeleton(cloud, o);
    nodes = s.nodes.size();
    voxel = s.graph.voxelSize;
    benchmark::DoNotOptimize(s);
  }
  state.counters["points"] = static_cast<double>(cloud.size());
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["voxel"] = voxel;  // cloud units (metres): the fits' band is max(0.01, 0.1 voxel)
}
BENCHMARK(BM_ExtractSkeleton1M)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_AutoSkeletonSketch1M(benchmark::State& state) {
  const auto& cloud = cloud1M();
  double skel = 0, fit = 0, sweep = 0, completion = 0, contraction = 0;
  std::size_t nodes = 0, forks = 0;
  // Arg 0: defaults. Arg 1: the fits' inlier band 15 % of the hypothesis's radius (the earliest fits).
  // Arg 2: the earlier leaf-off model (earlierLeafOffSkeleton, no allometric radius bound). Arg 3: no
  // completion (the model before it). Arg 4: the skeleton on the scan's own points (no drawing
  // together). For same-run ratios.
  skeleton::AutoSkeletonOptions o;
  if (state.range(0) == 3) o.completion.enabled = false;
  if (state.range(0) == 4) o.contractionNoises = 0;
  if (state.range(0) == 1) o.fit.circle.inlierThresholdRelative = 0.15;
  if (state.range(0) == 2) {
    earlierLeafOffSkeleton(o.skeleton);
    o.radii.allometryMaxRatio = 0;
  }
  for (auto _ : state) {
    auto r = skeleton::autoSkeletonSketch(cloud, o);
    skel = r.skeletonMs;
    fit = r.fitMs;
    sweep = r.sweepMs;
    completion = r.completionMs;
    contraction = r.contraction;
    nodes = r.model.size();
    forks = skeleton::countBranchPoints(r.model);
    benchmark::DoNotOptimize(r);
  }
  state.counters["points"] = static_cast<double>(cloud.size());
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["forks"] = static_cast<double>(forks);
  state.counters["skeletonMs"] = skel;
  state.counters["fitMs"] = fit;
  state.counters["sweepMs"] = sweep;
  state.counters["completionMs"] = completion;
  state.counters["contraction"] = contraction;
}
BENCHMARK(BM_AutoSkeletonSketch1M)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);

const geom::PointCloud& leafyCloud1M() {
  static const geom::PointCloud cloud = [] {
    gen::TreeOptions to = gen::presetOptions("default");
    to.leaves = true;
    const gen::GeneratedTree tree = gen::generateTree(to);
    scan::SphereScanOptions so;
    so.rays = 9400000;    // about 1M hits
    so.jitterDeg = 20.0;  // spread the rays over the whole crown
    return scan::sphereScan(std::vector<geom::TriMesh>{tree.branches.mesh, tree.leaves}, so).cloud;
  }();
  return cloud;
}

void BM_AutoSkeletonSketchLeafOn1M(benchmark::State& state) {
  const auto& cloud = leafyCloud1M();
  skeleton::AutoSkeletonOptions o = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOn);
  // Arg 0: the leaf-on defaults. Arg 1: every node fitted (leaf pieces too). Arg 2: every node
  // fitted and the plane test on all points (the first leaf-on path). Arg 3: the defaults with the fits'
  // inlier band 15 % of the hypothesis's radius (the earlier fits). For same-run ratios.
  if (state.range(0) == 1 || state.range(0) == 2) o.maxFitFlatFraction = 1.0;
  if (state.range(0) == 2) o.skeleton.leafPlaneMaxPointsPerVoxel = 0;
  if (state.range(0) == 2 || state.range(0) == 3) o.fit.circle.inlierThresholdRelative = 0.15;
  double skel = 0, fit = 0;
  std::size_t nodes = 0, fitted = 0;
  for (auto _ : state) {
    auto r = skeleton::autoSkeletonSketch(cloud, o);
    skel = r.skeletonMs;
    fit = r.fitMs;
    nodes = r.model.size();
    fitted = 0;
    for (const auto& f : r.fits) fitted += f.status == fit::NodeStatus::Fitted;
    benchmark::DoNotOptimize(r);
  }
  state.counters["points"] = static_cast<double>(cloud.size());
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["fitted"] = static_cast<double>(fitted);
  state.counters["skeletonMs"] = skel;
  state.counters["fitMs"] = fit;
}
BENCHMARK(BM_AutoSkeletonSketchLeafOn1M)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

// The points set aside before the automatic model: the strays alone (Arg 0) against the ground
// and then the strays (Arg 1), and those with the stems at breast height (Arg 2), on the 1M-point tree standing on 1M points of level, bumpy terrain
// 12 m across (2M points), for a same-run ratio.
void BM_GroundAndStrays(benchmark::State& state) {
  static const geom::PointCloud cloud = [] {
    geom::PointCloud c = cloud1M();
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> uni(-6.0, 6.0);
    std::normal_distribution<double> gauss(0.0, 0.005);
    for (int i = 0; i < 1000000; ++i) {
      const double x = uni(rng), z = uni(rng);
      if (x * x + z * z < 0.09) continue;  // under the trunk
      c.positions.emplace_back(x, 0.02 * std::sin(3 * x) * std::cos(2 * z) - 0.02 + gauss(rng), z);
    }
    return c;
  }();
  std::size_t aside = 0, stems = 0;
  for (auto _ : state) {
    if (state.range(0) == 3) {  // the repeated points alone (part of Arg 1 and 2)
      const std::vector<std::uint32_t> repeated = cloud::findRepeatedPoints(cloud);
      aside = repeated.size();
      benchmark::DoNotOptimize(repeated);
      continue;
    }
    const cloud::StrayPoints s = state.range(0) == 0 ? cloud::findStrayPoints(cloud)
                                                     : cloud::findStrayAndGroundPoints(cloud, geom::UpAxis::Y);
    aside = s.count();
    benchmark::DoNotOptimize(s);
    if (state.range(0) == 2) {  // and the stems at breast height above that ground, as the verdict asks
      const cloud::Stems found =
          cloud::findStems(cloud, geom::UpAxis::Y, cloud::setAsideFor(s, cloud::StrayReason::Ground), s.spacing);
      stems = found.stems.size();
      benchmark::DoNotOptimize(found);
    }
  }
  state.counters["points"] = static_cast<double>(cloud.size());
  state.counters["setAside"] = static_cast<double>(aside);
  if (state.range(0) == 2) state.counters["stems"] = static_cast<double>(stems);
}
BENCHMARK(BM_GroundAndStrays)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
