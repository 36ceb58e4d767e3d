// The automatic skeleton as a sketch source. Every skeleton node becomes a point node of a
// sketch::Sketch (plane normal = local branch direction, sampling sizes scaled to the local
// radius); recon::Reconstruction fits them with the fit module's slice + RANSAC circle (the same
// as a user's node); the radii are regularised along the branches (robust smoothing, no child
// thicker than its parent, optional pipe model) and handed back in the sketch as kept circles.
// The sketch is what `treesketch reconstruct` and the viewer take as is; the user refines it.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/cloud/ground.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/fit/node_fit.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/sketch/sketch.h"
#include "treesketch/util/progress.h"

namespace treesketch::skeleton {

/// Sampling sizes of the sketch nodes, from each node's radius estimate r and the voxel size v.
struct SkeletonSketchOptions {
  /// Slice half-thickness ε = max(sliceRadii × r, sliceVoxels × v): thin enough to follow a
  /// bending branch, thick enough to hold a few dozen points.
  double sliceRadii = 0.6;
  double sliceVoxels = 1.5;
  /// Initial test radius lineEpsilon = lineRadii × r + lineVoxels × v: the whole circle plus the
  /// skeleton's position error, and little of a neighbouring branch.
  double lineRadii = 1.6;
  double lineVoxels = 1.0;
  /// lineEpsilon growth step after a failed fit = stepRadii × r + stepVoxels × v.
  double stepRadii = 0.5;
  double stepVoxels = 0.5;
};

/// Rules applied to the fitted radii, each with a default.
struct RadiusRules {
  /// A fit is accepted only when its radius ≤ maxRadiusRatio × the skeleton's estimate + slack,
  /// its centre ≤ maxCentreShiftRadii × estimate + slack from the skeleton node, and its RMS
  /// residual ≤ maxRelativeRms × its radius + rmsFloorVoxels voxels: a skeleton node knows
  /// roughly where and how thick its branch is, so a fit far from that took in something else.
  double maxRadiusRatio = 2.0;
  double maxCentreShiftRadii = 1.5;
  double maxRelativeRms = 0.35;
  /// The slack above, in voxels: the skeleton's estimates are good to about one voxel.
  double slackVoxels = 1.0;
  /// The RMS floor above, in voxels: a thin twig's scan noise is a fraction of a voxel, not of its radius.
  double rmsFloorVoxels = 0.25;
  /// Running median over this many nodes along each branch (odd; 1 = off): one bad fit no longer shows.
  int medianWindow = 5;
  /// No node thicker than its parent: along a branch the radii are the least-squares
  /// non-increasing fit (isotonic regression; trusted fits weigh 4× interpolated radii), so they
  /// never grow towards the tip and one thin fit (a twig's circle taken on the trunk) lowers only
  /// its neighbourhood instead of capping everything above it as a running minimum did; a side
  /// branch is capped by the node it forks from.
  bool childNotThicker = true;
  /// Pipe model at forks (Shinozaki et al. 1964, area-preserving: r_parent² = Σ r_child²), applied
  /// by growing a fork's radius when its children need more (never shrinking it). Off by default:
  /// the fits measure radii, the rule only fills in where they are unreliable.
  bool pipeModel = false;
  /// Pipe-model bound (a factor ≥ 1; 0 = off): the pipe model's law r = a·L^0.5 (radius against
  /// the length a node carries), its scale taken from the measured stem
  /// (skeleton/radius_allometry.h), rejects fits more than this factor above it, and no final
  /// radius exceeds it by more. Only an upper bound: a fit that took in noise, a neighbour or a
  /// one-sided arc is too thick far more often than too thin, and raising thin radii put real
  /// scans' points inside the model. The factor is the room real crowns take beyond the pure
  /// pipe model: 3 keeps the volume of every credible tuning scan within 0.67–1.5× of TreeQSM's
  /// model of it (2 cut clean scans' crowns to half, 4 let a noisy crown to 1.7×;
  /// docs/notes/radii_and_volume.md).
  double allometryMaxRatio = 3.0;
  /// A fit wider than this factor times the median of the last three fits kept below it on its
  /// branch, and wider than the pipe law from the stem (the bound above at factor 1), is set aside
  /// (a factor ≥ 1; 0 = off). A branch does not thicken towards its tip: such a circle took in a
  /// neighbouring stem, a fork's limbs or a blob of noise, and the law says the branch's length
  /// does not carry it (a thin one-sided arc below a thick true section leaves the section under
  /// the law, so it stays). The tracked stem's radii are measured and never set aside. 1.5 took the
  /// synthetic matrix's mean volume error 9.4 → 8.7 % and its cases over 25 % from 11 to 7 with
  /// the raise of inferred radii to their points (surface_bound.h) (docs/notes/radii_and_volume.md).
  double maxGrowthRatio = 1.5;
  /// The points' bound (skeleton/surface_bound.h): no tube thicker than the lower quartile of its
  /// points' distances to its axis plus four times the scan's noise measured on the cloud.
  bool surfaceBound = true;
};

/// How the branch axes are re-estimated after the fits (skeleton/axis_smoothing.h): a local,
/// weighted, robust line fit of each branch's node positions against arc length. A level-set
/// centroid lies on the scanned side of a sparsely sampled branch, so unsmoothed axes zigzag.
struct AxisRules {
  /// Half-width of the window, in nodes along the branch (0 = off). 4 (nine nodes, 5–10
  /// radii on a trunk) averages a sparse trunk's centroids, which scatter around its whole
  /// circumference, and keeps bends longer than the window; the error figures are the same for
  /// 2–4 (docs/notes/skeleton_options.md), the pictures straighter with 4.
  int halfWindowNodes = 4;
  /// Weight of a node without an accepted fit (its position is a piece's centroid), relative to
  /// a fitted circle's centre (1).
  double unfittedWeight = 0.25;
  /// A node moves at most this many of its (regularised) radii: a piece's centroid lies on the
  /// branch's surface, within one radius of its axis, so a longer move would cut a real bend (a
  /// thin twig's centroid is on its axis to within its radius and hardly moves).
  double maxShiftRadii = 1.0;
};

/// Builds the sketch: node i of `skeleton.nodes` becomes sketch node id i (point node at the
/// node's position, normal = its direction), with sampling sizes from its radius. sketch.up =
/// skeleton.up; sketch.defaults = the root's sizes. Empty skeleton → empty sketch.
sketch::Sketch skeletonToSketch(const Skeleton& skeleton, const SkeletonSketchOptions& options = {});

/// Regularises radii along the skeleton's branches. `fitted[i]` is node i's fitted radius and
/// `valid[i]` whether to trust it; invalid ones are interpolated along the branch by arc length
/// from valid neighbours (or take the skeleton's estimate when the branch has none). Returns one
/// radius per node, > 0. Throws OptionsError when the sizes differ or an option is out of range.
/// `kept`, when given, receives per node whether its radius rests on its own fit (valid, and not
/// rejected as far thicker than the pipe law) or on the tracked stem's circles.
std::vector<double> regularizeRadii(const std::vector<SkeletonNode>& nodes, const std::vector<double>& fitted,
                                    const std::vector<char>& valid, const RadiusRules& rules = {},
                                    std::vector<char>* kept = nullptr);

/// The node fit used by the automatic sketch: the fit module's defaults (the inlier band is the
/// same fixed width as a user's node's), except that the test region grows at most 3 times (a
/// skeleton node knows where its branch is; a node that fails then gets an interpolated radius
/// instead of a circle from the whole slice) and fewer RANSAC samples are drawn.
inline fit::NodeFitOptions autoNodeFitOptions() {
  fit::NodeFitOptions o;
  o.maxGrowthSteps = 3;
  // A fixed inlier band, not one relative to the hypothesis's radius: a relative band lets the
  // sampler drift to large circles that take in bark, neighbours and noise.
  // 500 samples find an all-inlier triple with p = 0.999 down to ~24 % inliers; below that the
  // slice is mostly something else and the radius is interpolated anyway.
  o.circle.maxIterations = 500;
  return o;
}

/// Completion of the model from the points it leaves unexplained (skeleton/completion.h): where
/// twigs cross or lie within a voxel or two of each other, a level set holds them as one piece and
/// one node, and the twigs off that node's tube are left out. The same pipeline is run on the
/// points farther than a margin outside the model, one connected part at a time (largest first),
/// and each part is grafted onto the model at its nearest node (a part of one node, a stub
/// shorter than two level sets, as one tube to its tip); then again on what is still out
/// (CompletionRules::maxRounds). On leaf-off, off in the leaf-on
/// preset (leaf clusters off the twigs are not wood).
struct CompletionRules {
  bool enabled = true;
  /// A point is unexplained when it lies farther than this many voxels outside the model's
  /// surface (beside a tube with a fitted circle, three spreads of that circle's points, if less). 1 measured best on the tuning half (docs/notes/skeleton_options.md, "The model
  /// completed from the points it leaves out"): 0.75 let 10 mm range noise through as twigs (tips up to 2× the limbs), 1.5 left most of the
  /// gain on the table.
  double marginVoxels = 1.0;
  /// A part needs this many points (fewer are a scatter beside the model, not a stub or a twig).
  int minPoints = 10;
  /// A part's nearest node lies within this many voxels of the model's surface, and its voxel
  /// graph bridges no longer gaps: a part farther out is a neighbour or noise and its bridge a
  /// guess (8 drew straight tubes through the air and raised the backward error).
  double maxGapVoxels = 4.0;
  /// At most this many parts are modelled in a round, largest first (each is a skeleton run).
  int maxParts = 200;
  /// Rounds run while one grafts a part (the points beyond a grafted part are the next round's),
  /// at most this many: on the real scans the second round added 0.4–2.5 points of the share
  /// within ±2 cm and the fourth nothing that shows.
  int maxRounds = 4;
};

struct AutoSkeletonOptions {
  SkeletonOptions skeleton;
  SkeletonSketchOptions sketch;
  fit::NodeFitOptions fit = autoNodeFitOptions();
  RadiusRules radii;
  AxisRules axes;
  /// Nodes whose piece is more than this share flat voxels (leaves; SkeletonNode::flatFraction,
  /// only the leaf-on settings measure it) are not fitted: their slices hold blades, not the twig.
  /// 1 = fit every node.
  double maxFitFlatFraction = 0.5;
  /// The fits' inlier band is at least this many voxels, so it follows the cloud's units (the fit
  /// module's 0.01-unit band would be 0.01 mm on a cloud in millimetres). 0 = the band as given.
  double minInlierBandVoxels = 0.1;
  /// The skeleton of a scan whose noise blurs its branches (docs/notes/radii_and_volume.md, "The
  /// skeleton of a noisy scan"): when this many of the scan's range noises (rangeNoise, read on a
  /// first model) reach three quarters of a voxel, the model is made again on a skeleton grown from the points
  /// drawn together: each point moved twice to the mean of its neighbours within that radius, so
  /// that a branch thinner than it becomes a line of points and the noise's shell round it goes.
  /// The points of the first model's tubes at least that thick stay (a stem the noise does not
  /// hide is measured as it is). The fits, the radii and the fit report still read the scan's
  /// own points. Leaf-off settings only (leaf-on ones have the leaf machinery); 0 = off.
  double contractionNoises = 2.0;
  /// Node i is fitted with seed `seed + i`.
  std::uint64_t seed = 1;
  /// Vertices per ring of the swept mesh.
  int ringVertices = 16;
  CompletionRules completion;
  /// Points far from the tree are set aside before anything else (cloud/stray_points.h): one
  /// stray point 50 m out stretched the voxel size and the model with it.
  cloud::StrayPointOptions strays;
  /// The ground under the tree is set aside with them (cloud/ground.h): left in, the skeleton
  /// started from the terrain and its shell of tubes tripled a small tree's volume.
  cloud::GroundOptions ground;
  /// Points the file classifies as noise (ASPRS classes 7 and 18) are set aside first
  /// (cloud/stray_points.h).
  cloud::MarkedNoiseOptions markedNoise;
};
// The measurements behind these defaults: docs/notes/auto_sketch_options.md.

/// What the user says about the scan (never guessed from the data).
enum class Foliage { LeafOff, LeafOn };

/// The one named preset per condition: leaf-off = the defaults; leaf-on = the skeleton's
/// leafOnSkeletonOptions() (finer level sets, weak cross-section rule, leaf-entry positions).
/// `up` is the cloud's up axis.
AutoSkeletonOptions autoSkeletonPreset(Foliage foliage, geom::UpAxis up = geom::UpAxis::Y);

/// Whether autoSkeletonSketch leaves `node` unfitted as a leaf piece (see maxFitFlatFraction).
inline bool isLeafPiece(const SkeletonNode& node, const AutoSkeletonOptions& options) {
  return node.flatFraction > options.maxFitFlatFraction;
}

/// A section's radius is resolved by its points when it is at least this many of the scanner's
/// range noise (AutoSkeletonResult::rangeNoise): from there up, its points' median distance to the
/// axis lies within 3 % of the radius (skeleton/range_noise.h); under it the points are the noise's
/// blob, and a circle fitted round them takes its shape from the noise. A radius under it counts as
/// inferred; an inferred radius whose points' median is over it is raised to what they show.
inline constexpr double kResolvableNoises = 1.5;

struct AutoSkeletonResult {
  Skeleton skeleton;
  /// The automatic model as an editable sketch: every node carries its model circle as a kept
  /// circle (the accepted fit, or the skeleton's position with the regularised radius), bridged
  /// forks are disabled. recon::Reconstruction rebuilds `mesh` from it exactly, and an edit
  /// re-fits only the nodes it touches.
  sketch::Sketch sketch;
  std::vector<fit::NodeResult> fits;  ///< the fit pass, per model node (= sketch id)
  std::vector<char> fitAccepted;      ///< the fit passed the RadiusRules checks
  /// The node's radius is measured: its accepted fit's (not set aside as far thicker than the pipe
  /// law) or the tracked stem's; otherwise inferred (interpolated, the pipe law, the crown).
  std::vector<char> radiusMeasured;
  /// skeleton.nodes with positions moved to the accepted fit centres and radii regularised (what
  /// the cylinder table is written from).
  std::vector<SkeletonNode> model;
  geom::TriMesh mesh;  ///< recon's tubes through `sketch`
  /// No circle could be fitted and no stem measured (a sparse airborne cloud): every radius is
  /// the pipe model's from a stem inferred from the crown's width (none accepted in fitAccepted).
  bool radiiFromCrown = false;
  /// The scan's noise measured on the cloud (cloud units): the smaller of the tracked stem's points'
  /// spread about its surface and the accepted circles' (surface_bound.h: stemNoise,
  /// measuredNoise), or half a voxel when neither could be measured (noiseMeasured false).
  double noise = 0;
  bool noiseMeasured = false;
  /// The scanner's range noise read from the points about the model's tubes (cloud units; -1 when
  /// fewer than three tubes hold enough points): the differences between neighbouring points'
  /// distances to their tube's axis (skeleton/range_noise.h). The circles' residuals above see
  /// little of it (a circle fitted to a noisy arc takes the noise into its own shape); this reading
  /// sets which radii the points can measure and is the noise the report gives.
  double rangeNoise = -1;
  /// The radius the skeleton's points were drawn together by (AutoSkeletonOptions::
  /// contractionNoises; cloud units), 0 when the skeleton is the scan's own.
  double contraction = 0;
  /// Nodes whose radius was lowered because the points around their tube lie inside it (a scanner
  /// sees the surface; see surface_bound.h).
  std::size_t thinnedBySurface = 0;
  /// Nodes without a measured radius raised because the points around their tube lie outside it.
  std::size_t thickenedBySurface = 0;
  /// The points set aside as strays before modelling (indices into the input cloud); the model
  /// is made from the others (cloud::keptPoints), and is measured against them.
  cloud::StrayPoints strays;
  /// Wall times: the skeleton's extraction; the slice index and the fit passes; the radius rules
  /// and the sweep; the completion's residual, parts and grafts (CompletionRules).
  double skeletonMs = 0, fitMs = 0, sweepMs = 0, completionMs = 0;
};

/// The automatic skeleton as a sketch source: the points the file marks as noise, the ground and
/// the stray points set aside (options.markedNoise, options.ground, options.strays), then
/// on the kept points extractSkeleton, skeletonToSketch, then
/// recon::Reconstruction fits every node (the fit pass, in parallel), the RadiusRules accept fits
/// and regularise the radii, the model goes into the sketch as kept circles, and the same
/// Reconstruction sweeps that sketch. recon is the only place that fits and sweeps. Empty cloud →
/// empty result. Throws OptionsError for bad options or NaN input. `progress` reports the
/// extraction's four steps (done of 4), then the fit pass (done of the node count); an exception
/// it throws (e.g. treesketch::Cancelled) stops the work and propagates.
AutoSkeletonResult autoSkeletonSketch(const geom::PointCloud& cloud, const AutoSkeletonOptions& options = {},
                                      const ProgressFn& progress = {});

}  // namespace treesketch::skeleton
