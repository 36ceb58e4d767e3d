// ViewerState itself and its edit commands: construction, the cloud, the edit protocol (undo,
// rebuild, autosave) and every sketch action. See viewer_state.h for the map of the files that
// implement ViewerState and of the parts it is made of.
#include "treesketch/viewer/viewer_state.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <new>

#include "treesketch/edit/correction_tools.h"
#include "treesketch/io/file_info.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/sketch/auto_sketch.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"
#include "treesketch/viewer/picking.h"

namespace treesketch::viewer {

using geom::Vec2;
using geom::Vec3;

namespace {

/// A reconstruction that fits nothing (used when no factory can build one).
class NullReconstruction : public ViewerReconstruction {
 public:
  void update(const sketch::Sketch&) override {}
  NodeFitView nodeFit(NodeId) const override { return {}; }
  std::vector<std::uint32_t> slicePoints(NodeId) const override { return {}; }
  std::vector<std::uint32_t> inlierPoints(NodeId) const override { return {}; }
  const geom::TriMesh& mesh() const override { return mesh_; }

 private:
  geom::TriMesh mesh_;
};

}  // namespace

ViewerState::ViewerState(const ViewerOptions& options, ReconstructionFactory factory)
    : options_(options), factory_(std::move(factory)), status_(options.statusInfoSeconds), undo_(options.undoLimit) {
  if (!factory_) factory_ = [](const geom::PointCloud& c) { return makeDefaultReconstruction(c); };
  recon_ = std::make_unique<NullReconstruction>();
}

// ~ViewerState is in background_job.cpp, where the job it stops is a complete type.

bool ViewerState::runAction(const std::string& name, const std::function<void()>& action) {
  try {
    action();
    return true;
  } catch (const std::bad_alloc&) {
    error(name + ": out of memory");
  } catch (const std::exception& e) {
    error(name + ": " + e.what());
  } catch (...) {
    error(name + ": unknown error");
  }
  return false;
}

// ---- data ----------------------------------------------------------------------------------------

namespace {

/// Refuses a cloud nothing can be sketched on, before anything of the open one is replaced: the
/// view, the sampling sizes and every fit need an extent (a box under a micrometre, or under 1e-9
/// of its distance from the origin, where doubles no longer resolve it, is no extent).
void checkSketchable(const geom::PointCloud& cloud, const geom::BBox& box) {
  if (cloud.empty()) throw InputError("the point cloud is empty");
  const double d = box.diagonal();
  const double offset = box.empty() ? 0.0 : std::max(box.min.cwiseAbs().maxCoeff(), box.max.cwiseAbs().maxCoeff());
  if (box.empty() || !std::isfinite(d) || !std::isfinite(offset))
    throw InputError("the cloud's bounding box is not finite");
  if (!(d >= 1e-6) || !(d >= 1e-9 * offset)) {
    char text[200];
    std::snprintf(text, sizeof text, "the cloud has no extent to sketch on: its %zu points span %.3g (every point "
                  "at one place%s)", cloud.size(), d, d > 0 ? ", or the wrong units" : "");
    throw DegenerateInputError(text);
  }
}

}  // namespace

bool ViewerState::setCloud(geom::PointCloud cloud, geom::UpAxis up, const std::filesystem::path& sourcePath) {
  if (refuseWhileBusy("open")) return false;  // the job reads the cloud
  geom::BBox box;
  sketch::SamplingParams defaults;
  // Everything that can fail is done before the open cloud and sketch are touched.
  if (!runAction("open", [&] {
        box = cloud.bounds();
        checkSketchable(cloud, box);
        defaults = sketch::defaultSamplingFor(box);
      }))
    return false;
  closeSession();  // the previous cloud's autosave goes when it holds nothing unsaved
  return runAction("open", [&] {
    recon_ = std::make_unique<NullReconstruction>();
    cloud_ = std::move(cloud);
    ++cloudVersion_;
    up_ = up;
    view_.up_ = toUpDirection(up);
    sketch_ = sketch::Sketch{};
    sketch_.up = up;
    bounds_ = box;
    sketch_.defaults = defaults;
    undo_.clear();
    lastEditKey_.clear();
    tools_.selected_ = tools_.active_ = kNoNode;
    tools_.activeChosen_ = false;
    dirty_ = false;
    doc_.setCloud(sourcePath, cloud_);

    view_.orbit_.setSceneBounds(bounds_);
    view_.orbit_.preset(geom::PresetView::Front, upDirectionVector(view_.up_));
    scene_.colorsStale_ = true;
    classes_.reset();  // the classification was the previous cloud's
    ++classesVersion_;
    resetReconstruction();
    rebuild();
    info("opened " + (sourcePath.empty() ? std::string("cloud") : sourcePath.string()) + ": " +
         std::to_string(cloud_.size()) + " points, up " + toString(view_.up_));
    view_.upWarningDismissed_ = false;
    if (std::string w = lyingDownWarning(); !w.empty()) info("warning: " + w);
    // Last, so that the offer of an earlier autosave is the message shown.
    detectRecovery();
  });
}

void ViewerState::resetReconstruction() {
  try {
    recon_ = factory_(cloud_);
  } catch (const std::exception& e) {
    recon_.reset();
    error(std::string("reconstruction unavailable: ") + e.what());
  }
  if (!recon_) recon_ = std::make_unique<NullReconstruction>();
}

bool ViewerState::openFile(const std::filesystem::path& path, geom::UpAxis up, const ProgressFn& progress) {
  geom::PointCloud cloud;
  bool ok = runAction("open " + path.string(), [&] {
    io::FileInfo fileInfo = io::inspectFile(path);
    if (fileInfo.isMesh) {
      info("scanning mesh " + path.string() + " (" + std::to_string(fileInfo.mesh.triangles.size()) + " triangles)");
      scan::ScanResult scanned = scan::sphereScan(std::vector<geom::TriMesh>{fileInfo.mesh}, {}, progress);
      cloud = std::move(scanned.cloud);
      if (cloud.empty()) throw InputError(path.string() + ": the scan of this mesh hit nothing");
    } else {
      cloud = std::move(fileInfo.cloud);
    }
  });
  return ok && setCloud(std::move(cloud), up, path);
}

// ---- editing -------------------------------------------------------------------------------------

void ViewerState::endEdit() {
  dirty_ = true;
  untouchedAuto_ = false;  // the automatic sketches set it again after their edit
  fixSelection();
  rebuild();
  // A drag is one edit: it is saved once, when the button is released.
  if (tools_.gesture_ == Gesture::DragNode)
    autosavePending_ = true;
  else
    autosave();
}

void ViewerState::fixSelection() {
  if (tools_.selected_ != kNoNode && !sketch_.contains(tools_.selected_)) tools_.selected_ = kNoNode;
  if (tools_.active_ != kNoNode && !sketch_.contains(tools_.active_)) tools_.active_ = kNoNode;
  if (tools_.active_ == kNoNode) tools_.activeChosen_ = false;
  if (tools_.active_ == kNoNode && !sketch_.empty()) tools_.active_ = sketch_.root();
}

void ViewerState::rebuild() {
  const Stopwatch timer;
  runAction("rebuild", [&] { recon_->update(sketch_); });
  lastRebuildMs_ = timer.ms();
  ++sceneVersion_;
  if (view_.display_.colorMode == ColorMode::CircleDistance) scene_.colorsStale_ = true;
}

void ViewerState::autosave() {
  // An earlier session's autosave waits for the person's choice: never overwrite it before.
  if (doc_.autosavePath().empty() || doc_.recoveryPending()) return;
  // An empty sketch (undone or cleared to nothing) removes the autosave: nothing to bring back.
  runAction("autosave to " + doc_.autosavePath().string(), [&] { doc_.writeAutosave(sketch_); });
}

bool ViewerState::edit(const std::string& name, const std::string& label, const std::string& mergeKey,
                       const std::function<void()>& body) {
  if (refuseWhileBusy(name)) return false;
  sketch::Sketch before = sketch_;
  NodeId selBefore = tools_.selected_, actBefore = tools_.active_;
  if (!runAction(name, body)) {
    sketch_ = std::move(before);
    tools_.selected_ = selBefore;
    tools_.active_ = actBefore;
    return false;
  }
  if (mergeKey.empty() || mergeKey != lastEditKey_) undo_.push(before, label);
  lastEditKey_ = mergeKey;
  endEdit();
  return true;
}

bool ViewerState::addNodeAt(const Vec2& screen) {
  if (cloud_.empty()) {
    error("add node: open a point cloud first");
    return false;
  }
  std::string how;
  NodeId added = kNoNode, parent = kNoNode;
  const std::size_t errorsBefore = status_.errorCount();
  if (!view_.orbit_.viewport().contains(screen)) {
    error("add node: the point is outside the view");
    return false;
  }
  // A node's circle is fitted from the points along its view ray: where the ray meets none, the
  // node could only be skipped (or fit something far away), so nothing is added.
  if (!pickPoint(cloud_, view_.orbit_.camera(), screen, options_.pickRadiusPx).found) {
    info("add node: nothing added: the view ray there meets no points (none within " +
         std::to_string(static_cast<int>(options_.pickRadiusPx)) + " px of the click)");
    return false;
  }
  bool ok = edit("add node", "add node", "", [&] {
    if (!sketch_.empty()) {
      // A node the person made active is the parent (the thesis's chain of clicks). Without one
      // (after a load or an automatic sketch the active node is only the root by default), a click
      // that missed a marker in a dense skeleton means "here, next to that node": attach it to the
      // nearest marker, never silently to the root.
      if (tools_.activeChosen_ && tools_.active_ != kNoNode && sketch_.contains(tools_.active_)) {
        parent = tools_.active_;
      } else {
        parent = scene_.nearestMarker(screen);
        how = parent != kNoNode ? " (the nearest node; select a node to attach elsewhere)"
                                : " (the root: no node is visible in this view)";
        if (parent == kNoNode) parent = sketch_.root();
      }
    }
    int cam = sketch_.addCamera(view_.orbit_.camera());
    added = sketch_.addScreenNode(parent, cam, screen);
    tools_.selected_ = tools_.active_ = added;
  });
  if (ok) tools_.activeChosen_ = true;
  if (ok && status_.errorCount() == errorsBefore) {  // a rebuild error stays the message shown
    info(parent == kNoNode ? "added node " + std::to_string(added) + " (the root)"
                           : "added node " + std::to_string(added) + " under node " + std::to_string(parent) + how);
  }
  // Never a silent jump in depth: say where the circle went when it is not where the
  // parent (or the front-most surface) said it would be.
  if (ok && recon_->nodeFit(added).depthJump)
    info("warning: node " + std::to_string(added) + ": " + recon_->nodeFit(added).warning);
  return ok;
}

bool ViewerState::selectNode(NodeId id) {
  if (id == kNoNode) {
    tools_.selected_ = kNoNode;
    ++sceneVersion_;
    return true;
  }
  if (!sketch_.contains(id)) {
    error("select: no node " + std::to_string(id));
    return false;
  }
  tools_.selected_ = tools_.active_ = id;
  tools_.activeChosen_ = true;
  lastEditKey_.clear();
  ++sceneVersion_;
  return true;
}

bool ViewerState::setActiveNode(NodeId id) {
  if (!sketch_.contains(id)) {
    error("make active: no node " + std::to_string(id));
    return false;
  }
  tools_.active_ = id;
  tools_.activeChosen_ = true;
  ++sceneVersion_;
  return true;
}

Vec3 ViewerState::anchor(NodeId id) const {
  NodeFitView f = recon_->nodeFit(id);
  if (f.status == NodeStatus::Fitted) return f.circle.centre;
  sketch::NodeGeometry g = sketch_.geometry(id);
  if (!g.hasLine) return g.planePoint;
  Vec3 c = cloud_.empty() ? g.linePoint : bounds_.centre();
  return g.linePoint + (c - g.linePoint).dot(g.lineDir) * g.lineDir;
}

bool ViewerState::moveNodeTo(NodeId id, const Vec2& screen) { return moveNodeImpl(id, screen, ""); }

bool ViewerState::moveNodeImpl(NodeId id, const Vec2& screen, const std::string& key) {
  return edit("move node", "move node " + std::to_string(id), key, [&] {
    const sketch::Node& node = sketch_.node(id);
    geom::Camera cur = view_.orbit_.camera();
    if (node.isScreenNode() && sameAsCurrent(sketch_.cameras()[node.camera])) {
      sketch_.moveNode(id, screen);
    } else {
      // Keep the node's own camera: move its 3D anchor along the current view plane to the mouse,
      // then re-project it into the camera it was drawn under.
      Vec3 p = anchor(id);
      double depth = cur.project(p).z();
      Vec3 moved = cur.unproject(screen, depth);
      if (node.isScreenNode()) {
        Vec3 s = sketch_.cameras()[node.camera].project(moved);
        sketch_.moveNode(id, s.head<2>());
      } else {
        sketch_.movePointNode(id, moved, node.normal);
      }
    }
  });
}

bool ViewerState::deleteSelected(bool withSubtree) {
  if (tools_.selected_ == kNoNode) {
    error("delete: no node selected");
    return false;
  }
  NodeId id = tools_.selected_;
  if (withSubtree && !sketch_.node(id).children.empty()) return requestDeleteSubtree(id);
  return edit("delete node", std::string(withSubtree ? "delete subtree " : "delete node ") + std::to_string(id), "",
              [&] {
                NodeId parent = sketch_.node(id).parent;
                sketch_.removeNode(id, withSubtree);
                if (parent != kNoNode && sketch_.contains(parent)) {
                  tools_.selected_ = tools_.active_ = parent;
                } else {
                  tools_.selected_ = kNoNode;
                  tools_.active_ = sketch_.empty() ? kNoNode : sketch_.root();
                }
              });
}

sketch::SamplingParams ViewerState::paramsForEdit() const {
  if (tools_.selected_ != kNoNode && sketch_.contains(tools_.selected_)) return sketch_.node(tools_.selected_).params;
  return sketch_.defaults;
}

bool ViewerState::applyParams(const sketch::SamplingParams& params, const std::string& label, const std::string& key) {
  NodeId id = (tools_.selected_ != kNoNode && sketch_.contains(tools_.selected_)) ? tools_.selected_ : kNoNode;
  std::string fullKey = key + ":" + std::to_string(id);
  return edit(label, label + (id == kNoNode ? " (new nodes)" : " of node " + std::to_string(id)), fullKey, [&] {
    if (id == kNoNode)
      sketch_.defaults = params;
    else
      sketch_.setParams(id, params);
  });
}

bool ViewerState::setSamplingSize(double sketch::SamplingParams::*size, double value, const std::string& name,
                                  const std::string& key) {
  if (!(value > 0) || !std::isfinite(value)) {
    error(name + " must be a positive number");
    return false;
  }
  sketch::SamplingParams p = paramsForEdit();
  p.*size = value;
  return applyParams(p, "set " + name, key);
}

bool ViewerState::setSliceHalfThickness(double value) {
  return setSamplingSize(&sketch::SamplingParams::sliceHalfThickness, value, "slice half-thickness", "slice");
}

bool ViewerState::setLineEpsilon(double value) {
  return setSamplingSize(&sketch::SamplingParams::lineEpsilon, value, "lineEpsilon", "lineEpsilon");
}

bool ViewerState::setNodeEnabled(bool enabled) {
  sketch::SamplingParams p = paramsForEdit();
  p.enabled = enabled;
  return applyParams(p, enabled ? "enable node" : "disable node", "enabled");
}

bool ViewerState::undo() {
  if (refuseWhileBusy("undo")) return false;
  if (!undo_.canUndo()) {
    info("nothing to undo");
    return false;
  }
  std::string label = undo_.undo(sketch_);
  lastEditKey_.clear();
  endEdit();
  info("undo: " + label);
  return true;
}

bool ViewerState::redo() {
  if (refuseWhileBusy("redo")) return false;
  if (!undo_.canRedo()) {
    info("nothing to redo");
    return false;
  }
  std::string label = undo_.redo(sketch_);
  lastEditKey_.clear();
  endEdit();
  info("redo: " + label);
  return true;
}

bool ViewerState::clearSketch() {
  return edit("clear sketch", "clear sketch", "", [&] {
    sketch::Sketch fresh;
    fresh.up = sketch_.up;
    fresh.defaults = sketch_.defaults;
    sketch_ = std::move(fresh);
    tools_.selected_ = tools_.active_ = kNoNode;
    tools_.activeChosen_ = false;
  });
}

bool ViewerState::autoSketchUniform(int nodes) {
  if (cloud_.empty()) {
    error("automatic sketch: open a point cloud first");
    return false;
  }
  if (!libraryUpAxis(view_.up_)) {
    error(std::string("automatic sketch: needs up +y or +z (the view's up is ") + toString(view_.up_) + ")");
    return false;
  }
  bool ok = edit("automatic sketch", "uniform automatic sketch", "", [&] {
    sketch::Sketch uniform = sketch::uniformAutoSketch(cloud_, view_.orbit_.camera(), nodes, up_);
    edit::copyNotWood(sketch_, uniform);  // the person's lassos stay
    sketch_ = std::move(uniform);
    tools_.selected_ = kNoNode;
    std::vector<NodeId> order = sketch_.topologicalOrder();
    tools_.active_ = order.empty() ? kNoNode : order.back();
  });
  if (ok) untouchedAuto_ = true, tools_.activeChosen_ = false;
  return ok;
}

bool ViewerState::askBeforeReplacing(const std::string& question, std::function<bool()> action) {
  if (!hasHandEdits()) return action();
  return ask(question, std::move(action));
}

bool ViewerState::ask(const std::string& question, std::function<bool()> action) {
  pendingQuestion_ = question;
  pendingAction_ = std::move(action);
  info(question);
  return false;
}

bool ViewerState::answerConfirmation(bool yes) {
  if (!pendingAction_) {
    error("confirm: no question is waiting");
    return false;
  }
  std::function<bool()> action = std::move(pendingAction_);
  pendingAction_ = nullptr;
  pendingQuestion_.clear();
  if (pendingDelete_ != kNoNode) pendingDelete_ = kNoNode, ++sceneVersion_;  // the highlight goes
  if (!yes) {
    info("kept the sketch (" + std::to_string(sketch_.size()) + " nodes)");
    return false;
  }
  return action();
}

bool ViewerState::requestAutoSketchUniform(int nodes) {
  return askBeforeReplacing("Replace the sketch (" + std::to_string(sketch_.size()) +
                                " nodes, with hand edits) by a uniform automatic sketch? (undoable)",
                            [this, nodes] { return autoSketchUniform(nodes); });
}

bool ViewerState::requestAutoSketchSkeleton(bool leafOn) {
  return askBeforeReplacing("Replace the sketch (" + std::to_string(sketch_.size()) +
                                " nodes, with hand edits) by the automatic skeleton? (undoable)",
                            [this, leafOn] { return startAutoSkeletonJob(leafOn); });
}

bool ViewerState::autoSketchSkeleton(bool leafOn) {
  if (cloud_.empty()) {
    error("automatic skeleton sketch: open a point cloud first");
    return false;
  }
  if (!libraryUpAxis(view_.up_)) {
    error(std::string("automatic skeleton sketch: needs up +y or +z (the view's up is ") + toString(view_.up_) + ")");
    return false;
  }
  bool ok = edit("automatic skeleton sketch", "automatic skeleton sketch", "", [&] {
    const skeleton::AutoSkeletonOptions options =
        skeleton::autoSkeletonPreset(leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, up_);
    // The not-wood lassos are honoured (the skeleton never sees their points) and kept.
    geom::PointCloud wood;
    if (!sketch_.notWood().empty()) wood = edit::woodOnly(cloud_, sketch_);
    skeleton::AutoSkeletonResult result =
        skeleton::autoSkeletonSketch(sketch_.notWood().empty() ? cloud_ : wood, options);
    if (result.sketch.empty()) throw OptionsError("no skeleton found in this cloud");
    edit::copyNotWood(sketch_, result.sketch);
    sketch_ = std::move(result.sketch);
    tools_.selected_ = kNoNode;
    tools_.active_ = sketch_.root();
    info("automatic skeleton sketch: " + std::to_string(sketch_.size()) +
         " nodes keep the automatic model's circles "
         "(edit a node, or Refit, to fit it from the cloud)");
  });
  if (ok) untouchedAuto_ = true, tools_.activeChosen_ = false;
  return ok;
}

bool ViewerState::refitSelected() {
  if (tools_.selected_ == kNoNode || !sketch_.contains(tools_.selected_)) {
    error("refit: select a node first");
    return false;
  }
  if (!sketch_.node(tools_.selected_).kept) {
    info("refit: node " + std::to_string(tools_.selected_) + " is fitted from the cloud already");
    return false;
  }
  const NodeId id = tools_.selected_;
  return edit("refit node", "refit node " + std::to_string(id), "", [&] { sketch_.setKeptCircle(id, std::nullopt); });
}

bool ViewerState::refitAll() {
  if (sketch_.keptCircleCount() == 0) {
    info("refit all: no node keeps a circle; every node is fitted from the cloud already");
    return false;
  }
  return edit("refit all", "refit all nodes", "", [&] { sketch_.clearKeptCircles(); });
}

}  // namespace treesketch::viewer
