// Robust 2D circle fitting: RANSAC over 3-point circles with an adaptive iteration count, then a
// least-squares refinement on the inliers (algebraic Kåsa fit, then geometric Gauss–Newton).
// Source: thesis §4.4 and appendix B (RANSAC with probability 0.999 of an outlier-free sample,
// Ziv Yaniv's CircleParamEstimator); Fischler & Bolles 1981 for the adaptive sample count.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "treesketch/geom/types.h"

namespace treesketch::fit {

/// An optional check of where the circle's centre may lie (plane coordinates): within
/// `maxDistance` of a line (hasLine) or of a point. It is applied to the final circle only: RANSAC
/// picks the best-supported circle regardless, and the fit fails if that circle's centre is
/// outside. (Constraining the candidates instead made RANSAC settle for junk circles through a
/// sliver of the true branch while the true circle was excluded.) Used by the node fit's sanity
/// rule (see node_fit.h).
struct CentreRegion {
  bool active = false;
  bool hasLine = false;
  geom::Vec2 origin = geom::Vec2::Zero();  ///< a point on the line, or the point
  geom::Vec2 dir = geom::Vec2::UnitX();    ///< unit direction of the line (hasLine)
  double maxDistance = std::numeric_limits<double>::infinity();

  /// True when `c` satisfies the constraint (always true when not active).
  bool contains(const geom::Vec2& c) const;
};

struct CircleFitOptions {
  /// Probability that at least one sample is outlier-free. Thesis appendix B: 0.999.
  double probability = 0.999;
  /// Absolute inlier threshold on |distance to centre − radius|, world units. Design choice:
  /// 0.01 (about 2σ of the 5 mm range noise of a terrestrial scanner; metres). The thesis used
  /// the estimator's delta of 0.5 scene units. Clouds in other units need their own value.
  double inlierThreshold = 0.01;
  /// Optional relative mode: the threshold becomes max(inlierThreshold, inlierThresholdRelative ·
  /// candidate radius), so wide trunks tolerate bark roughness. Off (0) by default: a band that
  /// widens with the radius favours huge circles through scattered outliers (their band covers
  /// more points), which made RANSAC pick them in tests with 30 % outliers. Use small values
  /// (≤ 0.02) together with maxRadius.
  double inlierThresholdRelative = 0.0;
  /// Minimum support: at least this many inliers... (design choice)
  int minInliers = 8;
  /// ...and at least this fraction of the input points (design choice: 0.1).
  double minInlierFraction = 0.1;
  /// Minimum angular coverage of the inliers around the centre, degrees, counted in bins of
  /// arcBinDegrees that hold at least a quarter of the fullest bin's count (design choice: 90°). A scan sees one side of a branch (arcs of 120–180°), but
  /// a small circle grazing the inside of a wide trunk's arc, or a circle threaded through a few
  /// clutter points, gathers its inliers on a short arc of itself: this rejects those. 0 = off.
  double minArcDegrees = 90.0;
  double arcBinDegrees = 10.0;
  /// Accepted radius range, world units.
  double minRadius = 0.0;
  double maxRadius = std::numeric_limits<double>::infinity();
  /// Hard cap and floor on the number of RANSAC samples (the adaptive count lies in between).
  int maxIterations = 2000;
  int minIterations = 10;
  /// Hypotheses are scored on a fixed random subset of at most this many points (the final
  /// inliers are always classified on all points). 0 = score on all points. Speed design choice.
  int maxScoringPoints = 500;
  /// The least-squares refinement uses an evenly strided subset of at most this many inliers
  /// (0 = all). Speed design choice: 500 points fix a circle far below the scan noise (the
  /// centre's standard error is about 2σ/√500, under 0.3 mm for σ = 3 mm; 300 failed the 120°
  /// arc accuracy test).
  int maxRefinePoints = 500;
  /// Gauss–Newton iterations of the geometric refinement, and inlier re-classification rounds.
  int refineIterations = 10;
  int refineRounds = 2;
  /// The caller guarantees that every point is finite (slices from CloudIndex, which leaves
  /// non-finite points out): the scan for NaN/Inf coordinates is skipped. Results with a
  /// non-finite point are then undefined (no crash, but no meaningful circle).
  bool inputFinite = false;
  /// Seed of the random sampler: equal seeds and inputs give equal results.
  std::uint64_t seed = 1;
  /// Optional centre constraint.
  CentreRegion centreRegion;
};

struct CircleFitResult {
  bool ok = false;
  std::string reason;  ///< why no circle was found (empty when ok)
  geom::Vec2 centre = geom::Vec2::Zero();
  double radius = 0.0;
  std::vector<std::uint32_t> inliers;  ///< indices into the input, increasing
  int iterations = 0;                   ///< RANSAC samples drawn
  double rms = 0.0;                     ///< RMS geometric residual over the inliers, world units
};

/// Fits a circle to 2D points (plane coordinates, world units). Returns ok=false with a reason
/// for fewer than 3 points, all-collinear/duplicate input, no circle with enough support and arc
/// inside the radius bounds, or a best circle centred outside the centre region. NaN/Inf points are never counted as inliers. Throws
/// OptionsError for invalid options (probability outside (0,1), negative thresholds...).
CircleFitResult fitCircleRansac(const std::vector<geom::Vec2>& points, const CircleFitOptions& options = {});

/// The circle through three points; false when they are (nearly) collinear.
bool circleFrom3(const geom::Vec2& a, const geom::Vec2& b, const geom::Vec2& c, geom::Vec2* centre, double* radius);

/// Least-squares circle through `points[indices]`: algebraic (Kåsa) start refined by Gauss–Newton
/// on the geometric distance. With `warmStart`, Gauss–Newton starts from the circle given in
/// *centre / *radius instead (when it is finite with a positive radius; else from Kåsa's): the
/// RANSAC refinement's later rounds start from the previous round's circle, which is already at
/// the minimum for nearly the same inliers. Returns false for fewer than 3 points or a
/// degenerate system.
bool fitCircleLeastSquares(const std::vector<geom::Vec2>& points, const std::vector<std::uint32_t>& indices,
                           int iterations, geom::Vec2* centre, double* radius, bool warmStart = false);

}  // namespace treesketch::fit
