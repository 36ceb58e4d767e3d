// A laser beam of finite width, and the "mixed pixel" it returns at edges.
//
// A real beam leaves the scanner a few millimetres wide and widens with range (divergence ~0.2-0.4
// mrad: a 3 mm beam is ~6 mm wide at 10 m). Where it grazes an edge, part of it lands on the near
// surface and part on what lies behind; a phase-shift scanner measures the blend of the two echoes
// and reports one range between them (Hebert & Krotkov 1992, "3D measurements from imaging laser
// radars"; the "mixed pixels" of TLS tree scans, the cloud of points floating between a twig and
// the background). Here a beam is a bundle of sub-rays: the central ray plus a ring of K around it,
// each standing for an equal share (1 / (K + 1)) of the footprint's area; the ring sits at the
// radius that halves the area of its annulus, sqrt((1 + 1/(K+1)) / 2) of the footprint radius
// (0.76 for K = 6). The beam's return, along the central ray:
//   - no sub-ray hits: a miss;
//   - fewer than minHitShare of the sub-rays hit: a weak echo, dropped (no point);
//   - the sub-rays that hit agree on the range (spread <= surfaceTolerance): one surface, the
//     central ray's exact hit (or, when the central ray missed, their mean range: the beam's edge
//     lit the surface, so an edge is dilated by up to the footprint's radius, as in real scans);
//   - they disagree: a mixed return at the mean of their ranges (each sub-ray's share of the
//     footprint weighs its range), a point between the surfaces.
#pragma once

#include <cstdint>

#include "treesketch/accel/ray_scene.h"
#include "treesketch/geom/types.h"

namespace treesketch::scan {

/// The beam's width and how its sub-rays' echoes combine. Off by default: each ray is then an
/// infinitely thin line (the thesis's scanner) and clouds are those of earlier versions.
struct BeamFootprint {
  bool enabled = false;
  /// Full divergence angle, milliradians (FARO Focus, Leica P-series, Riegl VZ: 0.2-0.4).
  double divergenceMrad = 0.3;
  /// Beam diameter at the scanner's exit, metres (2-4 mm on those scanners).
  double exitDiameter = 0.003;
  /// Sub-rays on the ring around the central ray, 3..32 (a beam casts ringRays + 1 rays).
  int ringRays = 6;
  /// Least share of the sub-rays that must hit for the echo to be detected, 0..1. 0.5: an edge
  /// gains as many returns (central ray off the edge, most of the beam on it) as it loses (the
  /// reverse) on average, so silhouettes are neither widened nor narrowed in point count; 0 keeps
  /// every return any sub-ray sees; 1 drops every partial one.
  double minHitShare = 0.5;
  /// Sub-ray ranges within this spread are one surface (metres): no mixing on a wall or a trunk.
  double surfaceTolerance = 0.01;
};

/// Throws OptionsError when a field is out of range (negative or non-finite widths, ring outside
/// 3..32, share outside [0, 1]). Checked only when the footprint is enabled.
void checkBeamFootprint(const BeamFootprint& beam);

/// What one beam returned.
struct BeamReturn {
  bool hit = false;                       ///< a point is returned (false: a miss or a weak echo)
  bool weak = false;                      ///< some sub-rays hit, fewer than minHitShare: dropped
  bool mixed = false;                     ///< the sub-rays' ranges disagreed: the range is their blend
  bool partial = false;                   ///< not every sub-ray hit
  int subRaysHit = 0;                     ///< of ringRays + 1
  geom::Vec3 point = geom::Vec3::Zero();  ///< world coordinates, on the central ray
  double range = 0.0;                     ///< distance from the ray's origin along its direction, scene units
  std::int32_t meshIndex = -1;            ///< the central sub-ray's mesh, or the nearest sub-ray's when it missed
};

/// Casts the beam whose central ray is `ray` (any non-zero direction; ranges are limited to
/// [tnear, tfar] x |dir|) at `scene`. `unitMetres` is the size of one scene unit in metres
/// (converts exitDiameter and surfaceTolerance); `ringPhase` (radians) turns the ring about the
/// central ray, so that a pattern's sub-rays do not line up with straight edges. Thread-safe.
/// Expects a valid footprint (checkBeamFootprint) and unitMetres > 0.
BeamReturn castBeam(const accel::RayScene& scene, const accel::Ray& ray, const BeamFootprint& beam, double unitMetres,
                    double ringPhase = 0.0);

}  // namespace treesketch::scan
