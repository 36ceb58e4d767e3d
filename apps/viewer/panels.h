// The window's Dear ImGui parts: the side panel (file actions, sketch tools, the selected node's
// sampling sizes and fit, display options, messages), the status bar, and the node markers drawn
// over the 3D view. Every button calls one ViewerState action; nothing here keeps sketch state.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "treesketch/viewer/viewer_state.h"

namespace treesketch::gui {

/// Window layout in pixels: the side panel on the left, the status bar at the bottom, the 3D view
/// in the rest.
struct Layout {
  static constexpr float kPanelWidth = 340.0f;
  static constexpr float kStatusHeight = 26.0f;
  /// The panel's Node section keeps this many rows' height whether a node is selected or not (a
  /// fitted node's details, its sizes and its buttons fit).
  static constexpr float kNodeSectionRows = 9.0f;
  /// The 3D view's rectangle for a window of `width` x `height` pixels.
  static geom::Viewport sceneViewport(int width, int height);
};

/// Marker fill colours (RGB), shared with the screenshot checker through the docs.
inline constexpr unsigned char kMarkerFitted[3] = {60, 220, 90};
inline constexpr unsigned char kMarkerSkipped[3] = {255, 80, 40};
inline constexpr unsigned char kMarkerPending[3] = {200, 200, 200};

struct PanelState {
  std::string sketchPath;  ///< the sketch file as the File menu and its dialogs last named it
  std::string meshPath = "treesketch_mesh.obj";
  std::string screenshotPath = "treesketch_screenshot.png";
  std::string inputName;  ///< shown at the top
  int autoNodes = 12;
  /// The automatic skeleton's leaves: leaf-off, in leaf (every point, the settings for leafy
  /// scans) or wood only (the classified wood, the leaf-off settings).
  static constexpr int kLeafOff = 0, kInLeaf = 1, kWoodOnly = 2;
  int autoLeaves = kLeafOff;
  bool screenshotRequested = false;  ///< set by the Screenshot button; the main loop takes it
  bool showHelp = true;
  /// A panel button pressed by a script (its label; empty: none), taken in by the next frame.
  std::string press;
};

/// What the panel's Files buttons do: the File menu's actions (window_ui.h), so that the panel and
/// the menu save, open and export one way, with the same dialogs and questions.
struct PanelFileActions {
  std::function<void()> openSketch, save, saveAs, exportMesh;
};

/// Builds the side panel and the status bar for this frame (between ImGui::NewFrame and Render).
/// `menuBar`, when given, draws the panel's menu bar (window_ui.h); `files` are the Files buttons'
/// actions (none: the buttons do nothing).
void drawPanels(viewer::ViewerState& state, PanelState& panel, int width, int height,
                const std::function<void()>& menuBar = {}, const PanelFileActions& files = {});
/// The correction tools section (tools_panel.cpp).
void toolsSection(viewer::ViewerState& state);
/// Draws node markers and parent links over the 3D view (ImGui background draw list).
void drawMarkers(const viewer::ViewerState& state);
/// Over the 3D view: the path of the drag being drawn (stroke, lasso, region) and the active tool's
/// name (bottom centre), so that no tool is used blind.
void drawToolOverlay(const viewer::ViewerState& state);

}  // namespace treesketch::gui
