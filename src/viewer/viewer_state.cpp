// ViewerState, part 1 of 3: the state itself and its edit commands — construction, the cloud,
// the edit protocol (undo, rebuild, autosave) and every sketch action, save/load/export.
// Input handling (mouse, wheel, keys, the view they steer) is in viewer_input.cpp; what is drawn
// (colours, markers, lines, status messages) in viewer_draw.cpp.
#include "treesketch/viewer/viewer_state.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <new>

#include "treesketch/io/file_info.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/sketch/auto_sketch.h"
#include "treesketch/util/error.h"

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
    : options_(options), factory_(std::move(factory)), undo_(options.undoLimit) {
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

bool ViewerState::setCloud(geom::PointCloud cloud, geom::UpAxis up, const std::filesystem::path& sourcePath) {
  if (refuseWhileBusy("open")) return false;  // the job reads the cloud
  return runAction("open", [&] {
    if (cloud.empty()) throw InputError("the point cloud is empty");
    recon_.reset();
    cloud_ = std::move(cloud);
    ++cloudVersion_;
    up_ = up;
    viewUp_ = toUpDirection(up);
    sourcePath_ = sourcePath;
    sketch_ = sketch::Sketch{};
    sketch_.up = up;
    bounds_ = cloud_.bounds();
    sketch_.defaults = sketch::defaultSamplingFor(bounds_);
    undo_.clear();
    lastEditKey_.clear();
    selected_ = active_ = kNoNode;
    activeChosen_ = false;
    dirty_ = false;

    orbit_.setSceneBounds(bounds_);
    orbit_.preset(geom::PresetView::Front, upDirectionVector(viewUp_));
    colorsStale_ = true;
    resetReconstruction();
    rebuild();
    info("opened " + (sourcePath.empty() ? std::string("cloud") : sourcePath.string()) + ": " +
         std::to_string(cloud_.size()) + " points, up " + toString(viewUp_));
    upWarningDismissed_ = false;
    if (std::string w = lyingDownWarning(); !w.empty()) info("warning: " + w);
    // The whole file name, not the stem: tree.las and tree.xyz in one folder are two clouds. Set
    // last, so that the offer of an earlier autosave is the message shown.
    if (!sourcePath.empty())
      setAutosavePath(sourcePath.parent_path() / (sourcePath.filename().string() + ".autosave.sketch.json"));
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
  if (gesture_ == Gesture::DragNode)
    autosavePending_ = true;
  else
    autosave();
}

void ViewerState::fixSelection() {
  if (selected_ != kNoNode && !sketch_.contains(selected_)) selected_ = kNoNode;
  if (active_ != kNoNode && !sketch_.contains(active_)) active_ = kNoNode;
  if (active_ == kNoNode) activeChosen_ = false;
  if (active_ == kNoNode && !sketch_.empty()) active_ = sketch_.root();
}

void ViewerState::rebuild() {
  auto t0 = std::chrono::steady_clock::now();
  runAction("rebuild", [&] { recon_->update(sketch_); });
  lastRebuildMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ++sceneVersion_;
  if (display_.colorMode == ColorMode::CircleDistance) colorsStale_ = true;
}

void ViewerState::autosave() {
  // An earlier session's autosave waits for the person's choice: never overwrite it before.
  if (autosavePath_.empty() || recoveryPending_) return;
  runAction("autosave to " + autosavePath_.string(), [&] {
    if (sketch_.empty()) {
      // An empty sketch cannot be a valid sketch file; keep the last saved work instead.
      return;
    }
    io::writeSketch(autosavePath_, sketch_);
  });
}

bool ViewerState::edit(const std::string& name, const std::string& label, const std::string& mergeKey,
                       const std::function<void()>& body) {
  if (refuseWhileBusy(name)) return false;
  sketch::Sketch before = sketch_;
  NodeId selBefore = selected_, actBefore = active_;
  if (!runAction(name, body)) {
    sketch_ = std::move(before);
    selected_ = selBefore;
    active_ = actBefore;
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
  const std::size_t errorsBefore = errorCount_;
  bool ok = edit("add node", "add node", "", [&] {
    if (!orbit_.viewport().contains(screen)) throw OptionsError("the point is outside the view");
    if (!sketch_.empty()) {
      // A node the person made active is the parent (the thesis's chain of clicks). Without one
      // (after a load or an automatic sketch the active node is only the root by default), a click
      // that missed a marker in a dense skeleton means "here, next to that node": attach it to the
      // nearest marker, never silently to the root.
      if (activeChosen_ && active_ != kNoNode && sketch_.contains(active_)) {
        parent = active_;
      } else {
        parent = nearestMarker(screen);
        how = parent != kNoNode ? " (the nearest node; select a node to attach elsewhere)"
                                : " (the root: no node is visible in this view)";
        if (parent == kNoNode) parent = sketch_.root();
      }
    }
    int cam = sketch_.addCamera(orbit_.camera());
    added = sketch_.addScreenNode(parent, cam, screen);
    selected_ = active_ = added;
  });
  if (ok) activeChosen_ = true;
  if (ok && errorCount_ == errorsBefore) {  // a rebuild error stays the message shown
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
    selected_ = kNoNode;
    ++sceneVersion_;
    return true;
  }
  if (!sketch_.contains(id)) {
    error("select: no node " + std::to_string(id));
    return false;
  }
  selected_ = active_ = id;
  activeChosen_ = true;
  lastEditKey_.clear();
  ++sceneVersion_;
  return true;
}

bool ViewerState::setActiveNode(NodeId id) {
  if (!sketch_.contains(id)) {
    error("make active: no node " + std::to_string(id));
    return false;
  }
  active_ = id;
  activeChosen_ = true;
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
    geom::Camera cur = orbit_.camera();
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
  if (selected_ == kNoNode) {
    error("delete: no node selected");
    return false;
  }
  NodeId id = selected_;
  return edit("delete node", std::string(withSubtree ? "delete subtree " : "delete node ") + std::to_string(id), "",
              [&] {
                NodeId parent = sketch_.node(id).parent;
                sketch_.removeNode(id, withSubtree);
                if (parent != kNoNode && sketch_.contains(parent)) {
                  selected_ = active_ = parent;
                } else {
                  selected_ = kNoNode;
                  active_ = sketch_.empty() ? kNoNode : sketch_.root();
                }
              });
}

sketch::SamplingParams ViewerState::paramsForEdit() const {
  if (selected_ != kNoNode && sketch_.contains(selected_)) return sketch_.node(selected_).params;
  return sketch_.defaults;
}

bool ViewerState::applyParams(const sketch::SamplingParams& params, const std::string& label, const std::string& key) {
  NodeId id = (selected_ != kNoNode && sketch_.contains(selected_)) ? selected_ : kNoNode;
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
    selected_ = active_ = kNoNode;
    activeChosen_ = false;
  });
}

bool ViewerState::autoSketchUniform(int nodes) {
  if (cloud_.empty()) {
    error("automatic sketch: open a point cloud first");
    return false;
  }
  if (!libraryUpAxis(viewUp_)) {
    error(std::string("automatic sketch: needs up +y or +z (the view's up is ") + toString(viewUp_) + ")");
    return false;
  }
  bool ok = edit("automatic sketch", "uniform automatic sketch", "", [&] {
    sketch_ = sketch::uniformAutoSketch(cloud_, orbit_.camera(), nodes, up_);
    selected_ = kNoNode;
    std::vector<NodeId> order = sketch_.topologicalOrder();
    active_ = order.empty() ? kNoNode : order.back();
  });
  if (ok) untouchedAuto_ = true, activeChosen_ = false;
  return ok;
}

bool ViewerState::askBeforeReplacing(const std::string& question, std::function<bool()> action) {
  if (!hasHandEdits()) return action();
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
  if (!libraryUpAxis(viewUp_)) {
    error(std::string("automatic skeleton sketch: needs up +y or +z (the view's up is ") + toString(viewUp_) + ")");
    return false;
  }
  bool ok = edit("automatic skeleton sketch", "automatic skeleton sketch", "", [&] {
    const skeleton::AutoSkeletonOptions options =
        skeleton::autoSkeletonPreset(leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, up_);
    skeleton::AutoSkeletonResult result = skeleton::autoSkeletonSketch(cloud_, options);
    if (result.sketch.empty()) throw OptionsError("no skeleton found in this cloud");
    sketch_ = std::move(result.sketch);
    selected_ = kNoNode;
    active_ = sketch_.root();
    info("automatic skeleton sketch: " + std::to_string(sketch_.size()) +
         " nodes keep the automatic model's circles "
         "(edit a node, or Refit, to fit it from the cloud)");
  });
  if (ok) untouchedAuto_ = true, activeChosen_ = false;
  return ok;
}

bool ViewerState::refitSelected() {
  if (selected_ == kNoNode || !sketch_.contains(selected_)) {
    error("refit: select a node first");
    return false;
  }
  if (!sketch_.node(selected_).kept) {
    info("refit: node " + std::to_string(selected_) + " is fitted from the cloud already");
    return false;
  }
  const NodeId id = selected_;
  return edit("refit node", "refit node " + std::to_string(id), "", [&] { sketch_.setKeptCircle(id, std::nullopt); });
}

bool ViewerState::refitAll() {
  if (sketch_.keptCircleCount() == 0) {
    info("refit all: no node keeps a circle; every node is fitted from the cloud already");
    return false;
  }
  return edit("refit all", "refit all nodes", "", [&] { sketch_.clearKeptCircles(); });
}

bool ViewerState::saveSketch(const std::filesystem::path& path) {
  return runAction("save sketch", [&] {
    if (sketch_.empty()) throw OptionsError("the sketch is empty: nothing to save");
    io::writeSketch(path, sketch_);
    dirty_ = false;
    info("saved sketch to " + path.string() + " (" + std::to_string(sketch_.size()) + " nodes)");
  });
}

bool ViewerState::loadSketch(const std::filesystem::path& path) {
  sketch::Sketch loaded;
  if (!runAction("load sketch", [&] { loaded = io::readSketch(path); })) return false;
  bool ok = edit("load sketch", "load sketch " + path.filename().string(), "", [&] {
    sketch_ = std::move(loaded);
    selected_ = kNoNode;
    active_ = kNoNode;
  });
  if (ok) dirty_ = false, activeChosen_ = false;
  if (ok) info("loaded sketch " + path.string() + " (" + std::to_string(sketch_.size()) + " nodes)");
  return ok;
}

bool ViewerState::exportMesh(const std::filesystem::path& path) { return exportModel(ModelFile::Mesh, path); }

bool ViewerState::exportModel(ModelFile what, const std::filesystem::path& path, double unitMetres) {
  static constexpr const char* kNames[] = {"mesh", "cylinder table", "TreeQSM table", "metrics", "report"};
  const char* name = kNames[static_cast<int>(what)];
  return runAction(std::string("export ") + name, [&] {
    if (!recon_) throw OptionsError("no cloud is open");
    if (what == ModelFile::Mesh ? recon_->mesh().empty() : false)
      throw OptionsError("no mesh to export: no node has been fitted yet");
    const model::TreeModel tree = model::fromReconstruction(recon_->result(), sketch_.up);
    if (what != ModelFile::Mesh && tree.empty())
      throw OptionsError(std::string("no ") + name + " to export: no two linked nodes are fitted yet");
    model::OutputPaths out;
    std::string* target[] = {&out.mesh, &out.cylinders, &out.qsm, &out.metrics, &out.report};
    *target[static_cast<int>(what)] = path.string();
    model::checkOutputs(out, {sourcePath_.string()});
    model::MeasureOptions mo;
    mo.unitMetres = unitMetres;
    mo.fit = what == ModelFile::Report;
    const bool measured = what == ModelFile::Metrics || what == ModelFile::Report;
    const model::ModelMeasures m = measured ? model::measure(tree, cloud_, mo) : model::ModelMeasures{};
    nlohmann::json header;
    header["cloud"] = sourcePath_.string();
    header["sketch"] = sketchPath_.string();
    header["nodes"] = sketch_.size();
    model::writeOutputs(tree, m, out, header);
    info("exported " + std::string(name) + " to " + path.string() +
         (what == ModelFile::Mesh ? " (" + std::to_string(tree.mesh.triangles.size()) + " triangles)"
                                  : " (" + std::to_string(tree.cylinders.size()) + " cylinders)"));
  });
}

}  // namespace treesketch::viewer
