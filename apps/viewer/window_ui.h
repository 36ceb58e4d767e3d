// The window's own tools, beside the side panel: the menu bar (menu_bar.cpp), the open/save
// dialogs (file_dialog.cpp), the unsaved-work prompt, recent files, point picking and measuring,
// and the overlays over the 3D view (overlays.cpp: legend, axis gizmo, scale bar, picks, help).
// WindowActions holds what the menus, the keys and --script window verbs do, so the three cannot
// disagree; main.cpp only forwards to it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "file_dialog.h"
#include "panels.h"
#include "treesketch/viewer/action_script.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/picking.h"
#include "treesketch/viewer/recent_files.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::gui {

/// What the window needs from main.cpp.
struct WindowHooks {
  /// Asks the main loop to end (the window closes after this frame).
  std::function<void()> close;
  /// Whether the main loop is ending.
  std::function<bool()> closing;
  /// Moves the mouse pointer to window pixels (the script verb hover).
  std::function<void(const geom::Vec2&)> moveCursor;
  /// How many frames drew the 3D scene anew (the others showed the renderer's kept image).
  std::function<std::uint64_t()> sceneDraws;
};

class WindowActions {
 public:
  WindowActions(viewer::ViewerState& state, PanelState& panel, WindowHooks hooks);

  // ---- File ---------------------------------------------------------------------------------------
  void openCloudDialog();
  void openSketchDialog();
  /// Saves to the sketch path (the Save dialog when there is none); true on success.
  bool save();
  void saveAsDialog();
  void exportMeshDialog();
  /// The Save dialog for one of the model's other outputs (cylinder table, TreeQSM table, metrics,
  /// report), written as the command line writes them.
  void exportModelDialog(viewer::ViewerState::ModelFile what);
  /// Opens another cloud (asking about unsaved work first); the load happens at the start of the
  /// next frame, after a frame that says so. "" or a message.
  void requestOpenCloud(const std::filesystem::path& path);
  /// Loads a sketch file (asking about unsaved work first).
  void requestOpenSketch(const std::filesystem::path& path);
  void openRecent(std::size_t index);
  /// Quit from the menu, Ctrl+Q or the window's close button: asks about unsaved work.
  void requestQuit();

  // ---- the unsaved-work prompt ----------------------------------------------------------------------
  bool promptOpen() const { return promptOpen_; }
  /// Save (then go on if it worked), Discard (go on) or Cancel (stay).
  void answerPrompt(const std::string& answer);

  // ---- tools ----------------------------------------------------------------------------------------
  bool pickMode() const { return pickMode_; }
  void setPickMode(bool on);
  /// A click in pick mode at `screen` (window pixels). False when no point is near.
  bool pickAt(const geom::Vec2& screen);
  const viewer::PickSession& picks() const { return picks_; }
  void clearPicks() { picks_.clear(); }

  // ---- per frame ------------------------------------------------------------------------------------
  /// Runs a pending cloud load (call once per frame before drawing).
  void beforeFrame();
  /// A cloud load is waiting for its "Opening ..." frame: the window must not sleep until it runs.
  bool hasPendingWork() const { return !pendingOpen_.empty(); }
  /// Draws the menu bar (inside the side panel's window, see menu_bar.cpp), dialogs, prompt, help
  /// and about windows, and the overlays over the 3D view.
  void drawMenuBar();
  void drawWindows();
  void drawOverlays();
  /// Keys the window handles itself (F1, M, Ctrl+O, Ctrl+Shift+S, Ctrl+E, Ctrl+Q, Esc in pick mode,
  /// Ctrl+S through save()). `key` is the GLFW key code, `mods` viewer::Modifier bits. True when
  /// the key was taken (not forwarded to the state).
  bool onKey(int glfwKey, int mods);
  /// A --script window verb; "" or what failed.
  std::string runScriptVerb(const viewer::ScriptAction& action);

  FileDialog& dialog() { return dialog_; }
  bool helpOpen() const { return showHelp_; }
  void toggleHelp() { showHelp_ = !showHelp_; }
  const viewer::RecentFiles& recent() const { return recent_; }
  /// The legend of the current colouring, recomputed when the cloud or mode changes.
  const viewer::Legend& legend();
  /// Whether the last frame showed a tooltip.
  bool tooltipShown() const;

 private:
  void drawFileMenu();
  void drawViewMenu();
  std::string runMenuVerb(const viewer::ScriptAction& a);
  std::string expectWindow(const viewer::ScriptAction& a);
  double windowReading(const std::string& key);
  void flushPendingOpen();
  /// Runs `then` now when nothing would be lost, else after the prompt's Save or Discard.
  void guardUnsaved(const std::string& what, std::function<void()> then);
  void openCloudNow(const std::filesystem::path& path);
  void remember(viewer::RecentKind kind, const std::filesystem::path& path);
  std::filesystem::path dialogFolder() const;

  viewer::ViewerState& state_;
  PanelState& panel_;
  WindowHooks hooks_;
  FileDialog dialog_;
  viewer::RecentFiles recent_;
  std::filesystem::path recentPath_;
  bool promptOpen_ = false;
  std::string promptWhat_;
  std::function<void()> afterPrompt_;
  std::filesystem::path pendingOpen_;
  int pendingFrames_ = 0;
  bool pickMode_ = false;
  viewer::PickSession picks_;
  bool showHelp_ = false, showAbout_ = false;
  std::string forcedMenu_;  ///< a menu kept open by the script verb showMenu (screenshots)
  std::uint64_t sceneDrawsRead_ = 0;  ///< the scene draws at the last "sceneRedrawn" reading
  bool showLegend_ = true, showGizmo_ = true, showScaleBar_ = true;
  viewer::Legend legend_;
  std::uint64_t legendCloud_ = ~0ull;
  viewer::ColorMode legendMode_ = viewer::ColorMode::Plain;
};

}  // namespace treesketch::gui
