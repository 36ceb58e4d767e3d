// Fitting one sketch node: slice the cloud with the node's plane, keep the slice points near the
// node's line (or point), fit a circle in the plane with RANSAC, and grow the line tolerance
// while no circle is found (thesis §3.1.3, §4.4, appendix B: SketchNode::CollectPoints/CalcDisc).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "treesketch/fit/circle_fit.h"
#include "treesketch/fit/cloud_index.h"
#include "treesketch/geom/types.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::fit {

enum class NodeStatus { Fitted, Skipped, Disabled };
/// "fitted", "skipped", "disabled".
const char* toString(NodeStatus status);

/// What the sketch knows about a node's parent (so that fits survive clutter): its circle.
/// A screen node's line L crosses every surface along its view ray; with a prior the fit chooses
/// among the depth hypotheses the one continuing the parent, and refuses circles much wider than
/// the parent's.
struct FitPrior {
  geom::Vec3 centre = geom::Vec3::Zero();  ///< the parent's circle centre, world
  double radius = 0.0;                     ///< the parent's radius, world units (> 0)
};

struct DepthChoiceOptions {
  /// Test points further apart than this along L (world units) belong to different surfaces;
  /// 0 = 4 slice half-thicknesses (design choice: wider than the scan noise and a slice's
  /// thickness, narrower than the gap between two limbs lined up in depth).
  double gap = 0.0;
  /// With a prior: circles wider than this many parent radii (plus one slice half-thickness) are
  /// refused (design choice: 2 — a child is rarely wider than its parent; 0.26 m on a 0.06 m
  /// trunk was the failure that asked for it). 0 = no limit.
  double maxRadiusOfParent = 2.0;
  /// A chosen circle counts as a depth jump when its depth along L differs by more than this
  /// many of its own radii plus `gap` from where it was expected (the parent's depth; without a
  /// parent, the front-most surface with a circle). Design choice: 3.
  double jumpRadii = 3.0;
  /// With a prior, circles farther along L from the parent's depth than maxTurn times the
  /// parent's sideways distance from L (plus jumpRadii parent radii and the gap) are refused: the
  /// branch would have to turn more than atan(maxTurn) towards or away from the viewer, and a
  /// person draws such a branch from another view. Design choice: 1.0 (45°); measured on the
  /// dev trees leaf-on (docs/evaluation/README.md, "A person's help").
  double maxTurn = 1.0;
};

struct NodeFitOptions {
  /// The RANSAC circle fit. Its centreRegion is set by fitNode (see "sanity rule" below); the
  /// seed is used as given.
  CircleFitOptions circle;
  /// Safety cap on lineEpsilon growth steps (the thesis loop has none; it ends when the test
  /// points equal the slice, which the cap never pre-empts for clouds < 10,000 steps across).
  int maxGrowthSteps = 10000;
  /// Also compute and keep the full slice (nearPts) indices, even when the first fit succeeds.
  /// Off by default: the full slab is only computed when a fit fails (lazy), see NodeResult.
  bool keepSlice = false;
  /// Thesis reference path: every slice by a scan of all points (for benchmarks and tests).
  bool bruteForce = false;
  /// Screen nodes: choose among the depth hypotheses along L instead of accepting the
  /// best-supported circle of all the test points. Off by default: the thesis's procedure, which
  /// the automatic skeleton's internal fits (point nodes, unaffected anyway) and the benchmarks
  /// keep; the viewer and the evaluation's sketches turn it on (recon::ReconstructionOptions).
  bool chooseDepth = false;
  DepthChoiceOptions depth;
  /// Screen nodes: grow the test region around L after a failed fit (the thesis's loop). Off: a
  /// screen node is fitted in its first test region only, and skipped when that holds no circle
  /// (a person clicked on the limb they mean; a circle found only after the region has grown past
  /// the click lay off the node's limb for 30 of 31 of the simulated careful user's nodes,
  /// leaf-on). On by default: the thesis's procedure, and off it fits fewer nodes, which trades
  /// forward for backward error (docs/evaluation/README.md, "The careful user's fits on the
  /// classified wood"). Point nodes follow their SamplingParams::maxGrowthSteps either way.
  bool growScreenNodes = true;
};

