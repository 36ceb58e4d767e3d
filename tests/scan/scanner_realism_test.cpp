// Tests of the scanner's realism options: instrument figures in metres (unitMetres), the
// per-station registration error, the beam footprint's mixed returns at edges, and each point's
// scanner position (kept through PLY).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <tuple>

#include "scan/scan_test_meshes.h"
#include "treesketch/io/ply.h"
#include "treesketch/scan/beam_footprint.h"
#include "treesketch/scan/pattern_cast.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/scan/tls_scan.h"
#include "treesketch/util/error.h"

namespace {

using namespace treesketch;
using geom::TriMesh;
using geom::Vec3;
namespace tt = treesketch::test;

// ---- units ---------------------------------------------------------------------------------

TEST(ScanUnits, RangeNoiseInMetresScalesWithTheSceneUnit) {
  // Same seed, same rays: the noise of each point is the same draw, so in a scene of decimetres
  // (unitMetres 0.1) every point's offset from its exact hit is 10x that in a scene of metres.
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1))};
  for (const bool tls : {false, true}) {
    auto scanWith = [&](double noise, double unit) {
      if (tls) {
        scan::TlsScanOptions o;
        o.stepDeg = 4.0;
        o.stations = {Vec3(0.1, -0.2, 0.05)};
        o.rangeNoise = noise;
        o.unitMetres = unit;
        o.seed = 9;
        return scan::tlsScan(meshes, o);
      }
      scan::SphereScanOptions o;
      o.subdivisions = 3;
      o.rangeNoise = noise;
      o.unitMetres = unit;
      o.seed = 9;
      return scan::sphereScan(meshes, o);
    };
    const scan::ScanResult exact = scanWith(0.0, 0.1);
    const scan::ScanResult metres = scanWith(0.004, 1.0);
    const scan::ScanResult decimetres = scanWith(0.004, 0.1);
    ASSERT_GT(exact.cloud.size(), 500u);
    ASSERT_EQ(metres.cloud.size(), exact.cloud.size());
    ASSERT_EQ(decimetres.cloud.size(), exact.cloud.size());
    double s2 = 0.0;
    for (std::size_t i = 0; i < exact.cloud.size(); ++i) {
      const Vec3 dm = metres.cloud.positions[i] - exact.cloud.positions[i];
      const Vec3 dd = decimetres.cloud.positions[i] - exact.cloud.positions[i];
      ASSERT_NEAR((dd - 10.0 * dm).norm(), 0.0, 1e-9) << i;
      s2 += dd.squaredNorm();
    }
    // 4 mm in decimetres: sigma 0.04 scene units.
    EXPECT_NEAR(std::sqrt(s2 / exact.cloud.size()), 0.04, 0.004) << (tls ? "tls" : "sphere");
  }
}

TEST(ScanUnits, StationHeightAndMaximumRangeAreMetres) {
  geom::BBox box;
  box.add(Vec3(-1, -2, 0));
  box.add(Vec3(3, 2, 40));
  scan::TlsScanOptions o;
  o.up = geom::UpAxis::Z;
  o.stationRadius = 5.0;  // scene units
  o.stationHeight = 1.5;  // metres
  o.unitMetres = 0.1;
  for (const Vec3& s : scan::tlsStationPositions(o, box)) {
    EXPECT_NEAR(s.z(), 15.0, 1e-12);  // a tripod's 1.5 m = 15 decimetres
    EXPECT_NEAR(std::hypot(s.x() - 1.0, s.y()), 5.0, 1e-12);
  }
  // Maximum range: 0.12 m in decimetres is 1.2 scene units.
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1))};
  scan::TlsScanOptions m;
  m.stepDeg = 5.0;
  m.stations = {Vec3(0, 0, 0)};
  m.rangeNoise = 0.0;
  m.maxRange = 1.2;
  const std::size_t inMetres = scan::tlsScan(meshes, m).cloud.size();
  m.maxRange = 0.12;
  m.unitMetres = 0.1;
  const scan::ScanResult r = scan::tlsScan(meshes, m);
  EXPECT_GT(r.cloud.size(), 0u);
  EXPECT_LT(r.cloud.size(), r.stats.raysCast);
  EXPECT_EQ(r.cloud.size(), inMetres);
  for (const Vec3& p : r.cloud.positions) EXPECT_LE(p.norm(), 1.2 + 1e-9);
}

