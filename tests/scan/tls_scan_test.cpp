// Tests of the terrestrial (TLS) scanner: ray counts and order, station indices and positions,
// range noise statistics, maximum range, misses, determinism, mesh ids, bad options.
#include "treesketch/scan/tls_scan.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

#include "scan/scan_test_meshes.h"
#include "treesketch/util/error.h"

namespace {

using namespace treesketch;
using geom::TriMesh;
using geom::Vec3;
namespace tt = treesketch::test;

constexpr double kDeg = std::numbers::pi / 180.0;

// Distance from p (inside the box [-h, h]^3) along unit d to the box's boundary.
double exitDistance(const Vec3& p, const Vec3& d, double h) {
  double t = INFINITY;
  for (int k = 0; k < 3; ++k)
    if (d[k] != 0.0) t = std::min(t, ((d[k] > 0 ? h : -h) - p[k]) / d[k]);
  return t;
}

TEST(TlsScan, RayCountsFollowTheParameters) {
  scan::TlsScanOptions o;
  o.stepDeg = 10.0;
  o.zenithMinDeg = 0.0;
  o.zenithMaxDeg = 150.0;
  o.stationCount = 3;
  EXPECT_EQ(scan::tlsAzimuthSteps(o), 36u);
  EXPECT_EQ(scan::tlsZenithSteps(o), 16u);
  EXPECT_EQ(scan::tlsRaysPerStation(o), 576u);
  EXPECT_EQ(scan::tlsRayCount(o), 1728u);
  o.stepDeg = 0.2;  // the default: 1800 x 751
  EXPECT_EQ(scan::tlsAzimuthSteps(o), 1800u);
  EXPECT_EQ(scan::tlsZenithSteps(o), 751u);
  o.stepDeg = 7.0;  // 360/7 = 51.4 -> 52 azimuths (last at 357 deg); 150/7 -> 22 zeniths
  EXPECT_EQ(scan::tlsAzimuthSteps(o), 52u);
  EXPECT_EQ(scan::tlsZenithSteps(o), 22u);
  o.stations = {Vec3(0, 0, 0), Vec3(1, 0, 0)};  // explicit stations override the ring
  EXPECT_EQ(scan::tlsRayCount(o), 2u * 52u * 22u);
}

TEST(TlsScan, EnclosingBoxGetsEveryRayWithStationsAndOrder) {
  // A big closed box around the scene catches every ray: points = rays, in ray order.
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-10, -10, -10), Vec3(10, 10, 10))};
  scan::TlsScanOptions o;
  o.stepDeg = 10.0;
  o.up = geom::UpAxis::Z;
  o.zenithMaxDeg = 170.0;
  o.stations = {Vec3(0, 0, 0), Vec3(2, 1, -3), Vec3(-4, 0.5, 1)};
  o.rangeNoise = 0.0;
  const scan::ScanResult r = scan::tlsScan(meshes, o);
  const std::uint64_t perStation = scan::tlsRaysPerStation(o);
  EXPECT_EQ(perStation, 36u * 18u);
  ASSERT_EQ(r.cloud.size(), scan::tlsRayCount(o));
  ASSERT_EQ(r.cloud.station.size(), r.cloud.size());
  EXPECT_TRUE(r.cloud.meshId.empty());
  for (std::size_t i = 0; i < r.cloud.size(); ++i) {
    const std::size_t s = i / perStation, rem = i % perStation;
    ASSERT_EQ(r.cloud.station[i], static_cast<std::int32_t>(s));
    const double az = static_cast<double>(rem / 18) * 10.0 * kDeg, zen = static_cast<double>(rem % 18) * 10.0 * kDeg;
    const Vec3 d(std::sin(zen) * std::cos(az), std::sin(zen) * std::sin(az), std::cos(zen));  // Z up
    const Vec3 v = r.cloud.positions[i] - o.stations[s];
    EXPECT_NEAR((v.normalized() - d).norm(), 0.0, 1e-9) << i;
    EXPECT_NEAR(v.norm(), exitDistance(o.stations[s], d, 10.0), 1e-9) << i;
  }
}

