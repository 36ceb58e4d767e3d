// From a skeleton to an editable sketch and a tree model: every skeleton node becomes a point
// node of a sketch::Sketch (plane normal = local branch direction, sampling sizes scaled to the
// local radius), each node is fitted with the fit module's slice + RANSAC circle (the same as a
// user's node), and the radii are regularised along the branches (robust smoothing, no child
// thicker than its parent, optional pipe model). The sketch is what `treesketch reconstruct` and
// the viewer take as is; the user refines it from there.
#pragma once

#include <cstdint>
#include <vector>

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
  /// A fit is rejected (its radius interpolated instead) when its radius exceeds
  /// maxRadiusRatio × the skeleton's estimate + one voxel, or its centre is further than
  /// maxCentreShiftRadii × estimate + one voxel from the skeleton node, or its RMS residual
  /// exceeds maxRelativeRms × its radius + 0.25 voxel.
  double maxRadiusRatio = 2.0;
  double maxCentreShiftRadii = 1.5;
  double maxRelativeRms = 0.35;
  /// Running median over this many nodes along each branch (odd; 1 = off).
  int medianWindow = 5;
  /// No node thicker than its parent (along a branch: radii never grow towards the tip).
  bool childNotThicker = true;
  /// Pipe model at forks (Shinozaki et al. 1964): r_parent^e = Σ r_child^e, applied by growing a
  /// fork's radius when its children need more (never shrinking it). Off by default: the fits
  /// measure radii, the rule only fills in where they are unreliable.
  bool pipeModel = false;
  double pipeExponent = 2.0;
};

/// Builds the sketch: node i of `skeleton.nodes` becomes sketch node id i (point node at the
/// node's position, normal = its direction), with sampling sizes from its radius. sketch.up =
/// skeleton.up; sketch.defaults = the root's sizes. Empty skeleton → empty sketch.
sketch::Sketch skeletonToSketch(const Skeleton& skeleton, const SkeletonSketchOptions& options = {});

/// Regularises radii along the skeleton's branches. `fitted[i]` is node i's fitted radius and
/// `valid[i]` whether to trust it; invalid ones are interpolated along the branch by arc length
/// from valid neighbours (or take the skeleton's estimate when the branch has none). Returns one
/// radius per node, > 0. Throws OptionsError when the sizes differ or an option is out of range.
std::vector<double> regularizeRadii(const std::vector<SkeletonNode>& nodes, const std::vector<double>& fitted,
                                    const std::vector<char>& valid, const RadiusRules& rules = {});

/// The node fit used by the automatic sketch: the fit module's defaults (the inlier band is the
/// same fixed width as a user's node's), except that the test region grows at most 3 times (a
/// skeleton node knows where its branch is; a node that fails then gets an interpolated radius
/// instead of a circle from the whole slice) and fewer RANSAC samples are drawn.
inline fit::NodeFitOptions autoNodeFitOptions() {
  fit::NodeFitOptions o;
  o.maxGrowthSteps = 3;
  // No band relative to the radius (CircleFitOptions::inlierThresholdRelative): in RANSAC a
  // relative band is the hypothesis's own, so larger circles get wider bands and more inliers,
  // and the sampler drifts to circles that take in bark, neighbours and noise. Measured on the
  // four ez-tree trees × sphere / TLS scanned without leaves (mean backward / forward RMS % of
  // the diagonal): relative 0.15 (sessions 2-6) 0.143 / 0.180, 0.05 0.133 / 0.185, 0.03 0.125 /
  // 0.189; none, fixed band 0.005 / 0.01 (default) / 0.02 / 0.04 units 0.121 / 0.099 / 0.105 /
  // 0.110 backward at 0.186-0.188 forward. In leaf: 1.313 / 0.849 -> 1.313 / 0.866. The band is
  // also at least AutoSkeletonOptions::minInlierBandVoxels (0.1 voxel: 0.011-0.026 units on those
  // trees, 0.104 / 0.186), so that it follows the cloud's scale.
  // 500 samples find an all-inlier triple with p = 0.999 down to ~24 % inliers; below that a
  // skeleton node's slice is mostly something else (leaves) and its radius is interpolated
  // anyway. Measured on the test trees: the same accuracy as the fit module's 2,000 in every
  // condition, 40 % less fit time on leaf-on crowns.
  o.circle.maxIterations = 500;
  return o;
}