TEST(ScanUnits, BadUnitIsRefused) {
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1))};
  for (const double unit : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    scan::TlsScanOptions t;
    t.stepDeg = 10.0;
    t.unitMetres = unit;
    EXPECT_THROW(scan::tlsScan(meshes, t), OptionsError) << unit;
    scan::SphereScanOptions s;
    s.subdivisions = 1;
    s.unitMetres = unit;
    EXPECT_THROW(scan::sphereScan(meshes, s), OptionsError) << unit;
  }
}

// ---- registration error ----------------------------------------------------------------------

// A trunk on the ground seen from three stations, Z up.
std::vector<TriMesh> trunkOnGround() { return {tt::makeTube(Vec3(0, 0, 0), 0.3, 4.0, 16), tt::makeSquare(5.0)}; }

scan::TlsScanOptions threeStations() {
  scan::TlsScanOptions o;
  o.stepDeg = 2.0;
  o.stationCount = 3;
  o.stationRadius = 3.0;
  o.up = geom::UpAxis::Z;
  o.rangeNoise = 0.0;
  return o;
}

TEST(ScanRegistration, EachStationMovesRigidly) {
  const std::vector<TriMesh> meshes = trunkOnGround();
  scan::TlsScanOptions o = threeStations();
  o.recordScanner = true;
  const scan::ScanResult exact = scan::tlsScan(meshes, o);
  o.registration.rotationSigmaDeg = 0.5;
  o.registration.translationSigma = 0.05;
  const scan::ScanResult moved = scan::tlsScan(meshes, o);
  const geom::PointCloud &a = exact.cloud, &b = moved.cloud;
  ASSERT_GT(a.size(), 1000u);
  ASSERT_EQ(b.size(), a.size());  // the error is applied to the points, not to the rays
  ASSERT_EQ(b.station, a.station);

  // Exactly the documented transform, p' = s + R (p - s) + t, and the scanner moves by t.
  geom::BBox scene = meshes[0].bounds();
  scene.add(meshes[1].bounds());
  const std::vector<Vec3> st = scan::tlsStationPositions(o, scene);
  const std::vector<scan::StationPose> poses = scan::tlsRegistrationErrors(o, st.size());
  ASSERT_EQ(poses.size(), 3u);
  for (const scan::StationPose& p : poses) {
    EXPECT_NEAR((p.rotation * p.rotation.transpose() - geom::Mat3::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(p.rotation.determinant(), 1.0, 1e-12);
    EXPECT_GT(p.translation.norm(), 1e-4);  // three N(0, 0.05) draws: ~0.08
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto s = static_cast<std::size_t>(a.station[i]);
    const Vec3 want = st[s] + poses[s].rotation * (a.positions[i] - st[s]) + poses[s].translation;
    ASSERT_NEAR((b.positions[i] - want).norm(), 0.0, 1e-9) << i;
    ASSERT_NEAR((a.scanner[i] - st[s]).norm(), 0.0, 1e-12) << i;
    ASSERT_NEAR((b.scanner[i] - (st[s] + poses[s].translation)).norm(), 0.0, 1e-12) << i;
  }

  // Distances within a station are kept; between stations they are not.
  double withinWorst = 0.0, betweenWorst = 0.0;
  for (std::size_t i = 0; i < a.size(); i += 7)
    for (std::size_t j = i + 3; j < a.size(); j += 97) {
      const double change =
          std::abs((b.positions[i] - b.positions[j]).norm() - (a.positions[i] - a.positions[j]).norm());
      if (a.station[i] == a.station[j])
        withinWorst = std::max(withinWorst, change);
      else
        betweenWorst = std::max(betweenWorst, change);
    }
  EXPECT_LT(withinWorst, 1e-9);
  EXPECT_GT(betweenWorst, 0.01);
}

TEST(ScanRegistration, DeterministicSeededAndInMetres) {
  const std::vector<TriMesh> meshes = trunkOnGround();
  scan::TlsScanOptions o = threeStations();
  o.registration.rotationSigmaDeg = 0.2;
  o.registration.translationSigma = 0.01;
  o.rangeNoise = 0.002;
  o.seed = 4;
  scan::ScanResult one, two;
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    one = scan::tlsScan(meshes, o);
  }
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 2);
    two = scan::tlsScan(meshes, o);
  }
  ASSERT_GT(one.cloud.size(), 0u);
  EXPECT_EQ(one.cloud.positions, two.cloud.positions);
  o.seed = 5;
  EXPECT_NE(scan::tlsScan(meshes, o).cloud.positions, one.cloud.positions);

  // The per-axis sigmas over many stations: translation in metres / unitMetres, rotation in degrees.
  o.unitMetres = 0.1;
  const std::vector<scan::StationPose> poses = scan::tlsRegistrationErrors(o, 4000);
  double t2 = 0.0, w2 = 0.0;
  for (const scan::StationPose& p : poses) {
    t2 += p.translation.squaredNorm();
    const double angle = Eigen::AngleAxisd(p.rotation).angle();
    w2 += angle * angle;
  }
  EXPECT_NEAR(std::sqrt(t2 / (3.0 * poses.size())), 0.1, 0.004);  // 0.01 m = 0.1 dm
  EXPECT_NEAR(std::sqrt(w2 / (3.0 * poses.size())) * 180.0 / M_PI, 0.2, 0.008);
  // Off: identity poses, and a bad sigma is refused.
  o.registration = {};
  for (const scan::StationPose& p : scan::tlsRegistrationErrors(o, 3)) {
    EXPECT_EQ(p.rotation, geom::Mat3::Identity());
    EXPECT_EQ(p.translation, Vec3::Zero());
  }
  o.registration.translationSigma = -0.01;
  EXPECT_THROW(scan::tlsScan(meshes, o), OptionsError);
  o.registration.translationSigma = 0.0;
  o.registration.rotationSigmaDeg = NAN;
  EXPECT_THROW(scan::tlsScan(meshes, o), OptionsError);
}

