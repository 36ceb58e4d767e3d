// The interactive sketching tool's state and actions, in plain C++ (no GL, no window): the cloud,
// the sketch and its live reconstruction, the orbit camera, selection and active node, undo/redo,
// display options, status messages and autosave; and "what to draw" (point colours, node markers
// in screen space, 3D lines for circles and the selected node's sampling region, highlighted slice
// points, the tube mesh). The desktop window (apps/viewer) only draws this and forwards input;
// tests and the script runner drive it directly. No action ever throws: a failure becomes an error
// status message and the sketch is kept.
// ViewerState is implemented in three files by concern: src/viewer/viewer_state.cpp (the state
// and its edit commands: cloud, sketch edits, undo, save/load), viewer_input.cpp (mouse, wheel,
// keys and the view they steer) and viewer_draw.cpp (what is drawn: colours, markers, lines,
// status).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "treesketch/geom/camera.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/sketch/sketch.h"
#include "treesketch/util/progress.h"
#include "treesketch/viewer/orbit_camera.h"
#include "treesketch/viewer/point_colors.h"
#include "treesketch/viewer/undo_stack.h"

namespace treesketch::viewer {

using sketch::kNoNode;
using sketch::NodeId;

/// Point colourings. The last three colour by the file's attributes (viewer/color_legend.h says
/// which a cloud has); a cloud without the attribute is drawn plain.
enum class ColorMode { Height, CircleDistance, Plain, Intensity, FileColor, Classification };
enum class MeshStyle { Solid, Wireframe, Hidden };
enum class MouseButton { Left, Right, Middle };
/// Modifier key bits for mouse and key events.
enum Modifier : int { kModNone = 0, kModShift = 1, kModCtrl = 2, kModAlt = 4 };

/// Parses "height" / "distance" / "plain" / "intensity" / "rgb" / "classification"; throws
/// OptionsError otherwise.
ColorMode parseColorMode(const std::string& s);
/// Parses "solid" / "wireframe" / "hidden"; throws OptionsError otherwise.
MeshStyle parseMeshStyle(const std::string& s);
const char* toString(ColorMode mode);
const char* toString(MeshStyle style);

struct ViewerOptions {
  /// A click within this distance of a node marker picks the node, window pixels.
  double pickRadiusPx = 9.0;
  /// A press that moves less than this before release is a click, not a drag, window pixels.
  double dragThresholdPx = 4.0;
  /// Undo steps kept.
  std::size_t undoLimit = 500;
  /// Points drawn around each fitted circle's ring (line segments per circle).
  int circleSegments = 48;
  /// Distance colouring: distance (world units) mapped to the ramp's end, as a fraction of the
  /// cloud's bounding-box diagonal (design choice: 2 %, a few branch radii on an 8 m tree).
  double distanceColorScale = 0.02;
  /// Colour of every point in ColorMode::Plain.
  Rgb plainColor = {170, 170, 170};
};

struct DisplayOptions {
  ColorMode colorMode = ColorMode::Height;
  float pointSize = 2.0f;  ///< window pixels
  MeshStyle meshStyle = MeshStyle::Solid;
  bool showCloud = true;
  bool showNodes = true;
  bool showCircles = true;
  bool showSamplingRegion = true;  ///< the selected node's slab, cylinder and slice points
};

/// A node's reconstruction outcome, as the viewer shows it.
enum class NodeStatus { Pending, Fitted, Skipped };
const char* toString(NodeStatus status);

/// Everything the viewer knows about one node's fit (from the reconstruction).
struct NodeFitView {
  NodeStatus status = NodeStatus::Pending;
  std::string reason;             ///< why it was skipped ("" when fitted)
  Circle3 circle;                 ///< valid when fitted
  double finalLineEpsilon = 0.0;  ///< the cylinder radius the fit ended with, world units
  std::size_t slicePoints = 0, testPoints = 0, inliers = 0;
  /// Fitted from the node's kept circle (an automatic sketch's model), not from the cloud.
  bool kept = false;
};

/// A node as drawn over the view: screen position (window pixels) under the current camera.
struct NodeMarker {
  sketch::NodeId id = sketch::kNoNode;
  sketch::NodeId parent = sketch::kNoNode;
  geom::Vec2 screen = geom::Vec2::Zero();
  bool visible = true;        ///< false when behind the camera or outside the depth range
  bool inCurrentView = true;  ///< drawn under the current camera (false: projected from 3D)
  bool selected = false;
  bool active = false;
  NodeStatus status = NodeStatus::Pending;
};

/// A coloured 3D line segment (world frame).
struct Line3 {
  geom::Vec3 a = geom::Vec3::Zero(), b = geom::Vec3::Zero();
  Rgb color = {255, 255, 255};
};

/// The selected node's sampling region (thesis §4.4): the slab |dist to plane| < ε and the
/// cylinder of radius lineEpsilon around the line L, for drawing.
struct SamplingRegion {
  bool valid = false;
  sketch::NodeGeometry geometry;
  double sliceHalfThickness = 0.0;
  double lineEpsilon = 0.0;  ///< the final (possibly grown) radius when the node was fitted
};

/// A status message for the status bar / log.
struct StatusMessage {
  bool error = false;
  std::string text;
};

/// The reconstruction the viewer runs after every edit. Implemented over recon::Reconstruction in
/// the library; tests may plug in their own.
class ViewerReconstruction {
 public:
  virtual ~ViewerReconstruction() = default;
  /// Re-fits what changed in `sketch` (nodes added, moved, re-parameterised, removed) and
  /// rebuilds the mesh.
  virtual void update(const sketch::Sketch& sketch) = 0;
  /// The fit of node `id` (Pending when unknown).
  virtual NodeFitView nodeFit(sketch::NodeId id) const = 0;
  /// Indices into the cloud of the node's slice (nearPts) and of its circle's inliers.
  virtual std::vector<std::uint32_t> slicePoints(sketch::NodeId id) const = 0;
  virtual std::vector<std::uint32_t> inlierPoints(sketch::NodeId id) const = 0;
  virtual const geom::TriMesh& mesh() const = 0;
};

/// The default reconstruction (recon::Reconstruction over `cloud`, which must outlive it).
std::unique_ptr<ViewerReconstruction> makeDefaultReconstruction(const geom::PointCloud& cloud);

class ViewerState {
 public:
  using ReconstructionFactory = std::function<std::unique_ptr<ViewerReconstruction>(const geom::PointCloud&)>;

