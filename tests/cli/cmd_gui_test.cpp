// `treesketch gui` (apps/cli/cmd_gui.cpp): the CLI runs the desktop tool from its own directory and
// says clearly when it was not built. These cases never open a window.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_support.h"
#include "test_support.h"

namespace treesketch {
namespace {

TEST(GuiCommand, MissingToolIsAClearUsageError) {
  // A copy of the CLI alone in a directory: no treesketch-gui beside it.
  test::TempDir dir;
  std::filesystem::copy_file(test::cliPath(), dir / "treesketch");
  std::string out;
  int code = test::runCommand(test::quoted(dir / "treesketch") + " gui", &out);
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("not built"), std::string::npos) << out;
  EXPECT_NE(out.find("libimgui-dev"), std::string::npos) << out;
}

TEST(GuiCommand, MissingInputIsRejectedBeforeAnyWindow) {
  std::string out;
  EXPECT_EQ(test::runCli("gui /no/such/cloud.xyz", &out), 2) << out;
  EXPECT_EQ(test::runCli("gui --help", &out), 0) << out;
  EXPECT_NE(out.find("--sketch"), std::string::npos);
}

}  // namespace
}  // namespace treesketch
