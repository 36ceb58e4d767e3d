// Internal: a scanner's range noise read from the cloud, and a tube's radius read through it.
//
// A scanner's range noise moves each point along its ray, independently of its neighbours; a real
// branch's departures from a circle (bark, an oval section, a collar) are smooth over the surface.
// So two points side by side on a surface differ in their distance to the tube's axis by the noise
// alone: half the variance of those differences (a variogram's nugget) is the noise's, where the
// spread of the distances themselves holds the shape too.
//
// Range noise σ about a round section of radius R, seen from one side or several (points on the
// near half of the section, each moved along its ray), has its points' median distance to the axis
// on the radius while R is above about 1.5 σ, and above it below that: at 0.68 σ for a twig much
// thinner than the noise (the points are a blob about the axis). Both relations below were measured
// by simulating that model (1, 4 and 8 directions of view agree within 0.02 σ).
#pragma once

#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton::detail {

/// The median distance to the axis, over σ, of the points of a round section of radius x σ under
/// range noise σ (the simulation above; linear between its samples, x + 0.01 beyond x = 4).
double noisyMedianOverNoise(double x);

/// The radius whose points' median distance to the axis is `median` under range noise `noise`: the
/// inverse of noisyMedianOverNoise. A median at or under the blob's (0.68 σ) cannot tell a radius
/// from none: it gives a quarter of the noise, the smallest radius the relation resolves, or the
/// median itself when that is less. `median` unchanged when `noise` is not positive.
double radiusUnderNoise(double median, double noise);

/// The scan's range noise (cloud units) read from the tubes of `model`: per tube with at least 12
/// points (those within `band` plus 0.6 of its radius outside it), each point paired with its
/// nearest neighbour over the tube's surface (along the axis and round it), 1.4826 × the median
/// difference of the pair's distances to the axis over √2 (the nugget), divided by the share of the
/// noise that a section of that tube's size shows in it (0.46–0.61, from the tube's median distance
/// over its nugget); the median over the tubes. -1 with fewer than three tubes.
double rangeNoise(const std::vector<SkeletonNode>& model, const geom::PointCloud& cloud, double band);

}  // namespace treesketch::skeleton::detail