  /// `factory` builds the reconstruction for a cloud (default: makeDefaultReconstruction).
  explicit ViewerState(const ViewerOptions& options = {}, ReconstructionFactory factory = {});
  ~ViewerState();
  ViewerState(const ViewerState&) = delete;
  ViewerState& operator=(const ViewerState&) = delete;

  // ---- data -------------------------------------------------------------------------------------
  /// Takes a cloud (world units, `up` axis): resets the sketch, history and selection, frames the
  /// view (front preset). `sourcePath` names it in messages and places the autosave file beside it
  /// ("<stem>.autosave.sketch.json"); empty: no autosave unless setAutosavePath is called.
  /// Returns false (error status) for an empty cloud.
  bool setCloud(geom::PointCloud cloud, geom::UpAxis up, const std::filesystem::path& sourcePath = {});
  /// Reads a cloud file (io::readPointCloud) and calls setCloud. Mesh files (.obj, PLY with faces)
  /// are scanned first with the sphere scanner's defaults; `progress` reports the scan.
  bool openFile(const std::filesystem::path& path, geom::UpAxis up, const ProgressFn& progress = {});
  const geom::PointCloud& cloud() const { return cloud_; }
  /// The cloud's bounding box (computed once per cloud).
  const geom::BBox& bounds() const { return bounds_; }
  /// Increases whenever a new cloud is set.
  std::uint64_t cloudVersion() const { return cloudVersion_; }
  geom::UpAxis up() const { return up_; }
  const sketch::Sketch& sketch() const { return sketch_; }
  /// Where the sketch is autosaved after every edit (empty: never).
  void setAutosavePath(const std::filesystem::path& path) { autosavePath_ = path; }
  const std::filesystem::path& autosavePath() const { return autosavePath_; }
  /// Where Ctrl+S saves the sketch (empty: Ctrl+S reports that a path is needed).
  void setSketchPath(const std::filesystem::path& path) { sketchPath_ = path; }
  const std::filesystem::path& sketchPath() const { return sketchPath_; }

  // ---- view -------------------------------------------------------------------------------------
  /// The 3D view's rectangle in window pixels (top-left origin).
  void setViewport(const geom::Viewport& viewport);
  OrbitCamera& orbit() { return orbit_; }
  const OrbitCamera& orbit() const { return orbit_; }
  geom::Camera camera() const { return orbit_.camera(); }
  void fitView();
  void presetView(geom::PresetView view);
  void setOrthographic(bool ortho);
  DisplayOptions& display() { return display_; }
  const DisplayOptions& display() const { return display_; }
  void setColorMode(ColorMode mode);

