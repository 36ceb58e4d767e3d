// Why a simulated careful user's node found no circle: its sketch is made from the true branch
// axes, so each screen node has a true point on a limb, and a simulated scan labels each point
// with the surface its ray hit (geom::PointCloud::meshId, 0 = wood). That tells apart a limb the
// leaves hid from the scanner, wood the wood/leaf classification called leaf, wood the circle fit
// saw and rejected (and by which of its tests), and a node drawn off its limb.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "treesketch/fit/node_fit.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::eval {

/// Why a node has, or lacks, a circle; the first cause that applies, in this order.
enum class NodeCause {
  Fitted,       ///< the node has a circle
  OffLimb,      ///< its line passes farther from the true axis point than its first test region
  Hidden,       ///< few points of the limb in its slice carry the scanner's wood label
  ClassedLeaf,  ///< the wood is there, but the classification calls most of it leaf
  Rejected,     ///< the wood is there and classed wood, and the circle fit rejects it
};
/// "fitted", "off-limb", "hidden", "classed-leaf", "rejected".
const char* toString(NodeCause cause);

struct NodeCauseOptions {
  /// Fewer scanner-labelled (or classed) wood points than this near the node's true point count as
  /// "few": the circle fit's minimum support (fit::CircleFitOptions::minInliers, 8).
  std::size_t fewPoints = 8;
  /// The limb's points near the node: within this many true radii plus one slice half-thickness of
  /// the true axis point, inside the node's slab (2: a limb leaning 60° off the slab's normal
  /// still has its whole cross-section inside).
  double nearRadii = 2.0;
};

/// One node's cause with the counts behind it.
struct NodeCauseRecord {
  sketch::NodeId id = sketch::kNoNode;
  NodeCause cause = NodeCause::Fitted;
  std::size_t woodPoints = 0;   ///< points with the scanner's wood label near the true axis point, in the slab
  std::size_t classedWood = 0;  ///< of those, the ones the fit's cloud keeps (classed wood)
  double offAxis = 0;           ///< distance from the true axis point to the node's line, world units
  double radius = 0;            ///< the true radius there, world units
  /// Fitted, and the circle's centre lies on the limb: within nearRadii true radii plus one slice
  /// half-thickness of the true axis point (the region the points are counted in). A fitted node
  /// off its limb took another surface's circle (a limb behind, or one beside its line).
  bool onLimb = false;
  /// Rejected: the circle fit's test that refused the first test region ("support", "arc", ...),
  /// see rejectionTest; empty otherwise.
  std::string test;
};

/// The true limb under each node of a simulated user's sketch: point (world), unit tangent and
/// radius (world units), in the sketch's node-id order.
struct TrueNode {
  geom::Vec3 point = geom::Vec3::Zero();
  geom::Vec3 tangent = geom::Vec3::UnitY();
  double radius = 0;
};

/// What the fit saw, for userNodeCauses.
struct NodeCauseInput {
  const geom::PointCloud& cloud;          ///< the scan, with meshId (0 = wood)
  const std::vector<std::uint8_t>& kept;  ///< per point of `cloud`: 1 when the fit's cloud holds it (classed wood)
  const sketch::Sketch& sketch;           ///< the user's screen sketch
  const std::vector<TrueNode>& truth;     ///< one per sketch node, in id order
  const std::map<sketch::NodeId, fit::NodeResult>& results;  ///< the fits, by node id
  /// The options the nodes were fitted with; circle.seed is the base seed (recon's: node id added).
  fit::NodeFitOptions fit;
};

/// The cause of every node of `in.sketch` (in id order). A skipped node's rejecting test is read
/// from a fit of its first test region alone (no growth, no parent's prior) on the kept points;
/// when that fit succeeds, the node's own fit was refused by its depth choice ("depth choice"). Throws OptionsError
/// when truth, kept or meshId do not match the sketch and the cloud in size.
std::vector<NodeCauseRecord> userNodeCauses(const NodeCauseInput& in, const NodeCauseOptions& options = {});

/// The circle fit's test named by a reason string of fit::fitNode / fit::fitCircleRansac: "too few
/// points", "no admissible circle", "support", "centre off the line", "arc", "depth choice",
/// "empty slice" or "other".
std::string rejectionTest(const std::string& reason);

/// Counts per cause, and per rejecting test; "off-limb 1, hidden 4, classed-leaf 6, rejected 8
/// (arc 5, support 3)" for the log.
struct NodeCauseCounts {
  std::map<NodeCause, int> causes;
  std::map<std::string, int> tests;
  int onLimb = 0;  ///< fitted nodes whose circle lies on their limb
  std::string text() const;
};
NodeCauseCounts countCauses(const std::vector<NodeCauseRecord>& records);

}  // namespace treesketch::eval
