// The window's costs, measured for bench/README.md (bench_viewer runs these): an idle window, and
// a mouse moving over the side panel. Each runs the interactive loop (draw only on change) and
// prints one line on stderr.
#pragma once

#include <cstdint>
#include <functional>

struct GLFWwindow;

namespace treesketch::gui {

/// What the measures need of the window's App (main.cpp).
struct MeasuredWindow {
  std::function<int()> pendingFrames;       ///< frames still to draw after the last event
  std::function<double()> nextWakeSeconds;  ///< App::nextWakeSeconds
  std::function<void()> frame;              ///< draws one frame
  std::function<std::uint64_t()> framesDrawn;
  std::function<std::uint64_t()> sceneDraws;  ///< frames that drew the 3D scene (the cloud) anew
};

/// --measure-idle S: the loop with no input; the first second after the cloud is taken in
/// (frames drawn then: the legend and the restore offer appear without a mouse move), then S
/// seconds measured: frames drawn and process CPU time.
int measureIdle(GLFWwindow* window, const MeasuredWindow& app, double seconds);
/// --measure-hover N: N mouse moves over the side panel, 50 ms apart, after a settling second;
/// frames drawn, scene draws (the cloud drawn anew) and CPU time, per move.
int measureHover(GLFWwindow* window, const MeasuredWindow& app, int moves);

}  // namespace treesketch::gui
