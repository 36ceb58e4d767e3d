// `treesketch gui [CLOUD | MESH] [--sketch SKETCH.json] [--script ACTIONS.json] ...`: runs the
// desktop sketching tool. The tool is a separate program, treesketch-gui, built beside this one
// when its packages (GLFW, GLEW, OpenGL, Dear ImGui, stb) are installed, so that this CLI links no
// GL at all; this subcommand only finds it in its own directory and runs it in its place.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace {

struct GuiArgs {
  std::string input, sketch, script, up, autosave, demo;
  std::uint64_t demoRays = 0;
};

std::filesystem::path selfDirectory() {
  std::error_code ec;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return std::filesystem::current_path();
  return self.parent_path();
}

void runGui(const GuiArgs& a) {
  std::filesystem::path tool = selfDirectory() / "treesketch-gui";
  if (!std::filesystem::exists(tool))
    throw OptionsError("the desktop tool was not built (" + tool.string() +
                       " is missing): install libglfw3-dev libglew-dev libimgui-dev libstb-dev and rebuild "
                       "with -DTREESKETCH_GUI=ON");
  std::vector<std::string> args{tool.string()};
  if (!a.input.empty()) args.push_back(a.input);
  auto add = [&](const char* flag, const std::string& v) {
    if (v.empty()) return;
    args.push_back(flag);
    args.push_back(v);
  };
  add("--sketch", a.sketch);
  add("--script", a.script);
  add("--up", a.up);
  add("--autosave", a.autosave);
  add("--demo", a.demo);
  if (a.demoRays > 0) add("--demo-rays", std::to_string(a.demoRays));
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  ::execv(tool.c_str(), argv.data());
  throw OptionsError("cannot run " + tool.string() + ": " + std::strerror(errno));
}

}  // namespace

void registerGui(CLI::App& app, Action& action) {
  auto args = std::make_shared<GuiArgs>();
  CLI::App* sub = app.add_subcommand(
      "gui", "Open the interactive sketching tool on a cloud or a mesh (scanned first); no input: the demo tree");
  sub->add_option("input", args->input,
                  "Point cloud (.ply .xyz .txt .csv .pts .asc .las .laz) or mesh (.obj, PLY with faces)")
      ->check(CLI::ExistingFile);
  sub->add_option("--sketch", args->sketch, "Sketch file to open (if it exists) and to save to");
  sub->add_option("--script", args->script, "Run a scripted session (JSON actions) and exit")->check(CLI::ExistingFile);
  sub->add_option("--up", args->up,
                  "Up of the input: y or z, or +x -x +y -y +z -z for the view (default: the file's declaration, else "
                  "z; the demo tree is y)");
  sub->add_option("--autosave", args->autosave, "Autosave file (default: beside the cloud)");
  sub->add_option("--demo", args->demo, "Demo tree preset when no input is given");
  sub->add_option("--demo-rays", args->demoRays, "Rays of the demo tree's scan");
  sub->callback([args, &action] { action = [args] { runGui(*args); }; });
}

}  // namespace treesketch::cli
