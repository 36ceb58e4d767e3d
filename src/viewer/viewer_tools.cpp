// ViewerState, the correction tools: stroke, lasso, region, re-attach, delete subtree,
// automatic below a node — each an undoable edit over edit/correction_tools.h, and their share of
// the mouse and keys. Kept apart from viewer_input.cpp, which only forwards to toolMouseDown /
// toolMouseUp / toolKey.
#include <cmath>
#include <limits>

#include "treesketch/edit/correction_tools.h"
#include "treesketch/recon/radius_inference.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

using geom::Vec2;
using geom::Vec3;

namespace {

std::map<NodeId, edit::NodeAnchor> toEdit(const std::map<NodeId, std::pair<Vec3, double>>& a) {
  std::map<NodeId, edit::NodeAnchor> out;
  for (const auto& [id, v] : a) out[id] = edit::NodeAnchor{v.first, v.second};
  return out;
}

}  // namespace

void ViewerState::setTool(Tool tool) {
  tools_.tool_ = tool;
  tools_.reattachSource_ = kNoNode;
  tools_.toolPath_.clear();
  ++sceneVersion_;
  info(std::string("tool: ") + toolHelp(tool));
}

std::map<NodeId, std::pair<Vec3, double>> ViewerState::anchorsForTools() const {
  std::map<NodeId, std::pair<Vec3, double>> out;
  for (const auto& [id, node] : sketch_.nodes()) {
    NodeFitView f = recon_->nodeFit(id);
    if (f.status == NodeStatus::Fitted)
      out[id] = {f.circle.centre, f.circle.radius};
    else if (node.kept)
      out[id] = {node.kept->centre, node.kept->radius};
    else if (!node.isScreenNode())
      out[id] = {node.point, 0.0};
  }
  return out;
}

bool ViewerState::strokeLimb(const std::vector<Vec2>& stroke) {
  if (cloud_.empty()) {
    error("stroke: open a point cloud first");
    return false;
  }
  edit::StrokeResult r;
  const auto anchors = toEdit(anchorsForTools());
  bool ok = edit("draw limb", "draw limb", "", [&] {
    const geom::Camera cam = view_.orbit_.camera();
    // The stroke follows the wood: the not-wood points and, once the cloud is classified, the
    // points classed leaf (after the lassos) are not candidates for its depth.
    const sketch::Sketch& sk = sketch_;
    const std::vector<std::uint8_t> leaf = leafFlags();
    edit::ViewPicker picker(cloud_, cam, 4.0,
                            [&sk, &leaf](std::size_t i, const Vec3& p) { return !edit::isWoodPoint(sk, leaf, i, p); });
    r = edit::drawLimb(sketch_, picker, cloud_, stroke, anchors);
    tools_.selected_ = tools_.active_ = r.added.back();
  });
  if (ok) {
    info("drew a limb: " + std::to_string(r.added.size()) + " nodes under node " + std::to_string(r.attachedTo) + "; " +
         limbFitSummary(r.added));
    if (!r.warning.empty()) info("stroke: " + r.warning);
  }
  return ok;
}

std::string ViewerState::limbFitSummary(const std::vector<NodeId>& nodes) const {
  // How many of the limb's nodes fitted, and why the others did not, by kind of reason (a sparse
  // limb's nodes mostly fail on the minimum support: the person sees why, not only a thin tube).
  const recon::ReconstructionResult r = recon_->result();
  return recon::summarizeFits(r.results, r.radii, nodes).text();
}

bool ViewerState::lassoNotWood(const std::vector<Vec2>& polygon) {
  if (cloud_.empty()) {
    error("lasso: open a point cloud first");
    return false;
  }
  std::size_t marked = 0, refit = 0;
  bool ok = edit("not-wood lasso", "not-wood lasso", "", [&] {
    marked = edit::lassoNotWood(sketch_, cloud_, view_.orbit_.camera(), polygon);
    refit = edit::refitNotWoodCircles(sketch_);  // a model circle inside the lasso is fitted again
  });
  if (ok) {
    scene_.colorsStale_ = true;
    info("lasso: " + std::to_string(marked) + " points marked not-wood (left out of fits and the automatic skeleton)" +
         (refit ? "; " + std::to_string(refit) + " model circles inside it are fitted again from the other points"
                : std::string()));
  }
  return ok;
}

