// A terrestrial laser scanner (TLS) simulator, the thesis's future work (Leavenworth 2012, §6.3:
// "follow the exact same patterns as the real-world laser scanner ... register these samples into
// a single point cloud"): stations around the tree, each sweeping a full turn in azimuth and a
// zenith range at a fixed angular step, with Gaussian range noise and a maximum range. The
// stations' points are merged into one cloud in world coordinates, each tagged with its station
// (and, optionally, the scanner's position). Optional realism: a beam footprint with mixed returns
// at edges (beam_footprint.h) and a per-station registration error.
//
// Units: the instrument's figures (range noise, maximum range, station height, beam exit
// diameter, registration shift) are in metres and converted with unitMetres; what places the
// stations in the scene (explicit positions, ring radius) is in scene units.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "treesketch/accel/ray_scene.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/geom/types.h"
#include "treesketch/scan/pattern_cast.h"
#include "treesketch/util/progress.h"

namespace treesketch::scan {

/// The residual of registering the stations into one cloud: each station's points are moved by
/// a small random rigid transform about the station, p' = s + R (p - s) + t, drawn per station
/// from the seed. Rotation and shift are Gaussian per axis (R from a rotation vector). Residuals
/// of a few millimetres and hundredths of a degree are typical of registered TLS surveys; both 0
/// (the default) = perfect registration.
struct RegistrationError {
  double rotationSigmaDeg = 0.0;  ///< per axis, degrees
  double translationSigma = 0.0;  ///< per axis, metres
  bool enabled() const { return rotationSigmaDeg > 0.0 || translationSigma > 0.0; }
};

/// One station's registration error: p' = station + rotation (p - station) + translation
/// (translation in scene units).
struct StationPose {
  geom::Mat3 rotation = geom::Mat3::Identity();
  geom::Vec3 translation = geom::Vec3::Zero();
};

struct TlsScanOptions {
  /// Station positions, world coordinates. When empty, `stationCount` stations are placed on a
  /// horizontal circle around the scene's bounding-box centre (see below).
  std::vector<geom::Vec3> stations;
  /// Ring of stations: how many (>= 1). Typical single-tree TLS surveys use 3-6 scan positions.
  int stationCount = 4;
  /// Ring radius, scene units; <= 0 means radiusFactor x the scene's bounding-box diagonal.
  double stationRadius = 0.0;
  /// Default ring radius as a multiple of the bbox diagonal (stations about a tree height away).
  double radiusFactor = 1.0;
  /// Station height above the bottom of the scene's bounding box along `up`, metres (a surveying
  /// tripod).
  double stationHeight = 1.5;
  /// Azimuth of the first ring station around the centre, degrees from the first horizontal axis
  /// (X for Z-up, Z for Y-up); the others follow every 360/stationCount degrees.
  double ringStartDeg = 0.0;
  /// Angular step in azimuth and zenith, degrees (0.2 deg = 3.5 mm at 1 m, 3.5 cm at 10 m; real
  /// scanners offer ~0.01-0.2 deg).
  double stepDeg = 0.2;
  /// Zenith range swept, degrees from `up` (0 = straight up). 0..150 is a 300-degree vertical
  /// field of view, as in phase-shift scanners (e.g. FARO Focus); below it is the tripod.
  double zenithMinDeg = 0.0;
  double zenithMaxDeg = 150.0;
  /// Size of one scene unit in metres (0.1: the scene is in decimetres, as the ez-tree test trees
  /// are taken to be). Converts every metre figure of these options.
  double unitMetres = 1.0;
  /// Gaussian range noise sigma along each ray, metres (0.002 = the ~2 mm ranging noise quoted
  /// for current TLS at 10-25 m).
  double rangeNoise = 0.002;
  /// Rays find hits only within this distance of their station, metres.
  double maxRange = std::numeric_limits<double>::infinity();
  /// Beam width and mixed returns at edges; off by default.
  BeamFootprint beam;
  /// Per-station registration residual; none by default.
  RegistrationError registration;
  /// Which axis is up (station heights, zenith angles). Y, like the meshes of the thesis and of
  /// gen/; real TLS data are Z-up.
  geom::UpAxis up = geom::UpAxis::Y;
  /// Seed of the range noise, the beam's ring phases and the registration errors; each ray's
  /// values depend only on (seed, ray index), each station's error on (seed, station index).
  std::uint64_t seed = 1;
  /// Record PointCloud::meshId (which input mesh each point lies on).
  bool recordMesh = false;
  /// Record PointCloud::scanner (each point's station position, after the registration error).
  bool recordScanner = false;
};

/// Azimuth steps per station: the directions i * stepDeg for i = 0.. with i * stepDeg < 360.
std::uint64_t tlsAzimuthSteps(const TlsScanOptions& options);
/// Zenith steps per station: zenithMinDeg + j * stepDeg for j = 0.. up to zenithMaxDeg inclusive
/// (within 1e-9 of a step).
std::uint64_t tlsZenithSteps(const TlsScanOptions& options);
/// Rays per station (azimuth steps x zenith steps) and over all stations. Throw OptionsError
/// for invalid options (step <= 0, zenith range outside [0, 180] or reversed, no stations...).
std::uint64_t tlsRaysPerStation(const TlsScanOptions& options);
std::uint64_t tlsRayCount(const TlsScanOptions& options);

/// Station positions the options give for a scene with bounding box `bounds` (world
/// coordinates): `options.stations` when not empty, else the ring. Throws OptionsError when the
/// ring is needed and `bounds` is empty.
std::vector<geom::Vec3> tlsStationPositions(const TlsScanOptions& options, const geom::BBox& bounds);

/// The registration error of each of `stationCount` stations for these options (identity poses
/// when options.registration is off). Depends only on (seed, station index, sigmas, unitMetres).
/// Throws OptionsError for negative or non-finite sigmas.
std::vector<StationPose> tlsRegistrationErrors(const TlsScanOptions& options, std::size_t stationCount);

/// Scans `scene` from every station. Ray order (and point order): station, then azimuth, then
/// zenith (the fast mirror axis). PointCloud::station holds each point's station index.
/// Each station's points (and scanner positions) are then moved by its registration error, so
/// points of one station keep their distances to each other and stations no longer fit exactly.
/// Returns the merged cloud and stats; rays that miss or go beyond maxRange add nothing. An
/// empty scene with ring stations throws OptionsError (no centre to ring around). Deterministic
/// for a given seed whatever the thread count. `progress`: see castPattern.
ScanResult tlsScan(const accel::RayScene& scene, const TlsScanOptions& options = {}, const ProgressFn& progress = {});
/// Convenience: builds a RayScene over `meshes` (mesh i -> meshId i) and scans it.
ScanResult tlsScan(const std::vector<geom::TriMesh>& meshes, const TlsScanOptions& options = {},
                   const ProgressFn& progress = {});

}  // namespace treesketch::scan
