// treesketch-gui's command line: what it takes, its usage text and its exit codes.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "treesketch/viewer/demo_scene.h"

namespace treesketch::gui {

constexpr int kExitOk = 0, kExitFailed = 1, kExitUsage = 2, kExitInput = 3;

struct Args {
  std::string input;  ///< empty: the demo tree
  std::string sketchPath, scriptPath, autosavePath;
  /// --up as given ("" when not given: the library's rule, io::chooseUpAxis, decides).
  std::string up;
  viewer::DemoSceneOptions demo;
  int width = 1280, height = 800;
  double measureIdleSeconds = 0;  ///< --measure-idle: measure the idle window's cost and exit
  int measureHoverMoves = 0;      ///< --measure-hover: measure mouse moves over the panel and exit
};

/// The usage text.
void usage(std::ostream& out);

/// The command line; --help and --version print and exit 0. Throws OptionsError on a bad option.
Args parseArgs(int argc, char** argv);

}  // namespace treesketch::gui