  // ---- input (window pixels; what a mouse and keyboard do) -------------------------------------
  /// Left button: press on a node picks it (release without moving selects it and makes it
  /// active — with Ctrl it only selects it; moving drags it); press elsewhere and release adds a
  /// node there as a child of the active node (the first node is the root). Right button drag (or
  /// Alt + left): trackball orbit. Middle button drag (or Shift + right): pan. Presses outside the
  /// viewport are ignored.
  void mouseDown(const geom::Vec2& pos, MouseButton button, int mods = kModNone);
  void mouseMove(const geom::Vec2& pos);
  void mouseUp(const geom::Vec2& pos, MouseButton button, int mods = kModNone);
  /// Wheel: `steps` notches (positive zooms in).
  void scroll(double steps);
  /// Press and release at `pos`.
  void clickAt(const geom::Vec2& pos, MouseButton button = MouseButton::Left, int mods = kModNone);
  /// Press at `from`, move to `to` in `steps` equal moves (calling `afterEachMove`, if any, after
  /// each: the script runner draws a frame there, as a real drag would), release.
  void dragTo(const geom::Vec2& from, const geom::Vec2& to, MouseButton button = MouseButton::Left, int mods = kModNone,
              int steps = 8, const std::function<void()>& afterEachMove = {});
  /// A key press by name: "delete"/"backspace" (delete selected, children re-attached; with Shift
  /// the subtree too), "ctrl+z"-style names are accepted (mods parsed from the prefix), "z" with
  /// Ctrl (undo), "y" with Ctrl or "z" with Ctrl+Shift (redo), "s" with Ctrl (save to sketchPath()), "escape"
  /// (deselect), "f" (fit), "o" (ortho/perspective), "1"/"2"/"3" (front/side/top view),
  /// "a" (uniform automatic sketch), "w" (cycle mesh style), "c" (cycle colour mode). Returns false
  /// for a key with no binding.
  bool keyPress(const std::string& key, int mods = kModNone);

  // ---- sketch actions (each one undoable, rebuilds, autosaves; false + error status on failure) --
  bool addNodeAt(const geom::Vec2& screen);
  bool selectNode(sketch::NodeId id);  ///< also makes it active; kNoNode clears the selection
  bool setActiveNode(sketch::NodeId id);
  /// Moves `id` so its marker lies at `screen` in the current view (its own camera is kept).
  bool moveNodeTo(sketch::NodeId id, const geom::Vec2& screen);
  bool deleteSelected(bool withSubtree);
  /// Sampling sizes of the selected node, or of new nodes (sketch defaults) when none is
  /// selected. World units, > 0. Consecutive changes of one value merge into one undo step.
  bool setSliceHalfThickness(double value);
  bool setLineEpsilon(double value);
  bool setNodeEnabled(bool enabled);
  bool undo();
  bool redo();
  bool clearSketch();
  /// Replaces the sketch by the thesis's uniform automatic sketch (nodes at regular heights).
  bool autoSketchUniform(int nodes = 12);
  /// Replaces the sketch by the automatic skeleton sketch (skeleton::autoSkeletonSketch, as
  /// `reconstruct --auto`: point nodes along the branches with their own sampling sizes, each
  /// keeping its model circle, so the view shows the automatic model and an edit re-fits only the
  /// nodes it touches). leafOn: the tree was scanned in leaf (skeleton::leafOnSkeletonOptions).
  bool autoSketchSkeleton(bool leafOn = false);
  /// Drops the selected node's kept circle (it is then fitted from the cloud) / every node's.
  /// Undoable; an error message when there is nothing to refit.
  bool refitSelected();
  bool refitAll();
  /// Ends the current merge of consecutive edits (call when a slider is released).
  void finishEdit() { lastEditKey_.clear(); }
  bool saveSketch(const std::filesystem::path& path);
  bool loadSketch(const std::filesystem::path& path);
  /// Writes the current tube mesh (.obj or .ply, atomically).
  bool exportMesh(const std::filesystem::path& path);

  sketch::NodeId selected() const { return selected_; }
  sketch::NodeId active() const { return active_; }
  bool canUndo() const { return undo_.canUndo(); }
  bool canRedo() const { return undo_.canRedo(); }
  const UndoStack& history() const { return undo_; }

