// `treesketch gui` (apps/cli/cmd_gui.cpp): the CLI runs the desktop tool from its own directory and
// says clearly when it was not built. These cases never open a window.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "test_support.h"

namespace treesketch::viewer {
namespace {

int run(const std::string& command, std::string* output) {
  test::TempDir dir;
  std::string cmd = command + " > " + (dir / "out.txt").string() + " 2>&1";
  int status = std::system(cmd.c_str());
  *output = test::readText(dir / "out.txt");
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(GuiCommand, MissingToolIsAClearUsageError) {
  // A copy of the CLI alone in a directory: no treesketch-gui beside it.
  test::TempDir dir;
  std::filesystem::copy_file(TS_CLI_PATH, dir / "treesketch");
  std::string out;
  int code = run((dir / "treesketch").string() + " gui", &out);
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("not built"), std::string::npos) << out;
  EXPECT_NE(out.find("libimgui-dev"), std::string::npos) << out;
}

TEST(GuiCommand, MissingInputIsRejectedBeforeAnyWindow) {
  std::string out;
  EXPECT_EQ(run(std::string(TS_CLI_PATH) + " gui /no/such/cloud.xyz", &out), 2) << out;
  EXPECT_EQ(run(std::string(TS_CLI_PATH) + " gui --help", &out), 0) << out;
  EXPECT_NE(out.find("--sketch"), std::string::npos);
}

}  // namespace
}  // namespace treesketch::viewer
