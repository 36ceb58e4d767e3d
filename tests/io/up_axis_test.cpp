// The up-axis rule: an explicit --up wins, else what the file declares (LAS: z; a PLY's
// `comment up_axis` line, which the writer adds for a cloud that knows its up), else z.
#include "treesketch/io/up_axis.h"

#include <gtest/gtest.h>

#include <sstream>

#include "io_test_util.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/util/error.h"

namespace treesketch::io {
namespace {

geom::PointCloud fourPoints() {
  geom::PointCloud c;
  for (int i = 0; i < 4; ++i) c.positions.emplace_back(i, 2 * i, 3 * i);
  return c;
}

TEST(UpAxis, ExplicitWinsThenDeclaredThenZ) {
  geom::PointCloud c = fourPoints();
  EXPECT_EQ(chooseUpAxis("", c).up, geom::UpAxis::Z);
  EXPECT_NE(chooseUpAxis("", c).reason.find("default"), std::string::npos);
  c.up = geom::UpAxis::Y;
  EXPECT_EQ(chooseUpAxis("", c).up, geom::UpAxis::Y);
  EXPECT_NE(chooseUpAxis("", c).reason.find("declares"), std::string::npos);
  EXPECT_EQ(chooseUpAxis("z", c).up, geom::UpAxis::Z);
  EXPECT_EQ(chooseUpAxis("Z", c).reason, "--up z");
  EXPECT_THROW(chooseUpAxis("x", c), OptionsError);
}

TEST(UpAxis, PlySaysItsUpAndTextDoesNot) {
  test::TempDir dir;
  geom::PointCloud c = fourPoints();
  writePointCloud(dir / "none.ply", c);
  EXPECT_FALSE(readPointCloud(dir / "none.ply").up.has_value());
  for (geom::UpAxis up : {geom::UpAxis::Y, geom::UpAxis::Z}) {
    c.up = up;
    writePointCloud(dir / "c.ply", c);
    const geom::PointCloud back = readPointCloud(dir / "c.ply");
    ASSERT_TRUE(back.up.has_value());
    EXPECT_EQ(*back.up, up);
    EXPECT_EQ(back.positions, c.positions);
  }
  writePointCloud(dir / "c.xyz", c);  // text has no place for it: the field's convention applies
  EXPECT_FALSE(readPointCloud(dir / "c.xyz").up.has_value());
  EXPECT_EQ(chooseUpAxis("", readPointCloud(dir / "c.xyz")).up, geom::UpAxis::Z);
}

TEST(UpAxis, AsciiPlyCommentFromAnotherTool) {
  std::istringstream in(
      "ply\nformat ascii 1.0\ncomment up_axis Y\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n");
  EXPECT_EQ(readPointCloud(in, "a.ply", CloudFormat::Ply).up, geom::UpAxis::Y);
  std::istringstream other(
      "ply\nformat ascii 1.0\ncomment up_axis w\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n");
  EXPECT_FALSE(readPointCloud(other, "b.ply", CloudFormat::Ply).up.has_value());  // unknown value: not declared
}

TEST(UpAxis, LasIsZUpBySpec) {
  testing::LasSpec spec;
  spec.points = {{0, 0, 0}, {1000, 0, 0}, {0, 1000, 0}, {0, 0, 1000}};
  std::istringstream in(testing::buildLas(spec));
  const geom::PointCloud c = readPointCloud(in, "t.las", CloudFormat::Las);
  ASSERT_TRUE(c.up.has_value());
  EXPECT_EQ(*c.up, geom::UpAxis::Z);
  EXPECT_EQ(chooseUpAxis("", c).up, geom::UpAxis::Z);
  EXPECT_EQ(chooseUpAxis("y", c).up, geom::UpAxis::Y);  // an explicit --up still wins
}

}  // namespace
}  // namespace treesketch::io