  // ---- what to draw -----------------------------------------------------------------------------
  /// Per-point colours for the current colour mode (recomputed only when stale).
  const std::vector<Rgb>& pointColors();
  /// Increases whenever pointColors() would change.
  std::uint64_t colorsVersion() const { return colorsVersion_; }
  /// Markers of all nodes under the current camera.
  std::vector<NodeMarker> nodeMarkers() const;
  /// The node whose marker is nearest to `screen` within the pick radius (kNoNode if none).
  sketch::NodeId nodeAt(const geom::Vec2& screen) const;
  /// 3D lines: fitted circles (selected one highlighted) and the selected node's sampling region.
  std::vector<Line3> sceneLines() const;
  SamplingRegion samplingRegion() const;
  /// Cloud indices of the selected node's slice points and circle inliers (empty when none).
  std::vector<std::uint32_t> highlightedSlicePoints() const;
  std::vector<std::uint32_t> highlightedInliers() const;
  NodeFitView nodeFit(sketch::NodeId id) const;
  const geom::TriMesh& mesh() const;
  /// Increases whenever the mesh, the markers or the lines may have changed.
  std::uint64_t sceneVersion() const { return sceneVersion_; }
  /// Counts of fitted and skipped nodes.
  std::size_t fittedCount() const;
  std::size_t skippedCount() const;

  // ---- status -----------------------------------------------------------------------------------
  double lastRebuildMs() const { return lastRebuildMs_; }
  const std::vector<StatusMessage>& messages() const { return messages_; }
  StatusMessage lastMessage() const { return messages_.empty() ? StatusMessage{} : messages_.back(); }
  std::size_t errorCount() const { return errorCount_; }
  void info(const std::string& text);
  void error(const std::string& text);
  const ViewerOptions& options() const { return options_; }

 private:
  enum class Gesture { None, PendingAdd, PendingNode, DragNode, Orbit, Pan };
  bool runAction(const std::string& name, const std::function<void()>& action);
  /// The edit protocol: runs `body` on the sketch; on success records the previous sketch for undo
  /// (merged with the previous edit when `mergeKey` is non-empty and repeats) and calls endEdit; on
  /// failure restores the sketch and selection and reports the error.
  bool edit(const std::string& name, const std::string& label, const std::string& mergeKey,
            const std::function<void()>& body);
  bool moveNodeImpl(sketch::NodeId id, const geom::Vec2& screen, const std::string& mergeKey);
  /// After an edit: fixes selection, rebuilds, autosaves.
  void endEdit();
  void rebuild();
  void autosave();
  void resetReconstruction();
  void fixSelection();
  bool sameAsCurrent(const geom::Camera& cam) const;
  geom::Vec3 anchor(sketch::NodeId id) const;
  sketch::SamplingParams paramsForEdit() const;
  bool applyParams(const sketch::SamplingParams& params, const std::string& label, const std::string& key);
  /// Sets one sampling size (`name` in messages, `key` merges repeats into one undo step);
  /// rejects a value that is not a positive finite number.
  bool setSamplingSize(double sketch::SamplingParams::*size, double value, const std::string& name,
                       const std::string& key);

  ViewerOptions options_;
  ReconstructionFactory factory_;
  geom::PointCloud cloud_;
  geom::BBox bounds_;
  geom::UpAxis up_ = geom::UpAxis::Y;
  std::filesystem::path sourcePath_;
  std::filesystem::path autosavePath_;
  std::filesystem::path sketchPath_;
  sketch::Sketch sketch_;
  std::unique_ptr<ViewerReconstruction> recon_;
  OrbitCamera orbit_;
  DisplayOptions display_;
  UndoStack undo_;
  std::string lastEditKey_;
  sketch::NodeId selected_ = sketch::kNoNode;
  sketch::NodeId active_ = sketch::kNoNode;

  Gesture gesture_ = Gesture::None;
  MouseButton gestureButton_ = MouseButton::Left;
  int gestureMods_ = kModNone;
  geom::Vec2 pressPos_ = geom::Vec2::Zero();
  geom::Vec2 lastPos_ = geom::Vec2::Zero();
  sketch::NodeId gestureNode_ = sketch::kNoNode;
  std::uint64_t dragSerial_ = 0;
  bool autosavePending_ = false;

  std::vector<Rgb> colors_;
  ColorMode colorsMode_ = ColorMode::Height;
  bool colorsStale_ = true;
  std::uint64_t colorsVersion_ = 1;
  std::uint64_t cloudVersion_ = 0;
  std::uint64_t sceneVersion_ = 1;
  geom::TriMesh emptyMesh_;
  double lastRebuildMs_ = 0.0;
  std::vector<StatusMessage> messages_;
  std::size_t errorCount_ = 0;
};

}  // namespace treesketch::viewer
