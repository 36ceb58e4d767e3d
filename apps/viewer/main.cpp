// treesketch-gui: the interactive sketching tool (`treesketch gui` runs it). A GLFW window with an
// OpenGL 3.3 core context (through GLEW) and Dear ImGui panels over a viewer::ViewerState, which
// holds everything the tool knows and does; this file only opens the window, loads the input
// (scanning a mesh first, with progress), forwards mouse and keys, draws, and runs --script
// sessions headless.
#include <GL/glew.h>
// GLEW must come before GLFW's GL header.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <tuple>

#include "build_info.h"
#include "dialogs.h"
#include "gui_args.h"
#include "measure_window.h"
#include "panels.h"
#include "renderer.h"
#include "screenshot.h"
#include "treesketch/io/file_info.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/cancel.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"
#include "treesketch/viewer/action_script.h"
#include "treesketch/viewer/demo_scene.h"
#include "treesketch/viewer/point_lod.h"
#include "treesketch/viewer/viewer_state.h"
#include "window_ui.h"

namespace fs = std::filesystem;
using namespace treesketch;

namespace {

using gui::Args;
using gui::kExitFailed;
using gui::kExitInput;
using gui::kExitOk;
using gui::kExitUsage;
using gui::parseArgs;
using gui::usage;

/// Loads the input on a worker thread so the window can show progress.
struct Loader {
  std::atomic<std::uint64_t> done{0}, total{0};
  std::atomic<bool> finished{false}, cancel{false};
  std::atomic<const char*> stage{"loading"};
  std::string error;
  geom::PointCloud cloud;
  std::thread thread;

  void start(const Args& args) {
    thread = std::thread([this, args] {
      // Cancel (the loading window's button) throws Cancelled from the next report.
      ProgressFn progress = cancellableProgress(cancel, [this](std::uint64_t d, std::uint64_t t) {
        done = d;
        total = t;
      });
      try {
        if (args.input.empty()) {
          stage = "scanning the demo tree";
          cloud = viewer::demoTreeCloud(args.demo, progress);
        } else {
          io::FileInfo info = io::inspectFile(args.input);
          if (info.isMesh) {
            stage = "scanning the mesh";
            cloud = scan::sphereScan(std::vector<geom::TriMesh>{info.mesh}, {}, progress).cloud;
            if (cloud.empty()) throw InputError(args.input + ": the scan of this mesh hit nothing");
          } else {
            cloud = std::move(info.cloud);
          }
        }
      } catch (const Cancelled&) {
        error = "cancelled";
      } catch (const std::exception& e) {
        error = e.what();
      }
      finished = true;
    });
  }
  ~Loader() {
    cancel = true;
    if (thread.joinable()) thread.join();
  }
};

const char* keyName(int key) {
  static char letter[2] = {0, 0};
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) {
    letter[0] = static_cast<char>('a' + (key - GLFW_KEY_A));
    return letter;
  }
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) {
    letter[0] = static_cast<char>('0' + (key - GLFW_KEY_0));
    return letter;
  }
  switch (key) {
    case GLFW_KEY_DELETE:
      return "delete";
    case GLFW_KEY_BACKSPACE:
      return "backspace";
    case GLFW_KEY_ESCAPE:
      return "escape";
    default:
      return nullptr;
  }
}

int toMods(int glfwMods) {
  int m = viewer::kModNone;
  if (glfwMods & GLFW_MOD_SHIFT) m |= viewer::kModShift;
  if (glfwMods & GLFW_MOD_CONTROL) m |= viewer::kModCtrl;
  if (glfwMods & GLFW_MOD_ALT) m |= viewer::kModAlt;
  return m;
}