bool ViewerState::clearNotWood() {
  if (sketch_.notWood().empty()) {
    info("clear lassos: no lasso to clear");
    return false;
  }
  bool ok = edit("clear lassos", "clear not-wood and wood lassos", "", [&] { sketch_.clearNotWood(); });
  if (ok) scene_.colorsStale_ = true;
  return ok;
}

bool ViewerState::deleteSubtree(NodeId id) {
  return edit("delete subtree", "delete subtree " + std::to_string(id), "", [&] {
    const NodeId parent = sketch_.node(id).parent;
    sketch::deleteSubtree(sketch_, id);
    tools_.selected_ = kNoNode;
    tools_.active_ = parent != kNoNode && sketch_.contains(parent) ? parent : kNoNode;
  });
}

bool ViewerState::requestDeleteSubtree(NodeId id) {
  if (!sketch_.contains(id)) {
    error("delete subtree: no node " + std::to_string(id));
    return false;
  }
  std::size_t below = 0;
  for (std::vector<NodeId> stack = sketch_.node(id).children; !stack.empty();) {
    const NodeId n = stack.back();
    stack.pop_back();
    ++below;
    for (NodeId c : sketch_.node(n).children) stack.push_back(c);
  }
  if (below == 0) return deleteSubtree(id);
  pendingDelete_ = id;
  ++sceneVersion_;
  return ask("Delete node " + std::to_string(id) + " and the " + std::to_string(below) +
                 " nodes below it (drawn in red)? (undoable)",
             [this, id] { return deleteSubtree(id); });
}

bool ViewerState::reattachNode(NodeId id, NodeId newParent, bool reverse) {
  std::size_t turned = 0;
  bool ok = edit("re-attach", std::string(reverse ? "reverse limb at node " : "re-attach node ") + std::to_string(id) +
                                  " to " + std::to_string(newParent),
                 "", [&] {
                   if (reverse)
                     turned = sketch::reattachReversed(sketch_, id, newParent).size();
                   else
                     sketch::reattach(sketch_, id, newParent);
                 });
  if (ok)
    info("node " + std::to_string(id) + " now grows from node " + std::to_string(newParent) +
         (reverse ? " (the limb's " + std::to_string(turned) + " nodes turned round: node " + std::to_string(id) +
                        " is its base)"
                  : std::string()));
  return ok;
}

const geom::PointCloud& ViewerState::pointsForAutomatic(geom::PointCloud& store) const {
  // Once the cloud is classified, "automatic from here" models the wood (after the lassos) with
  // the leaf-off settings, as the automatic skeleton on the wood does; before, every point.
  if (!classes_) return cloud_;
  store = edit::woodOnly(cloud_, sketch_, leafFlags());
  return store;
}

bool ViewerState::automaticBelow(NodeId id) {
  if (cloud_.empty()) {
    error("automatic below: open a point cloud first");
    return false;
  }
  edit::AutoHereResult r;
  const auto anchors = toEdit(anchorsForTools());
  bool ok = edit("automatic below", "automatic below node " + std::to_string(id), "", [&] {
    edit::AutoHereOptions o;
    o.skeleton = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOff, up_);
    geom::PointCloud wood;
    r = edit::automaticBelow(sketch_, pointsForAutomatic(wood), id, anchors, o);
  });
  if (ok)
    info("automatic below node " + std::to_string(id) + ": " + std::to_string(r.added.size()) + " nodes added (" +
         std::to_string(r.duplicates) + " repeats of existing nodes dropped, " + std::to_string(r.regionPoints) +
         " points)");
  return ok;
}

bool ViewerState::automaticInRegion(const std::vector<Vec2>& polygon) {
  if (cloud_.empty()) {
    error("automatic in region: open a point cloud first");
    return false;
  }
  edit::AutoHereResult r;
  const auto anchors = toEdit(anchorsForTools());
  bool ok = edit("automatic in region", "automatic in region", "", [&] {
    edit::AutoHereOptions o;
    o.skeleton = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOff, up_);
    geom::PointCloud wood;
    r = edit::automaticInRegion(sketch_, pointsForAutomatic(wood), view_.orbit_.camera(), polygon, anchors, o);
    if (tools_.active_ == kNoNode && !sketch_.empty()) tools_.active_ = sketch_.root();
  });
  if (ok)
    info("automatic in region: " + std::to_string(r.added.size()) + " nodes added (" + std::to_string(r.duplicates) +
         " repeats dropped, " + std::to_string(r.regionPoints) + " points)");
  return ok;
}