struct AutoSkeletonOptions {
  SkeletonOptions skeleton;
  SkeletonSketchOptions sketch;
  fit::NodeFitOptions fit = autoNodeFitOptions();
  RadiusRules radii;
  /// Foliage by fit: tips whose circle fit was rejected are trimmed, repeatedly (a chain of
  /// unfitted nodes at a branch end is most often leaves, whose slices hold no circle). The
  /// sketch, fits, model and skeleton.nodes then hold only the kept nodes (re-indexed). Off by
  /// default: on sparse scans many real twigs fail their fits too (aspen leaf-off, 160k rays:
  /// forward RMS 5.1 % -> 7.9 %), while leaf-on it helps (7.0 % -> 1.2 % with minTubularFraction 0).
  bool trimUnfittedTips = false;
  /// Forks without an accepted fit are bridged in the swept mesh (no ring of their own: the
  /// children's tubes join the fork's parent ring). A fork's level set holds the bases of its
  /// children, so its centroid often sits between the branches, off the wood; when its circle
  /// fit was rejected there is nothing to move it onto. Those rings were half of the squared
  /// backward error on the leaf-off test trees; bridging them measured (mean of the four
  /// ez-tree trees, backward / forward RMS % of the diagonal) sphere 0.150 / 0.169 -> 0.136 /
  /// 0.164 and TLS 0.163 / 0.204 -> 0.152 / 0.200. Bridging every fork (accepted or not) was
  /// worse (sphere backward 0.193: long trunk bridges cut the corners of bends). The node stays
  /// in `model`, the sketch and the cylinder table.
  bool bridgeUnfittedForks = true;
  /// Leaf pieces are not fitted: a node whose piece is more than this share flat voxels (leaves,
  /// SkeletonNode::flatFraction; only the leaf-on settings run that test) keeps the skeleton's
  /// position and radius (as a rejected fit does). A slice through a leaf cluster holds the
  /// blades, not the twig hidden among them: such fits, when accepted, had radii 2.8-7.6 times the
  /// true twig radius (median, leaf-on test trees). Measured on the four ez-tree trees × sphere /
  /// TLS scanned in leaf (mean backward / forward RMS % of the diagonal, total fit time): every
  /// node fitted 1.346 / 0.817, 9.6 s; above 0.8 not fitted 1.334 / 0.831, 2.1 s; above 0.5 (the
  /// default) 1.334 / 0.836, 1.3 s; above 0.3 1.326 / 0.881, 1.0 s. 1 = fit every node. Leaf-off
  /// settings are unaffected (flatFraction is 0).
  double maxFitFlatFraction = 0.5;
  /// The sketch hands over the model itself: every node carries its model circle as a kept
  /// circle (sketch::Node::kept: the accepted fit, or the skeleton's position where the fit was
  /// rejected or not run, with the regularised radius), and forks the mesh bridges are disabled.
  /// A rebuild of the sketch (viewer, `reconstruct --sketch`) then gives this result's mesh, and
  /// an edit re-fits only the nodes it touches. Without it a rebuild fits every node from the
  /// cloud with no radius rules: measured on the four ez-tree trees × sphere / TLS (per scan,
  /// backward / forward RMS % of the diagonal), leaf-off 0.07-0.15 / 0.12-0.31 (this mesh) became
  /// 0.08-0.18 / 0.14-0.59, leaf-on 0.70-2.23 / 0.33-2.39 became 0.96-2.31 / 0.30-3.15.
  bool keepModelCircles = true;
  /// The fits' inlier band is at least this many voxels (fit.circle.inlierThreshold is in cloud
  /// units, 0.01 by default: right for metres and for the test trees' units, but a cloud in
  /// millimetres would be fitted with a 0.01 mm band, and its fits would fail). 0 = the band as
  /// given. Measured on the four ez-tree trees × sphere / TLS without leaves, the same scans in
  /// scene units and × 1000: 0 gave 0.099 / 0.188 and 0.195 / 0.167 (backward / forward RMS %),
  /// 0.1 gives 0.104 / 0.186 at both scales; real scans in metres keep the 0.01 m band (0.1 voxel is
  /// a few millimetres there).
  double minInlierBandVoxels = 0.1;
  /// Node i is fitted with seed `seed + i`.
  std::uint64_t seed = 1;
  /// Vertices per ring of the swept mesh.
  int ringVertices = 16;
};

/// Whether autoSkeletonSketch leaves `node` unfitted as a leaf piece (see maxFitFlatFraction).
inline bool isLeafPiece(const SkeletonNode& node, const AutoSkeletonOptions& options) {
  return node.flatFraction > options.maxFitFlatFraction;
}

struct AutoSkeletonResult {
  Skeleton skeleton;
  sketch::Sketch sketch;
  std::vector<fit::NodeResult> fits;  ///< per model node (= sketch id)
  std::vector<char> fitAccepted;      ///< the fit passed the RadiusRules checks
  /// The final model: skeleton.nodes (minus trimmed tips, re-indexed; `raw` still points into
  /// skeleton.rawNodes) with positions moved to the accepted fit centres and radii regularised
  /// (what the writers and the sweep take).
  std::vector<SkeletonNode> model;
  geom::TriMesh mesh;  ///< tubes swept through `model`
  double skeletonMs = 0, fitMs = 0, sweepMs = 0;
};

/// One shot: extractSkeleton, skeletonToSketch, fit every node (TBB, in parallel), regularise
/// the radii, sweep. Empty cloud → empty result. Throws OptionsError for bad options or NaN input.
AutoSkeletonResult autoSkeletonSketch(const geom::PointCloud& cloud, const AutoSkeletonOptions& options = {},
                                      const ProgressFn& progress = {});

}  // namespace treesketch::skeleton
