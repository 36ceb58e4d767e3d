// The thesis's sphere scanner (Leavenworth 2012, §4.2): see include/treesketch/scan/sphere_scan.h.
#include "treesketch/scan/sphere_scan.h"

#include <cmath>
#include <numbers>
#include <string>

#include "scan/orthonormal_basis.h"
#include "treesketch/scan/counter_rng.h"
#include "treesketch/util/error.h"

namespace treesketch::scan {

namespace {

using geom::Vec3;

constexpr int kMaxSubdivisions = 12;  // 18 * 4^12 = 302 M rays
constexpr std::uint64_t kMaxGrid = 3ull << (kMaxSubdivisions - 1);
// counter_rng streams for the jitter: 2 per rejection attempt from here on (the range noise uses
// streams 8 and 9, see pattern_cast.cpp).
constexpr std::uint32_t kJitterStream = 16;
// Rejection attempts before giving up on a jitter sample (each succeeds with probability pi/4).
constexpr int kMaxJitterAttempts = 64;

void checkOptions(const SphereScanOptions& o) {
  if (!std::isfinite(o.radius)) throw OptionsError("sphere scan: radius must be finite");
  if (o.radius <= 0.0 && !(o.radiusFactor > 0.0 && std::isfinite(o.radiusFactor)))
    throw OptionsError("sphere scan: radius factor must be > 0, got " + std::to_string(o.radiusFactor));
  if (!(o.jitterDeg >= 0.0 && o.jitterDeg <= 90.0))
    throw OptionsError("sphere scan: jitter must be in [0, 90] degrees, got " + std::to_string(o.jitterDeg));
  if (!(o.rangeNoise >= 0.0) || !std::isfinite(o.rangeNoise))
    throw OptionsError("sphere scan: range noise must be a finite number >= 0, got " + std::to_string(o.rangeNoise));
  if (!(o.unitMetres > 0.0) || !std::isfinite(o.unitMetres))
    throw OptionsError("sphere scan: the scene unit must be a finite number of metres > 0, got " +
                       std::to_string(o.unitMetres));
  checkBeamFootprint(o.beam);
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

namespace {

// Position of a ray origin on the octahedron grid: face f (0..7), row r (0..n-1) from the face's
// apex, triangle c (0..2r) in the row.
struct GridCell {
  std::uint64_t f = 0, r = 0, c = 0;
};

GridCell gridCell(std::uint64_t n, std::uint64_t index) {
  const std::uint64_t perFace = n * n;
  GridCell g;
  g.f = index / perFace;
  const std::uint64_t k = index - g.f * perFace;
  // Row r holds triangles r^2 .. r^2 + 2r of the face.
  g.r = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(k)));
  if (g.r * g.r > k) --g.r;  // sqrt of a double is exact enough that one step corrects it
  if ((g.r + 1) * (g.r + 1) <= k) ++g.r;
  g.c = k - g.r * g.r;
  return g;
}

// Steps to the next cell in index order.
void nextCell(std::uint64_t n, GridCell& g) {
  if (++g.c <= 2 * g.r) return;
  g.c = 0;
  if (++g.r < n) return;
  g.r = 0;
  ++g.f;
}

// Face f has corners A = sz Z (apex), B = sx X, C = sy Y. The centroid of triangle c of row r,
// in grid coordinates (a along A->B, b along A->C, units of 1/n): upright triangles (c even)
// (r-m, m), (r+1-m, m), (r-m, m+1); inverted (c odd) (r-m, m), (r-m-1, m+1), (r-m, m+1); m = c/2.
Vec3 cellDirection(std::uint64_t n, const GridCell& g) {
  const double sx = (g.f & 1) ? -1.0 : 1.0, sy = (g.f & 2) ? -1.0 : 1.0, sz = (g.f & 4) ? -1.0 : 1.0;
  const std::uint64_t m = g.c >> 1;
  const bool inverted = g.c & 1;
  const double a = static_cast<double>(g.r - m) + (inverted ? -1.0 / 3.0 : 1.0 / 3.0);
  const double b = static_cast<double>(m) + (inverted ? 2.0 / 3.0 : 1.0 / 3.0);
  const Vec3 p(sx * a, sy * b, sz * (static_cast<double>(n) - a - b));
  return p / p.norm();
}

}  // namespace

Vec3 sphereGridDirection(std::uint64_t n, std::uint64_t index) { return cellDirection(n, gridCell(n, index)); }

namespace {

// A direction uniform in the spherical cap of cosine cosJitter around unit d, drawn from
// (seed, index). Marsaglia's trick: a point (x, y) uniform in the unit disc has s = x^2 + y^2
// uniform in [0, 1] and an angle independent of s, so s gives the cap's cosine
// (1 - s (1 - cosJitter), uniform as the cap's area requires) and (x, y) / sqrt(s) its azimuth:
// no trigonometry per ray.
Vec3 jitterInCap(const Vec3& d, double cosJitter, std::uint64_t seed, std::uint64_t index) {
  for (int attempt = 0; attempt < kMaxJitterAttempts; ++attempt) {
    const std::uint32_t stream = kJitterStream + 2 * static_cast<std::uint32_t>(attempt);
    const double x = 2.0 * counterUniform(seed, index, stream) - 1.0;
    const double y = 2.0 * counterUniform(seed, index, stream + 1) - 1.0;
    const double s = x * x + y * y;
    if (s > 1.0 || s == 0.0) continue;
    const double cosA = 1.0 - s * (1.0 - cosJitter);
    const double sinA = std::sqrt(std::max(0.0, 1.0 - cosA * cosA));
    const double inv = sinA / std::sqrt(s);
    Vec3 e1, e2;
    orthonormalBasis(d, e1, e2);
    return cosA * d + (inv * x) * e1 + (inv * y) * e2;
  }
  return d;  // probability (1 - pi/4)^64 ~ 1e-43
}

}  // namespace

namespace {

// The pattern's geometry for given options and scene bounds.
struct SpherePattern {
  std::uint64_t n = 1;
  Vec3 centre = Vec3::Zero();
  double radius = 1.0;
  double cosJitter = 1.0;
  std::uint64_t seed = 1;

