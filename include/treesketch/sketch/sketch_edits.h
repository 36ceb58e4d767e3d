// Structural sketch edits of the correction tools that need nothing but the sketch:
// delete a subtree, re-attach a node to another parent, graft one sketch into another. The tools
// that need the cloud (a stroke's depth, a lasso's points, the automatic skeleton on a region)
// are in edit/correction_tools.h and call these.
#pragma once

#include <vector>

#include "treesketch/sketch/sketch.h"

namespace treesketch::sketch {

/// Removes `id` and everything below it; returns the removed ids (increasing). Throws
/// OptionsError for an unknown id. Removing the root empties the sketch.
std::vector<NodeId> deleteSubtree(Sketch& sketch, NodeId id);

/// Makes `newParent` the parent of `id` (its subtree moves with it). Throws OptionsError for an
/// unknown id, for the root (the root has no parent to change: re-attach a child instead), for
/// `newParent` == kNoNode, and when `newParent` lies in `id`'s own subtree (a cycle).
void reattach(Sketch& sketch, NodeId id, NodeId newParent);

/// Re-attaches a limb hung by its tip the right way round: `base` (the node that should start the
/// limb) becomes a child of `newParent`, and the chain from `base` up to (not including) the
/// nearest ancestor it shares with `newParent` is reversed — each node on it becomes the child of
/// the node that was its child — so the old top of the chain (the limb's tip) ends as the leaf
/// end. Side branches stay on the nodes they grow from. Returns the reversed chain, `base` first.
/// Throws OptionsError as reattach does (unknown ids, no new parent, `newParent` in `base`'s
/// subtree) and when `base` is the root.
std::vector<NodeId> reattachReversed(Sketch& sketch, NodeId base, NodeId newParent);

/// The ids of `id`'s subtree, `id` first, parents before children.
std::vector<NodeId> subtreeOf(const Sketch& sketch, NodeId id);

/// Copies every node of `piece` into `target` under `attachTo` (the piece's root becomes its
/// child; kNoNode: `target` must be empty and the piece's root becomes the root). Structure,
/// params and kept circles are kept; screen nodes bring their cameras. `keep` (optional, indexed
/// by piece id via the piece's ids()) filters nodes: a dropped node's children go to its nearest
/// kept ancestor (or to `attachTo`). Returns the new ids, in the piece's parent-before-child
/// order. Throws OptionsError for an unknown `attachTo` or a non-empty target without one.
std::vector<NodeId> graft(Sketch& target, const Sketch& piece, NodeId attachTo,
                          const std::vector<NodeId>& dropFromPiece = {});

}  // namespace treesketch::sketch