TEST(TlsScan, MissesThroughAnOpenFaceAddNothing) {
  // Open-topped box around the station: rays leaving through the top miss.
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1), 5)};
  scan::TlsScanOptions o;
  o.stepDeg = 7.0;
  o.zenithMaxDeg = 180.0;
  o.up = geom::UpAxis::Z;
  o.stations = {Vec3(0.01, 0.02, 0.03)};
  o.rangeNoise = 0.0;
  const scan::ScanResult r = scan::tlsScan(meshes, o);
  std::uint64_t expected = 0;
  const std::uint64_t nAz = scan::tlsAzimuthSteps(o), nZen = scan::tlsZenithSteps(o);
  for (std::uint64_t a = 0; a < nAz; ++a)
    for (std::uint64_t z = 0; z < nZen; ++z) {
      const double az = a * 7.0 * kDeg, zen = z * 7.0 * kDeg;
      const Vec3 d(std::sin(zen) * std::cos(az), std::sin(zen) * std::sin(az), std::cos(zen));
      const Vec3 exit = o.stations[0] + exitDistance(o.stations[0], d, 1.0) * d;
      if (exit.z() < 1.0 - 1e-9) ++expected;  // leaves through a side or the bottom
    }
  EXPECT_EQ(r.stats.raysCast, nAz * nZen);
  EXPECT_GT(expected, 0u);
  EXPECT_LT(expected, nAz * nZen);
  EXPECT_EQ(r.cloud.size(), expected);
  for (const Vec3& p : r.cloud.positions) EXPECT_LE(tt::pointMeshDistance(p, meshes[0]), 1e-9);
}

TEST(TlsScan, RangeNoiseHasTheRequestedSigma) {
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1))};
  scan::TlsScanOptions o;
  o.stepDeg = 2.0;  // 180 x 76 = 13,680 rays
  o.stations = {Vec3(0.1, -0.2, 0.05)};
  o.rangeNoise = 0.01;
  o.seed = 5;
  const scan::ScanResult r = scan::tlsScan(meshes, o);
  ASSERT_EQ(r.cloud.size(), scan::tlsRayCount(o));
  double s = 0, s2 = 0;
  for (const Vec3& p : r.cloud.positions) {
    const Vec3 v = p - o.stations[0];
    const double residual = v.norm() - exitDistance(o.stations[0], v.normalized(), 1.0);
    s += residual;
    s2 += residual * residual;
  }
  const double n = static_cast<double>(r.cloud.size());
  const double mean = s / n, sd = std::sqrt(s2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0 * 0.01 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.01, 0.0005);
}

TEST(TlsScan, MaximumRange) {
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1))};
  scan::TlsScanOptions o;
  o.stepDeg = 5.0;
  o.stations = {Vec3(0, 0, 0)};
  o.rangeNoise = 0.0;
  o.up = geom::UpAxis::Z;
  o.maxRange = 0.95;
  EXPECT_TRUE(scan::tlsScan(meshes, o).cloud.empty());
  o.maxRange = 1.2;
  const scan::ScanResult r = scan::tlsScan(meshes, o);
  std::uint64_t expected = 0;
  for (std::uint64_t a = 0; a < scan::tlsAzimuthSteps(o); ++a)
    for (std::uint64_t z = 0; z < scan::tlsZenithSteps(o); ++z) {
      const double az = a * 5.0 * kDeg, zen = z * 5.0 * kDeg;
      const Vec3 d(std::sin(zen) * std::cos(az), std::sin(zen) * std::sin(az), std::cos(zen));
      if (exitDistance(Vec3::Zero(), d, 1.0) <= 1.2) ++expected;
    }
  EXPECT_GT(expected, 0u);
  EXPECT_EQ(r.cloud.size(), expected);
  for (const Vec3& p : r.cloud.positions) EXPECT_LE(p.norm(), 1.2 + 1e-9);
}

