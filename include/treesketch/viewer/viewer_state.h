// The desktop tool's state and actions, in plain C++ (no GL, no window), as a façade over its
// parts, each a header of its own that says what it owns:
//   document()  the sketch's files: its cloud's record, save path, autosave, recovery offer
//               (viewer/sketch_document.h);
//   view()      camera, viewport, up direction, colouring and display options (viewer/view_settings.h);
//   tools()     the active tool, the path being dragged, the selected and active node
//               (viewer/tool_state.h);
//   jobs()      the automatic model on a worker thread, its progress and cancel (viewer/jobs.h);
//   status()    the messages and the status line (viewer/status_log.h);
//   scene()     what the window draws of it: colours, markers, lines, the mesh (viewer/scene.h).
// ViewerState itself keeps the cloud, the sketch with its undo history and live reconstruction,
// and the operations that cross parts: opening a cloud, every edit (undoable, rebuilt, autosaved),
// mouse and keys, saving and loading. The desktop window (apps/viewer) only draws this and forwards input; tests and
// the script runner drive it directly. No action ever throws: a failure becomes an error status message and the sketch
// is kept. Implemented in several files by concern: src/viewer/viewer_state.cpp (the cloud, the edit protocol, sketch
// edits, undo), viewer_files.cpp (save, load, export, through SketchDocument), viewer_input.cpp (mouse, wheel, keys),
// viewer_draw.cpp (the Scene part), viewer_tools.cpp (the correction tools), viewer_view.cpp (the up direction),
// recovery.cpp (the earlier session's autosave offered back), background_job.cpp (the automatic skeleton through Jobs),
// wood_classes.cpp (the wood/leaf classification, the wood lasso, the automatic skeleton on the wood).
#pragma once

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "treesketch/classify/classify.h"
#include "treesketch/geom/camera.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/sketch/sketch.h"
#include "treesketch/util/progress.h"
#include "treesketch/viewer/jobs.h"
#include "treesketch/viewer/point_colors.h"
#include "treesketch/viewer/scene.h"
#include "treesketch/viewer/scene_items.h"
#include "treesketch/viewer/sketch_document.h"
#include "treesketch/viewer/status_log.h"
#include "treesketch/viewer/tool_state.h"
#include "treesketch/viewer/undo_stack.h"
#include "treesketch/viewer/view_settings.h"
#include "treesketch/viewer/view_up.h"

