// The `treesketch render` subcommand, run as a process.
#include <gtest/gtest.h>

#include <string>

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
  int code = test::runCli("render --cloud '" + (dir / "c.xyz").string() + "' --skeleton '" + (dir / "s.obj").string() +
                              "' --size 64x48 --view front -o '" + (dir / "c.png").string() + "'",
                          &out);
  EXPECT_EQ(code, 0) << out;
  EXPECT_TRUE(isPng(test::readText(dir / "c.png")));
  code = test::runCli("render --cloud '" + (dir / "c.xyz").string() + "' --color-by none --wireframe -o '" +
                          (dir / "iso.png").string() + "'",
                      &out);
  EXPECT_EQ(code, 0) << out;
  EXPECT_TRUE(isPng(test::readText(dir / "iso.png")));
}

TEST(CmdRender, BadInputFileIsExit3AndLeavesNoOutput) {
  test::TempDir dir;
  test::writeText(dir / "bad.xyz", "1 2 3\n4 five 6\n");
  std::string out;
  EXPECT_EQ(
      test::runCli("render --cloud '" + (dir / "bad.xyz").string() + "' -o '" + (dir / "o.png").string() + "'", &out),
      3)
      << out;
  EXPECT_NE(out.find("bad.xyz"), std::string::npos);
  EXPECT_EQ(
      test::runCli("render --cloud '" + (dir / "missing.ply").string() + "' -o '" + (dir / "o.png").string() + "'"), 3);
  test::writeText(dir / "noline.obj", "v 0 0 0\n");
  EXPECT_EQ(
      test::runCli("render --skeleton '" + (dir / "noline.obj").string() + "' -o '" + (dir / "o.png").string() + "'"),
      3);
  EXPECT_FALSE(std::filesystem::exists(dir / "o.png"));
}

TEST(CmdRender, BadOptionsAreExit2) {
  test::TempDir dir;
  test::writeText(dir / "c.xyz", tinyCloud());
  const std::string cloud = " --cloud '" + (dir / "c.xyz").string() + "'";
  const std::string outPng = " -o '" + (dir / "o.png").string() + "'";
  EXPECT_EQ(test::runCli("render" + cloud + " --size 64by48" + outPng), 2);
  EXPECT_EQ(test::runCli("render" + cloud + " --view diagonal" + outPng), 2);
  EXPECT_EQ(test::runCli("render" + outPng), 2);  // nothing to draw
  EXPECT_EQ(test::runCli("render" + cloud), 2);   // no output
  EXPECT_EQ(test::runCli("render" + cloud + " -o '" + (dir / "no" / "o.png").string() + "'"), 4);
}

}  // namespace
}  // namespace treesketch
