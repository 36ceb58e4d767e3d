// `treesketch scan MESH... -o CLOUD`: virtual LIDAR. Casts the thesis's sphere pattern or
// terrestrial-scanner stations at one or more meshes and writes the nearest hits as a cloud.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "treesketch/accel/ray_scene.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/scan/tls_scan.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"
#include "treesketch/util/progress.h"

namespace treesketch::cli {

namespace {

struct ScanArgs {
  std::vector<std::string> meshes;
  std::string output;
  std::string pattern = "sphere";
  int subdiv = scan::SphereScanOptions{}.subdivisions;
  std::uint64_t rays = 0;
  double radius = 0.0;
  double jitter = scan::SphereScanOptions{}.jitterDeg;
  double noise = 0.0;
  bool noiseGiven = false;  // else the pattern's default
  std::uint64_t seed = 1;
  std::string up = geom::toString(scan::TlsScanOptions{}.up);
  int stations = scan::TlsScanOptions{}.stationCount;
  double stationRadius = 0.0;
  double stationHeight = scan::TlsScanOptions{}.stationHeight;
  double step = scan::TlsScanOptions{}.stepDeg;
  double maxRange = 0.0;
  bool maxRangeGiven = false;  // else unlimited
  bool recordMesh = false;
};

void runScan(const ScanArgs& a) {
  for (const std::string& m : a.meshes) checkNotAnInput(a.output, {m});
  std::vector<geom::TriMesh> meshes;
  for (const std::string& m : a.meshes) meshes.push_back(io::readMesh(m));

  scan::ScanResult result;
  {
    const accel::RayScene scene(meshes);
    ProgressBar bar("scan", ProgressBar::stderrIsTerminal());
    if (a.pattern == "sphere") {
      scan::SphereScanOptions o;
      o.subdivisions = a.subdiv;
      o.rays = a.rays;
      o.radius = a.radius;
      o.jitterDeg = a.jitter;
      if (a.noiseGiven) o.rangeNoise = a.noise;
      o.seed = a.seed;
      o.recordMesh = a.recordMesh;
      result = scan::sphereScan(scene, o, bar.callback());
    } else {
      scan::TlsScanOptions o;
      o.stationCount = a.stations;
      o.stationRadius = a.stationRadius;
      o.stationHeight = a.stationHeight;
      o.stepDeg = a.step;
      if (a.noiseGiven) o.rangeNoise = a.noise;
      if (a.maxRangeGiven) o.maxRange = a.maxRange;
      o.up = geom::parseUpAxis(a.up);
      o.seed = a.seed;
      o.recordMesh = a.recordMesh;
      result = scan::tlsScan(scene, o, bar.callback());
    }
  }
  io::writePointCloud(a.output, result.cloud);

  const scan::ScanStats& s = result.stats;
  std::printf("scan: %s, %llu rays, %llu points (%.1f%% hit) in %.0f ms", a.pattern.c_str(),
              static_cast<unsigned long long>(s.raysCast), static_cast<unsigned long long>(s.hits),
              s.raysCast ? 100.0 * s.hits / s.raysCast : 0.0, s.milliseconds);
  if (meshes.size() > 1) {
    // The first mesh is taken as the wood (branches), the others as leaves etc.
    std::printf(", wood fraction %.3f (points on %s)", s.fraction(0), a.meshes[0].c_str());
  }
  std::printf(" -> %s\n", a.output.c_str());
}

}  // namespace

void registerScan(CLI::App& app, Action& action) {
  auto* sub =
      app.add_subcommand("scan", "Virtual LIDAR: scan meshes into a point cloud (thesis sphere or TLS stations)");
  auto a = std::make_shared<ScanArgs>();
  sub->add_option("meshes", a->meshes, "Mesh files (.obj .ply); with several, the first is counted as wood")
      ->required();
  sub->add_option("-o,--output", a->output, "Output cloud (.ply keeps station/mesh ids, .xyz .txt)")->required();
  sub->add_option("--pattern", a->pattern, "sphere (thesis §4.2) or tls (terrestrial stations)")
      ->check(CLI::IsMember({"sphere", "tls"}))
      ->capture_default_str();
  auto* subdiv = sub->add_option("--subdiv", a->subdiv, "sphere: subdivision level k, 18*4^k rays (thesis: 6-8)")
                     ->capture_default_str();
  auto* rays = sub->add_option("--rays", a->rays, "sphere: target ray count (instead of --subdiv)");
  subdiv->excludes(rays);
  sub->add_option("--radius", a->radius, "sphere: radius in mesh units (default: 1 x bbox diagonal)");
  sub->add_option("--jitter", a->jitter, "sphere: half-angle of the random aim jitter, degrees")->capture_default_str();
  auto* noise = sub->add_option("--noise", a->noise,
                                "Gaussian range noise sigma, mesh units (default: 0 for sphere, 0.002 for tls)");
  sub->add_option("--seed", a->seed, "Random seed (jitter, noise)")->capture_default_str();
  sub->add_option("--up", a->up, "tls: up axis, y or z")->capture_default_str();
  sub->add_option("--stations", a->stations, "tls: number of stations on a ring around the tree")
      ->capture_default_str();
  sub->add_option("--station-radius", a->stationRadius, "tls: ring radius, mesh units (default: 1 x bbox diagonal)");
  sub->add_option("--station-height", a->stationHeight, "tls: station height above the scene's bottom, mesh units")
      ->capture_default_str();
  sub->add_option("--step", a->step, "tls: angular step in azimuth and zenith, degrees")->capture_default_str();
  auto* maxRange = sub->add_option("--max-range", a->maxRange, "tls: maximum range, mesh units (default: unlimited)");
  sub->add_flag("--record-mesh", a->recordMesh, "Store which input mesh each point lies on (PLY mesh id)");
  sub->callback([a, noise, maxRange, &action] {
    a->noiseGiven = noise->count() > 0;
    a->maxRangeGiven = maxRange->count() > 0;
    action = [a] { runScan(*a); };
  });
}

}  // namespace treesketch::cli