// ---- beam footprint ------------------------------------------------------------------------

// A fan of rays from (0, 0, 10) down to the line y = 0, z = 0, x in [-5, 5] cm, 0.25 mm apart.
constexpr std::uint64_t kFanRays = 401;
scan::ScanRay fanRay(std::uint64_t i) {
  scan::ScanRay r;
  r.ray.origin = Vec3(0, 0, 10);
  r.ray.dir = (Vec3(-0.05 + 0.00025 * static_cast<double>(i), 0, 0) - r.ray.origin).normalized();
  return r;
}

// A 2 cm wide bar ("twig") whose top is 9 m from the scanner, and a wall 10 m away.
TriMesh twig() { return tt::makeBox(Vec3(-0.01, -1, 0.99), Vec3(0.01, 1, 1.0)); }
TriMesh wall() { return tt::makeSquare(5.0); }

scan::CastOptions footprintOn() {
  scan::CastOptions o;
  o.beam.enabled = true;  // defaults: 0.3 mrad, 3 mm at the exit, 6 + 1 sub-rays
  o.recordMesh = true;
  return o;
}

TEST(BeamFootprint, MixedReturnsBetweenATwigEdgeAndTheWallBehind) {
  const accel::RayScene scene(std::vector<TriMesh>{twig(), wall()});
  const scan::ScanResult thin = scan::castPattern(scene, kFanRays, fanRay);
  const scan::ScanResult wide = scan::castPattern(scene, kFanRays, fanRay, footprintOn());
  // Every ray sees the twig or the wall; thin rays only ever on one of them.
  ASSERT_EQ(thin.cloud.size(), kFanRays);
  ASSERT_EQ(wide.cloud.size(), kFanRays);
  auto between = [](const Vec3& p) { return p.z() > 0.01 && p.z() < 0.98; };
  EXPECT_EQ(std::count_if(thin.cloud.positions.begin(), thin.cloud.positions.end(), between), 0);
  EXPECT_EQ(thin.stats.mixed, 0u);

  // Mixed points: between the surfaces, on their central ray, at a range that is the share-
  // weighted mean of 9 m (twig) and 10 m (wall): 10 - k/7 m for k of the 7 sub-rays on the twig.
  std::uint64_t mixed = 0;
  std::set<int> shares;
  for (std::size_t i = 0; i < wide.cloud.size(); ++i) {
    const Vec3& p = wide.cloud.positions[i];
    if (!between(p)) {
      // Not mixed: exactly on the twig's top or on the wall.
      EXPECT_TRUE(std::abs(p.z()) < 1e-9 || std::abs(p.z() - 1.0) < 1e-9) << i << " " << p.transpose();
      continue;
    }
    ++mixed;
    const Vec3 d = fanRay(i).ray.dir;
    EXPECT_NEAR((p - Vec3(0, 0, 10)).normalized().dot(d), 1.0, 1e-12) << i;
    const double range = (p - Vec3(0, 0, 10)).norm();
    const int k = static_cast<int>(std::lround((10.0 - range) * 7.0));
    EXPECT_GE(k, 1);
    EXPECT_LE(k, 6);
    EXPECT_NEAR(range, 10.0 - k / 7.0, 2e-4) << i;
    shares.insert(k);
  }
  EXPECT_EQ(mixed, wide.stats.mixed);
  // Two edges, each blended over ~2 x 0.76 x the footprint radius (2.85 mm at 9 m): ~17 rays each.
  EXPECT_GE(mixed, 16u);
  EXPECT_LE(mixed, 60u);
  EXPECT_GE(shares.size(), 3u);       // several blends, not one
  EXPECT_EQ(wide.stats.partial, 0u);  // the wall catches every sub-ray
  EXPECT_EQ(wide.stats.weak, 0u);
}

