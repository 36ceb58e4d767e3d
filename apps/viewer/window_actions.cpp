// WindowActions: what the menus, the window's keys and --script window verbs do (see window_ui.h).
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>  // FindWindowByName: is a tooltip up

#include <cmath>
#include <sstream>

#include "treesketch/io/file_info.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/unsaved_work.h"
#include "window_ui.h"

namespace treesketch::gui {

namespace fs = std::filesystem;

WindowActions::WindowActions(viewer::ViewerState& state, PanelState& panel, WindowHooks hooks)
    : state_(state), panel_(panel), hooks_(std::move(hooks)) {
  recentPath_ = viewer::recentFilesPath(viewer::configDirectory());
  std::string message = recent_.load(recentPath_);
  if (!message.empty()) state_.status().info(message);
}

void WindowActions::remember(viewer::RecentKind kind, const fs::path& path) {
  recent_.add(kind, path);
  std::string message = recent_.save(recentPath_);
  if (!message.empty()) state_.status().info(message);
}

fs::path WindowActions::dialogFolder() const {
  fs::path p =
      state_.document().sketchPath().empty() ? fs::path() : fs::absolute(state_.document().sketchPath()).parent_path();
  return p;
}

// ---- File -----------------------------------------------------------------------------------------

void WindowActions::openCloudDialog() {
  dialog_.open(FileDialog::Mode::Open, "Open a point cloud (or a mesh, which is scanned)", viewer::cloudFileFilter(),
               dialogFolder(), "", [this](const fs::path& p) {
                 requestOpenCloud(p);
                 return std::string();
               });
}

void WindowActions::openSketchDialog() {
  dialog_.open(FileDialog::Mode::Open, "Open a sketch", viewer::sketchFileFilter(), dialogFolder(), "",
               [this](const fs::path& p) {
                 requestOpenSketch(p);
                 return std::string();
               });
}

bool WindowActions::save() {
  if (state_.document().sketchPath().empty()) {
    saveAsDialog();
    return false;
  }
  if (!state_.saveSketch(state_.document().sketchPath())) return false;
  remember(viewer::RecentKind::Sketch, state_.document().sketchPath());
  return true;
}

void WindowActions::saveAsDialog() {
  fs::path current = state_.document().sketchPath();
  dialog_.open(FileDialog::Mode::Save, "Save the sketch as", viewer::sketchFileFilter(), dialogFolder(),
               current.filename().string(), [this](const fs::path& p) {
                 // The dialog asked before replacing a file: no second question.
                 if (!state_.saveSketch(p, true)) return state_.status().lastMessage().text;
                 state_.setSketchPath(p);
                 panel_.sketchPath = p.string();
                 remember(viewer::RecentKind::Sketch, p);
                 return std::string();
               });
}

void WindowActions::exportMeshDialog() {
  fs::path current = panel_.meshPath;
  dialog_.open(FileDialog::Mode::Save, "Export the mesh (OBJ or PLY)", viewer::meshFileFilter(),
               current.has_parent_path() ? fs::absolute(current).parent_path() : dialogFolder(),
               current.filename().string(), [this](const fs::path& p) {
                 if (!state_.exportMesh(p)) return state_.status().lastMessage().text;
                 panel_.meshPath = p.string();
                 return std::string();
               });
}

void WindowActions::exportModelDialog(viewer::ViewerState::ModelFile what) {
  using F = viewer::ViewerState::ModelFile;
  struct Kind {
    const char* title;
    viewer::FileFilter filter;
    const char* suffix;
  };
  const Kind kind = what == F::Cylinders ? Kind{"Export the cylinder table (CSV)", {"CSV", {".csv"}}, "_cylinders.csv"}
                    : what == F::Qsm     ? Kind{"Export the cylinders in TreeQSM's layout", {"Text", {".txt"}}, "_qsm.txt"}
                    : what == F::Metrics ? Kind{"Export the tree metrics (JSON)", {"JSON", {".json"}}, "_metrics.json"}
                                         : Kind{"Export the fit report (JSON)", {"JSON", {".json"}}, "_report.json"};
  const fs::path source =
      state_.document().sketchPath().empty() ? fs::path(panel_.meshPath) : state_.document().sketchPath();
  const std::string name = (source.empty() ? std::string("tree") : source.stem().string()) + kind.suffix;
  dialog_.open(FileDialog::Mode::Save, kind.title, kind.filter, dialogFolder(), name, [this, what](const fs::path& p) {
    return state_.exportModel(what, p) ? std::string() : state_.status().lastMessage().text;
  });
}

void WindowActions::requestOpenCloud(const fs::path& path) {
  guardUnsaved("opening " + path.filename().string(), [this, path] {
    pendingOpen_ = path;
    pendingFrames_ = 1;  // one frame says "opening ...", the next loads
  });
}

void WindowActions::requestOpenSketch(const fs::path& path) {
  guardUnsaved("opening " + path.filename().string(), [this, path] {
    if (!state_.loadSketch(path)) return;
    state_.setSketchPath(path);
    panel_.sketchPath = path.string();
    remember(viewer::RecentKind::Sketch, path);
  });
}

void WindowActions::openRecent(std::size_t index) {
  if (index >= recent_.entries().size()) {
    state_.status().error("recent files: there is no entry " + std::to_string(index));
    return;
  }
  viewer::RecentFile e = recent_.entries()[index];
  std::error_code ec;
  if (!fs::exists(e.path, ec)) {
    state_.status().error(e.path.string() + ": no longer exists (removed from the recent files)");
    recent_.remove(e);
    recent_.save(recentPath_);
    return;
  }
  if (e.kind == viewer::RecentKind::Cloud)
    requestOpenCloud(e.path);
  else
    requestOpenSketch(e.path);
}

void WindowActions::openCloudNow(const fs::path& path) {
  geom::PointCloud cloud;
  try {
    io::FileInfo info = io::inspectFile(path);
    if (info.isMesh) {
      state_.status().info("scanning mesh " + path.string());
      cloud = scan::sphereScan(std::vector<geom::TriMesh>{info.mesh}, {}).cloud;
      if (cloud.empty()) throw InputError(path.string() + ": the scan of this mesh hit nothing");
    } else {
      cloud = std::move(info.cloud);
    }
  } catch (const std::exception& e) {
    state_.status().error(std::string("open: ") + e.what());  // the current cloud and sketch stay
    return;
  }
  // The up-axis rule of the CLI (io/up_axis.h): the file's declaration, else Z (field scans).
  io::UpAxisChoice up = io::chooseUpAxis("", cloud);
  if (!state_.setCloud(std::move(cloud), up.up, path)) return;
  state_.status().info("up axis: " + up.reason);
  panel_.inputName = path.string();
  // The cloud's own sketch file (tree.las -> tree.las.sketch.json), set by setCloud.
  const fs::path sketch = state_.document().sketchPath();
  panel_.sketchPath = sketch.string();
  picks_.clear();
  remember(viewer::RecentKind::Cloud, path);
  std::error_code ec;
  if (!sketch.empty() && fs::exists(sketch, ec) && state_.loadSketch(sketch))
    state_.status().info("loaded the sketch saved beside it, " + sketch.filename().string());
}

void WindowActions::requestQuit() {
  guardUnsaved("quitting", [this] {
    if (hooks_.close) hooks_.close();
  });
}

void WindowActions::guardUnsaved(const std::string& what, std::function<void()> then) {
  if (!viewer::hasUnsavedWork(state_)) {
    then();
    return;
  }
  promptOpen_ = true;
  promptWhat_ = what;
  afterPrompt_ = std::move(then);
}

void WindowActions::answerPrompt(const std::string& answer) {
  if (!promptOpen_) return;
  if (answer == "cancel") {
    promptOpen_ = false;
    afterPrompt_ = nullptr;
    return;
  }
  if (answer == "save" && state_.document().sketchPath().empty()) {
    // The Save dialog cannot open over the prompt (one modal at a time): say what to do instead.
    state_.status().error("save: the sketch has no file; type one in Files (or Cancel and use Save sketch as...)");
    return;
  }
  if (answer == "save" && !save()) return;  // the prompt stays; the error is in the status bar
  if (answer == "discard") state_.discardUnsavedWork();  // and its autosave, not offered back
  promptOpen_ = false;
  std::function<void()> then = std::move(afterPrompt_);
  afterPrompt_ = nullptr;
  if (then) then();
}

// ---- tools ------------------------------------------------------------------------------------------

void WindowActions::setPickMode(bool on) {
  pickMode_ = on;
  state_.status().info(
      on ? "pick mode: left click picks a point; a second pick measures the distance (M or Esc to leave)"
         : "pick mode off: left click sketches again");
}

bool WindowActions::pickAt(const geom::Vec2& screen) {
  // Within the point's drawn size, and never less than a few pixels (design choice: 6 px).
  double radius = std::max(6.0, 1.5 * static_cast<double>(state_.view().display().pointSize));
  viewer::PickedPoint p = viewer::pickPoint(state_.cloud(), state_.view().camera(), screen, radius);
  if (!picks_.add(p)) {
    state_.status().info("pick: no point within " + std::to_string(static_cast<int>(radius)) + " px");
    return false;
  }
  std::vector<std::string> lines = viewer::describePoint(state_.cloud(), p.index);
  std::string text = "picked point " + std::to_string(p.index) + ": " + (lines.empty() ? "" : lines[0]);
  if (picks_.hasMeasurement()) {
    viewer::Measurement m = picks_.measurement(state_.up());
    char buf[160];
    std::snprintf(buf, sizeof buf, "; distance %.4f (vertical %.4f, horizontal %.4f)", m.distance, m.vertical,
                  m.horizontal);
    text += buf;
  }
  state_.status().info(text);
  return true;
}

bool WindowActions::tooltipShown() const {
  ImGuiWindow* w = ImGui::FindWindowByName("##Tooltip_00");  // Dear ImGui's name for the first tooltip
  return w && w->Active;
}

// ---- per frame -----------------------------------------------------------------------------------------

void WindowActions::beforeFrame() {
  if (pendingOpen_.empty()) return;
  if (pendingFrames_-- > 0) return;
  fs::path p = std::move(pendingOpen_);
  pendingOpen_.clear();
  openCloudNow(p);
}

const viewer::Legend& WindowActions::legend() {
  // Only the attribute legends cost O(points) (quantiles, class counts): those are cached per cloud
  // and mode. Height and distance legends follow the view's up, the colour scale and the fits,
  // and are O(1): made afresh every frame so they never go stale.
  const viewer::ColorMode mode = state_.view().display().colorMode;
  // The wood class legend's counts are kept by the state (O(1)).
  const bool perPoint = mode == viewer::ColorMode::Intensity || mode == viewer::ColorMode::Classification;
  if (!perPoint || legendCloud_ != state_.cloudVersion() || legendMode_ != mode) {
    legend_ = viewer::colorLegend(state_);
    legendCloud_ = state_.cloudVersion();
    legendMode_ = state_.view().display().colorMode;
  }
  return legend_;
}

bool WindowActions::onKey(int key, int mods) {
  const bool ctrl = mods & viewer::kModCtrl, shift = mods & viewer::kModShift;
  if (key == GLFW_KEY_F1) {
    toggleHelp();
  } else if (key == GLFW_KEY_M && !ctrl) {
    setPickMode(!pickMode_);
  } else if (key == GLFW_KEY_O && ctrl) {
    openCloudDialog();
  } else if (key == GLFW_KEY_S && ctrl && shift) {
    saveAsDialog();
  } else if (key == GLFW_KEY_S && ctrl) {
    save();
  } else if (key == GLFW_KEY_E && ctrl) {
    exportMeshDialog();
  } else if (key == GLFW_KEY_Q && ctrl) {
    requestQuit();
  } else if (key == GLFW_KEY_ESCAPE && pickMode_ && picks_.count() > 0) {
    picks_.clear();
  } else if (key == GLFW_KEY_ESCAPE && pickMode_) {
    setPickMode(false);
  } else {
    return false;
  }
  return true;
}

// What an expectWindow key (other than the distances) reads from the window.
double WindowActions::windowReading(const std::string& key) {
  double got = 0.0;
  if (key == "dialogOpen")
    got = dialog_.isOpen();
  else if (key == "dialogEntries")
    got = static_cast<double>(dialog_.listing().entries.size());
  else if (key == "promptOpen")
    got = promptOpen_;
  else if (key == "picks")
    got = picks_.count();
  else if (key == "recent")
    got = static_cast<double>(recent_.entries().size());
  else if (key == "quitting")
    got = hooks_.closing && hooks_.closing();
  else if (key == "helpOpen")
    got = showHelp_;
  else if (key == "legendClasses")
    got = static_cast<double>(legend().classes.size());
  else if (key == "dialogError")
    got = dialog_.isOpen() && !dialog_.error().empty();
  else if (key == "tooltip")
    got = tooltipShown();
  else if (key == "sceneRedrawn") {
    // Drawn anew since the last reading: a frame drawn for the panel alone reuses the scene's image.
    const std::uint64_t draws = hooks_.sceneDraws ? hooks_.sceneDraws() : 0;
    got = draws > sceneDrawsRead_;
    sceneDrawsRead_ = draws;
  }
  return got;
}

// {"expectWindow": {...}}: what differs ("" when every key holds).
std::string WindowActions::expectWindow(const viewer::ScriptAction& a) {
  std::string failure;
  for (const auto& [key, want] : a.expect) {
    double got = 0.0;
    bool ok;
    if (key == "distanceMin" || key == "distanceMax") {
      if (!picks_.hasMeasurement()) {
        failure += (failure.empty() ? "" : "; ") + key + ": no measurement (two picks needed)";
        continue;
      }
      got = picks_.measurement(state_.up()).distance;
      ok = key == "distanceMin" ? got >= want : got <= want;
    } else {
      got = windowReading(key);
      ok = got == want;
    }
    if (!ok) {
      std::ostringstream s;
      s << key << ": expected "
        << (key == "distanceMin"   ? "at least "
            : key == "distanceMax" ? "at most "
                                   : "")
        << want << ", got " << got;
      failure += (failure.empty() ? "" : "; ") + s.str();
    }
  }
  return failure;
}

// {"menu": ...}: the menu item's action; returns what failed ("").
std::string WindowActions::runMenuVerb(const viewer::ScriptAction& a) {
  const std::string& m = a.text;
  if (m == "open-cloud")
    openCloudDialog();
  else if (m == "open-sketch")
    openSketchDialog();
  else if (m == "save")
    save();
  else if (m == "save-as")
    saveAsDialog();
  else if (m == "export")
    exportMeshDialog();
  else if (m == "export-cylinders")
    exportModelDialog(viewer::ViewerState::ModelFile::Cylinders);
  else if (m == "export-qsm")
    exportModelDialog(viewer::ViewerState::ModelFile::Qsm);
  else if (m == "export-metrics")
    exportModelDialog(viewer::ViewerState::ModelFile::Metrics);
  else if (m == "export-report")
    exportModelDialog(viewer::ViewerState::ModelFile::Report);
  else if (m == "quit")
    requestQuit();
  else if (m == "help")
    toggleHelp();
  else if (m == "about")
    showAbout_ = !showAbout_;
  else if (m == "reset-camera")
    state_.view().presetView(geom::PresetView::Front);
  else if (m == "pick-mode")
    setPickMode(!pickMode_);
  else if (m == "recent") {
    if (a.value < 0 || a.value != std::floor(a.value)) return "menu recent: value must be an index 0, 1, ...";
    openRecent(static_cast<std::size_t>(a.value));
  }
  return {};
}

// A script does not wait for the "opening ..." frame: load now, so the next action sees it.
void WindowActions::flushPendingOpen() {
  if (!pendingOpen_.empty()) {
    pendingFrames_ = 0;
    beforeFrame();
  }
}

std::string WindowActions::runScriptVerb(const viewer::ScriptAction& a) {
  const std::size_t errorsBefore = state_.status().errorCount();
  if (a.name == "menu") {
    if (std::string failure = runMenuVerb(a); !failure.empty()) return failure;
    flushPendingOpen();
  } else if (a.name == "dialog") {
    if (!dialog_.isOpen()) return "dialog " + a.text + ": no dialog is open";
    if (!a.path.empty()) dialog_.setTyped(a.path.string());
    if (a.text == "ok") dialog_.accept();
    if (a.text == "cancel") dialog_.cancel();
    flushPendingOpen();
    // An error the dialog shows (no such file, a folder that cannot be read) fails the action.
    if (a.text == "ok" && dialog_.isOpen() && !dialog_.error().empty()) return "dialog: " + dialog_.error();
  } else if (a.name == "prompt") {
    if (!promptOpen_) return "prompt " + a.text + ": no prompt is open";
    answerPrompt(a.text);
    flushPendingOpen();
  } else if (a.name == "pick") {
    if (!pickMode_) setPickMode(true);
    if (!pickAt(a.from)) return state_.status().lastMessage().text;
  } else if (a.name == "hover") {
    if (!hooks_.moveCursor) return "hover needs a window";
    hooks_.moveCursor(a.from);
  } else if (a.name == "panel") {
    panel_.press = a.text;  // the next frame's panel presses it
  } else if (a.name == "showMenu") {
    forcedMenu_ = a.text == "none" ? std::string() : a.text;
  } else if (a.name == "closeWindow") {
    requestQuit();
  } else if (a.name == "expectWindow") {
    return expectWindow(a);
  }
  if (state_.status().errorCount() > errorsBefore) return state_.status().lastMessage().text;
  return {};
}

}  // namespace treesketch::gui