double ViewerState::selectedDepth() const {
  if (tools_.selected_ == kNoNode || !sketch_.contains(tools_.selected_))
    return std::numeric_limits<double>::quiet_NaN();
  NodeFitView f = recon_->nodeFit(tools_.selected_);
  if (f.status != NodeStatus::Fitted) return std::numeric_limits<double>::quiet_NaN();
  return (f.circle.centre - view_.orbit_.camera().eye()).norm();
}

// ---- input -----------------------------------------------------------------------------------------

bool ViewerState::toolMouseDown(const Vec2& pos, MouseButton button, int mods) {
  if (tools_.tool_ == Tool::Select || tools_.tool_ == Tool::AddNodes || button != MouseButton::Left || (mods & kModAlt))
    return false;
  tools_.gesture_ = Gesture::ToolPath;
  tools_.gestureNode_ = tools_.tool_ == Tool::Reattach ? scene_.nodeAt(pos) : kNoNode;
  tools_.toolPath_ = {pos};
  return true;
}

bool ViewerState::toolMouseUp(const Vec2& pos) {
  std::vector<Vec2> path = std::move(tools_.toolPath_);
  tools_.toolPath_.clear();
  if (path.empty() || path.back() != pos) path.push_back(pos);
  ++sceneVersion_;
  switch (tools_.tool_) {
    case Tool::Select:
    case Tool::AddNodes:
      return false;
    case Tool::Stroke:
      return strokeLimb(path);
    case Tool::Lasso:
      return lassoNotWood(path);
    case Tool::LassoWood:
      return lassoWood(path);
    case Tool::Region:
      return automaticInRegion(path);
    case Tool::Reattach:
      if (tools_.gestureNode_ == kNoNode) {
        error("re-attach: click on a node");
        return false;
      }
      // The first click in the tool names the node to move (whatever was selected before), the
      // second its new parent; Shift on the second turns the limb round.
      if (tools_.reattachSource_ == kNoNode || !sketch_.contains(tools_.reattachSource_) ||
          tools_.reattachSource_ == tools_.gestureNode_) {
        tools_.reattachSource_ = tools_.gestureNode_;
        selectNode(tools_.gestureNode_);
        info("re-attach: now click the new parent of node " + std::to_string(tools_.gestureNode_) +
             " (Shift+click: make node " + std::to_string(tools_.gestureNode_) +
             " the base of its limb, turned round)");
        return true;
      } else {
        const NodeId source = tools_.reattachSource_;
        tools_.reattachSource_ = kNoNode;
        return reattachNode(source, tools_.gestureNode_, tools_.gestureMods_ & kModShift);
      }
  }
  return false;
}

bool ViewerState::toolKey(const std::string& key, int mods) {
  if (mods & (kModCtrl | kModAlt)) return false;
  auto toggle = [&](Tool t) { setTool(tools_.tool_ == t ? Tool::Select : t); };
  if (key == "n") {
    toggle(Tool::AddNodes);
  } else if (key == "g") {
    toggle(Tool::Stroke);
  } else if (key == "x" && (mods & kModShift)) {  // Shift+X: the opposite lasso, points are wood
    toggle(Tool::LassoWood);
  } else if (key == "x") {  // X: cross points out as not-wood (L is the node labels)
    toggle(Tool::Lasso);
  } else if (key == "k") {
    startClassifyJob();
  } else if (key == "r") {
    toggle(Tool::Region);
  } else if (key == "p") {
    toggle(Tool::Reattach);
  } else if (key == "h") {
    if (tools_.selected_ == kNoNode) {
      error("automatic below: select a node first");
    } else {
      automaticBelow(tools_.selected_);
    }
  } else if (key == "escape" && tools_.tool_ != Tool::Select) {
    setTool(Tool::Select);
    return false;  // Escape also clears the selection, as before
  } else {
    return false;
  }
  return true;
}

}  // namespace treesketch::viewer