TEST(BeamFootprint, NoMixingOnAFlatWall) {
  // Square-on and at 50 degrees: the beam sees one surface and returns its exact hit.
  for (const double tiltDeg : {0.0, 50.0}) {
    TriMesh w = wall();
    const Eigen::AngleAxisd tilt(tiltDeg * M_PI / 180.0, Vec3::UnitY());
    for (Vec3& v : w.vertices) v = tilt * v;
    const accel::RayScene scene(w);
    const scan::ScanResult thin = scan::castPattern(scene, kFanRays, fanRay);
    const scan::ScanResult wide = scan::castPattern(scene, kFanRays, fanRay, footprintOn());
    ASSERT_EQ(wide.cloud.size(), kFanRays);
    EXPECT_EQ(wide.stats.mixed, 0u);
    EXPECT_EQ(wide.stats.partial, 0u);
    for (std::size_t i = 0; i < kFanRays; ++i)
      ASSERT_NEAR((wide.cloud.positions[i] - thin.cloud.positions[i]).norm(), 0.0, 1e-9) << tiltDeg << " " << i;
  }
}

TEST(BeamFootprint, PartialReturnsAtAnEdgeAgainstTheSky) {
  // The twig alone: beams half off its edges see nothing behind. Kept or dropped by share.
  const accel::RayScene scene(twig());
  const std::size_t thin = scan::castPattern(scene, kFanRays, fanRay).cloud.size();
  ASSERT_GT(thin, 50u);
  std::size_t count[3];
  const double shares[3] = {0.0, 0.5, 1.0};
  for (int s = 0; s < 3; ++s) {
    scan::CastOptions o = footprintOn();
    o.beam.minHitShare = shares[s];
    const scan::ScanResult r = scan::castPattern(scene, kFanRays, fanRay, o);
    count[s] = r.cloud.size();
    EXPECT_EQ(r.stats.mixed, 0u);
    // Every return lies in the twig's top face's plane (an edge return is off the edge, in the air).
    for (const Vec3& p : r.cloud.positions) EXPECT_NEAR(p.z(), 1.0, 1e-4);
    if (s == 0) EXPECT_GT(r.stats.partial, 0u);
    if (s == 0) EXPECT_EQ(r.stats.weak, 0u);
    if (s == 2) EXPECT_EQ(r.stats.partial, 0u);
    if (s == 2) EXPECT_GT(r.stats.weak, 0u);
    EXPECT_EQ(r.stats.raysCast, kFanRays);
  }
  EXPECT_GT(count[0], thin);  // keeping every echo widens the twig by the beam's radius
  EXPECT_LT(count[2], thin);  // keeping only whole echoes narrows it
  EXPECT_GE(count[1], count[2]);
  EXPECT_LE(count[1], count[0]);
}

