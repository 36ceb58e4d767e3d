// Terrestrial laser scanner stations (thesis §6.3 future work): see
// include/treesketch/scan/tls_scan.h.
#include "treesketch/scan/tls_scan.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>
#include <string>

#include "treesketch/scan/counter_rng.h"
#include "treesketch/util/error.h"

namespace treesketch::scan {

namespace {

using geom::Vec3;

constexpr double kDeg = std::numbers::pi / 180.0;
// Tolerance, in steps, when counting how many steps fit in a range (so 150/0.2 counts 751).
constexpr double kStepSlack = 1e-9;
// Refuse patterns beyond this many rays (memory for the points would be the problem first).
constexpr std::uint64_t kMaxRays = 1ull << 36;
// counter_rng streams of the registration error, indexed by station (rays use streams 8-10 and
// 16 and up, indexed by ray: distinct streams keep the two independent): rotation vector x, y, z
// then shift x, y, z, two streams each (counterGaussian).
constexpr std::uint32_t kRegistrationStream = 200;

void checkOptions(const TlsScanOptions& o) {
  if (!(o.stepDeg > 0.0) || !std::isfinite(o.stepDeg))
    throw OptionsError("TLS scan: angular step must be > 0 degrees, got " + std::to_string(o.stepDeg));
  if (!(o.zenithMinDeg >= 0.0 && o.zenithMaxDeg <= 180.0 && o.zenithMinDeg <= o.zenithMaxDeg))
    throw OptionsError("TLS scan: zenith range must satisfy 0 <= min <= max <= 180 degrees, got " +
                       std::to_string(o.zenithMinDeg) + ".." + std::to_string(o.zenithMaxDeg));
  if (o.stations.empty() && o.stationCount < 1)
    throw OptionsError("TLS scan: need at least one station, got " + std::to_string(o.stationCount));
  for (std::size_t i = 0; i < o.stations.size(); ++i)
    if (!o.stations[i].allFinite()) throw OptionsError("TLS scan: station " + std::to_string(i) + " is not finite");
  if (!std::isfinite(o.stationRadius) || !std::isfinite(o.stationHeight) || !std::isfinite(o.ringStartDeg))
    throw OptionsError("TLS scan: station radius, height and ring start must be finite");
  if (o.stations.empty() && o.stationRadius <= 0.0 && !(o.radiusFactor > 0.0 && std::isfinite(o.radiusFactor)))
    throw OptionsError("TLS scan: radius factor must be > 0, got " + std::to_string(o.radiusFactor));
  if (!(o.rangeNoise >= 0.0) || !std::isfinite(o.rangeNoise))
    throw OptionsError("TLS scan: range noise must be a finite number >= 0, got " + std::to_string(o.rangeNoise));
  if (!(o.maxRange > 0.0)) throw OptionsError("TLS scan: maximum range must be > 0, got " + std::to_string(o.maxRange));
  if (!(o.unitMetres > 0.0) || !std::isfinite(o.unitMetres))
    throw OptionsError("TLS scan: the scene unit must be a finite number of metres > 0, got " +
                       std::to_string(o.unitMetres));
  const RegistrationError& r = o.registration;
  if (!(r.rotationSigmaDeg >= 0.0) || !std::isfinite(r.rotationSigmaDeg) || !(r.translationSigma >= 0.0) ||
      !std::isfinite(r.translationSigma))
    throw OptionsError("TLS scan: registration sigmas must be finite numbers >= 0, got " +
                       std::to_string(r.rotationSigmaDeg) + " degrees and " + std::to_string(r.translationSigma) +
                       " m");
  checkBeamFootprint(o.beam);
}

// Horizontal axes (e1, e2) with e1 x e2 = up.
void horizontalAxes(geom::UpAxis up, Vec3& e1, Vec3& e2) {
  if (up == geom::UpAxis::Z) {
    e1 = Vec3::UnitX();
    e2 = Vec3::UnitY();
  } else {
    e1 = Vec3::UnitZ();
    e2 = Vec3::UnitX();
  }
}

}  // namespace

std::uint64_t tlsAzimuthSteps(const TlsScanOptions& o) {
  checkOptions(o);
  const double steps = 360.0 / o.stepDeg;
  auto n = static_cast<std::uint64_t>(std::ceil(steps - kStepSlack));
  return std::max<std::uint64_t>(n, 1);
}

std::uint64_t tlsZenithSteps(const TlsScanOptions& o) {
  checkOptions(o);
  return static_cast<std::uint64_t>(std::floor((o.zenithMaxDeg - o.zenithMinDeg) / o.stepDeg + kStepSlack)) + 1;
}

std::uint64_t tlsRaysPerStation(const TlsScanOptions& o) {
  const double rays = static_cast<double>(tlsAzimuthSteps(o)) * static_cast<double>(tlsZenithSteps(o));
  if (rays > static_cast<double>(kMaxRays))
    throw OptionsError("TLS scan: step " + std::to_string(o.stepDeg) + " degrees gives too many rays per station");
  return tlsAzimuthSteps(o) * tlsZenithSteps(o);
}

std::uint64_t tlsRayCount(const TlsScanOptions& o) {
  const std::uint64_t stations =
      o.stations.empty() ? static_cast<std::uint64_t>(std::max(o.stationCount, 0)) : o.stations.size();
  const std::uint64_t perStation = tlsRaysPerStation(o);
  if (static_cast<double>(perStation) * static_cast<double>(stations) > static_cast<double>(kMaxRays))
    throw OptionsError("TLS scan: too many rays (" + std::to_string(stations) + " stations)");
  return perStation * stations;
}

std::vector<Vec3> tlsStationPositions(const TlsScanOptions& o, const geom::BBox& bounds) {
  checkOptions(o);
  if (!o.stations.empty()) return o.stations;
  if (bounds.empty())
    throw OptionsError("TLS scan: the scene is empty, so there is no centre to place stations around");
  Vec3 e1, e2;
  horizontalAxes(o.up, e1, e2);
  const Vec3 upv = geom::upVector(o.up);
  const Vec3 c = bounds.centre();
  const Vec3 base =
      c - upv * geom::height(c, o.up) + upv * (geom::height(bounds.min, o.up) + o.stationHeight / o.unitMetres);
  const double radius = o.stationRadius > 0.0 ? o.stationRadius : o.radiusFactor * bounds.diagonal();
  std::vector<Vec3> out;
  for (int s = 0; s < o.stationCount; ++s) {
    const double a = (o.ringStartDeg + 360.0 * s / o.stationCount) * kDeg;
    out.push_back(base + radius * (std::cos(a) * e1 + std::sin(a) * e2));
  }
  return out;
}

std::vector<StationPose> tlsRegistrationErrors(const TlsScanOptions& options, std::size_t stationCount) {
  checkOptions(options);
  std::vector<StationPose> poses(stationCount);
  const RegistrationError& r = options.registration;
  if (!r.enabled()) return poses;
  const double angleSigma = r.rotationSigmaDeg * kDeg;
  const double shiftSigma = r.translationSigma / options.unitMetres;  // scene units
  for (std::size_t s = 0; s < stationCount; ++s) {
    auto draw = [&](std::uint32_t k) { return counterGaussian(options.seed, s, kRegistrationStream + 2 * k); };
    const Vec3 w(angleSigma * draw(0), angleSigma * draw(1), angleSigma * draw(2));
    const double angle = w.norm();
    if (angle > 0.0) poses[s].rotation = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
    poses[s].translation = Vec3(shiftSigma * draw(3), shiftSigma * draw(4), shiftSigma * draw(5));
  }
  return poses;
}

ScanResult tlsScan(const accel::RayScene& scene, const TlsScanOptions& options, const ProgressFn& progress) {
  checkOptions(options);
  const std::vector<Vec3> stations = tlsStationPositions(options, scene.bounds());
  const std::uint64_t nAz = tlsAzimuthSteps(options), nZen = tlsZenithSteps(options);
  const std::uint64_t perStation = tlsRaysPerStation(options);
  const std::uint64_t total = tlsRayCount(options);
  Vec3 e1, e2;
  horizontalAxes(options.up, e1, e2);
  const Vec3 upv = geom::upVector(options.up);
  const double step = options.stepDeg * kDeg, zen0 = options.zenithMinDeg * kDeg;
  const double maxRange = options.maxRange / options.unitMetres;  // scene units (rays are unit length)

  // Direction tables: the sweep is a grid, so no trigonometry per ray.
  std::vector<double> cosAz(nAz), sinAz(nAz), cosZen(nZen), sinZen(nZen);
  for (std::uint64_t a = 0; a < nAz; ++a) {
    cosAz[a] = std::cos(static_cast<double>(a) * step);
    sinAz[a] = std::sin(static_cast<double>(a) * step);
  }
  for (std::uint64_t z = 0; z < nZen; ++z) {
    cosZen[z] = std::cos(zen0 + static_cast<double>(z) * step);
    sinZen[z] = std::sin(zen0 + static_cast<double>(z) * step);
  }
  const RayBatchGenerator generator = [&](std::uint64_t first, std::size_t count, ScanRay* out) {
    std::uint64_t s = first / perStation, rem = first % perStation;
    std::uint64_t a = rem / nZen, z = rem % nZen;
    for (std::size_t k = 0; k < count; ++k) {
      ScanRay& sr = out[k];
      sr.ray = accel::Ray{};
      sr.ray.origin = stations[s];
      sr.ray.dir = sinZen[z] * (cosAz[a] * e1 + sinAz[a] * e2) + cosZen[z] * upv;  // unit length
      sr.ray.tfar = maxRange;
      sr.station = static_cast<std::int32_t>(s);
      if (++z == nZen) {  // zenith is the fast (mirror) axis, then azimuth, then station
        z = 0;
        if (++a == nAz) {
          a = 0;
          ++s;
        }
      }
    }
  };
  CastOptions cast;
  cast.unitMetres = options.unitMetres;
  cast.rangeNoise = options.rangeNoise;
  cast.beam = options.beam;
  cast.seed = options.seed;
  cast.recordMesh = options.recordMesh;
  cast.recordStation = true;
  cast.recordScanner = options.recordScanner;
  ScanResult result = castPattern(scene, total, generator, cast, progress);

  // The registration residual: each station's points move rigidly about the station, as when
  // a real station's scan is placed into the common frame with a slightly wrong transform.
  if (options.registration.enabled()) {
    const std::vector<StationPose> poses = tlsRegistrationErrors(options, stations.size());
    geom::PointCloud& cloud = result.cloud;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 1 << 14),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) {
                          const auto s = static_cast<std::size_t>(cloud.station[i]);
                          const StationPose& pose = poses[s];
                          const Vec3& at = stations[s];
                          cloud.positions[i] = at + pose.rotation * (cloud.positions[i] - at) + pose.translation;
                          if (!cloud.scanner.empty()) cloud.scanner[i] += pose.translation;
                        }
                      });
  }
  return result;
}

ScanResult tlsScan(const std::vector<geom::TriMesh>& meshes, const TlsScanOptions& options,
                   const ProgressFn& progress) {
  tlsRayCount(options);  // validate before the (possibly long) BVH build
  const accel::RayScene scene(meshes);
  return tlsScan(scene, options, progress);
}

}  // namespace treesketch::scan
