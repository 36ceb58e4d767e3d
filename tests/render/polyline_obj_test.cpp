#include "treesketch/render/polyline_obj.h"

#include <gtest/gtest.h>

#include <sstream>

#include "test_support.h"
#include "treesketch/util/error.h"

namespace treesketch::render {
namespace {

std::vector<std::vector<geom::Vec3>> read(const std::string& text) {
  std::istringstream in(text);
  return readObjPolylines(in, "skel.obj");
}

std::string messageOf(const std::string& text) {
  try {
    read(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PolylineObj, ReadsLinesWithRelativeAndSlashedIndices) {
  auto lines = read("# skeleton\nv 0 0 0\nv 0 1 0\nv 1 2 0\r\nl 1 2 3\nf 1 2 3\nv 5 5 5\nl -1 2/7\n");
  ASSERT_EQ(lines.size(), 2u);
  ASSERT_EQ(lines[0].size(), 3u);
  EXPECT_EQ(lines[0][2], geom::Vec3(1, 2, 0));
  ASSERT_EQ(lines[1].size(), 2u);
  EXPECT_EQ(lines[1][0], geom::Vec3(5, 5, 5));
  EXPECT_EQ(lines[1][1], geom::Vec3(0, 1, 0));
}

TEST(PolylineObj, BadInputNamesTheLine) {
  EXPECT_NE(messageOf("v 0 0 0\nv 1 1 1\nl 1 3\n").find("skel.obj:3"), std::string::npos);
  EXPECT_NE(messageOf("v 0 0 0\nv 1 x 1\n").find("skel.obj:2"), std::string::npos);
  EXPECT_NE(messageOf("v 0 0 nan\n").find("skel.obj:1"), std::string::npos);
  EXPECT_NE(messageOf("v 0 0\n").find("skel.obj:1"), std::string::npos);
  EXPECT_NE(messageOf("v 0 0 0\nv 1 1 1\nl 1\n").find("skel.obj:3"), std::string::npos);
  EXPECT_NE(messageOf("v 0 0 0\nv 1 1 1\nl 1 0\n").find("skel.obj:3"), std::string::npos);
  EXPECT_NE(messageOf("v 0 0 0\nv 1 1 1\nl 1 two\n").find("skel.obj:3"), std::string::npos);
  EXPECT_NE(messageOf("v 0 0 0\nl 1 -2\n").find("skel.obj:2"), std::string::npos);
  EXPECT_NE(messageOf("v 0 0 0\nv 1 1 1\nf 1 2 1\n").find("no"), std::string::npos);  // no 'l' element
  EXPECT_NE(messageOf("").find("skel.obj"), std::string::npos);
}

TEST(PolylineObj, MissingFileIsAnInputError) {
  test::TempDir dir;
  EXPECT_THROW(readObjPolylines(dir / "absent.obj"), InputError);
  test::writeText(dir / "s.obj", "v 0 0 0\nv 0 0 1\nl 1 2\n");
  EXPECT_EQ(readObjPolylines(dir / "s.obj").size(), 1u);
}

}  // namespace
}  // namespace treesketch::render
