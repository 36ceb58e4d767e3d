// A simulated correcting user: starting from the automatic sketch, at each step the
// person looks at the worst visible error and makes the one edit a person would, with the
// correction tools the viewer offers (edit/correction_tools.h):
//  - a reference limb the model misses (its axis samples lie farther than the tolerance outside
//    the model's surface): a stroke along the missed part, from where the model still covers it
//    to its tip, drawn in the view (front, side, back, other side) where that part is longest on
//    screen and least hidden, with Gaussian hand jitter;
//  - a tube far from any reference wood (a node whose circle lies farther than the tolerance
//    outside the reference surface): the topmost such node's subtree is deleted when most of it
//    is wrong; otherwise the node alone (its children re-attached to its parent, the viewer's
//    Delete).
// The error of each candidate is its share of the squared distances the RMS figures sum (missed
// limb: Σ over uncovered axis samples of excess² · radius · step, the limb's surface; wrong
// tube: Σ excess² · radius · spacing); the largest is fixed first. Both RMS distances (backward:
// model → reference, forward: reference → model, % of the reference diagonal, as runEvaluation)
// are measured after every edit. The interactive-segmentation field reports "number of clicks to
// reach a target" the same way (NoC@90); here NoE@target, both directions.
// The person starts from the automatic model of every point (leaf-on: its leaf-on settings), or
// leaf-on from the model of the classified wood (CorrectingUserOptions::leafOnWoodOnly), which
// misses the limbs the classifier called leaf, and draws those. Every edit is rebuilt on the whole
// scan. Known limit: a stroke over a limb inside the foliage takes its depth from the leaves around
// it as often as from the limb (see docs/classify.md, "Correcting the model of the wood").
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "treesketch/eval/evaluation.h"
#include "treesketch/eval/mesh_distance.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::eval {

struct CorrectingUserOptions {
  /// Edits the person makes at most (the curve's length).
  int maxEdits = 20;
  /// The target both RMS distances must reach, % of the reference diagonal ("edits to reach").
  double targetPct = 0.5;
  /// Stop once the target is met both ways (false: run all maxEdits for the full curve).
  bool stopAtTarget = false;
  /// An axis sample or a tube counts as an error beyond this distance outside the other surface,
  /// % of the reference diagonal (design choice: 0.5 %, the target: smaller misses cost less
  /// RMS than an edit is worth).
  double tolerancePct = 0.5;
  /// Hand jitter of the strokes, pixels (the careful user's, EvalOptions::pixelNoise).
  double pixelNoise = 1.5;
  /// A subtree is deleted whole when at least this share of its tube surface (radius x spacing
  /// summed over its nodes) is wrong. Design choice: 0.9, a subtree a person sees is wrong as a
  /// whole; at 0.6 the subtrees taken held real limbs, and every such deletion was undone (the
  /// dev trees, leaf-on: no change in 20 edits).
  double subtreeWrongShare = 0.9;
  /// Leaf-on scans: true starts the person from the automatic model of the points the wood/leaf
  /// classification calls wood, with the leaf-off settings (eval::automaticModel with woodOnly,
  /// the "skeleton-wood" method; `reconstruct --auto --leaf-on --wood-only`, then correct). false:
  /// from the model of every point with the leaf-on settings (thousands of small tubes in the
  /// foliage). Leaf-off scans are not affected. Either way the model's nodes keep their circles,
  /// and the strokes' nodes are picked and fitted on every point of the scan: the person sees the
  /// whole cloud, and a limb the classifier called leaf has no wood points to fit on. Default
  /// false, measured (docs/classify.md, "Correcting the model of the wood", four trees, 20 edits):
  /// from the wood the forward error falls from 4.3 to 2.1 % but strokes inside the foliage raise
  /// the backward error from 0.5 to 1.2 % (sphere scans); from every point 1.20 / 0.41 %.
  bool leafOnWoodOnly = false;
  std::uint64_t seed = 1;
  DistanceOptions distance;
};

struct CorrectingStep {
  int edit = 0;        ///< 0 = the automatic model before any edit
  std::string action;  ///< "start", "stroke limb 12 (side view, 9 nodes)", "delete subtree 40 (7 nodes)"...
  int nodes = 0;
  double backwardRms = 0, forwardRms = 0;  ///< % of the reference diagonal
  double ms = 0;                           ///< the edit and its rebuild, wall time
};

struct CorrectingRun {
  std::string tree, condition, pattern, leaf;
  std::vector<CorrectingStep> steps;
  /// Edits until both RMS are <= targetPct (0: the automatic model already is; -1: not reached).
  int editsToTarget = -1;
};

/// Runs the simulated person on one scan (`cloud`, every point), from `automatic` (the automatic
/// skeleton's sketch; its nodes' kept circles are kept, whichever points they were fitted on).
/// Every rebuild, and every stroke's depth and fits, use all of `cloud`. `startLabel` names the
/// start in step 0's action.
CorrectingRun runCorrectingUser(const TreeCase& tree, const geom::PointCloud& cloud, const sketch::Sketch& automatic,
                                const CorrectingUserOptions& options,
                                const std::string& startLabel = "start (automatic model)");

/// Scans every tree under every condition of `evalOptions` (leaf states as it says), builds the
/// automatic model (leaf-on with options.leafOnWoodOnly: of the classified wood) and
/// runs the correcting user on each; `evalOptions.log` reports progress.
std::vector<CorrectingRun> runCorrectingEvaluation(const std::vector<TreeCase>& trees, const EvalOptions& evalOptions,
                                                   const CorrectingUserOptions& options);

/// Writes correcting_user.csv (one row per step), correcting_user.md (edits to target per case
/// and the means per leaf state and pattern) and correcting_user_{leaf-on,leaf-off}.svg (RMS
/// after each edit, both directions, mean over the cases of each pattern) into `folder`.
void writeCorrectingReport(const std::filesystem::path& folder, const std::vector<CorrectingRun>& runs,
                           const CorrectingUserOptions& options);

/// correcting_user.md's text.
std::string correctingMarkdown(const std::vector<CorrectingRun>& runs, const CorrectingUserOptions& options);

}  // namespace treesketch::eval
