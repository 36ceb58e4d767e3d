// `treesketch scan MESH... -o CLOUD`: virtual LIDAR. Casts the thesis's sphere pattern or
// terrestrial-scanner stations at one or more meshes and writes the nearest hits as a cloud;
// optionally with a beam footprint (mixed returns at edges), per-station registration error and
// each point's scanner position. Instrument figures are in metres (--units-metres converts).
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
  bool recordScanner = false;
  double unitMetres = 1.0;
  double regRotationDeg = 0.0;
  double regTranslation = 0.0;
  scan::BeamFootprint beam;
};

void runScan(const ScanArgs& a) {
  if (a.pattern == "sphere" && (a.regRotationDeg != 0.0 || a.regTranslation != 0.0))
    throw OptionsError("scan: --registration-* needs --pattern tls (the sphere pattern has no stations)");
  for (const std::string& m : a.meshes) checkNotAnInput(a.output, {m});
  checkOutputWritable(a.output);
  std::vector<geom::TriMesh> meshes;
  double area = 0.0;
  for (const std::string& m : a.meshes) {
    meshes.push_back(io::readMesh(m));
    area += meshes.back().area();
  }
  if (!(area > 0))
    throw DegenerateInputError(a.meshes[0] + (a.meshes.size() > 1 ? " and the other meshes" : "") +
                               ": zero area (every triangle has repeated or collinear corners); nothing a ray can hit");

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
      o.unitMetres = a.unitMetres;
      o.beam = a.beam;
      o.seed = a.seed;
      o.recordMesh = a.recordMesh;
      o.recordScanner = a.recordScanner;
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
      o.unitMetres = a.unitMetres;
      o.beam = a.beam;
      o.registration.rotationSigmaDeg = a.regRotationDeg;
      o.registration.translationSigma = a.regTranslation;
      o.seed = a.seed;
      o.recordMesh = a.recordMesh;
      o.recordScanner = a.recordScanner;
      result = scan::tlsScan(scene, o, bar.callback());
    }
  }
  const scan::ScanStats& s = result.stats;
  if (result.cloud.empty())
    throw DegenerateInputError("scan: none of the " + std::to_string(s.raysCast) + " rays hit " + a.meshes[0] +
                               (a.meshes.size() > 1 ? " or the other meshes" : "") +
                               " (scanner inside the mesh, range too short?); no cloud written to " + a.output);
  result.cloud.up = geom::parseUpAxis(a.up);  // the PLY says its up (io/up_axis.h)
  io::writePointCloud(a.output, result.cloud);

  std::printf("scan: %s, %llu rays, %llu points (%.1f%% hit) in %.0f ms", a.pattern.c_str(),
              static_cast<unsigned long long>(s.raysCast), static_cast<unsigned long long>(s.hits),
              s.raysCast ? 100.0 * s.hits / s.raysCast : 0.0, s.milliseconds);
  if (meshes.size() > 1) {
    // The first mesh is taken as the wood (branches), the others as leaves etc.
    std::printf(", wood fraction %.3f (points on %s)", s.fraction(0), a.meshes[0].c_str());
  }
  if (a.beam.enabled) {
    std::printf(", footprint: %llu mixed, %llu partial, %llu weak dropped", static_cast<unsigned long long>(s.mixed),
                static_cast<unsigned long long>(s.partial), static_cast<unsigned long long>(s.weak));
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
  sub->add_option("-o,--output", a->output,
                  "Output cloud (.ply keeps station/mesh ids and scanner positions, .xyz .txt)")
      ->required();
  sub->add_option("--pattern", a->pattern, "sphere (thesis §4.2) or tls (terrestrial stations)")
      ->check(CLI::IsMember({"sphere", "tls"}))
      ->capture_default_str();
  // Bounds refused before any work: 18*4^11 = 75M rays is several times the 20M-point scale test;
  // 0 rays is no scan (it used to fall back to the default quietly).
  auto* subdiv = sub->add_option("--subdiv", a->subdiv, "sphere: subdivision level k, 18*4^k rays (thesis: 6-8)")
                     ->check(CLI::Range(0, 11))
                     ->capture_default_str();
  auto* rays = sub->add_option("--rays", a->rays, "sphere: target ray count (instead of --subdiv; 1 to 100,000,000)")
                   ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{100000000}));
  subdiv->excludes(rays);
  sub->add_option("--radius", a->radius, "sphere: radius in mesh units (default: 1 x bbox diagonal)");
  sub->add_option("--jitter", a->jitter, "sphere: half-angle of the random aim jitter, degrees")->capture_default_str();
  sub->add_option("--units-metres", a->unitMetres,
                  "Size of one mesh unit in metres (0.1: the mesh is in decimetres); converts the metre options")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  auto* noise =
      sub->add_option("--noise", a->noise, "Gaussian range noise sigma, metres (default: 0 for sphere, 0.002 for tls)");
  sub->add_option("--seed", a->seed, "Random seed (jitter, noise, beam ring, registration error)")
      ->capture_default_str();
  sub->add_option(
         "--up", a->up,
         "Up axis of the meshes, y or z (tls: station heights and zenith angles); written into a PLY cloud as its up")
      ->capture_default_str();
  sub->add_option("--stations", a->stations, "tls: number of stations on a ring around the tree")
      ->capture_default_str();
  sub->add_option("--station-radius", a->stationRadius, "tls: ring radius, mesh units (default: 1 x bbox diagonal)");
  sub->add_option("--station-height", a->stationHeight, "tls: station height above the scene's bottom, metres")
      ->capture_default_str();
  sub->add_option("--step", a->step, "tls: angular step in azimuth and zenith, degrees")->capture_default_str();
  auto* maxRange = sub->add_option("--max-range", a->maxRange, "tls: maximum range, metres (default: unlimited)");
  sub->add_option("--registration-rotation", a->regRotationDeg,
                  "tls: per-station registration error, rotation sigma per axis, degrees (e.g. 0.01)")
      ->capture_default_str();
  sub->add_option("--registration-translation", a->regTranslation,
                  "tls: per-station registration error, shift sigma per axis, metres (e.g. 0.003)")
      ->capture_default_str();
  sub->add_flag("--footprint", a->beam.enabled,
                "Beam of finite width: sub-rays per beam, mixed ranges where it grazes an edge");
  sub->add_option("--beam-divergence", a->beam.divergenceMrad, "footprint: full divergence angle, mrad")
      ->capture_default_str();
  sub->add_option("--beam-diameter", a->beam.exitDiameter, "footprint: beam diameter at the exit, metres")
      ->capture_default_str();
  sub->add_option("--beam-rays", a->beam.ringRays, "footprint: sub-rays on the ring around the central ray (3-32)")
      ->capture_default_str();
  sub->add_option("--beam-min-share", a->beam.minHitShare,
                  "footprint: drop a return when fewer than this share of its sub-rays hit (0 keeps all)")
      ->capture_default_str();
  sub->add_option("--beam-tolerance", a->beam.surfaceTolerance,
                  "footprint: sub-ray ranges within this spread are one surface, metres")
      ->capture_default_str();
  sub->add_flag("--record-mesh", a->recordMesh, "Store which input mesh each point lies on (PLY mesh id)");
  sub->add_flag("--record-scanner", a->recordScanner,
                "Store each point's scanner position (PLY scanner_x, scanner_y, scanner_z)");
  sub->callback([a, noise, maxRange, &action] {
    a->noiseGiven = noise->count() > 0;
    a->maxRangeGiven = maxRange->count() > 0;
    action = [a] { runScan(*a); };
  });
}

}  // namespace treesketch::cli