TEST(BeamFootprint, DeterministicWhateverTheThreadsAndOffMeansOff) {
  const std::vector<TriMesh> meshes = {tt::makeTube(Vec3(0, 0, 0), 0.02, 3.0, 12),
                                       tt::makeTube(Vec3(0.3, 0.1, 0), 0.01, 3.0, 8), tt::makeSquare(4.0)};
  scan::TlsScanOptions o = threeStations();
  o.stationRadius = 2.0;
  o.stepDeg = 0.5;
  o.zenithMinDeg = 60.0;
  o.zenithMaxDeg = 120.0;
  o.rangeNoise = 0.002;
  o.recordMesh = true;
  o.beam.enabled = true;
  o.beam.divergenceMrad = 3.0;  // a wide beam, so that the thin tubes give many edges
  o.beam.exitDiameter = 0.01;
  scan::ScanResult one, two;
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    one = scan::tlsScan(meshes, o);
  }
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 2);
    two = scan::tlsScan(meshes, o);
  }
  ASSERT_GT(one.stats.mixed, 10u);
  EXPECT_EQ(one.cloud.positions, two.cloud.positions);
  EXPECT_EQ(one.cloud.meshId, two.cloud.meshId);
  EXPECT_EQ(one.stats.mixed, two.stats.mixed);
  EXPECT_EQ(one.stats.weak, two.stats.weak);

  // Disabled, the footprint's fields are ignored (even invalid ones): the thin-ray cloud.
  o.beam.enabled = false;
  const scan::ScanResult off = scan::tlsScan(meshes, o);
  o.beam.ringRays = 0;
  o.beam.minHitShare = -3.0;
  const scan::ScanResult offBad = scan::tlsScan(meshes, o);
  EXPECT_EQ(off.cloud.positions, offBad.cloud.positions);
  EXPECT_EQ(off.stats.mixed + off.stats.partial + off.stats.weak, 0u);
  // Enabled, they are checked.
  o.beam.enabled = true;
  EXPECT_THROW(scan::tlsScan(meshes, o), OptionsError);
  for (auto edit :
       {+[](scan::BeamFootprint& b) { b.ringRays = 2; }, +[](scan::BeamFootprint& b) { b.ringRays = 33; },
        +[](scan::BeamFootprint& b) { b.minHitShare = 1.5; }, +[](scan::BeamFootprint& b) { b.divergenceMrad = -0.1; },
        +[](scan::BeamFootprint& b) { b.exitDiameter = NAN; },
        +[](scan::BeamFootprint& b) { b.surfaceTolerance = -1.0; }}) {
    scan::BeamFootprint b;
    b.enabled = true;
    edit(b);
    EXPECT_THROW(scan::checkBeamFootprint(b), OptionsError);
  }
}

TEST(BeamFootprint, ScaleFollowsTheSceneUnit) {
  // The same twig and wall in decimetres (everything x10) with unitMetres 0.1 is the same beam:
  // the same mixed returns at 10x the coordinates.
  const accel::RayScene metres(std::vector<TriMesh>{twig(), wall()});
  std::vector<TriMesh> dm = {twig(), wall()};
  for (TriMesh& m : dm)
    for (Vec3& v : m.vertices) v *= 10.0;
  const accel::RayScene decimetres(dm);
  const scan::RayGenerator fanDm = [](std::uint64_t i) {
    scan::ScanRay r = fanRay(i);
    r.ray.origin *= 10.0;
    return r;
  };
  const scan::ScanResult a = scan::castPattern(metres, kFanRays, fanRay, footprintOn());
  scan::CastOptions o = footprintOn();
  o.unitMetres = 0.1;
  const scan::ScanResult b = scan::castPattern(decimetres, kFanRays, fanDm, o);
  ASSERT_EQ(a.cloud.size(), b.cloud.size());
  EXPECT_EQ(a.stats.mixed, b.stats.mixed);
  EXPECT_GT(a.stats.mixed, 0u);
  for (std::size_t i = 0; i < a.cloud.size(); ++i)
    EXPECT_NEAR((b.cloud.positions[i] - 10.0 * a.cloud.positions[i]).norm(), 0.0, 1e-6) << i;
}

// ---- scanner positions -----------------------------------------------------------------------