TEST(TlsScan, RingStationsAroundTheTreeForEachUpAxis) {
  geom::BBox box;
  box.add(Vec3(-1, -2, 0));
  box.add(Vec3(3, 2, 10));
  scan::TlsScanOptions o;
  o.stationCount = 4;
  o.stationRadius = 5.0;
  o.stationHeight = 1.5;
  o.up = geom::UpAxis::Z;
  auto st = scan::tlsStationPositions(o, box);
  ASSERT_EQ(st.size(), 4u);
  EXPECT_NEAR((st[0] - Vec3(6, 0, 1.5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((st[1] - Vec3(1, 5, 1.5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((st[2] - Vec3(-4, 0, 1.5)).norm(), 0.0, 1e-12);
  o.up = geom::UpAxis::Y;  // ground at y = -2; ring in the x-z plane around (1, ., 5)
  st = scan::tlsStationPositions(o, box);
  for (const Vec3& s : st) {
    EXPECT_NEAR(s.y(), -0.5, 1e-12);
    EXPECT_NEAR(std::hypot(s.x() - 1.0, s.z() - 5.0), 5.0, 1e-12);
  }
  // Auto radius: radiusFactor x diagonal.
  o.stationRadius = 0.0;
  o.radiusFactor = 2.0;
  st = scan::tlsStationPositions(o, box);
  EXPECT_NEAR(std::hypot(st[0].x() - 1.0, st[0].z() - 5.0), 2.0 * box.diagonal(), 1e-9);
  EXPECT_THROW(scan::tlsStationPositions(o, geom::BBox{}), OptionsError);
}

TEST(TlsScan, YUpZenithIsMeasuredFromY) {
  // Station below a ceiling at y = 1 (and nothing else): only zenith < 90 deg rays hit it.
  TriMesh ceiling = tt::makeSquare(100.0);
  for (Vec3& v : ceiling.vertices) v = Vec3(v.x(), 1.0, v.y());
  scan::TlsScanOptions o;
  o.up = geom::UpAxis::Y;
  o.stepDeg = 10.0;
  o.zenithMaxDeg = 180.0;
  o.stations = {Vec3(0, 0, 0)};
  o.rangeNoise = 0.0;
  const scan::ScanResult r = scan::tlsScan(std::vector<TriMesh>{ceiling}, o);
  // zenith 0..80 (9 values; zenith 0 repeats for each azimuth) x 36 azimuths.
  EXPECT_EQ(r.cloud.size(), 9u * 36u);
  for (const Vec3& p : r.cloud.positions) EXPECT_NEAR(p.y(), 1.0, 1e-12);
}

TEST(TlsScan, DeterministicAcrossThreadsAndSeedsMatter) {
  std::vector<TriMesh> meshes = {tt::makeTube(Vec3(0, 0, 0), 0.3, 4.0, 16), tt::makeSquare(5.0)};
  scan::TlsScanOptions o;
  o.stepDeg = 1.0;
  o.stationCount = 3;
  o.stationHeight = 1.5;
  o.rangeNoise = 0.005;
  o.up = geom::UpAxis::Z;
  o.recordMesh = true;
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
  EXPECT_EQ(one.cloud.station, two.cloud.station);
  EXPECT_EQ(one.cloud.meshId, two.cloud.meshId);
  // Mesh ids: both meshes seen; stats agree with the ids; each point lies near its mesh.
  ASSERT_EQ(one.cloud.meshId.size(), one.cloud.size());
  std::uint64_t counts[2] = {0, 0};
  for (std::size_t i = 0; i < one.cloud.size(); ++i) {
    const int m = one.cloud.meshId[i];
    ASSERT_TRUE(m == 0 || m == 1);
    ++counts[m];
    if (i % 17 == 0) {
      EXPECT_LE(tt::pointMeshDistance(one.cloud.positions[i], meshes[m]), 0.005 * 8);
    }
  }
  EXPECT_GT(counts[0], 0u);
  EXPECT_GT(counts[1], 0u);
  EXPECT_EQ(one.stats.hitsPerMesh[0], counts[0]);
  EXPECT_EQ(one.stats.hitsPerMesh[1], counts[1]);
  o.seed = 2;
  const scan::ScanResult other = scan::tlsScan(meshes, o);
  ASSERT_EQ(other.cloud.size(), one.cloud.size());  // noise does not change which rays hit
  EXPECT_NE(other.cloud.positions, one.cloud.positions);
}

TEST(TlsScan, BadOptionsAndEmptyScene) {
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1))};
  auto expectBad = [&](auto edit) {
    scan::TlsScanOptions o;
    o.stepDeg = 10.0;
    edit(o);
    EXPECT_THROW(scan::tlsScan(meshes, o), OptionsError);
  };
  expectBad([](scan::TlsScanOptions& o) { o.stepDeg = 0.0; });
  expectBad([](scan::TlsScanOptions& o) { o.stepDeg = NAN; });
  expectBad([](scan::TlsScanOptions& o) { o.zenithMinDeg = 100.0, o.zenithMaxDeg = 50.0; });
  expectBad([](scan::TlsScanOptions& o) { o.zenithMaxDeg = 181.0; });
  expectBad([](scan::TlsScanOptions& o) { o.stationCount = 0; });
  expectBad([](scan::TlsScanOptions& o) { o.rangeNoise = -0.01; });
  expectBad([](scan::TlsScanOptions& o) { o.maxRange = 0.0; });
  expectBad([](scan::TlsScanOptions& o) { o.stations = {Vec3(NAN, 0, 0)}; });
  expectBad([](scan::TlsScanOptions& o) { o.stepDeg = 1e-4; });  // ~6e12 rays
  scan::TlsScanOptions ring;
  ring.stepDeg = 10.0;
  EXPECT_THROW(scan::tlsScan(std::vector<TriMesh>{}, ring), OptionsError);  // no centre for the ring
  ring.stations = {Vec3(0, 0, 0)};
  const scan::ScanResult empty = scan::tlsScan(std::vector<TriMesh>{}, ring);
  EXPECT_TRUE(empty.cloud.empty());
  EXPECT_EQ(empty.stats.raysCast, scan::tlsRayCount(ring));
}

}  // namespace
