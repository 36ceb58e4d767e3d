// `treesketch compare A B [options]`: Metro/MeshLab-style Hausdorff comparison (thesis §2.5, §4.5).
// Forward = A sampled against B, backward = B sampled against A (skipped with --one-way), and the
// symmetric Hausdorff distance. A is a mesh (.obj, .ply); B is a mesh or a point cloud (.xyz
// .txt .csv .pts .asc .las .laz, or a .ply without faces). Prints a table; optionally writes the report as
// JSON and A's error mesh (binary PLY, per-vertex distance as quality, red = near, blue = far).
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "treesketch/compare/error_mesh.h"
#include "treesketch/compare/hausdorff.h"
#include "treesketch/io/file_info.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"
#include "treesketch/util/progress.h"
#include "treesketch/util/text.h"

namespace treesketch::cli {

namespace {

namespace fs = std::filesystem;

struct CompareArgs {
  std::string a, b;
  std::uint64_t samples = 0;
  bool noVertex = false, noEdge = false, noFace = false;
  double maxDist = std::numeric_limits<double>::infinity();
  double maxDistPct = 0;
  std::uint64_t seed = 1;
  bool oneWay = false;
  std::string json, errorMesh;
  std::vector<double> range;
  int bins = 10;
};

/// B: a mesh or a point cloud, decided by the file.
struct Target {
  bool isMesh = true;
  geom::TriMesh mesh;
  geom::PointCloud cloud;
};

std::string lowerExtension(const fs::path& p) { return lowercase(p.extension().string()); }

Target readTarget(const fs::path& path) {
  Target t;
  const std::string ext = lowerExtension(path);
  if (ext == ".ply") {
    io::FileInfo info = io::inspectFile(path);  // a PLY with a face element is a mesh, else a cloud
    t.isMesh = info.isMesh;
    t.mesh = std::move(info.mesh);
    t.cloud = std::move(info.cloud);
  } else if (ext == ".obj") {
    t.mesh = io::readMesh(path);
  } else {
    io::CloudReadOptions o;
    o.minPoints = 1;
    t.isMesh = false;
    t.cloud = io::readPointCloud(path, o);
  }
  if (t.isMesh && t.mesh.triangles.empty()) throw InputError(path.string() + ": the mesh has no triangles");
  if (!t.isMesh && t.cloud.empty()) throw InputError(path.string() + ": the point cloud has no points");
  return t;
}

/// Samples lie on triangles and percentages are of the sampled surface's bounding-box diagonal:
/// a mesh of zero area (every triangle with repeated or collinear corners) has neither.
void checkHasArea(const std::string& path, const geom::TriMesh& mesh) {
  if (!(mesh.area() > 0))
    throw DegenerateInputError(path + ": the mesh has zero area (its " + std::to_string(mesh.triangles.size()) +
                               " triangles all have repeated or collinear corners); nothing to compare");
}

/// "value (percent%)"; "-" for no value, "value (-)" when there is no diagonal to relate it to
/// (a cloud whose points are all equal).
std::string cell(double value, double percent) {
  if (std::isnan(value)) return "-";
  char buf[64];
  if (std::isfinite(percent))
    std::snprintf(buf, sizeof buf, "%.6g (%.4f%%)", value, percent);
  else
    std::snprintf(buf, sizeof buf, "%.6g (-)", value);
  return buf;
}

void printRow(const char* name, const compare::DistanceReport& r) {
  std::printf("%-9s %10llu %9llu  %-22s %-22s %-22s %-22s\n", name, static_cast<unsigned long long>(r.samplesUsed),
              static_cast<unsigned long long>(r.samplesDropped), cell(r.min, r.percent(r.min)).c_str(),
              cell(r.max, r.percent(r.max)).c_str(), cell(r.mean, r.percent(r.mean)).c_str(),
              cell(r.rms, r.percent(r.rms)).c_str());
}

// The comparison's table on stdout.
void printReport(const CompareArgs& args, const geom::TriMesh& a, const Target& b, const compare::BothReport& both) {
  std::printf("A: %s (%zu vertices, %zu triangles, bbox diagonal %.6g)\n", args.a.c_str(), a.vertices.size(),
              a.triangles.size(), a.bounds().diagonal());
  if (b.isMesh)
    std::printf("B: %s (%zu vertices, %zu triangles, bbox diagonal %.6g)\n", args.b.c_str(), b.mesh.vertices.size(),
                b.mesh.triangles.size(), b.mesh.bounds().diagonal());
  else
    std::printf("B: %s (point cloud, %zu points, bbox diagonal %.6g)\n", args.b.c_str(), b.cloud.size(),
                b.cloud.bounds().diagonal());
  std::printf("distances in the files' units; %% of the sampled surface's bbox diagonal\n");
  std::printf("%-9s %10s %9s  %-22s %-22s %-22s %-22s\n", "direction", "samples", "dropped", "min", "max", "mean",
              "RMS");
  printRow("forward", both.forward);
  if (!args.oneWay) printRow("backward", both.backward);
  const auto& f = both.forward;
  std::printf("forward samples: %llu vertex, %llu edge, %llu face\n", static_cast<unsigned long long>(f.vertexSamples),
              static_cast<unsigned long long>(f.edgeSamples), static_cast<unsigned long long>(f.faceSamples));
  if (std::isfinite(f.maxDistance)) std::printf("search distance: %.6g (farther samples dropped)\n", f.maxDistance);
  if (!args.oneWay) {
    if (std::isnan(both.hausdorff))
      std::printf("Hausdorff distance: - (a direction has no sample within the search distance)\n");
    else if (!std::isfinite(both.hausdorffPercent))
      std::printf("Hausdorff distance: %.6g\n", both.hausdorff);
    else
      std::printf("Hausdorff distance: %.6g (%.4f%% of A's bbox diagonal)\n", both.hausdorff, both.hausdorffPercent);
  }
}

// The JSON report and A's error mesh, when asked for.
void writeOutputs(const CompareArgs& args, const geom::TriMesh& a, const Target& b, const compare::BothReport& both) {
  const auto& f = both.forward;
  if (!args.json.empty()) {
    nlohmann::json j = args.oneWay ? nlohmann::json{{"forward", compare::toJson(both.forward)}} : compare::toJson(both);
    j["a"] = args.a;
    j["b"] = args.b;
    j["seed"] = args.seed;
    writeFileAtomically(
        args.json, [&](std::ostream& out) { out << j.dump(2) << "\n"; }, false);
  }
  if (!args.errorMesh.empty()) {
    // A's vertex samples give their distances; the vertices not sampled are measured now.
    std::vector<double> d = compare::vertexDistancesFromReport(f, a.vertices.size());
    if (b.isMesh)
      compare::fillVertexDistances(a, b.mesh, f.maxDistance, d);
    else
      compare::fillVertexDistances(a, b.cloud, f.maxDistance, d);
    compare::ErrorMeshOptions eo;
    if (args.range.size() == 2) {
      eo.rangeMin = args.range[0];
      eo.rangeMax = args.range[1];
    }
    const auto range = compare::colorRange(d, eo);
    io::writeMesh(args.errorMesh, compare::makeErrorMesh(a, d, eo));
    std::printf("error mesh: %s (quality = distance to B; red %.6g -> blue %.6g)\n", args.errorMesh.c_str(), range[0],
                range[1]);
  }
}

/// Most samples per kind: 20M backward samples held 2.6 GB in the scale test (docs/reliability.md).
constexpr std::uint64_t kMaxSamples = 20000000;

void runCompare(const CompareArgs& args) {
  if (args.samples > kMaxSamples)
    throw OptionsError("--samples " + std::to_string(args.samples) + ": at most " + std::to_string(kMaxSamples) +
                       " per kind (20M samples need about 2.6 GB)");
  if (!args.range.empty() && args.range.size() != 2) throw OptionsError("--range takes two values: MIN MAX (metres)");
  if (args.range.size() == 2 && !(args.range[0] <= args.range[1]))
    throw OptionsError("--range: MIN must not exceed MAX");
  if (!args.json.empty()) checkNotAnInput(args.json, {args.a, args.b});
  if (!args.errorMesh.empty()) {
    checkNotAnInput(args.errorMesh, {args.a, args.b});
    if (lowerExtension(args.errorMesh) != ".ply")
      throw OptionsError("--error-mesh " + args.errorMesh +
                         ": must be a .ply file (OBJ cannot hold colour and quality)");
  }
  checkOutputWritable(args.json);
  checkOutputWritable(args.errorMesh);

  const geom::TriMesh a = io::readMesh(args.a);
  checkHasArea(args.a, a);
  const Target b = readTarget(args.b);
  if (b.isMesh) checkHasArea(args.b, b.mesh);

  compare::CompareOptions o;
  o.sampling.vertices = !args.noVertex;
  o.sampling.edges = !args.noEdge;
  o.sampling.faces = !args.noFace;
  o.sampling.count = args.samples;
  o.sampling.seed = args.seed;
  o.maxDistance = args.maxDist;
  o.maxDistanceFraction = args.maxDistPct / 100.0;
  o.histogramBins = args.bins;
  o.keepSamples = !args.errorMesh.empty();
  ProgressBar bar("compare", ProgressBar::stderrIsTerminal());
  o.progress = bar.callback();

  compare::BothReport both;
  both.forward = b.isMesh ? compare::compareMeshes(a, b.mesh, o) : compare::compareMeshToCloud(a, b.cloud, o);
  if (!args.oneWay) {
    compare::CompareOptions back = o;
    back.keepSamples = false;
    both.backward = b.isMesh ? compare::compareMeshes(b.mesh, a, back) : compare::compareCloudToMesh(b.cloud, a, back);
    compare::finishBoth(both);
  }

  printReport(args, a, b, both);
  writeOutputs(args, a, b, both);
}

}  // namespace

void registerCompare(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand(
      "compare", "Hausdorff comparison of two surfaces as Metro / MeshLab (forward, backward, symmetric)");
  auto args = std::make_shared<CompareArgs>();
  sub->add_option("a", args->a, "Mesh A, e.g. the original (.obj .ply)")->required();
  sub->add_option("b", args->b,
                  "Mesh or point cloud B, e.g. the reconstruction (.obj .ply .xyz .txt .csv .pts .asc .las .laz)")
      ->required();
  sub->add_option("--samples", args->samples, "Samples per enabled kind (default: the sampled mesh's vertex count)");
  sub->add_flag("--no-vertex", args->noVertex, "Do not sample vertices");
  sub->add_flag("--no-edge", args->noEdge, "Do not sample edges");
  sub->add_flag("--no-face", args->noFace, "Do not sample faces");
  sub->add_option("--max-dist", args->maxDist, "Search distance: farther samples are dropped and counted")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--max-dist-pct", args->maxDistPct,
                  "Search distance as % of the sampled surface's bbox diagonal (MeshLab's default is 5)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--seed", args->seed, "Seed of the random samples")->capture_default_str();
  sub->add_flag("--one-way", args->oneWay, "Only the forward direction (A sampled against B)");
  sub->add_option("--json", args->json, "Write the report as JSON");
  sub->add_option("--error-mesh", args->errorMesh, "Write A coloured by distance to B (binary .ply)");
  sub->add_option("--range", args->range, "Colour range MIN MAX of the error mesh (default: the distances' min, max)")
      ->expected(2);
  sub->add_option("--bins", args->bins, "Histogram bins")->check(CLI::PositiveNumber)->capture_default_str();
  sub->callback([args, &action] { action = [args] { runCompare(*args); }; });
}

}  // namespace treesketch::cli
