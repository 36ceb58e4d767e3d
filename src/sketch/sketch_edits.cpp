// Structural sketch edits (see sketch_edits.h).
#include "treesketch/sketch/sketch_edits.h"

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::sketch {

std::vector<NodeId> subtreeOf(const Sketch& sketch, NodeId id) {
  sketch.node(id);  // throws for an unknown id
  std::vector<NodeId> out{id};
  for (std::size_t i = 0; i < out.size(); ++i)
    for (NodeId c : sketch.node(out[i]).children) out.push_back(c);
  return out;
}

std::vector<NodeId> deleteSubtree(Sketch& sketch, NodeId id) {
  std::vector<NodeId> gone = subtreeOf(sketch, id);
  sketch.removeNode(id, true);
  std::sort(gone.begin(), gone.end());
  return gone;
}

void reattach(Sketch& sketch, NodeId id, NodeId newParent) {
  const Node& n = sketch.node(id);
  if (n.parent == kNoNode) throw OptionsError("re-attach: node " + std::to_string(id) + " is the root");
  if (newParent == kNoNode) throw OptionsError("re-attach: give the new parent");
  sketch.node(newParent);  // throws for an unknown id
  const std::vector<NodeId> below = subtreeOf(sketch, id);
  if (std::find(below.begin(), below.end(), newParent) != below.end())
    throw OptionsError("re-attach: node " + std::to_string(newParent) + " lies below node " + std::to_string(id) +
                       " (that would make a cycle)");
  sketch.setParent(id, newParent);
}

std::vector<NodeId> reattachReversed(Sketch& sketch, NodeId base, NodeId newParent) {
  if (newParent == kNoNode) throw OptionsError("re-attach: give the new parent");
  sketch.node(newParent);  // throws for an unknown id
  if (sketch.node(base).parent == kNoNode) throw OptionsError("re-attach: node " + std::to_string(base) + " is the root");
  std::set<NodeId> above;  // newParent and its ancestors
  for (NodeId n = newParent; n != kNoNode; n = sketch.node(n).parent) above.insert(n);
  if (above.count(base))
    throw OptionsError("re-attach: node " + std::to_string(newParent) + " lies below node " + std::to_string(base) +
                       " (that would make a cycle)");
  std::vector<NodeId> chain;  // base, its parent, ... up to the common ancestor (excluded)
  for (NodeId n = base; n != kNoNode && !above.count(n); n = sketch.node(n).parent) chain.push_back(n);
  // Top-down is safe: base leaves the chain first, then each node hangs under the one below it,
  // which by then is under newParent, outside the moved node's subtree.
  reattach(sketch, base, newParent);
  for (std::size_t i = 1; i < chain.size(); ++i) reattach(sketch, chain[i], chain[i - 1]);
  return chain;
}

std::vector<NodeId> graft(Sketch& target, const Sketch& piece, NodeId attachTo, const std::vector<NodeId>& drop) {
  if (attachTo == kNoNode && !target.empty())
    throw OptionsError("graft: the sketch has a root already; give the node to attach to");
  if (attachTo != kNoNode) target.node(attachTo);  // throws for an unknown id
  const std::set<NodeId> dropped(drop.begin(), drop.end());
  std::map<NodeId, NodeId> newId;  // piece id -> target id (dropped: its kept ancestor's)
  std::map<int, int> cameraOf;
  std::vector<NodeId> added;
  for (NodeId pid : piece.topologicalOrder()) {
    const Node& n = piece.node(pid);
    NodeId parent = n.parent == kNoNode ? attachTo : newId.at(n.parent);
    if (dropped.count(pid)) {
      newId[pid] = parent;
      continue;
    }
    if (parent == kNoNode && !target.empty()) parent = target.root();  // a dropped piece root, empty target
    NodeId id;
    if (n.isScreenNode()) {
      auto it = cameraOf.find(n.camera);
      if (it == cameraOf.end()) it = cameraOf.emplace(n.camera, target.addCamera(piece.cameras()[n.camera])).first;
      id = target.addScreenNode(parent, it->second, n.screen, n.params);
    } else {
      id = target.addPointNode(parent, n.point, n.normal, n.params);
      if (n.kept) target.setKeptCircle(id, n.kept);
    }
    newId[pid] = id;
    added.push_back(id);
  }
  return added;
}

}  // namespace treesketch::sketch