class App {
 public:
  App(const Args& args, GLFWwindow* window) : args_(args), window_(window) {
    panel_.inputName = args.input.empty() ? "demo tree (" + args.demo.preset + ")" : args.input;
    renderer_ = std::make_unique<gui::Renderer>();
    gui::WindowHooks hooks;
    hooks.close = [this] { glfwSetWindowShouldClose(window_, GLFW_TRUE); };
    hooks.closing = [this] { return glfwWindowShouldClose(window_) != 0; };
    hooks.moveCursor = [this](const geom::Vec2& p) { glfwSetCursorPos(window_, p.x(), p.y()); };
    hooks.sceneDraws = [this] { return renderer_->sceneDraws(); };
    actions_ = std::make_unique<gui::WindowActions>(state_, panel_, hooks);
  }

  gui::WindowActions& actions() { return *actions_; }

  viewer::ViewerState& state() { return state_; }

  /// Draws one frame; writes `shot` (if given) from the back buffer before swapping.
  void frame(const fs::path* shot = nullptr) {
    const Stopwatch timer;
    const auto t0 = std::chrono::steady_clock::now();
    // Level of detail: while the view moves, a subsample within the adaptive budget; the whole
    // cloud when still and in screenshots.
    const bool moving = !loading() && !shot && state_.view().viewMoving(t0);
    int ww, wh, fbw, fbh;
    glfwGetWindowSize(window_, &ww, &wh);
    glfwGetFramebufferSize(window_, &fbw, &fbh);
    state_.view().setViewport(gui::Layout::sceneViewport(ww, wh));
    if (!loading()) {
      state_.pollJob();  // a finished background job's result comes in here
      actions_->beforeFrame();
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (loading())
      drawLoading(ww, wh);
    else {
      gui::drawPanels(
          state_, panel_, ww, wh, [this] { actions_->drawMenuBar(); }, panelFiles_);
      gui::drawMarkers(state_);
      gui::drawToolOverlay(state_);
      gui::drawRecoveryDialog(state_);
      gui::drawConfirmDialog(state_);
      gui::drawUpWarning(state_);
      gui::drawJobProgress(state_);
      actions_->drawOverlays();
      actions_->drawWindows();
    }
    ImGui::Render();
    glViewport(0, 0, fbw, fbh);
    glClearColor(gui::Renderer::kBackground[0], gui::Renderer::kBackground[1], gui::Renderer::kBackground[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!loading())
      renderer_->draw(state_, fbh, ww > 0 ? static_cast<double>(fbw) / ww : 1.0, moving ? pointBudget_ : SIZE_MAX);
    glViewport(0, 0, fbw, fbh);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (shot) gui::writeScreenshot(*shot, fbw, fbh);
    if (panel_.screenshotRequested) {
      panel_.screenshotRequested = false;
      try {
        gui::writeScreenshot(panel_.screenshotPath, fbw, fbh);
        state_.status().info("screenshot written to " + panel_.screenshotPath);
      } catch (const std::exception& e) {
        state_.status().error(std::string("screenshot: ") + e.what());
      }
    }
    glfwSwapBuffers(window_);
    const double ms = timer.ms();
    ++framesDrawn_;
    // Frame times of the 3D view (not the loading screen, not the first frame, which uploads the
    // cloud and compiles the shaders).
    if (!loading() && renderedOnce_) (moving ? movingStats_ : stillStats_).add(ms);
    if (!loading()) renderedOnce_ = true;
    if (moving)
      pointBudget_ =
          viewer::adaptPointBudget(pointBudget_, ms, kMovingFrameMs, kMinLodPoints, renderer_->cloudPoints());
    // A change since the last frame (a cloud taken in, a job's result, a question) is shown at
    // once, not at the next mouse move.
    if (shown() != shownLast_)
      wake();
    else if (pendingFrames_ > 0)
      --pendingFrames_;
    shownLast_ = shown();
  }

  // ---- redraw on change -------------------------------------------------------------------------
  /// An input event arrived: draw a few frames (Dear ImGui settles hover and focus over two or
  /// three), then sleep until the next event.
  void wake() { pendingFrames_ = 3; }
  int pendingFrames() const { return pendingFrames_; }
  /// What a frame shows that may change without an input event (Dear ImGui lays a new window out
  /// or opens a popup over the next two or three frames).
  using Shown = std::tuple<std::uint64_t, std::uint64_t, std::uint64_t, bool, bool, bool>;
  Shown shown() const {
    return {state_.cloudVersion(),          state_.sceneVersion(),
            state_.scene().colorsVersion(), state_.document().recoveryPending(),
            state_.confirmationPending(),   loading()};
  }
  /// Seconds until something changes by itself (a job's or the loading's progress: 10 Hz; an info
  /// message expiring; the moving view settling into the full cloud); negative: nothing will, wait
  /// for an event.
  double nextWakeSeconds() const {
    if (loading() || state_.jobs().busy()) return 0.1;
    if (actions_ && actions_->hasPendingWork()) return 0.0;  // the next frame opens the cloud
    const auto now = std::chrono::steady_clock::now();
    double t = -1.0;
    auto consider = [&](std::chrono::steady_clock::time_point when) {
      if (when <= now) return;
      double s = std::chrono::duration<double>(when - now).count() + 0.005;
      t = t < 0 ? s : std::min(t, s);
    };
    if (auto expiry = state_.status().expiry()) consider(*expiry);
    if (state_.view().viewMoving(now)) consider(state_.view().viewSettles());
    return t;
  }
  std::uint64_t framesDrawn() const { return framesDrawn_; }
  std::uint64_t sceneDraws() const { return renderer_->sceneDraws(); }
  struct FrameStats {
    std::uint64_t count = 0;
    double sumMs = 0, maxMs = 0;
    void add(double ms) { ++count, sumMs += ms, maxMs = std::max(maxMs, ms); }
    double meanMs() const { return count ? sumMs / double(count) : 0.0; }
  };
  /// One line for the log: frames drawn while the view moved (subsampled) and while it was still.
  std::string frameStatsLine() const {
    char text[256];
    std::snprintf(text, sizeof text,
                  "frames: %llu moving (mean %.1f ms, max %.1f ms, budget now %zu of %zu points), %llu still "
                  "(mean %.1f ms, max %.1f ms)",
                  static_cast<unsigned long long>(movingStats_.count), movingStats_.meanMs(), movingStats_.maxMs,
                  pointBudget_, renderer_->cloudPoints(), static_cast<unsigned long long>(stillStats_.count),
                  stillStats_.meanMs(), stillStats_.maxMs);
    return text;
  }

  /// Starts loading the input; frames show progress until finish() succeeds.
  void startLoading() { loader_.start(args_); }
  bool loading() const { return !loaded_; }
  /// Takes the loaded cloud into the state once the worker is done. Returns false while loading;
  /// sets `failed` when the input could not be read.
  bool pollLoaded(bool* failed) {
    *failed = false;
    if (loaded_) return true;
    if (!loader_.finished) return false;
    loader_.thread.join();
    loaded_ = true;
    wake();  // the cloud, its legend and any restore offer are drawn now, not at the next mouse move
    if (!loader_.error.empty()) {
      state_.status().error("open: " + loader_.error);
      *failed = true;
      return true;
    }
    // Up: the library's rule (viewer::chooseViewUp: --up, else the file's declaration, else Z;
    // the demo tree is Y-up); a direction the library has no axis for only turns the view.
    viewer::ViewUpChoice up = viewer::chooseViewUp(args_.up, loader_.cloud, args_.input.empty());
    const std::string upReason = up.reason;
    state_.setCloud(std::move(loader_.cloud), up.axis, args_.input.empty() ? fs::path() : fs::path(args_.input));
    if (up.view != viewer::toUpDirection(up.axis)) state_.setUpDirection(up.view);
    std::cerr << "treesketch-gui: up " << viewer::toString(state_.view().upDirection()) << " (" << upReason << ")\n";
    // The demo tree has no file: its sketch and autosave are named after it in the current folder.
    if (args_.input.empty()) {
      state_.setAutosavePath("treesketch_demo.autosave.sketch.json");
      state_.setSketchPath("treesketch_demo.sketch.json");
    }
    if (!args_.autosavePath.empty()) state_.setAutosavePath(args_.autosavePath);
    // --sketch, else the cloud's own sketch file (tree.las -> tree.las.sketch.json), loaded when
    // it is there; one made for another cloud asks first.
    if (!args_.sketchPath.empty()) state_.setSketchPath(args_.sketchPath);
    panel_.sketchPath = state_.document().sketchPath().string();
    std::error_code ec;
    if (!state_.document().sketchPath().empty() && fs::exists(state_.document().sketchPath(), ec))
      state_.loadSketch(state_.document().sketchPath());
    return true;
  }

  // ---- input forwarding (GLFW callbacks, chained before ImGui's) --------------------------------
  void onMouseButton(int button, int action, int mods) {
    viewer::MouseButton b = button == GLFW_MOUSE_BUTTON_RIGHT    ? viewer::MouseButton::Right
                            : button == GLFW_MOUSE_BUTTON_MIDDLE ? viewer::MouseButton::Middle
                                                                 : viewer::MouseButton::Left;
    if (button > GLFW_MOUSE_BUTTON_MIDDLE || loading()) return;
    double x, y;
    glfwGetCursorPos(window_, &x, &y);
    if (action == GLFW_PRESS) {
      if (ImGui::GetIO().WantCaptureMouse) return;
      if (b == viewer::MouseButton::Left && !(mods & GLFW_MOD_ALT) && actions_->pickMode()) {
        actions_->pickAt({x, y});  // pick mode: a left click picks instead of sketching
        return;
      }
      sceneButton_[button] = true;
      state_.mouseDown({x, y}, b, toMods(mods));
    } else if (action == GLFW_RELEASE && sceneButton_[button]) {
      sceneButton_[button] = false;
      state_.mouseUp({x, y}, b, toMods(mods));
    }
  }
  void onCursor(double x, double y) {
    if (!loading()) state_.mouseMove({x, y});
  }
  void onScroll(double dy) {
    if (!loading() && !ImGui::GetIO().WantCaptureMouse) state_.scroll(dy);
  }
  void onKey(int key, int action, int mods) {
    if (action == GLFW_RELEASE || loading() || ImGui::GetIO().WantCaptureKeyboard) return;
    if (action == GLFW_PRESS && actions_->onKey(key, toMods(mods))) return;  // F1, M, Ctrl+O/S/E/Q
    if (const char* name = keyName(key)) state_.keyPress(name, toMods(mods));
  }

 private:
  void drawLoading(int ww, int wh) {
    ImGui::SetNextWindowPos(ImVec2(ww * 0.5f, wh * 0.5f), 0, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(420, 0));
    ImGui::Begin("Loading", nullptr, ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove);
    ImGui::TextUnformatted(panel_.inputName.c_str());
    std::uint64_t t = loader_.total, d = loader_.done;
    float f = t > 0 ? static_cast<float>(static_cast<double>(d) / static_cast<double>(t)) : 0.0f;
    ImGui::TextUnformatted(loader_.stage.load());
    ImGui::ProgressBar(f);
    // Reading a file reports nothing until it is read; a mesh scan and the demo scan report often.
    ImGui::BeginDisabled(loader_.cancel);
    if (ImGui::Button("Cancel##loading")) loader_.cancel = true;
    ImGui::EndDisabled();
    ImGui::End();
  }

  Args args_;
  GLFWwindow* window_;
  viewer::ViewerState state_;
  gui::PanelState panel_;
  std::unique_ptr<gui::Renderer> renderer_;
  std::unique_ptr<gui::WindowActions> actions_;
  /// The panel's Files buttons: the File menu's actions.
  const gui::PanelFileActions panelFiles_{[this] { actions_->openSketchDialog(); }, [this] { actions_->save(); },
                                          [this] { actions_->saveAsDialog(); },
                                          [this] { actions_->exportMeshDialog(); }};
  Loader loader_;
  bool loaded_ = false;
  bool sceneButton_[3] = {false, false, false};
  /// A moving frame aims at 50 ms (20 frames a second: an orbit that follows the hand), and never
  /// draws fewer than 20,000 points (the tree's shape stays readable).
  static constexpr double kMovingFrameMs = 50.0;
  static constexpr std::size_t kMinLodPoints = 20000;
  std::size_t pointBudget_ = 200000;
  int pendingFrames_ = 3;
  Shown shownLast_{};
  bool renderedOnce_ = false;
  std::uint64_t framesDrawn_ = 0;
  FrameStats movingStats_, stillStats_;
};

App* appOf(GLFWwindow* w) { return static_cast<App*>(glfwGetWindowUserPointer(w)); }

// The GLFW window with an OpenGL 3.3 core context and GLEW loaded; nullptr (after saying why on
// stderr) when there is none.
GLFWwindow* openWindow(const Args& args, int width, int height) {
  glfwSetErrorCallback(
      [](int code, const char* text) { std::fprintf(stderr, "treesketch-gui: GLFW %d: %s\n", code, text); });
  if (!glfwInit()) {
    std::cerr << "treesketch-gui: error: cannot open a window (no display? set DISPLAY, or run under xvfb-run)\n";
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GL_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, args.scriptPath.empty() ? GLFW_TRUE : GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(width, height, "treesketch", nullptr, nullptr);
  if (!window) {
    std::cerr << "treesketch-gui: error: cannot create an OpenGL 3.3 core window\n";
    glfwTerminate();
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(args.scriptPath.empty() ? 1 : 0);
  glewExperimental = GL_TRUE;
  GLenum glewStatus = glewInit();
  glGetError();  // GLEW may leave GL_INVALID_ENUM behind on core profiles
  if (glewStatus != GLEW_OK && glewStatus != 4 /* GLEW_ERROR_NO_GLX_DISPLAY on Wayland-only builds */) {
    std::cerr << "treesketch-gui: error: GLEW: " << reinterpret_cast<const char*>(glewGetErrorString(glewStatus))
              << "\n";
    glfwDestroyWindow(window);
    glfwTerminate();
    return nullptr;
  }
  return window;
}

// Every event wakes the window for a few frames (redraw only when something changes).
void installCallbacks(GLFWwindow* window, App& app) {
  glfwSetWindowUserPointer(window, &app);
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int b, int a, int m) {
    appOf(w)->wake();
    appOf(w)->onMouseButton(b, a, m);
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    appOf(w)->wake();
    appOf(w)->onCursor(x, y);
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
    appOf(w)->wake();
    appOf(w)->onScroll(dy);
  });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int k, int, int a, int m) {
    appOf(w)->wake();
    appOf(w)->onKey(k, a, m);
  });
  glfwSetCharCallback(window, [](GLFWwindow* w, unsigned int) { appOf(w)->wake(); });
  glfwSetWindowSizeCallback(window, [](GLFWwindow* w, int, int) { appOf(w)->wake(); });
  glfwSetWindowRefreshCallback(window, [](GLFWwindow* w) { appOf(w)->wake(); });
  glfwSetWindowFocusCallback(window, [](GLFWwindow* w, int) { appOf(w)->wake(); });
  glfwSetCursorEnterCallback(window, [](GLFWwindow* w, int) { appOf(w)->wake(); });
  // The close button asks about unsaved work first (WindowActions::requestQuit closes when done).
  glfwSetWindowCloseCallback(window, [](GLFWwindow* w) {
    glfwSetWindowShouldClose(w, GLFW_FALSE);
    appOf(w)->wake();
    appOf(w)->actions().requestQuit();
  });
}

