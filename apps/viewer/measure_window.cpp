// The window's measured costs. See measure_window.h.
#include "measure_window.h"

#include <GLFW/glfw3.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "gui_args.h"
#include "panels.h"

namespace treesketch::gui {

namespace {

using Clock = std::chrono::steady_clock;

double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// The interactive loop (as main.cpp's) until `deadline`.
void loopUntil(GLFWwindow* window, const MeasuredWindow& app, Clock::time_point deadline) {
  while (!glfwWindowShouldClose(window)) {
    const auto now = Clock::now();
    if (now >= deadline) return;
    const double left = std::chrono::duration<double>(deadline - now).count();
    if (app.pendingFrames() > 0) {
      glfwPollEvents();
    } else {
      const double t = app.nextWakeSeconds();
      glfwWaitEventsTimeout(t < 0 ? left : std::min(t, left));
      if (Clock::now() >= deadline) return;  // woken only by the end of the measure
    }
    app.frame();
  }
}

Clock::time_point after(double seconds) {
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

int measureIdle(GLFWwindow* window, const MeasuredWindow& app, double seconds) {
  const std::uint64_t atLoad = app.framesDrawn();
  loopUntil(window, app, after(1.0));
  std::fprintf(stderr, "treesketch-gui: after load: %llu frames in the first second\n",
               static_cast<unsigned long long>(app.framesDrawn() - atLoad));
  const std::uint64_t frames0 = app.framesDrawn();
  const double cpu0 = cpuSeconds();
  const auto t0 = Clock::now();
  loopUntil(window, app, after(seconds));
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  const double cpu = cpuSeconds() - cpu0;
  const std::uint64_t frames = app.framesDrawn() - frames0;
  std::fprintf(stderr,
               "treesketch-gui: idle %.2f s: %llu frames drawn (%.2f per second), CPU %.3f s (%.2f %% of a core)\n",
               wall, static_cast<unsigned long long>(frames), double(frames) / wall, cpu, 100.0 * cpu / wall);
  return kExitOk;
}

int measureHover(GLFWwindow* window, const MeasuredWindow& app, int moves) {
  loopUntil(window, app, after(1.0));
  const std::uint64_t frames0 = app.framesDrawn(), scenes0 = app.sceneDraws();
  const double cpu0 = cpuSeconds();
  const auto t0 = Clock::now();
  for (int i = 0; i < moves; ++i) {
    // Down the panel's middle and back: the cursor stays over the panel's widgets.
    glfwSetCursorPos(window, Layout::kPanelWidth * 0.5 + 20.0 * (i % 2), 150.0 + 7.0 * (i % 60));
    loopUntil(window, app, after(0.05));
  }
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  const double cpu = cpuSeconds() - cpu0;
  const double n = moves > 0 ? double(moves) : 1.0;
  const std::uint64_t frames = app.framesDrawn() - frames0, scenes = app.sceneDraws() - scenes0;
  std::fprintf(stderr,
               "treesketch-gui: hover %d moves over the panel in %.2f s: %llu frames (%.2f per move), %llu scene "
               "draws (%.2f per move), CPU %.3f s (%.1f ms per move)\n",
               moves, wall, static_cast<unsigned long long>(frames), double(frames) / n,
               static_cast<unsigned long long>(scenes), double(scenes) / n, cpu, 1000.0 * cpu / n);
  return kExitOk;
}

}  // namespace treesketch::gui
