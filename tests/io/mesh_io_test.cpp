#include "treesketch/io/mesh_io.h"

#include <gtest/gtest.h>

#include <sstream>

#include "io_test_util.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch::io {
namespace {

using testing::expectError;

geom::TriMesh tetra() {
  geom::TriMesh m;
  m.vertices = {geom::Vec3(0, 0, 0), geom::Vec3(1, 0, 0), geom::Vec3(0, 1, 0), geom::Vec3(0, 0, 1)};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

TEST(MeshIo, WriteAndReadBackByExtension) {
  test::TempDir dir;
  geom::TriMesh m = tetra();
  m.quality = {0, 1, 2, 3};
  m.colors = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}};
  for (const char* name : {"m.obj", "m.ply", "M.PLY"}) {
    writeMesh(dir / name, m);
    geom::TriMesh back = readMesh(dir / name);
    EXPECT_EQ(back.vertices, m.vertices) << name;
    EXPECT_EQ(back.triangles, m.triangles) << name;
    EXPECT_NEAR(back.area(), m.area(), 1e-12);
  }
  EXPECT_EQ(readMesh(dir / "m.ply").quality, m.quality);
  EXPECT_EQ(readMesh(dir / "m.ply").colors, m.colors);
  expectError<OutputError>([&] { writeMesh(dir / "m.stl", m); }, {"m.stl", ".obj or .ply"});
}

TEST(MeshIo, StreamVersions) {
  for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Ply}) {
    std::stringstream ss;
    writeMesh(ss, f, tetra());
    EXPECT_EQ(readMesh(ss, "mem", f).triangles, tetra().triangles);
  }
}

TEST(MeshIo, BadInputs) {
  test::TempDir dir;
  expectError([&] { readMesh(dir / "a.stl"); }, {"a.stl", "unknown mesh extension", ".obj or .ply"});
  expectError([&] { readMesh(dir / "none.obj"); }, {"none.obj", "not found"});
  geom::PointCloud c;
  for (int i = 0; i < 5; ++i) c.positions.emplace_back(i, 0, 0);
  writePointCloud(dir / "cloud.ply", c);
  expectError([&] { readMesh(dir / "cloud.ply"); }, {"cloud.ply", "no 'face' element"});
  test::writeText(dir / "empty.obj", "");
  expectError([&] { readMesh(dir / "empty.obj"); }, {"empty.obj", "empty"});
}

}  // namespace
}  // namespace treesketch::io
