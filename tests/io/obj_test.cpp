#include "treesketch/io/obj.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "io_test_util.h"
#include "test_support.h"

namespace treesketch::io {
namespace {

using testing::expectError;
using Tri = std::array<std::uint32_t, 3>;

geom::TriMesh objFrom(const std::string& text, ObjStats* st = nullptr) {
  std::istringstream in(text);
  return readObj(in, "mem.obj", st);
}

TEST(Obj, QuadsPolygonsSlashesNegativeIndicesAndIgnoredLines) {
  std::string text =
      "# comment\r\n"
      "mtllib a.mtl\r\n"
      "o thing\r\n"
      "v 0 0 0\r\n"
      "v 1 0 0 1.0\r\n"
      "v 1 1 0 0.5 0.5 0.5\r\n"
      "v 0 1 0\r\n"
      "vt 0 0\nvn 0 0 1\ng group\nusemtl m\ns off\n"
      "f 1/1/1 2/2/1 3/3/1 4/4/1\n"  // quad -> 2 triangles
      "v 0.5 2 0\n"
      "f -5//1 -4//1 -1//1\n"  // negative: 1 2 5
      "f 1/1 3/3 5/5\n"
      "f 1 2 3 5 4\n"  // pentagon -> 3 triangles
      "l 1 2\n";
  ObjStats st;
  geom::TriMesh m = objFrom(text, &st);
  ASSERT_EQ(m.vertices.size(), 5u);
  EXPECT_EQ(m.vertices[2], geom::Vec3(1, 1, 0));
  ASSERT_EQ(m.triangles.size(), 2u + 1u + 1u + 3u);
  EXPECT_EQ(m.triangles[0], (Tri{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (Tri{0, 2, 3}));
  EXPECT_EQ(m.triangles[2], (Tri{0, 1, 4}));
  EXPECT_EQ(m.triangles[3], (Tri{0, 2, 4}));
  EXPECT_EQ(m.triangles[6], (Tri{0, 4, 3}));
  EXPECT_EQ(st.polygons, 4u);
  EXPECT_EQ(st.nonTriangles, 2u);
  EXPECT_EQ(st.ignoredLines, 8u);
}

TEST(Obj, RoundTripIsExact) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-50, 50);
  geom::TriMesh m;
  for (int i = 0; i < 100; ++i) m.vertices.emplace_back(u(rng), u(rng), 5e5 + u(rng));
  for (std::uint32_t i = 0; i + 2 < 100; ++i) m.triangles.push_back({i, i + 2, i + 1});
  std::stringstream ss;
  writeObj(ss, m);
  geom::TriMesh back = readObj(ss, "mem");
  EXPECT_EQ(back.vertices, m.vertices);
  EXPECT_EQ(back.triangles, m.triangles);
  test::TempDir dir;
  writeObj(dir / "m.obj", m);
  EXPECT_EQ(readObj(dir / "m.obj").triangles, m.triangles);
}

const std::string kVerts = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";

TEST(Obj, RejectsBadInputWithItsLine) {
  expectError([] { objFrom(""); }, {"mem.obj", "empty"});
  expectError([] { objFrom(kVerts + "f 1 2 5\n"); }, {"mem.obj:5:", "index 5 out of range"});
  expectError([] { objFrom(kVerts + "f 0 1 2\n"); }, {"mem.obj:5:", "index 0"});
  expectError([] { objFrom(kVerts + "f -1 -2 -5\n"); }, {"mem.obj:5:", "-5 out of range"});
  expectError([] { objFrom(kVerts + "f 1 2\n"); }, {"mem.obj:5:", "2 corners"});
  expectError([] { objFrom(kVerts + "f a b c\n"); }, {"mem.obj:5:", "'a'"});
  expectError([] { objFrom("v 0 0 0\nv 1 nan 0\n"); }, {"mem.obj:2:", "non-finite"});
  expectError([] { objFrom("v 0 0 0\nv 1 0\n"); }, {"mem.obj:2:", "3 numbers"});
  expectError([] { objFrom("hello world\n"); }, {"mem.obj:1:", "unknown OBJ keyword", "'hello'"});
  expectError([] { objFrom(kVerts); }, {"mem.obj", "no faces"});
  expectError([] { objFrom(kVerts + "f 1 2 5\n"); }, {"(vertices defined so far)"});
}

TEST(Obj, VerticesCanBeReadAsACloud) {
  std::istringstream in(kVerts + "f 1 2 3\n");
  EXPECT_EQ(readObjVertices(in, "mem").size(), 4u);
  std::istringstream noFaces(kVerts);
  EXPECT_EQ(readObjVertices(noFaces, "mem").size(), 4u);
}

TEST(Obj, WriterRejectsBadData) {
  geom::TriMesh m;
  m.vertices = {geom::Vec3(0, 0, 0), geom::Vec3(1, 0, 0), geom::Vec3(0, std::nan(""), 0)};
  m.triangles = {{0, 1, 2}};
  std::ostringstream out;
  expectError<OutputError>([&] { writeObj(out, m); }, {"vertex 2"});
  m.vertices[2].y() = 1;
  m.triangles = {{0, 1, 3}};
  expectError<OptionsError>([&] { writeObj(out, m); }, {"vertex 3"});
}

TEST(Obj, RealBranchMeshesHaveTheirDocumentedCounts) {
  const auto dir = test::sharedDataDir() / "trees";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no shared data";
  // Branch triangle counts from the folder's README (vertex counts where it was checked by hand).
  struct Documented {
    std::size_t vertices, triangles;  // vertices 0 = not documented
  };
  const std::map<std::string, Documented> documented = {
      {"aspen_medium_s101", {2820, 5088}}, {"pine_medium_s13977", {5516, 10032}},
      {"oak_medium_s35729", {2184, 3166}}, {"bush_2_s45590", {1900, 3352}},
      {"ash_small_s2203", {0, 5616}},      {"ash_medium_s7781", {0, 9120}},
      {"aspen_small_s914", {0, 2496}},     {"aspen_large_s5521", {0, 7200}},
      {"oak_small_s6120", {0, 3206}},      {"pine_small_s3391", {0, 11112}},
      {"aspen_medium_s4409", {0, 5088}},   {"pine_medium_s8817", {0, 10032}},
      {"oak_medium_s1290", {0, 3166}},     {"bush_2_s6644", {0, 3352}}};
  std::size_t read = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    const std::string suffix = ".branches.obj";
    if (f.size() <= suffix.size() || f.compare(f.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    const std::string name = f.substr(0, f.size() - suffix.size());
    geom::TriMesh m = readObj(e.path());
    ++read;
    if (auto it = documented.find(name); it != documented.end()) {
      if (it->second.vertices > 0) EXPECT_EQ(m.vertices.size(), it->second.vertices) << name;
      EXPECT_EQ(m.triangles.size(), it->second.triangles) << name;
    }
    EXPECT_NO_THROW(m.checkConsistent()) << name;
    EXPECT_GT(m.area(), 0.0) << name;
  }
  EXPECT_GE(read, 1u);
}

TEST(Obj, DamagedFilesGiveInputErrorsOnly) {
  std::string text = "# c\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1\nvt 0 1\nf 1/1/1 2/2/2 3/3/3 4/4/4\nf -1 -2 -3\n";
  testing::expectOnlyInputErrors(
      text, [](const std::string& b) { objFrom(b); }, 1000);
}

}  // namespace
}  // namespace treesketch::io