// Runs the action script against the window; returns the exit code.
int runScript(App& app, const Args& args, const viewer::ActionScript& script) {
  viewer::ScriptHooks hooks;
  hooks.frame = [&] {
    glfwPollEvents();
    app.frame();
  };
  hooks.screenshot = [&](const fs::path& p) { app.frame(&p); };
  hooks.sketchPath = args.sketchPath;
  hooks.window = [&](const viewer::ScriptAction& a) { return app.actions().runScriptVerb(a); };
  hooks.log = [](const viewer::ScriptAction&, const std::string& what) {
    std::cerr << "treesketch-gui: " << what << "\n";
  };
  viewer::ScriptReport report = viewer::runActionScript(app.state(), script, hooks);
  for (const std::string& f : report.failures) std::cerr << "treesketch-gui: failed: " << f << "\n";
  std::cerr << "treesketch-gui: " << report.actionsRun << " actions, " << report.failures.size()
            << " failed; last rebuild " << app.state().lastRebuildMs() << " ms\n";
  return report.ok() ? kExitOk : kExitFailed;
}

// The interactive loop, until the window closes.
void runInteractive(App& app, GLFWwindow* window) {
  // Redraw only when something changes: block in glfwWaitEvents until an event, or until the
  // next thing that changes by itself (App::nextWakeSeconds).
  while (!glfwWindowShouldClose(window)) {
    if (app.pendingFrames() > 0) {
      glfwPollEvents();
    } else if (double t = app.nextWakeSeconds(); t < 0) {
      glfwWaitEvents();
    } else {
      glfwWaitEventsTimeout(t);
    }
    app.frame();
  }
}