TEST(ScannerPosition, KeptPerPointAndThroughPly) {
  const std::vector<TriMesh> meshes = trunkOnGround();
  scan::TlsScanOptions o = threeStations();
  o.recordScanner = true;
  o.recordMesh = true;
  o.registration.translationSigma = 0.01;
  const scan::ScanResult r = scan::tlsScan(meshes, o);
  const geom::PointCloud& c = r.cloud;
  ASSERT_EQ(c.scanner.size(), c.size());
  // One position per station.
  std::set<std::int32_t> seen;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const std::size_t first =
        static_cast<std::size_t>(std::find(c.station.begin(), c.station.end(), c.station[i]) - c.station.begin());
    ASSERT_EQ(c.scanner[i], c.scanner[first]);
    seen.insert(c.station[i]);
  }
  EXPECT_EQ(seen.size(), 3u);

  std::stringstream ply;
  io::writePlyPointCloud(ply, c);
  const std::string bytes = ply.str();
  EXPECT_NE(bytes.find("property double scanner_x\nproperty double scanner_y\nproperty double scanner_z\n"),
            std::string::npos);
  std::istringstream in(bytes);
  const geom::PointCloud back = io::readPlyPointCloud(in, "memory");
  EXPECT_EQ(back.positions, c.positions);
  EXPECT_EQ(back.station, c.station);
  EXPECT_EQ(back.meshId, c.meshId);
  EXPECT_EQ(back.scanner, c.scanner);

  // An ASCII PLY from another tool: the three fields in any order, with other fields between.
  std::istringstream ascii(
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float scanner_z\nproperty float x\nproperty float y\n"
      "property float z\nproperty float intensity\nproperty float scanner_x\nproperty float scanner_y\nend_header\n"
      "1.5 1 2 3 0.5 10 20\n1.5 4 5 6 0.5 -10 -20\n");
  io::CloudReadOptions few;
  few.minPoints = 1;
  const geom::PointCloud other = io::readPlyPointCloud(ascii, "ascii", few);
  ASSERT_EQ(other.scanner.size(), 2u);
  EXPECT_EQ(other.scanner[0], Vec3(10, 20, 1.5));
  EXPECT_EQ(other.scanner[1], Vec3(-10, -20, 1.5));
  EXPECT_EQ(other.positions[1], Vec3(4, 5, 6));
  // Only two of the three: not a position, ignored.
  std::istringstream partial(
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
      "property float scanner_x\nproperty float scanner_y\nend_header\n1 2 3 4 5\n");
  EXPECT_TRUE(io::readPlyPointCloud(partial, "partial", few).scanner.empty());
  // Off by default.
  o.recordScanner = false;
  EXPECT_TRUE(scan::tlsScan(meshes, o).cloud.scanner.empty());
}

TEST(ScannerPosition, SpherePatternKeepsEachRaysOrigin) {
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1))};
  scan::SphereScanOptions o;
  o.subdivisions = 2;
  o.recordScanner = true;
  const scan::ScanResult r = scan::sphereScan(meshes, o);
  ASSERT_GT(r.cloud.size(), 0u);
  ASSERT_EQ(r.cloud.scanner.size(), r.cloud.size());
  const double radius = meshes[0].bounds().diagonal();
  std::set<std::tuple<double, double, double>> distinct;
  for (std::size_t i = 0; i < r.cloud.size(); ++i) {
    EXPECT_NEAR(r.cloud.scanner[i].norm(), radius, 1e-9);
    // The point lies on the ray from its scanner position inwards.
    EXPECT_LT((r.cloud.positions[i] - r.cloud.scanner[i]).norm(), radius);
    distinct.insert({r.cloud.scanner[i].x(), r.cloud.scanner[i].y(), r.cloud.scanner[i].z()});
  }
  EXPECT_EQ(distinct.size(), r.cloud.size());  // a position per ray, not per pattern
  // Appending clouds keeps the positions only when both have them.
  geom::PointCloud both = r.cloud;
  both.append(r.cloud);
  EXPECT_EQ(both.scanner.size(), both.size());
  geom::PointCloud plain;
  plain.positions = {Vec3(0, 0, 0)};
  plain.append(r.cloud);
  EXPECT_TRUE(plain.scanner.empty());
}

}  // namespace