/// Everything the fit of one node produced (plain data for the viewer and tests). Indices are
/// into the cloud the CloudIndex was built from, in the index's storage order (CloudIndex::query);
/// the brute-force path gives the same lists in the same order.
struct NodeResult {
  NodeStatus status = NodeStatus::Skipped;
  std::string reason;                       ///< why the node was skipped or disabled; empty when fitted
  geom::Vec3 centre = geom::Vec3::Zero();   ///< circle centre, world, on the node's plane
  geom::Vec3 normal = geom::Vec3::UnitY();  ///< the node's plane normal (unit, as given by the sketch)
  double radius = 0.0;                      ///< world units
  double rms = 0.0;                         ///< RMS residual of the inliers, world units
  /// The slice (points within ε of the plane). Computed only when a fit failed once, with
  /// keepSlice, or in bruteForce mode (sliceComputed says which); otherwise use nodeSlice().
  bool sliceComputed = false;
  std::vector<std::uint32_t> sliceIndices;
  std::vector<std::uint32_t> testIndices;    ///< slice points in the final test region
  std::vector<std::uint32_t> inlierIndices;  ///< the circle's inliers (subset of testIndices)
  int iterations = 0;                        ///< RANSAC samples drawn, summed over all growth steps
  double lineEpsilon = 0.0;                  ///< the test region radius used last (world units)
  int growthSteps = 0;                       ///< how many times lineEpsilon grew
  double ms = 0.0;                           ///< wall time of this fit
  /// The circle is the node's kept circle (sketch::Node::kept), not a fit: status Fitted, no
  /// slice was cut and no RANSAC ran (keptCircleResult).
  bool kept = false;
  /// Screen nodes fitted with chooseDepth: the circle centre's distance along L from its near
  /// point (the chosen depth, for the view to show; NaN otherwise), how many surfaces along L
  /// gave a circle, and whether the chosen one is not where the fit expected it (see
  /// DepthChoiceOptions::jumpRadii): then `warning` says so.
  double depth = std::numeric_limits<double>::quiet_NaN();
  int depthHypotheses = 0;
  bool depthJump = false;
  std::string warning;
};

/// The slab of a node: points within params.sliceHalfThickness of its plane.
SliceRegion slabRegion(const sketch::NodeGeometry& geometry, const sketch::SamplingParams& params);
/// The node's test region for a given line tolerance: slab ∩ cylinder of radius lineEpsilon
/// around L (screen nodes) or slab ∩ ball of that radius around planePoint (point nodes).
SliceRegion testRegion(const sketch::NodeGeometry& geometry, const sketch::SamplingParams& params, double lineEpsilon);
/// The node's slice (nearPts) indices, in the index's storage order: what the viewer highlights
/// for a selected node.
std::vector<std::uint32_t> nodeSlice(const CloudIndex& index, const sketch::NodeGeometry& geometry,
                                     const sketch::SamplingParams& params);

/// Fits one node. Procedure (thesis appendix B): test points = slice ∩ test region of radius
/// lineEpsilon; project them to 2D on an orthonormal basis of the plane (u along L's direction
/// for screen nodes); RANSAC; on failure lineEpsilon += lineEpsilonStep and retry, until a circle
/// is found or the test points are the whole slice (then the node is Skipped with a reason).
/// Sanity rule (design choice): the best circle's centre must lie within the current lineEpsilon
/// of L (screen nodes, distance measured in the plane) or of planePoint (point nodes); otherwise
/// that attempt counts as a failure and lineEpsilon grows. A circle centred outside the test
/// region is not the branch the user pointed at (or is, but seen through a sliver: growing then
/// takes in more of it). The radius is NOT limited by lineEpsilon: a line through a trunk's centre with a
/// small tolerance sees the near and far arcs of a wider circle, which is a valid fit.
/// Depth choice (options.chooseDepth, screen nodes): at each lineEpsilon the test points
/// are split into surfaces along L (gaps wider than DepthChoiceOptions::gap), a circle is fitted
/// to each surface as well as to all of them, and among the circles found the fit takes the one
/// nearest the parent's depth (`prior`: the projection of its centre on L) — without a prior the
/// front-most, the surface the person sees. With a prior, circles wider than maxRadiusOfParent
/// parent radii are refused. The result gives the chosen depth and flags a jump.
/// params.enabled = false gives status Disabled without touching the cloud.
/// Throws OptionsError for non-positive or non-finite sampling sizes, a zero normal/direction.
NodeResult fitNode(const CloudIndex& index, const sketch::NodeGeometry& geometry, const sketch::SamplingParams& params,
                   const NodeFitOptions& options = {}, const FitPrior* prior = nullptr);

/// A node's result from its kept circle instead of a fit: status Fitted, kept = true, the centre
/// projected onto the node's plane, the plane's normal, the circle's radius, rms 0. A disabled
/// node stays Disabled (params.enabled wins, as for a fit).
NodeResult keptCircleResult(const sketch::NodeGeometry& geometry, const sketch::SamplingParams& params,
                            const sketch::KeptCircle& circle);

}  // namespace treesketch::fit
