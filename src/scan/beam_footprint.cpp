// A beam of finite width and its mixed returns: see include/treesketch/scan/beam_footprint.h.
#include "treesketch/scan/beam_footprint.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "scan/orthonormal_basis.h"
#include "treesketch/util/error.h"

namespace treesketch::scan {

namespace {

using geom::Vec3;

constexpr int kMinRing = 3, kMaxRing = 32;

// Whether the segment origin + t d, t in [0, tmax], meets `box` grown by `margin` on every side
// (slab test).
bool segmentMeetsBox(const Vec3& origin, const Vec3& d, double tmax, const geom::BBox& box, double margin) {
  double t0 = 0.0, t1 = tmax;
  for (int k = 0; k < 3; ++k) {
    const double lo = box.min[k] - margin, hi = box.max[k] + margin;
    if (d[k] == 0.0) {
      if (origin[k] < lo || origin[k] > hi) return false;
      continue;
    }
    double a = (lo - origin[k]) / d[k], b = (hi - origin[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

void checkBeamFootprint(const BeamFootprint& b) {
  if (!b.enabled) return;
  if (!(b.divergenceMrad >= 0.0) || !std::isfinite(b.divergenceMrad))
    throw OptionsError("beam footprint: divergence must be a finite number >= 0 mrad, got " +
                       std::to_string(b.divergenceMrad));
  if (!(b.exitDiameter >= 0.0) || !std::isfinite(b.exitDiameter))
    throw OptionsError("beam footprint: exit diameter must be a finite number >= 0 m, got " +
                       std::to_string(b.exitDiameter));
  if (b.ringRays < kMinRing || b.ringRays > kMaxRing)
    throw OptionsError("beam footprint: ring sub-rays must be in [" + std::to_string(kMinRing) + ", " +
                       std::to_string(kMaxRing) + "], got " + std::to_string(b.ringRays));
  if (!(b.minHitShare >= 0.0 && b.minHitShare <= 1.0))
    throw OptionsError("beam footprint: minimum hit share must be in [0, 1], got " + std::to_string(b.minHitShare));
  if (!(b.surfaceTolerance >= 0.0) || !std::isfinite(b.surfaceTolerance))
    throw OptionsError("beam footprint: surface tolerance must be a finite number >= 0 m, got " +
                       std::to_string(b.surfaceTolerance));
}

BeamReturn castBeam(const accel::RayScene& scene, const accel::Ray& ray, const BeamFootprint& beam, double unitMetres,
                    double ringPhase) {
  BeamReturn out;
  const double dirNorm = ray.dir.norm();
  if (!(dirNorm > 0.0) || !std::isfinite(dirNorm) || !ray.origin.allFinite()) return out;
  const Vec3 d = ray.dir / dirNorm;
  // Range limits in scene units along d (the ray's t is in units of |dir|).
  const double rangeNear = ray.tnear * dirNorm, rangeFar = ray.tfar * dirNorm;

  const int ring = beam.ringRays;
  const int total = ring + 1;
  // Each sub-ray stands for 1/total of the footprint's area: the central one for the disc of
  // radius R / sqrt(total), each ring one for a sector of the annulus outside it, placed at the
  // radius that halves the annulus's area.
  const double ringFraction = std::sqrt(0.5 * (1.0 + 1.0 / total));
  const double offset0 = ringFraction * 0.5 * beam.exitDiameter / unitMetres;  // at the exit, scene units
  const double slope = ringFraction * 0.5 * beam.divergenceMrad * 1e-3;        // widening per unit range

  // Most beams of a TLS sweep pass far from the scene: when even the whole footprint (radius at
  // most `margin` out to the scene's far side) misses the scene's box, so does every sub-ray, and
  // the 7 traversals are skipped (the test costs less than one ray's setup).
  const geom::BBox& box = scene.bounds();
  if (box.empty()) return out;
  const double reach = std::min(rangeFar, (ray.origin - box.centre()).norm() + 0.5 * box.diagonal());
  const double margin = 0.5 * beam.exitDiameter / unitMetres + 0.5 * beam.divergenceMrad * 1e-3 * reach;
  if (!segmentMeetsBox(ray.origin, d, reach, box, margin)) return out;

  // Central sub-ray first: its exact hit is the answer whenever the beam sees a single surface.
  const accel::RayHit centre = scene.intersect(ray.origin, d, rangeNear, rangeFar);
  double rangeSum = 0.0, rangeMin = INFINITY, rangeMax = -INFINITY, nearestRange = INFINITY;
  std::int32_t nearestMesh = -1;
  int hits = 0;
  auto add = [&](double r, std::int32_t mesh) {
    ++hits;
    rangeSum += r;
    rangeMin = std::min(rangeMin, r);
    rangeMax = std::max(rangeMax, r);
    if (r < nearestRange) {
      nearestRange = r;
      nearestMesh = mesh;
    }
  };
  if (centre.hit()) add(centre.t, centre.meshIndex);  // d is unit: t is the range

  Vec3 e1, e2;
  orthonormalBasis(d, e1, e2);
  // Ring directions by turning (cos, sin) a step at a time: two sines and cosines a beam.
  const double step = 2.0 * std::numbers::pi / ring;
  const double cosStep = std::cos(step), sinStep = std::sin(step);
  double c = std::cos(ringPhase), sn = std::sin(ringPhase);
  for (int k = 0; k < ring; ++k) {
    const Vec3 u = c * e1 + sn * e2;
    const double next = c * cosStep - sn * sinStep;
    sn = sn * cosStep + c * sinStep;
    c = next;
    const Vec3 dir = (d + slope * u).normalized();
    const Vec3 origin = ray.origin + offset0 * u;
    const accel::RayHit h = scene.intersect(origin, dir, rangeNear, rangeFar);
    if (h.hit()) add((h.point - ray.origin).dot(d), h.meshIndex);
  }

  out.subRaysHit = hits;
  if (hits == 0) return out;
  out.partial = hits < total;
  if (out.partial && static_cast<double>(hits) < beam.minHitShare * total) {
    out.weak = true;
    return out;
  }
  out.hit = true;
  out.meshIndex = centre.hit() ? centre.meshIndex : nearestMesh;
  const double tolerance = beam.surfaceTolerance / unitMetres;
  out.mixed = rangeMax - rangeMin > tolerance;
  if (!out.mixed && centre.hit()) {
    out.point = centre.point;
    out.range = centre.t;
    return out;
  }
  out.range = rangeSum / hits;
  out.point = ray.origin + out.range * d;
  return out;
}

}  // namespace treesketch::scan
