// Scripted sessions for the viewer (`treesketch gui --script ACTIONS.json`): a JSON list of what a
// person does — clicks and drags at window positions, key presses, slider values, buttons, save,
// export, screenshot — parsed into actions and applied to a ViewerState one by one. The window
// draws a frame after each action and takes the screenshots; tests run scripts without a window.
//
// Format: either a JSON array of actions or {"window": [width, height], "actions": [...]}.
// An action is an object with one verb key, or a string "VERB [ARGUMENT]":
//   {"click": [x, y], "button": "left"|"right"|"middle", "mods": "shift+ctrl"}
//   {"drag": [[x0, y0], [x1, y1]], "button": ..., "mods": ..., "steps": 8, "hold": false}
//                                          (hold: the button stays down, for a screenshot of the
//                                          drag being drawn, until {"release": [x, y]})
//   {"scroll": steps}                      wheel notches, positive zooms in
//   {"key": "ctrl+z"}                      see ViewerState::keyPress
//   {"slider": "sliceHalfThickness"|"lineEpsilon"|"pointSize", "value": number}
//   {"option": "colorMode"|"meshStyle"|"projection"|"showCloud"|"showNodes"|"showCircles"|
//              "showRegion"|"labels"|"upAxis"|"holdJobs", "value": "height"|"wireframe"|"ortho"|
//              true|"auto"|"-z"|...}   (holdJobs: a test seam, see ViewerState::holdJobs)
//   {"view": "front"|"side"|"top"|"fit"}
//   {"select": nodeId}                     -1 clears the selection
//   {"button": "autoSketch"|"autoSkeleton"|"autoSkeletonWood"|"classify"|"undo"|"redo"|"clear"|"fit"|
//              "delete"|"deleteSubtree"|"refit"|"refitAll"|"clearNotWood"|"cancel"}
//                                          (autoSkeletonWood: the skeleton on the classified wood;
//                                          classify: the wood/leaf classification, a background job)
//   {"save": PATH}, {"load": PATH}, {"export": PATH}, {"screenshot": PATH}   ("save"/"load"
//                                          without a path use the session's sketch path)
//   Correction tools (each one undoable edit under the current view):
//   {"stroke": [[x, y], ...]}              draw a limb as one stroke (>= 2 points, base first)
//   {"lasso": [[x, y], ...]}               mark the points inside the polygon as not-wood
//   {"lassoWood": [[x, y], ...]}           mark the points inside the polygon as wood
//   {"region": [[x, y], ...]}              automatic skeleton inside the polygon, merged
//   {"deleteSubtree": nodeId}              delete a node and everything below it
//   {"reattach": [nodeId, newParentId], "reverse": false}   re-attach a node (and its subtree) to
//                                          another parent; reverse: the limb is turned round, the
//                                          node its base (sketch::reattachReversed)
//   {"automaticBelow": nodeId}             automatic skeleton below a node, merged
//   {"tool": "sketch"|"stroke"|"lasso"|"lassoWood"|"region"|"reattach"}   what a left drag does
//                                          (as keys G, X, Shift+X, R, P), so "drag" actions can
//                                          use the tools
//   {"recovery": "restore"|"discard"|"keep"}   answers the offer of an earlier session's autosave
//   {"confirm": true|false}               answers the question waiting (replace hand edits?)
//   {"start": "autoSkeleton"|"autoSkeletonWood"|"classify"}   starts the background job and goes
//                                          on at once (the
//                                          "autoSkeleton" button waits for its job to end, drawing
//                                          frames); {"button": "cancel"} cancels it; {"wait": "job"}
//                                          waits for it
//   {"wait": frames}
//   {"sleep": seconds}                     real time, drawing a frame every 0.1 s (a person idling)
//   {"expect": {"nodes": n, "fitted": n, "skipped": n, "selected": id, "active": id,
//               "errors": n, "meshTriangles": n, "kept": n, "notWood": n, "points": n,
//               "recoveryOffered": 0|1, "confirmPending": 0|1, "handEdits": 0|1, "labelsShown": 0|1,
//               "statusShown": 0|1, "lyingDown": 0|1, "legend": 0|1, "busy": 0|1, "woodLassos": n,
//               "classified": 0|1, "woodPoints": n}}
//                                          ("meshTriangles" checks "at least n"; "kept": nodes
//                                          with a kept circle; "notWood": lassos of both kinds;
//                                          "woodPoints": at least n points wood after the lassos;
//                                          "points": the cloud's size)
// Window verbs (the menus, dialogs and tools of apps/viewer; they need ScriptHooks::window, so a
// script without a window fails them with a message):
//   {"menu": ITEM}                         "open-cloud" "open-sketch" "save" "save-as" "export"
//                                          "quit" "help" "about" "reset-camera" "pick-mode";
//   {"menu": "recent", "value": i}         the i-th entry (0 = newest) of File > Recent files
//   {"dialog": "ok"|"cancel"|"type", "path": P}   in the open file dialog: type P into its path
//                                          box (optional), then press Open/Save ("ok": a folder is
//                                          entered, a file is taken), Cancel, or nothing ("type")
//   {"prompt": "save"|"discard"|"cancel"}  answers the unsaved-work prompt
//   {"pick": [x, y]}                       a left click in pick mode (window pixels)
//   {"hover": [x, y]}                      moves the mouse there (tooltips; window pixels)
//   "closeWindow"                          the window's close button
//   {"showMenu": "File"|"View"|"Tools"|"Help"|"none"}   keeps that menu open (for screenshots)
//   {"expectWindow": {"dialogOpen": 0|1, "dialogEntries": n, "promptOpen": 0|1, "picks": n,
//                     "distanceMin": d, "distanceMax": d, "recent": n, "quitting": 0|1,
//                     "helpOpen": 0|1, "legendClasses": n, "dialogError": 0|1, "tooltip": 0|1}}   (distanceMin/Max
//                                          bound the measured distance; recent: entries in the
//                                          recent files list; dialogError: the dialog shows one)
// Any object action may add "expectError": true: it then passes only when it fails (an error
// message), and the failure is not counted — how a script checks that bad input is refused and the
// session goes on.
// Paths are relative to the current directory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <istream>
#include <string>
#include <utility>
#include <vector>