namespace treesketch::viewer {

using sketch::kNoNode;
using sketch::NodeId;

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
  /// How long an info message stays in the status bar, seconds (errors stay until dismissed or
  /// replaced). Design choice: long enough to read two lines, short enough not to mislead later.
  double statusInfoSeconds = 6.0;
  /// LabelMode::Auto shows node numbers only up to this many nodes (an automatic skeleton has
  /// 300-800 and its numbers cover the tree).
  std::size_t autoLabelMaxNodes = 100;
};

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
  /// view (front preset). `sourcePath` names it in messages and, through document(), gives the
  /// sketch its default file and its autosave beside the cloud, named after the whole file name
  /// ("tree.las" -> "tree.las.sketch.json", "tree.las.autosave.sketch.json", so tree.las and
  /// tree.xyz in one folder keep apart); empty: no sketch path and no autosave unless set. An
  /// autosave found there is offered back (document().recoveryPending()). The previous cloud's autosave is
  /// removed when it holds nothing unsaved (as closeSession). Returns false (error status, the
  /// open cloud and sketch kept) for an empty cloud or one with no extent to sketch on (every point
  /// at one place, or a box under a micrometre or under 1e-9 of its distance from the origin).
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
  /// Where the sketch is autosaved after every edit (empty: never). An existing file there is work
  /// from an earlier session (a crash, or a window closed with unsaved edits): it is offered back
  /// (document().recoveryPending()) and never overwritten before resolveRecovery() is called.
  /// A path that must never be written (the open cloud, a file that failed to load) is refused
  /// with an error and the autosave stays where it was.
  void setAutosavePath(const std::filesystem::path& path);
  /// Where Ctrl+S saves the sketch (empty: Ctrl+S reports that a path is needed). setCloud sets it
  /// to the cloud's own sketch file (SketchDocument::sketchPathFor).
  void setSketchPath(const std::filesystem::path& path) { doc_.setSketchPath(path); }

  // ---- the parts ----------------------------------------------------------------------------------
  /// The open cloud's record (path, point count, hash), its sketch and autosave files, what may not
  /// be written, and the offer of an earlier session's autosave.
  const SketchDocument& document() const { return doc_; }
  ViewSettings& view() { return view_; }
  const ViewSettings& view() const { return view_; }
  const ToolState& tools() const { return tools_; }
  Jobs& jobs() { return jobs_; }
  const Jobs& jobs() const { return jobs_; }
  StatusLog& status() { return status_; }
  const StatusLog& status() const { return status_; }

  // ---- crash recovery ---------------------------------------------------------------------------
  /// What to do with an autosave found at start: load it (an undoable edit), delete it, or keep
  /// it for later (renamed "<autosave>.kept-<date>-<time>.sketch.json", loadable by hand).
  enum class RecoveryChoice { Restore, Discard, Keep };
  /// An earlier session's autosave waits for the person's choice while
  /// document().recoveryPending(); until then autosave writes nothing (edits still work; they are
  /// autosaved once the choice is made). Applies the choice; false (error status) when nothing is pending or the file
  /// cannot be read/moved (the file is then left where it is and the offer stays).
  bool resolveRecovery(RecoveryChoice choice);
  /// Edits since the sketch was last saved, loaded or the cloud opened.
  bool hasUnsavedChanges() const { return dirty_; }
  /// A clean end of the session: the autosave is deleted when there is nothing it would bring
  /// back (no pending offer, and the sketch is empty or is what its sketch file holds:
  /// hasUnsavedWork); else it stays, to be offered next time.
  void closeSession();
  /// The person chose to drop the unsaved work (the unsaved-work prompt's Discard): the autosave
  /// is deleted so that it is not offered back (an autosave found at start and still waiting for
  /// its offer's answer is left alone).
  void discardUnsavedWork();

  // ---- view (what crosses from view() to the cloud and the sketch) ---------------------------------
  /// The view's up direction (initially the cloud's up axis). Setting it re-orients the view
  /// (front preset) and the height colouring; the cloud and the sketch are untouched, and for +Y
  /// or +Z the library's up axis (automatic sketches, the sketch file's "up") follows. Other
  /// directions are for viewing and sketching by hand: the automatic sketches then refuse with a
  /// message, as they assume +Y or +Z.
  void setUpDirection(UpDirection up);
  /// The warning shown when the cloud looks lying down under the current up ("" when upright).
  /// The window shows it as a banner over the view, with the up-axis choice, until the up changes
  /// or the person dismisses it (upWarningShown()).
  std::string lyingDownWarning() const;
  bool upWarningShown() const { return !view_.upWarningDismissed() && !lyingDownWarning().empty(); }

  // ---- input (window pixels; what a mouse and keyboard do) -------------------------------------
  /// Left button: press on a node (the nearest marker within the pick radius) picks it (release
  /// without moving selects it and makes it active — with Ctrl it only selects it; moving drags
  /// it); press elsewhere and release clears the selection and says how to add a node, unless the
  /// tool is AddNodes or Shift is held: then it adds a node there as a child of the active node when
  /// the person chose one, else of the node whose marker is nearest to the click (the first node is
  /// the root); the status line names the parent. Right button drag (or
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
  /// "a" (uniform automatic sketch; asks first when it would replace hand edits), "w" (cycle mesh style), "c" (cycle
  /// colour mode). Returns false for a key with no binding.
  bool keyPress(const std::string& key, int mods = kModNone);

  // ---- sketch actions (each one undoable, rebuilds, autosaves; false + error status on failure) --
  /// Adds a screen node at `screen`. Where the view ray meets no cloud point (none projects
  /// within the pick radius) nothing is added and the status line says why.
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
  /// What the window's buttons and the A key call: the two automatic sketches above, but when the
  /// sketch holds a person's edits (hasHandEdits()) they first ask (confirmationPending()) and run
  /// only on answerConfirmation(true). Either way the replacement is one undoable edit.
  bool requestAutoSketchUniform(int nodes = 12);
  /// (The skeleton runs as a background job: startAutoSkeletonJob.)
  bool requestAutoSketchSkeleton(bool leafOn = false);
  /// The sketch is not empty and is not an untouched automatic sketch (a node was added, moved or
  /// changed by hand, a sketch was loaded or restored, or an edit was undone since).
  bool hasHandEdits() const { return !sketch_.empty() && !untouchedAuto_; }
  /// A question waits for a yes/no answer (the window shows it as a modal).
  bool confirmationPending() const { return static_cast<bool>(pendingAction_); }
  const std::string& confirmationQuestion() const { return pendingQuestion_; }
  /// Yes runs the waiting action, no drops it (an info message says so). False when nothing waits
  /// or the action failed.
  bool answerConfirmation(bool yes);
  // ---- long work on a worker thread ------------------------------------------------------------
  /// Starts the automatic skeleton sketch (as autoSketchSkeleton) on a worker thread and returns
  /// at once; the window keeps drawing, shows jobs().progress() and may jobs().cancel(). pollJob() takes
  /// the result in as one undoable edit. While the job runs, edits are refused with a message
  /// (the view still moves); the sketch is untouched until the result is taken in, so a cancel
  /// leaves it exactly as it was. False (error status) when a job runs already or no cloud is open.
  bool startAutoSkeletonJob(bool leafOn = false);
  /// Takes a finished job in (result, cancel message or error); call once a frame. True when a job
  /// ended in this call.
  bool pollJob();
  /// Blocks until the running job has ended and takes it in (scripts, and closing the window).
  void waitForJob();

  // ---- wood/leaf classification (src/viewer/wood_classes.cpp) ------------------------------------
  /// Starts the wood/leaf classification of the open cloud (classify::classifyWood with the model
  /// built into the library, on the view's up axis) as a background job (progress, Cancel: the
  /// classification reports nothing inside, so a cancel takes effect when it ends and drops it).
  /// pollJob() takes it in: from then on the fits of a person's nodes and the strokes use only
  /// the points classed wood, the lassos correcting the classes (a wood lasso makes its points
  /// wood, a not-wood lasso leaf; the last lasso over a point decides); the colour modes
  /// WoodProbability and WoodClass show it. The classes belong to the cloud, not to the sketch:
  /// they are not undone and go with the cloud. False (error status) when a job runs, no cloud is
  /// open or the view's up is not +Y or +Z.
  bool startClassifyJob();
  /// The open cloud's classification (nullptr until one is taken in).
  const classify::Classification* woodClasses() const { return classes_.get(); }
  /// Per point, 1 when it is wood after the lassos (what the fits use); empty with no
  /// classification. Kept until the lassos or the classification change.
  const std::vector<std::uint8_t>& woodAfterLassos() const;
  /// The points woodAfterLassos() calls wood.
  std::size_t woodPointCount() const;
  /// The automatic skeleton on the wood only, as `reconstruct --auto --wood-only`: the points
  /// classed wood (after the lassos) modelled with the leaf-off preset. A background job like
  /// startAutoSkeletonJob's, which classifies the cloud first when it is not classified (that
  /// classification is kept). False (error status) as startAutoSkeletonJob.
  bool startWoodSkeletonJob();
  /// What the window's "wood only" Auto skeleton calls: asks first when the sketch holds hand
  /// edits, as requestAutoSketchSkeleton.
  bool requestAutoSketchSkeletonWood();

  /// Drops the selected node's kept circle (it is then fitted from the cloud) / every node's.
  /// Undoable; an error message when there is nothing to refit.
  bool refitSelected();
  bool refitAll();
  // ---- correction tools (src/viewer/viewer_tools.cpp over edit/correction_tools.h) ----
  /// Chooses the tool a left click or drag uses (ToolState; the status line says how to use it).
  using Tool = viewer::Tool;
  void setTool(Tool tool);
  /// Each one undoable, rebuilds, autosaves; false + error status on failure. Screen points are
  /// window pixels under the current view.
  bool strokeLimb(const std::vector<geom::Vec2>& stroke);
  bool lassoNotWood(const std::vector<geom::Vec2>& polygon);
  /// The opposite lasso: its points are wood, whatever the classification (or an earlier
  /// not-wood lasso) said; saved in the sketch with the not-wood lassos.
  bool lassoWood(const std::vector<geom::Vec2>& polygon);
  /// Removes every lasso, not-wood and wood.
  bool clearNotWood();
  bool deleteSubtree(sketch::NodeId id);
  /// Delete subtree as the window's Shift+Delete and button do it: a node with children is not
  /// removed at once; the question names how many nodes go, their markers are drawn as doomed
  /// (NodeMarker::doomed) until the answer, and yes deletes them (one undoable edit).
  bool requestDeleteSubtree(sketch::NodeId id);
  /// `reverse`: sketch::reattachReversed — `id` starts the limb under `newParent` and the chain
  /// above it is turned round (a limb the automatic model hung by its tip). In the Reattach tool
  /// the first click names the node to move (never the node selected before), the second its new
  /// parent; Shift on the second click reverses.
  bool reattachNode(sketch::NodeId id, sketch::NodeId newParent, bool reverse = false);
  /// Once the cloud is classified (startClassifyJob), both model only its wood after the lassos.
  bool automaticBelow(sketch::NodeId id);
  bool automaticInRegion(const std::vector<geom::Vec2>& polygon);
  /// Where the selected node's circle lies along its view ray (the chosen depth, for the view to
  /// show; NaN when it has no circle) — the distance from the current camera's eye.
  double selectedDepth() const;

  /// Ends the current merge of consecutive edits (call when a slider is released).
  void finishEdit() { lastEditKey_.clear(); }
  /// Saves the sketch with its cloud's record (the autosave is then removed). Never writes the
  /// open cloud or a file that failed to load (error). Replacing a file that is not this
  /// document's (another cloud's sketch, or not a sketch) asks first (confirmationPending()) unless
  /// `replaceConfirmed` (the save dialog has asked already); false until the answer is yes.
  bool saveSketch(const std::filesystem::path& path, bool replaceConfirmed = false);
  /// Loads a sketch file. One made for another cloud (its record's point count or hash differ)
  /// asks first (confirmationPending(); false until the answer is yes); one without a record
  /// (older files) loads as before. A file that fails to load is never written afterwards.
  bool loadSketch(const std::filesystem::path& path);
  /// Writes the current tube mesh (.obj or .ply, atomically).
  bool exportMesh(const std::filesystem::path& path);
  /// The model's outputs, as every command writes them (model/tree_model.h): the tube mesh, the
  /// cylinder table, TreeQSM's text layout, the tree metrics, the fit report.
  enum class ModelFile { Mesh, Cylinders, Qsm, Metrics, Report };
  /// Writes one output of the current model (atomically), measured against the open cloud with
  /// `unitMetres` metres per cloud unit. False (error status) when no piece is fitted yet.
  bool exportModel(ModelFile what, const std::filesystem::path& path, double unitMetres = 1.0);

  bool canUndo() const { return undo_.canUndo(); }
  bool canRedo() const { return undo_.canRedo(); }
  const UndoStack& history() const { return undo_; }

  // ---- what to draw ------------------------------------------------------------------------------
  /// What the window draws of this state (viewer/scene.h): colours, markers, lines, the mesh.
  Scene& scene() { return scene_; }
  const Scene& scene() const { return scene_; }
  /// Increases whenever the mesh, the markers or the lines may have changed.
  std::uint64_t sceneVersion() const { return sceneVersion_; }

  // ---- status ------------------------------------------------------------------------------------
  double lastRebuildMs() const { return lastRebuildMs_; }
  const ViewerOptions& options() const { return options_; }

 private:
  using Gesture = ToolState::Gesture;
  void info(const std::string& text) { status_.info(text); }
  void error(const std::string& text) { status_.error(text); }
  geom::Camera camera() const { return view_.camera(); }
  /// The tools' share of the mouse (viewer_tools.cpp); true when the tool took the event.
  bool toolMouseDown(const geom::Vec2& pos, MouseButton button, int mods);
  bool toolMouseUp(const geom::Vec2& pos);
  bool toolKey(const std::string& key, int mods);
  std::map<sketch::NodeId, std::pair<geom::Vec3, double>> anchorsForTools() const;
  /// "3 of 7 fitted; 4 not: REASON" for the nodes a tool added (the status line after a stroke).
  std::string limbFitSummary(const std::vector<sketch::NodeId>& nodes) const;
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
  /// Looks for an earlier session's autosave (SketchDocument::findRecovery) and says what it found.
  void detectRecovery();
  bool takeJobOutcome(std::optional<Jobs::Outcome> outcome);
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
  SketchDocument doc_;
  ViewSettings view_;
  ToolState tools_;
  StatusLog status_;
  sketch::Sketch sketch_;
  std::unique_ptr<ViewerReconstruction> recon_;
  UndoStack undo_;
  std::string lastEditKey_;
  bool autosavePending_ = false;
  bool untouchedAuto_ = false;
  std::function<bool()> pendingAction_;
  sketch::NodeId pendingDelete_ = sketch::kNoNode;  ///< the subtree a waiting question would delete
  std::string pendingQuestion_;
  /// Runs `action` now, or asks `question` first when the sketch has hand edits.
  bool askBeforeReplacing(const std::string& question, std::function<bool()> action);
  /// Asks `question` (confirmationPending()); `action` runs on answerConfirmation(true).
  bool ask(const std::string& question, std::function<bool()> action);
  bool takeLoadedSketch(const std::filesystem::path& path, sketch::Sketch loaded, bool ownCloud);
  bool writeSketchFile(const std::filesystem::path& path);
  bool refuseWhileBusy(const std::string& name);
  bool dirty_ = false;

  // The wood/leaf classification (wood_classes.cpp).
  void takeClassification(std::shared_ptr<const classify::Classification> classes);
  /// Gives the reconstruction the points classed leaf (after a new classification or a new
  /// reconstruction).
  void applyLeafPoints();
  /// Per point, 1 = leaf by the classification (empty: not classified): what the fits leave out.
  std::vector<std::uint8_t> leafFlags() const;
  /// The points "automatic from here" (below a node, in a region) models: the cloud, or once it is
  /// classified its wood after the lassos (copied into `store`).
  const geom::PointCloud& pointsForAutomatic(geom::PointCloud& store) const;
  std::shared_ptr<const classify::Classification> classes_;
  std::uint64_t classesVersion_ = 0;  ///< increases with every classification taken in or dropped
  mutable std::vector<std::uint8_t> woodAfterLassos_;
  mutable std::size_t woodCount_ = 0;
  mutable std::uint64_t woodFor_ = 0;  ///< the classesVersion_ woodAfterLassos_ was made for
  mutable std::vector<std::pair<sketch::NotWoodLasso, geom::Camera>> woodLassos_;  ///< and the lassos

  std::uint64_t cloudVersion_ = 0;
  std::uint64_t sceneVersion_ = 1;
  double lastRebuildMs_ = 0.0;
  void viewMoved() {
    view_.lastViewChange_ = std::chrono::steady_clock::now();
    ++sceneVersion_;
  }
  friend class Scene;
  Scene scene_{*this};
  Jobs jobs_;  // last: destroyed first, so that a running job stops before the cloud it reads goes
};

}  // namespace treesketch::viewer
