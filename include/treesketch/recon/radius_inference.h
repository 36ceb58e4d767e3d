// The radii of a fitted sketch's model: which fits the model uses, and a radius inferred from the
// limb for every node that did not fit or whose fit is implausible. On a sparse limb most slices
// hold too few points for a circle, and the one circle that fits may be a noisy arc several times
// the limb; without this the tube joined the few fits it had into a cone from the trunk's radius
// to that one circle. The rules are the automatic model's (skeleton/skeleton_sketch.h,
// RadiusRules): a fit is compared with its limb, unfitted radii are interpolated along the limb by
// arc length, the limb's radii are made non-increasing towards the tip by the same least-squares
// taper (util/non_increasing_fit.h) and capped by the node the limb grows from.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "treesketch/fit/node_fit.h"
#include "treesketch/geom/types.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::recon {

using sketch::NodeId;

/// Where a node's radius in the model comes from.
enum class RadiusSource {
  Fitted,    ///< its circle fit, accepted (the radius may be lowered by the taper)
  Kept,      ///< the sketch's kept circle, as given
  Inferred,  ///< from its limb: it did not fit, or its fit was implausible
  None,      ///< no circle: disabled, or a screen node with no fit (its depth is unknown); bridged
};
/// "fitted", "kept", "inferred", "none".
const char* toString(RadiusSource source);

/// A node's circle in the model.
struct NodeRadius {
  RadiusSource source = RadiusSource::None;
  geom::Vec3 centre = geom::Vec3::Zero();   ///< world (a fit's centre, or a point node's point)
  geom::Vec3 normal = geom::Vec3::UnitY();  ///< the node's plane normal
  double radius = 0.0;                      ///< world units (> 0 unless source is None)
  /// Inferred: why its fit was not used — the fit's skip reason, or what made the fit
  /// implausible. Empty otherwise.
  std::string why;
};

struct RadiusInferenceOptions {
  /// Off: the model is the fits as they are, unfitted nodes bridged — the thesis's procedure, and
  /// what the automatic model's own passes use (its radius rules are its own). On for a person's
  /// sketch (recon::sketchReconstructionOptions).
  bool enabled = false;
  /// A fit on a limb that forks off another, wider than this many radii of the node it forks
  /// from, is implausible: a side limb is thinner than what carries it (the pipe model gives each child of
  /// an even fork 0.71 of its parent's radius; 0.9 leaves room for a fit's ±10 %), and a slice
  /// beside the fork that takes in the parent's surface fits the parent's radius. Design choice.
  double maxSideOfParent = 0.9;
  /// A fit wider than this many times the median of the accepted fits within `neighbourNodes`
  /// nodes along its limb (at least one) is implausible: a slice that took in a
  /// neighbouring limb or noise. Design choice: 2, as the automatic model's maxRadiusRatio.
  double maxOfNeighbours = 2.0;
  int neighbourNodes = 3;
  /// A point node's fit whose circle passes farther than this many of its radii (plus the node's
  /// slice half-thickness) from the node's point is implausible: the node was put on its limb (a
  /// stroke puts it on the limb's surface), so its circle holds the point; a circle away from it
  /// is another surface's (the stem's, seen through a slice beside the fork). Design choice: 1.
  double maxOffCircleRadii = 1.0;
  /// A fit whose RMS residual exceeds both this many times the sketch's noise (the median RMS of
  /// its accepted fits, measured on the cloud) and maxRelativeRms of its radius is implausible: a
  /// circle through scattered points. Design choice: 4 (the automatic model's surface bound
  /// allows four times the noise) and 0.35 (the automatic model's maxRelativeRms).
  double maxRmsOfNoise = 4.0;
  double maxRelativeRms = 0.35;
  /// Weight of an inferred radius in the limb's taper fit, relative to an accepted fit's (the
  /// automatic model's value for its interpolated radii).
  double inferredWeight = 0.25;
};

/// One node as the inference sees it (the sketch's parent-before-child order).
struct RadiusInput {
  NodeId id = sketch::kNoNode;
  NodeId parent = sketch::kNoNode;
  const fit::NodeResult* fit = nullptr;  ///< its fit (not null)
  sketch::NodeGeometry geometry;         ///< its line or point and its plane
  double sliceHalfThickness = 0.0;       ///< its sampling's (world units)
};

/// Every node's circle in the model (keyed by id). Nodes are in parent-before-child order; a
/// parent missing from `nodes` makes a root. Limbs are chains of nodes with a place (nodes with
/// none are bridged): at each node the straightest child continues the limb (at a root, the one
/// carrying the longest sketch below it), every other child starts one. A fit is accepted unless
/// implausible (see the options). A node with a place (a fit, or a point node with points in its
/// test region) and no accepted fit is Inferred: the ratio of radius to the pipe model's shape
/// (√ of the sketch's length it carries) interpolated by arc length between the limb's accepted
/// fits, the nearest one's beyond them; on a limb with none, the pipe model's share of the node
/// it forks from (at most an even fork's, 1/√2). Then each limb's radii are made non-increasing
/// towards the tip (the least-squares fit; kept circles are not changed) and capped by the node it
/// forks from. A limb with nothing to give a radius (no fit, no fork) stays None. Empty input →
/// empty map.
std::map<NodeId, NodeRadius> inferRadii(const std::vector<RadiusInput>& nodes, const RadiusInferenceOptions& options = {});

/// How a fitted sketch's nodes fared, for the fit report: how many fitted, were kept, were
/// disabled, and, per reason, why the others did not fit (a fit's skip reason reduced to its kind,
/// or the implausibility that set it aside), each with how many.
struct FitSummary {
  std::size_t nodes = 0, fitted = 0, kept = 0, disabled = 0, inferred = 0;
  std::map<std::string, std::size_t> notFitted;  ///< reason → how many
  /// "5 of 7 fitted; 2 not: too few points for a circle (2 inferred from the limb)".
  std::string text() const;
};

/// The kind of a fit's skip reason, without its figures ("too few points for a circle", "no
/// points in the slice", ...), so that reasons can be counted; the reason itself when unknown.
std::string reasonKind(const std::string& reason);

/// The summary of `ids` (all of `radii`'s nodes when `ids` is empty). `results` and `radii` are
/// a reconstruction's (ReconstructionResult); ids missing from them are left out.
FitSummary summarizeFits(const std::map<NodeId, fit::NodeResult>& results, const std::map<NodeId, NodeRadius>& radii,
                         const std::vector<NodeId>& ids = {});

}  // namespace treesketch::recon
