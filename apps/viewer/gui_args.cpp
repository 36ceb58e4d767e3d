#include "gui_args.h"

#include <cstdlib>
#include <iostream>

#include "build_info.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/view_up.h"

namespace treesketch::gui {

void usage(std::ostream& out) {
  out << "usage: treesketch-gui [CLOUD | MESH] [--sketch SKETCH.json] [--script ACTIONS.json]\n"
         "                      [--up y|z|+x|-x|+y|-y|+z|-z] [--autosave PATH] [--demo PRESET] [--demo-rays N]\n"
         "                      [--width W] [--height H] [--measure-idle SECONDS]\n"
         "                      [--measure-hover MOVES]\n"
         "Opens the interactive sketching tool on a point cloud (.ply .xyz .txt .csv .pts .asc .las .laz) or on a\n"
         "mesh (.obj, PLY with faces; scanned first with the sphere scanner's defaults). Without an input\n"
         "it opens the built-in demo tree. --script runs a scripted session and exits (0: every action\n"
         "succeeded, 1: some failed).\n";
}

Args parseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    std::string s = argv[i];
    auto value = [&](const char* name) -> std::string {
      if (i + 1 >= argc) throw OptionsError(std::string(name) + " needs a value");
      return argv[++i];
    };
    auto integer = [&](const char* name) -> long long {
      std::string v = value(name);
      char* end = nullptr;
      long long n = std::strtoll(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || n <= 0) throw OptionsError(std::string(name) + ": expected a positive integer");
      return n;
    };
    if (s == "-h" || s == "--help") {
      usage(std::cout);
      std::exit(kExitOk);
    } else if (s == "--version") {
      std::cout << cli::versionString() << "\n";
      std::exit(kExitOk);
    } else if (s == "--sketch")
      a.sketchPath = value("--sketch");
    else if (s == "--script")
      a.scriptPath = value("--script");
    else if (s == "--autosave")
      a.autosavePath = value("--autosave");
    else if (s == "--up") {
      a.up = value("--up");
      viewer::parseUpDirection(a.up);  // checked now: a bad value is a usage error
    } else if (s == "--demo")
      a.demo.preset = value("--demo");
    else if (s == "--demo-rays")
      a.demo.rays = static_cast<std::uint64_t>(integer("--demo-rays"));
    else if (s == "--measure-idle")
      a.measureIdleSeconds = static_cast<double>(integer("--measure-idle"));
    else if (s == "--measure-hover")
      a.measureHoverMoves = static_cast<int>(integer("--measure-hover"));
    else if (s == "--width")
      a.width = static_cast<int>(integer("--width"));
    else if (s == "--height")
      a.height = static_cast<int>(integer("--height"));
    else if (!s.empty() && s[0] == '-')
      throw OptionsError("unknown option " + s);
    else if (a.input.empty())
      a.input = s;
    else
      throw OptionsError("only one input file may be given");
  }
  return a;
}

}  // namespace treesketch::gui
