// The `treesketch render` subcommand, run as a process.
#include <gtest/gtest.h>

#include <string>

#include "cli_support.h"
#include "test_support.h"

namespace treesketch {
namespace {

std::string tinyCloud() {
  std::string text;
  for (int i = 0; i < 40; ++i)
    text +=
        std::to_string(0.05 * (i % 5)) + " " + std::to_string(0.03 * (i % 7)) + " " + std::to_string(0.1 * i) + "\n";
  return text;
}

bool isPng(const std::string& bytes) { return bytes.size() > 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0; }

TEST(CmdRender, RendersATinyCloudToPng) {
  test::TempDir dir;
  test::writeText(dir / "c.xyz", tinyCloud());
  test::writeText(dir / "s.obj", "v 0 0 0\nv 0 0 2\nv 0.1 0 3\nl 1 2 3\n");
  std::string out;
  int code =
      test::runCli("render --cloud " + test::quoted(dir / "c.xyz") + " --skeleton " + test::quoted(dir / "s.obj") +
                       " --size 64x48 --view front -o " + test::quoted(dir / "c.png"),
                   &out);
  EXPECT_EQ(code, 0) << out;
  EXPECT_TRUE(isPng(test::readText(dir / "c.png")));
  code = test::runCli("render --cloud " + test::quoted(dir / "c.xyz") + " --color-by none --wireframe -o " +
                          test::quoted(dir / "iso.png"),
                      &out);
  EXPECT_EQ(code, 0) << out;
  EXPECT_TRUE(isPng(test::readText(dir / "iso.png")));
}

TEST(CmdRender, BadInputFileIsExit3AndLeavesNoOutput) {
  test::TempDir dir;
  test::writeText(dir / "bad.xyz", "1 2 3\n4 five 6\n");
  std::string out;
  EXPECT_EQ(
      test::runCli("render --cloud " + test::quoted(dir / "bad.xyz") + " -o " + test::quoted(dir / "o.png"), &out), 3)
      << out;
  EXPECT_NE(out.find("bad.xyz"), std::string::npos);
  EXPECT_EQ(test::runCli("render --cloud " + test::quoted(dir / "missing.ply") + " -o " + test::quoted(dir / "o.png")),
            3);
  test::writeText(dir / "noline.obj", "v 0 0 0\n");
  EXPECT_EQ(
      test::runCli("render --skeleton " + test::quoted(dir / "noline.obj") + " -o " + test::quoted(dir / "o.png")), 3);
  EXPECT_FALSE(std::filesystem::exists(dir / "o.png"));
}

TEST(CmdRender, BadOptionsAreExit2) {
  test::TempDir dir;
  test::writeText(dir / "c.xyz", tinyCloud());
  const std::string cloud = " --cloud " + test::quoted(dir / "c.xyz");
  const std::string outPng = " -o " + test::quoted(dir / "o.png");
  EXPECT_EQ(test::runCli("render" + cloud + " --size 64by48" + outPng), 2);
  EXPECT_EQ(test::runCli("render" + cloud + " --view diagonal" + outPng), 2);
  EXPECT_EQ(test::runCli("render" + outPng), 2);  // nothing to draw
  EXPECT_EQ(test::runCli("render" + cloud), 2);   // no output
  // A missing output folder is created; a file in its way is an output error.
  test::writeText(dir / "file", "x");
  EXPECT_EQ(test::runCli("render" + cloud + " -o " + test::quoted(dir / "file" / "o.png")), 4);
  std::filesystem::create_directories(dir / "folder.png");
  EXPECT_EQ(test::runCli("render" + cloud + " -o " + test::quoted(dir / "folder.png")), 4);    // a folder
  EXPECT_EQ(test::runCli("render" + cloud + " -o " + test::quoted(dir / "no" / "o.png")), 0);  // folder created
}

}  // namespace
}  // namespace treesketch