  SpherePattern(const SphereScanOptions& options, const geom::BBox& box)
      : n(sphereGridSize(options)),
        centre(box.centre()),
        radius(options.radius > 0.0 ? options.radius : options.radiusFactor * box.diagonal()),
        cosJitter(std::cos(options.jitterDeg * std::numbers::pi / 180.0)),
        seed(options.seed) {}

  accel::Ray ray(std::uint64_t index, const GridCell& cell) const {
    const Vec3 u = cellDirection(n, cell);
    accel::Ray r;
    r.origin = centre + radius * u;
    r.dir = cosJitter < 1.0 ? jitterInCap(-u, cosJitter, seed, index) : Vec3(-u);
    return r;
  }
};

}  // namespace

accel::Ray sphereScanRay(const SphereScanOptions& options, const geom::BBox& bounds, std::uint64_t index) {
  checkOptions(options);
  if (bounds.empty()) throw OptionsError("sphere scan: empty bounds, no centre to aim at");
  const SpherePattern pattern(options, bounds);
  if (index >= 8 * pattern.n * pattern.n)
    throw OptionsError("sphere scan: ray " + std::to_string(index) + " of " +
                       std::to_string(8 * pattern.n * pattern.n));
  return pattern.ray(index, gridCell(pattern.n, index));
}

ScanResult sphereScan(const accel::RayScene& scene, const SphereScanOptions& options, const ProgressFn& progress) {
  checkOptions(options);
  const std::uint64_t n = sphereGridSize(options);
  CastOptions cast;
  cast.unitMetres = options.unitMetres;
  cast.rangeNoise = options.rangeNoise;
  cast.beam = options.beam;
  cast.seed = options.seed;
  cast.recordMesh = options.recordMesh;
  cast.recordScanner = options.recordScanner;
  const geom::BBox& box = scene.bounds();
  if (box.empty()) return castPattern(scene, 0, RayBatchGenerator{}, cast, progress);

  const SpherePattern pattern(options, box);
  const RayBatchGenerator generator = [&pattern](std::uint64_t first, std::size_t count, ScanRay* out) {
    GridCell cell = gridCell(pattern.n, first);
    for (std::size_t k = 0; k < count; ++k, nextCell(pattern.n, cell)) {
      out[k].ray = pattern.ray(first + k, cell);
      out[k].station = -1;
    }
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
