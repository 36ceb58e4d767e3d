// The thesis's sphere scanner (Leavenworth 2012, §4.2): see include/treesketch/scan/sphere_scan.h.
#include "treesketch/scan/sphere_scan.h"

#include <cmath>
#include <numbers>
#include <string>

#include "treesketch/scan/counter_rng.h"
#include "treesketch/util/error.h"

namespace treesketch::scan {

namespace {

using geom::Vec3;

constexpr int kMaxSubdivisions = 12;                  // 18 * 4^12 = 302 M rays
constexpr std::uint64_t kMaxGrid = 3ull << (kMaxSubdivisions - 1);
// counter_rng streams for the jitter (noise uses its own, see pattern_cast.cpp).
constexpr std::uint32_t kJitterStream = 0;

void checkOptions(const SphereScanOptions& o) {
  if (!std::isfinite(o.radius)) throw OptionsError("sphere scan: radius must be finite");
  if (o.radius <= 0.0 && !(o.radiusFactor > 0.0 && std::isfinite(o.radiusFactor)))
    throw OptionsError("sphere scan: radius factor must be > 0, got " + std::to_string(o.radiusFactor));
  if (!(o.jitterDeg >= 0.0 && o.jitterDeg <= 90.0))
    throw OptionsError("sphere scan: jitter must be in [0, 90] degrees, got " + std::to_string(o.jitterDeg));
  if (!(o.rangeNoise >= 0.0) || !std::isfinite(o.rangeNoise))
    throw OptionsError("sphere scan: range noise must be a finite number >= 0, got " + std::to_string(o.rangeNoise));
}

}  // namespace

std::uint64_t sphereGridSize(const SphereScanOptions& options) {
  if (options.rays > 0) {
    if (options.rays > 8 * kMaxGrid * kMaxGrid)
      throw OptionsError("sphere scan: at most " + std::to_string(8 * kMaxGrid * kMaxGrid) + " rays, asked for " +
                         std::to_string(options.rays));
    auto n = static_cast<std::uint64_t>(std::ceil(std::sqrt(static_cast<double>(options.rays) / 8.0)));
    while (n > 1 && 8 * (n - 1) * (n - 1) >= options.rays) --n;  // guard against rounding up too far
    while (8 * n * n < options.rays) ++n;
    return std::max<std::uint64_t>(n, 1);
  }
  if (options.subdivisions < 1 || options.subdivisions > kMaxSubdivisions)
    throw OptionsError("sphere scan: subdivisions must be in [1, " + std::to_string(kMaxSubdivisions) + "], got " +
                       std::to_string(options.subdivisions));
  return 3ull << (options.subdivisions - 1);
}

std::uint64_t sphereRayCount(const SphereScanOptions& options) {
  const std::uint64_t n = sphereGridSize(options);
  return 8 * n * n;
}

Vec3 sphereGridDirection(std::uint64_t n, std::uint64_t index) {
  // Face f of the octahedron: corners A = sz Z (apex), B = sx X, C = sy Y.
  const std::uint64_t perFace = n * n;
  const std::uint64_t f = index / perFace;
  const std::uint64_t k = index % perFace;
  const double sx = (f & 1) ? -1.0 : 1.0, sy = (f & 2) ? -1.0 : 1.0, sz = (f & 4) ? -1.0 : 1.0;
  // Row r (between grid lines a+b = r and r+1 counted from the apex) holds 2r+1 triangles.
  auto r = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(k)));
  while (r * r > k) --r;
  while ((r + 1) * (r + 1) <= k) ++r;
  const std::uint64_t c = k - r * r, m = c / 2;
  // Centroid in grid coordinates (a along A->B, b along A->C, in units of 1/n).
  double a, b;
  if (c % 2 == 0) {  // upright triangle: (r-m, m), (r+1-m, m), (r-m, m+1)
    a = static_cast<double>(r - m) + 1.0 / 3.0;
    b = static_cast<double>(m) + 1.0 / 3.0;
  } else {  // inverted: (r-m, m), (r-m-1, m+1), (r-m, m+1)
    a = static_cast<double>(r - m) - 1.0 / 3.0;
    b = static_cast<double>(m) + 2.0 / 3.0;
  }
  const double inv = 1.0 / static_cast<double>(n);
  const double wa = a * inv, wb = b * inv, wApex = 1.0 - wa - wb;
  return Vec3(sx * wa, sy * wb, sz * wApex).normalized();
}

ScanResult sphereScan(const accel::RayScene& scene, const SphereScanOptions& options, const ProgressFn& progress) {
  checkOptions(options);
  const std::uint64_t n = sphereGridSize(options);
  CastOptions cast;
  cast.rangeNoise = options.rangeNoise;
  cast.seed = options.seed;
  cast.recordMesh = options.recordMesh;
  const geom::BBox& box = scene.bounds();
  if (box.empty()) return castPattern(scene, 0, {}, cast, progress);

  const Vec3 centre = box.center();
  const double radius = options.radius > 0.0 ? options.radius : options.radiusFactor * box.diagonal();
  const double cosJitter = std::cos(options.jitterDeg * std::numbers::pi / 180.0);
  const std::uint64_t seed = options.seed;
  auto generator = [=](std::uint64_t i) {
    const Vec3 u = sphereGridDirection(n, i);
    ScanRay sr;
    sr.ray.origin = centre + radius * u;
    Vec3 d = -u;
    if (cosJitter < 1.0) {  // uniform direction in the cap of half-angle jitterDeg around d
      const double cosA = 1.0 - counterUniform(seed, i, kJitterStream) * (1.0 - cosJitter);
      const double sinA = std::sqrt(std::max(0.0, 1.0 - cosA * cosA));
      const double phi = 2.0 * std::numbers::pi * counterUniform(seed, i, kJitterStream + 1);
      const Vec3 e1 = geom::anyPerpendicular(d);
      const Vec3 e2 = d.cross(e1);
      d = cosA * d + sinA * (std::cos(phi) * e1 + std::sin(phi) * e2);
    }
    sr.ray.dir = d;
    return sr;
  };
  return castPattern(scene, 8 * n * n, generator, cast, progress);
}

ScanResult sphereScan(const std::vector<geom::TriMesh>& meshes, const SphereScanOptions& options,
                      const ProgressFn& progress) {
  checkOptions(options);
  sphereGridSize(options);  // validate before the (possibly long) BVH build
  const accel::RayScene scene(meshes);
  return sphereScan(scene, options, progress);
}

}  // namespace treesketch::scan