int run(const Args& args) {
  viewer::ActionScript script;
  if (!args.scriptPath.empty()) script = viewer::parseActionScript(fs::path(args.scriptPath));
  int width = args.scriptPath.empty() ? args.width : script.windowWidth;
  int height = args.scriptPath.empty() ? args.height : script.windowHeight;

  GLFWwindow* window = openWindow(args, width, height);
  if (!window) return kExitFailed;

  int code = kExitOk;
  {
    App app(args, window);
    installCallbacks(window, app);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains to the callbacks above
    ImGui_ImplOpenGL3_Init("#version 330 core");

    app.startLoading();
    bool failed = false;
    while (!app.pollLoaded(&failed) && !glfwWindowShouldClose(window)) {
      glfwPollEvents();
      app.frame();
      std::this_thread::sleep_for(std::chrono::milliseconds(15));
    }
    if (!args.scriptPath.empty()) {
      if (failed) {
        std::cerr << "treesketch-gui: error: " << app.state().status().lastMessage().text << "\n";
        code = kExitInput;
      } else {
        code = runScript(app, args, script);
      }
    } else if (args.measureIdleSeconds > 0 || args.measureHoverMoves > 0) {
      const gui::MeasuredWindow m{[&] { return app.pendingFrames(); }, [&] { return app.nextWakeSeconds(); },
                                  [&] { app.frame(); }, [&] { return app.framesDrawn(); },
                                  [&] { return app.sceneDraws(); }};
      code = args.measureHoverMoves > 0 ? gui::measureHover(window, m, args.measureHoverMoves)
                                        : gui::measureIdle(window, m, args.measureIdleSeconds);
    } else {
      runInteractive(app, window);
    }
    if (!args.scriptPath.empty()) std::cerr << "treesketch-gui: " << app.frameStatsLine() << "\n";
    app.state().jobs().cancel();  // closing the window stops a background job (its result is dropped)
    app.state().waitForJob();
    // A clean end: the autosave goes when it holds nothing unsaved; else it is offered next time.
    // Scripted sessions keep it: their tests inspect it afterwards.
    if (args.scriptPath.empty()) app.state().closeSession();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  treesketch::removeTempFilesOnSignals();  // a sketch being saved when the window is killed leaves no temp file
  Args args;
  try {
    args = parseArgs(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "treesketch-gui: error: " << e.what() << "\n";
    usage(std::cerr);
    return kExitUsage;
  }
  try {
    return run(args);
  } catch (const InputError& e) {
    std::cerr << "treesketch-gui: error: " << e.what() << "\n";
    return kExitInput;
  } catch (const OptionsError& e) {
    std::cerr << "treesketch-gui: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "treesketch-gui: error: " << e.what() << "\n";
    return kExitFailed;
  }
}
