// The `treesketch sketch auto` subcommand, run as a process.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "cli_support.h"
#include "test_support.h"
#include "treesketch/io/sketch_file.h"

namespace treesketch {
namespace {

/// A vertical cylinder of points (radius 0.2, height 5, Y up) as XYZ text.
std::string cylinderXyz(bool zUp = false) {
  std::ostringstream s;
  for (int i = 0; i < 50; ++i)
    for (int k = 0; k < 12; ++k) {
      double a = 2 * M_PI * k / 12, h = 0.1 * i;
      double x = 0.2 * std::cos(a), y = 0.2 * std::sin(a);
      if (zUp)
        s << x << " " << y << " " << h << "\n";
      else
        s << x << " " << h << " " << y << "\n";
    }
  return s.str();
}

TEST(CmdSketch, AutoUniformWritesAChain) {
  test::TempDir dir;
  test::writeText(dir / "c.xyz", cylinderXyz());
  std::string out;
  int rc = test::runCli(
      "sketch auto " + test::quoted(dir / "c.xyz") + " --nodes 7 --view side --up y -o " + test::quoted(dir / "s.json"),
      &out);
  ASSERT_EQ(rc, 0) << out;
  sketch::Sketch sk = io::readSketch(dir / "s.json");
  EXPECT_EQ(sk.size(), 7u);
  EXPECT_EQ(sk.up, geom::UpAxis::Y);
  for (sketch::NodeId id : sk.ids()) EXPECT_LE(sk.node(id).children.size(), 1u);
  EXPECT_FALSE(sk.cameras().front().isOrthographic());
  EXPECT_NE(out.find("7 nodes"), std::string::npos) << out;
}

TEST(CmdSketch, AutoWithZUpOrthoAndCameraFile) {
  test::TempDir dir;
  test::writeText(dir / "c.xyz", cylinderXyz(true));
  std::string out;
  int rc = test::runCli("sketch auto " + test::quoted(dir / "c.xyz") + " --nodes 4 --view front --up z --ortho -o " +
                            test::quoted(dir / "s.json"),
                        &out);
  ASSERT_EQ(rc, 0) << out;
  sketch::Sketch sk = io::readSketch(dir / "s.json");
  EXPECT_EQ(sk.up, geom::UpAxis::Z);
  EXPECT_TRUE(sk.cameras().front().isOrthographic());
  // The root's slice is horizontal in a Z-up world.
  EXPECT_NEAR(std::abs(sk.geometry(sk.root()).planeNormal.z()), 1.0, 1e-9);
  // The same camera through a camera file gives the same sketch.
  io::writeCamera(dir / "cam.json", sk.cameras().front());
  rc = test::runCli("sketch auto " + test::quoted(dir / "c.xyz") + " --nodes 4 --view " +
                        test::quoted(dir / "cam.json") + " --up z -o " + test::quoted(dir / "s2.json"),
                    &out);
  ASSERT_EQ(rc, 0) << out;
  sketch::Sketch sk2 = io::readSketch(dir / "s2.json");
  for (sketch::NodeId id : sk.ids()) EXPECT_EQ(sk.node(id).screen, sk2.node(id).screen);
}

TEST(CmdSketch, BadInvocations) {
  test::TempDir dir;
  test::writeText(dir / "c.xyz", cylinderXyz());
  std::string cloud = test::quoted(dir / "c.xyz");
  std::string out = " -o " + test::quoted(dir / "s.json");
  std::string msg;
  EXPECT_EQ(test::runCli("sketch auto " + test::quoted(dir / "missing.xyz") + out, &msg), 3) << msg;
  EXPECT_EQ(test::runCli("sketch auto " + cloud + " --nodes 0" + out, &msg), 2) << msg;
  EXPECT_EQ(test::runCli("sketch auto " + cloud + " --method nope" + out, &msg), 2) << msg;
  EXPECT_EQ(test::runCli("sketch auto " + cloud + " --up x" + out, &msg), 2) << msg;
  EXPECT_EQ(test::runCli("sketch auto " + cloud, &msg), 2) << msg;  // no -o
  test::writeText(dir / "cam.json", "{\"view\": [1, 2]}");
  EXPECT_EQ(test::runCli("sketch auto " + cloud + " --view " + test::quoted(dir / "cam.json") + out, &msg), 3) << msg;
  EXPECT_NE(msg.find("cam.json"), std::string::npos) << msg;
  EXPECT_EQ(test::runCli("sketch auto " + cloud + " -o " + cloud, &msg), 4) << msg;  // never overwrite the input
  test::writeText(dir / "file", "x");  // a file where the output folder should be
  EXPECT_EQ(test::runCli("sketch auto " + cloud + " -o " + test::quoted(dir / "file/such/dir.json"), &msg), 4) << msg;
  std::filesystem::create_directories(dir / "folder.json");
  EXPECT_EQ(test::runCli("sketch auto " + cloud + " -o " + test::quoted(dir / "folder.json"), &msg), 4) << msg;
  EXPECT_FALSE(std::filesystem::exists(dir / "s.json"));
}

}  // namespace
}  // namespace treesketch
