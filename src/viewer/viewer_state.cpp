#include "treesketch/viewer/viewer_state.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <limits>
#include <new>

#include "treesketch/io/file_info.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/sketch/auto_sketch.h"
#include "treesketch/util/error.h"

namespace treesketch::viewer {

using geom::Vec2;
using geom::Vec3;
using sketch::kNoNode;
using sketch::NodeId;

namespace {

constexpr Rgb kCircleColor = {255, 150, 30};
constexpr Rgb kSelectedCircleColor = {255, 50, 50};
constexpr Rgb kSlabColor = {40, 200, 255};
constexpr Rgb kCylinderColor = {255, 60, 255};

bool sameMatrix(const geom::Mat4& a, const geom::Mat4& b) {
  double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return (a - b).cwiseAbs().maxCoeff() <= 1e-12 * std::max(scale, 1.0);
}

/// Appends a polyline ring (circle of `radius` around `centre` in the plane of unit `normal`).
void addRing(std::vector<Line3>& out, const Vec3& centre, const Vec3& normal, double radius, int segments,
             const Rgb& color) {
  Vec3 u = geom::anyPerpendicular(normal);
  Vec3 v = normal.normalized().cross(u);
  segments = std::max(segments, 3);
  Vec3 prev = centre + radius * u;
  for (int i = 1; i <= segments; ++i) {
    double a = 2.0 * M_PI * i / segments;
    Vec3 p = centre + radius * (std::cos(a) * u + std::sin(a) * v);
    out.push_back(Line3{prev, p, color});
    prev = p;
  }
}

/// The parameter range [t0, t1] where the line p + t d passes through `box` grown by `margin`;
/// false when it misses.
bool clipLineToBox(const Vec3& p, const Vec3& d, const geom::BBox& box, double margin, double* t0, double* t1) {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    double mn = box.min[k] - margin, mx = box.max[k] + margin;
    if (std::abs(d[k]) < 1e-15) {
      if (p[k] < mn || p[k] > mx) return false;
      continue;
    }
    double a = (mn - p[k]) / d[k], b = (mx - p[k]) / d[k];
    lo = std::max(lo, std::min(a, b));
    hi = std::min(hi, std::max(a, b));
  }
  if (!(lo <= hi)) return false;
  *t0 = lo;
  *t1 = hi;
  return true;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

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

ColorMode parseColorMode(const std::string& s) {
  std::string k = lower(s);
  if (k == "height") return ColorMode::Height;
  if (k == "distance" || k == "circle-distance") return ColorMode::CircleDistance;
  if (k == "plain") return ColorMode::Plain;
  throw OptionsError("colour mode must be 'height', 'distance' or 'plain', got '" + s + "'");
}

MeshStyle parseMeshStyle(const std::string& s) {
  std::string k = lower(s);
  if (k == "solid") return MeshStyle::Solid;
  if (k == "wireframe") return MeshStyle::Wireframe;
  if (k == "hidden") return MeshStyle::Hidden;
  throw OptionsError("mesh style must be 'solid', 'wireframe' or 'hidden', got '" + s + "'");
}

const char* toString(ColorMode mode) {
  switch (mode) {
    case ColorMode::Height:
      return "height";
    case ColorMode::CircleDistance:
      return "distance";
    case ColorMode::Plain:
      return "plain";
  }
  return "?";
}

const char* toString(MeshStyle style) {
  switch (style) {
    case MeshStyle::Solid:
      return "solid";
    case MeshStyle::Wireframe:
      return "wireframe";
    case MeshStyle::Hidden:
      return "hidden";
  }
  return "?";
}

const char* toString(NodeStatus status) {
  switch (status) {
    case NodeStatus::Pending:
      return "pending";
    case NodeStatus::Fitted:
      return "fitted";
    case NodeStatus::Skipped:
      return "skipped";
  }
  return "?";
}

ViewerState::ViewerState(const ViewerOptions& options, ReconstructionFactory factory)
    : options_(options), factory_(std::move(factory)), undo_(options.undoLimit) {
  if (!factory_) factory_ = [](const geom::PointCloud& c) { return makeDefaultReconstruction(c); };
  recon_ = std::make_unique<NullReconstruction>();
}

ViewerState::~ViewerState() = default;

// ---- status --------------------------------------------------------------------------------------

void ViewerState::info(const std::string& text) { messages_.push_back(StatusMessage{false, text}); }

void ViewerState::error(const std::string& text) {
  messages_.push_back(StatusMessage{true, text});
  ++errorCount_;
}

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
  return runAction("open", [&] {
    if (cloud.empty()) throw InputError("the point cloud is empty");
    recon_.reset();
    cloud_ = std::move(cloud);
    ++cloudVersion_;
    up_ = up;
    sourcePath_ = sourcePath;
    sketch_ = sketch::Sketch{};
    sketch_.up = up;
    bounds_ = cloud_.bounds();
    sketch_.defaults = sketch::defaultSamplingFor(bounds_);
    undo_.clear();
    lastEditKey_.clear();
    selected_ = active_ = kNoNode;
    if (!sourcePath.empty()) {
      autosavePath_ = sourcePath.parent_path() / (sourcePath.stem().string() + ".autosave.sketch.json");
    }
    orbit_.setSceneBounds(bounds_);
    orbit_.preset(geom::PresetView::Front, up_);
    colorsStale_ = true;
    resetReconstruction();
    rebuild();
    info("opened " + (sourcePath.empty() ? std::string("cloud") : sourcePath.string()) + ": " +
         std::to_string(cloud_.size()) + " points");
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

// ---- view ----------------------------------------------------------------------------------------

void ViewerState::setViewport(const geom::Viewport& viewport) { orbit_.setViewport(viewport); }

void ViewerState::fitView() { orbit_.fit(); }

void ViewerState::presetView(geom::PresetView view) { orbit_.preset(view, up_); }

void ViewerState::setOrthographic(bool ortho) { orbit_.setOrthographic(ortho); }

void ViewerState::setColorMode(ColorMode mode) { display_.colorMode = mode; }

bool ViewerState::sameAsCurrent(const geom::Camera& cam) const {
  geom::Camera cur = orbit_.camera();
  return sameMatrix(cam.view, cur.view) && sameMatrix(cam.projection, cur.projection) &&
         cam.viewport.x == cur.viewport.x && cam.viewport.y == cur.viewport.y &&
         cam.viewport.width == cur.viewport.width && cam.viewport.height == cur.viewport.height;
}

// ---- editing -------------------------------------------------------------------------------------

void ViewerState::endEdit() {
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
  if (autosavePath_.empty()) return;
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
  return edit("add node", "add node", "", [&] {
    const geom::Viewport& vp = orbit_.viewport();
    if (screen.x() < vp.x || screen.y() < vp.y || screen.x() > vp.x + vp.width || screen.y() > vp.y + vp.height)
      throw OptionsError("the point is outside the view");
    NodeId parent = kNoNode;
    if (!sketch_.empty()) parent = (active_ != kNoNode && sketch_.contains(active_)) ? active_ : sketch_.root();
    int cam = sketch_.addCamera(orbit_.camera());
    NodeId id = sketch_.addScreenNode(parent, cam, screen);
    selected_ = active_ = id;
  });
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
  ++sceneVersion_;
  return true;
}

Vec3 ViewerState::anchor(NodeId id) const {
  NodeFitView f = recon_->nodeFit(id);
  if (f.status == NodeStatus::Fitted) return f.circle.centre;
  sketch::NodeGeometry g = sketch_.geometry(id);
  if (!g.hasLine) return g.planePoint;
  Vec3 c = cloud_.empty() ? g.linePoint : bounds_.center();
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

bool ViewerState::setSliceHalfThickness(double value) {
  if (!(value > 0) || !std::isfinite(value)) {
    error("slice half-thickness must be a positive number");
    return false;
  }
  sketch::SamplingParams p = paramsForEdit();
  p.sliceHalfThickness = value;
  return applyParams(p, "set slice half-thickness", "slice");
}

bool ViewerState::setLineEpsilon(double value) {
  if (!(value > 0) || !std::isfinite(value)) {
    error("lineEpsilon must be a positive number");
    return false;
  }
  sketch::SamplingParams p = paramsForEdit();
  p.lineEpsilon = value;
  return applyParams(p, "set lineEpsilon", "lineEpsilon");
}

bool ViewerState::setNodeEnabled(bool enabled) {
  sketch::SamplingParams p = paramsForEdit();
  p.enabled = enabled;
  return applyParams(p, enabled ? "enable node" : "disable node", "enabled");
}

bool ViewerState::undo() {
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
  });
}

bool ViewerState::autoSketchUniform(int nodes) {
  if (cloud_.empty()) {
    error("automatic sketch: open a point cloud first");
    return false;
  }
  return edit("automatic sketch", "uniform automatic sketch", "", [&] {
    sketch_ = sketch::uniformAutoSketch(cloud_, orbit_.camera(), nodes, up_);
    selected_ = kNoNode;
    std::vector<NodeId> order = sketch_.topologicalOrder();
    active_ = order.empty() ? kNoNode : order.back();
  });
}

bool ViewerState::autoSketchSkeleton(bool leafOn) {
  if (cloud_.empty()) {
    error("automatic skeleton sketch: open a point cloud first");
    return false;
  }
  return edit("automatic skeleton sketch", "automatic skeleton sketch", "", [&] {
    skeleton::AutoSkeletonOptions options;
    if (leafOn) options.skeleton = skeleton::leafOnSkeletonOptions();
    options.skeleton.up = up_;
    skeleton::AutoSkeletonResult result = skeleton::autoSkeletonSketch(cloud_, options);
    if (result.sketch.empty()) throw OptionsError("no skeleton found in this cloud");
    sketch_ = std::move(result.sketch);
    selected_ = kNoNode;
    active_ = sketch_.root();
    info("automatic skeleton sketch: " + std::to_string(sketch_.size()) +
         " nodes keep the automatic model's circles "
         "(edit a node, or Refit, to fit it from the cloud)");
  });
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
  if (ok) info("loaded sketch " + path.string() + " (" + std::to_string(sketch_.size()) + " nodes)");
  return ok;
}

bool ViewerState::exportMesh(const std::filesystem::path& path) {
  return runAction("export mesh", [&] {
    const geom::TriMesh& m = recon_->mesh();
    if (m.empty()) throw OptionsError("no mesh to export: no node has been fitted yet");
    io::writeMesh(path, m);
    info("exported mesh to " + path.string() + " (" + std::to_string(m.triangles.size()) + " triangles)");
  });
}

// ---- input ---------------------------------------------------------------------------------------

void ViewerState::mouseDown(const Vec2& pos, MouseButton button, int mods) {
  const geom::Viewport& vp = orbit_.viewport();
  gesture_ = Gesture::None;
  if (pos.x() < vp.x || pos.y() < vp.y || pos.x() > vp.x + vp.width || pos.y() > vp.y + vp.height) return;
  pressPos_ = lastPos_ = pos;
  gestureButton_ = button;
  gestureMods_ = mods;
  if (button == MouseButton::Left && !(mods & kModAlt)) {
    gestureNode_ = nodeAt(pos);
    gesture_ = gestureNode_ != kNoNode ? Gesture::PendingNode : Gesture::PendingAdd;
  } else if ((button == MouseButton::Right && !(mods & kModShift)) || button == MouseButton::Left) {
    gesture_ = Gesture::Orbit;
  } else {
    gesture_ = Gesture::Pan;
  }
}

void ViewerState::mouseMove(const Vec2& pos) {
  switch (gesture_) {
    case Gesture::PendingNode:
      if ((pos - pressPos_).norm() < options_.dragThresholdPx) break;
      gesture_ = Gesture::DragNode;
      ++dragSerial_;
      selected_ = active_ = gestureNode_;
      [[fallthrough]];
    case Gesture::DragNode:
      moveNodeImpl(gestureNode_, pos, "drag:" + std::to_string(dragSerial_));
      break;
    case Gesture::Orbit:
      orbit_.rotate(lastPos_, pos);
      ++sceneVersion_;
      break;
    case Gesture::Pan:
      orbit_.pan(pos - lastPos_);
      ++sceneVersion_;
      break;
    default:
      break;
  }
  lastPos_ = pos;
}

void ViewerState::mouseUp(const Vec2& pos, MouseButton button, int mods) {
  (void)mods;
  if (gesture_ == Gesture::None || button != gestureButton_) return;
  if (pos != lastPos_) mouseMove(pos);
  Gesture g = gesture_;
  gesture_ = Gesture::None;
  if (g == Gesture::PendingNode) {
    if (gestureMods_ & kModCtrl) {
      // Ctrl+click: inspect a node without changing where new nodes attach.
      selected_ = gestureNode_;
      ++sceneVersion_;
    } else {
      selectNode(gestureNode_);
    }
  } else if (g == Gesture::PendingAdd) {
    if ((pos - pressPos_).norm() < options_.dragThresholdPx) addNodeAt(pos);
  } else if (g == Gesture::DragNode) {
    lastEditKey_.clear();
    if (autosavePending_) {
      autosavePending_ = false;
      autosave();
    }
  }
}

void ViewerState::scroll(double steps) {
  orbit_.zoom(steps);
  ++sceneVersion_;
}

void ViewerState::clickAt(const Vec2& pos, MouseButton button, int mods) {
  mouseDown(pos, button, mods);
  mouseUp(pos, button, mods);
}

void ViewerState::dragTo(const Vec2& from, const Vec2& to, MouseButton button, int mods, int steps) {
  steps = std::max(steps, 1);
  mouseDown(from, button, mods);
  for (int i = 1; i <= steps; ++i) mouseMove(from + (to - from) * (double(i) / steps));
  mouseUp(to, button, mods);
}

bool ViewerState::keyPress(const std::string& keyName, int mods) {
  std::string key = lower(keyName);
  for (;;) {
    if (key.rfind("ctrl+", 0) == 0)
      mods |= kModCtrl, key = key.substr(5);
    else if (key.rfind("shift+", 0) == 0)
      mods |= kModShift, key = key.substr(6);
    else if (key.rfind("alt+", 0) == 0)
      mods |= kModAlt, key = key.substr(4);
    else
      break;
  }
  bool ctrl = mods & kModCtrl, shift = mods & kModShift;
  if (key == "delete" || key == "backspace") {
    deleteSelected(shift);
  } else if (key == "z" && ctrl) {
    if (shift)
      redo();
    else
      undo();
  } else if (key == "y" && ctrl) {
    redo();
  } else if (key == "s" && ctrl) {
    if (sketchPath_.empty())
      error("save: no sketch path (type one in the panel and use Save)");
    else
      saveSketch(sketchPath_);
  } else if (key == "escape") {
    selectNode(kNoNode);
  } else if (key == "f") {
    fitView();
  } else if (key == "o") {
    setOrthographic(!orbit_.orthographic());
  } else if (key == "1") {
    presetView(geom::PresetView::Front);
  } else if (key == "2") {
    presetView(geom::PresetView::Side);
  } else if (key == "3") {
    presetView(geom::PresetView::Top);
  } else if (key == "a") {
    autoSketchUniform();
  } else if (key == "w") {
    display_.meshStyle = static_cast<MeshStyle>((static_cast<int>(display_.meshStyle) + 1) % 3);
  } else if (key == "c") {
    display_.colorMode = static_cast<ColorMode>((static_cast<int>(display_.colorMode) + 1) % 3);
  } else {
    return false;
  }
  return true;
}

// ---- what to draw --------------------------------------------------------------------------------

const std::vector<Rgb>& ViewerState::pointColors() {
  if (colorsStale_ || colorsMode_ != display_.colorMode || colors_.size() != cloud_.size()) {
    colorsMode_ = display_.colorMode;
    switch (colorsMode_) {
      case ColorMode::Height:
        colors_ = heightColors(cloud_, up_);
        break;
      case ColorMode::Plain:
        colors_ = plainColors(cloud_, options_.plainColor);
        break;
      case ColorMode::CircleDistance: {
        std::vector<Circle3> circles;
        for (NodeId id : sketch_.ids()) {
          NodeFitView f = recon_->nodeFit(id);
          if (f.status == NodeStatus::Fitted) circles.push_back(f.circle);
        }
        double scale = options_.distanceColorScale * std::max(bounds_.diagonal(), 1e-12);
        colors_ = circleDistanceColors(cloud_, circles, scale);
        break;
      }
    }
    colorsStale_ = false;
    ++colorsVersion_;
  }
  return colors_;
}

NodeFitView ViewerState::nodeFit(NodeId id) const { return recon_->nodeFit(id); }

std::vector<NodeMarker> ViewerState::nodeMarkers() const {
  std::vector<NodeMarker> markers;
  geom::Camera cur = orbit_.camera();
  markers.reserve(sketch_.size());
  for (const auto& [id, node] : sketch_.nodes()) {
    NodeMarker m;
    m.id = id;
    m.parent = node.parent;
    m.selected = id == selected_;
    m.active = id == active_;
    m.status = recon_->nodeFit(id).status;
    if (node.isScreenNode() && sameAsCurrent(sketch_.cameras()[node.camera])) {
      m.screen = node.screen;
      m.inCurrentView = true;
      m.visible = true;
    } else {
      m.inCurrentView = false;
      try {
        Vec3 s = cur.project(anchor(id));
        m.screen = s.head<2>();
        m.visible = s.allFinite() && s.z() >= 0.0 && s.z() <= 1.0;
      } catch (const std::exception&) {
        m.visible = false;
      }
    }
    markers.push_back(m);
  }
  return markers;
}

NodeId ViewerState::nodeAt(const Vec2& screen) const {
  NodeId best = kNoNode;
  double bestD = options_.pickRadiusPx;
  for (const NodeMarker& m : nodeMarkers()) {
    if (!m.visible) continue;
    double d = (m.screen - screen).norm();
    if (d <= bestD) {
      bestD = d;
      best = m.id;
    }
  }
  return best;
}

SamplingRegion ViewerState::samplingRegion() const {
  SamplingRegion r;
  if (selected_ == kNoNode || !sketch_.contains(selected_)) return r;
  try {
    const sketch::Node& node = sketch_.node(selected_);
    r.geometry = sketch_.geometry(selected_);
    r.sliceHalfThickness = node.params.sliceHalfThickness;
    NodeFitView f = recon_->nodeFit(selected_);
    r.lineEpsilon = f.finalLineEpsilon > 0 ? f.finalLineEpsilon : node.params.lineEpsilon;
    r.valid = true;
  } catch (const std::exception&) {
    r.valid = false;
  }
  return r;
}

std::vector<Line3> ViewerState::sceneLines() const {
  std::vector<Line3> lines;
  if (display_.showCircles) {
    for (NodeId id : sketch_.ids()) {
      NodeFitView f = recon_->nodeFit(id);
      if (f.status != NodeStatus::Fitted) continue;
      addRing(lines, f.circle.centre, f.circle.normal, f.circle.radius, options_.circleSegments,
              id == selected_ ? kSelectedCircleColor : kCircleColor);
    }
  }
  SamplingRegion r = samplingRegion();
  if (!display_.showSamplingRegion || !r.valid) return lines;
  const sketch::NodeGeometry& g = r.geometry;
  Vec3 n = g.planeNormal.normalized();
  Vec3 centre = anchor(selected_);
  // The slab: two squares at ±ε around the node's region, joined at the corners.
  Vec3 u = g.hasLine ? g.lineDir.normalized() : geom::anyPerpendicular(n);
  Vec3 v = n.cross(u).normalized();
  const geom::BBox& box = bounds_;
  double half = std::max(1.5 * r.lineEpsilon, 0.05 * box.diagonal());
  Vec3 corners[4] = {centre + half * (u + v), centre + half * (-u + v), centre + half * (-u - v),
                     centre + half * (u - v)};
  for (int side = -1; side <= 1; side += 2) {
    Vec3 off = side * r.sliceHalfThickness * n;
    for (int i = 0; i < 4; ++i) lines.push_back(Line3{corners[i] + off, corners[(i + 1) % 4] + off, kSlabColor});
  }
  for (int i = 0; i < 4; ++i)
    lines.push_back(Line3{corners[i] - r.sliceHalfThickness * n, corners[i] + r.sliceHalfThickness * n, kSlabColor});
  // The test region: the cylinder of radius lineEpsilon around L within the cloud's box, or the
  // disc around a point node's point.
  if (g.hasLine) {
    Vec3 d = g.lineDir.normalized();
    double t0, t1;
    if (clipLineToBox(g.linePoint, d, box, r.lineEpsilon, &t0, &t1)) {
      Vec3 a = g.linePoint + t0 * d, b = g.linePoint + t1 * d;
      addRing(lines, a, d, r.lineEpsilon, options_.circleSegments, kCylinderColor);
      addRing(lines, b, d, r.lineEpsilon, options_.circleSegments, kCylinderColor);
      Vec3 p = geom::anyPerpendicular(d), q = d.cross(p);
      for (int i = 0; i < 8; ++i) {
        double ang = 2.0 * M_PI * i / 8;
        Vec3 off = r.lineEpsilon * (std::cos(ang) * p + std::sin(ang) * q);
        lines.push_back(Line3{a + off, b + off, kCylinderColor});
      }
    }
  } else {
    addRing(lines, g.planePoint, n, r.lineEpsilon, options_.circleSegments, kCylinderColor);
  }
  return lines;
}

std::vector<std::uint32_t> ViewerState::highlightedSlicePoints() const {
  if (!display_.showSamplingRegion || selected_ == kNoNode) return {};
  return recon_->slicePoints(selected_);
}

std::vector<std::uint32_t> ViewerState::highlightedInliers() const {
  if (!display_.showSamplingRegion || selected_ == kNoNode) return {};
  return recon_->inlierPoints(selected_);
}

const geom::TriMesh& ViewerState::mesh() const { return recon_ ? recon_->mesh() : emptyMesh_; }

std::size_t ViewerState::fittedCount() const {
  std::size_t n = 0;
  for (NodeId id : sketch_.ids()) n += recon_->nodeFit(id).status == NodeStatus::Fitted;
  return n;
}

std::size_t ViewerState::skippedCount() const {
  std::size_t n = 0;
  for (NodeId id : sketch_.ids()) n += recon_->nodeFit(id).status == NodeStatus::Skipped;
  return n;
}

}  // namespace treesketch::viewer