#include "treesketch/geom/types.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

struct ScriptAction {
  enum class Kind {
    Click,
    Drag,
    Scroll,
    Key,
    Slider,
    Option,
    View,
    Select,
    Button,
    Save,
    Load,
    Export,
    Screenshot,
    Wait,
    Sleep,
    Recovery,
    Confirm,
    Start,
    Expect,
    Path,    ///< stroke / lasso / region: `name` and `points`
    NodeOp,  ///< deleteSubtree / reattach / automaticBelow: `name`, node `value`, parent `value2`
    Tool,    ///< `name`
    Window   ///< a window verb (menu, dialog, prompt, pick, closeWindow, expectWindow): `name`
  };
  Kind kind = Kind::Wait;
  std::size_t index = 0;  ///< position in the script (0-based), for messages
  geom::Vec2 from = geom::Vec2::Zero(), to = geom::Vec2::Zero();
  MouseButton button = MouseButton::Left;
  int mods = kModNone;
  int steps = 8;       ///< drag: mouse moves; wait: frames
  double value = 0.0;  ///< scroll steps, slider value, select id
  std::string name;    ///< key, slider, option, view or button name
  std::string text;    ///< option value (text form)
  std::filesystem::path path;
  std::vector<std::pair<std::string, double>> expect;
  std::vector<geom::Vec2> points;  ///< Path
  double value2 = 0.0;             ///< NodeOp reattach: the new parent
  bool expectError = false;        ///< passes only when the action fails (see the format above)
};

struct ActionScript {
  int windowWidth = 1280, windowHeight = 800;  ///< pixels
  std::vector<ScriptAction> actions;
};

/// Parses a script. Throws InputError naming `source`, the action's index and what was expected
/// (or the byte offset of malformed JSON) for: malformed JSON, an unknown verb, a missing or
/// non-numeric coordinate, NaN/Inf, an unknown button/modifier/slider/option/view name, a
/// non-positive window size. An empty action list is valid.
ActionScript parseActionScript(std::istream& in, const std::string& source);
ActionScript parseActionScript(const std::filesystem::path& path);

struct ScriptHooks {
  /// Draws one frame (called after every action; may be empty when there is no window).
  std::function<void()> frame;
  /// Writes a screenshot of the current frame; throws on failure. Empty: screenshots fail with a
  /// message ("needs a window").
  std::function<void(const std::filesystem::path&)> screenshot;
  /// The sketch path "save"/"load" use when the action gives none.
  std::filesystem::path sketchPath;
  /// Called with each action's index and a one-line description before it runs (logging).
  std::function<void(const ScriptAction&, const std::string&)> log;
  /// Runs a window verb (ScriptAction::Kind::Window); returns "" or what failed. Empty: window
  /// verbs fail ("needs a window").
  std::function<std::string(const ScriptAction&)> window;
};

struct ScriptReport {
  std::size_t actionsRun = 0;
  /// One line per failed action ("action 3 (export mesh.obj): no mesh to export ...").
  std::vector<std::string> failures;
  bool ok() const { return failures.empty(); }
};

/// Applies every action to `state` in order; an action that fails (an error status message, a
/// failed expectation, a failed screenshot) is recorded and the script goes on, as a person would.
ScriptReport runActionScript(ViewerState& state, const ActionScript& script, const ScriptHooks& hooks = {});

/// A one-line description of an action ("click (640, 300) left").
std::string describe(const ScriptAction& action);

}  // namespace treesketch::viewer
