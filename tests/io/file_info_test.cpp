#include "treesketch/io/file_info.h"

#include <gtest/gtest.h>

#include "io_test_util.h"
#include "test_support.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch::io {
namespace {

using testing::expectError;

std::string detail(const FileInfo& info, const std::string& key) {
  for (const auto& [k, v] : info.details)
    if (k == key) return v;
  return "<none>";
}

TEST(FileInfo, DescribesEachFormat) {
  test::TempDir dir;
  geom::TriMesh m;
  m.vertices = {geom::Vec3(0, 0, 0), geom::Vec3(2, 0, 0), geom::Vec3(0, 2, 0)};
  m.triangles = {{0, 1, 2}};
  writeMesh(dir / "m.ply", m);
  FileInfo a = inspectFile(dir / "m.ply");
  EXPECT_EQ(a.format, "PLY binary_little_endian");
  EXPECT_TRUE(a.isMesh);
  EXPECT_EQ(a.mesh.triangles.size(), 1u);
  EXPECT_DOUBLE_EQ(a.mesh.area(), 2.0);
  EXPECT_EQ(detail(a, "element vertex"), "3 x (double x, double y, double z)");
  EXPECT_EQ(detail(a, "element face"), "1 x (list uchar int vertex_indices)");

  writeMesh(dir / "m.obj", m);
  FileInfo b = inspectFile(dir / "m.obj");
  EXPECT_EQ(b.format, "OBJ");
  EXPECT_EQ(b.mesh.vertices.size(), 3u);

  geom::PointCloud c;
  c.positions = {geom::Vec3(1, 2, 3)};
  writePointCloud(dir / "one.ply", c);
  FileInfo d = inspectFile(dir / "one.ply");  // info accepts any non-empty cloud
  EXPECT_FALSE(d.isMesh);
  EXPECT_EQ(d.cloud.size(), 1u);

  testing::LasSpec s;
  s.versionMinor = 4;
  s.pointFormat = 6;
  s.points = {{1, 2, 3}, {4, 5, 6}};
  test::writeText(dir / "p.las", testing::buildLas(s));
  FileInfo e = inspectFile(dir / "p.las");
  EXPECT_EQ(e.format, "LAS 1.4");
  EXPECT_EQ(detail(e, "point data format"), "6");
  EXPECT_EQ(detail(e, "scale"), "0.001 0.001 0.001");
  EXPECT_EQ(e.cloud.size(), 2u);
  EXPECT_EQ(detail(e, "withheld points"), "0");

  expectError([&] { inspectFile(dir / "x.laz"); }, {"x.laz", "not found"});
  expectError([&] { inspectFile(dir / "x.doc"); }, {"x.doc", "unknown"});
}

// A LAS file's withheld records: dropped from the cloud, their count among the details.
TEST(FileInfo, CountsTheWithheldPointsOfALasFile) {
  test::TempDir dir;
  for (int fmt : {1, 6}) {
    testing::LasSpec s;
    s.versionMinor = fmt >= 6 ? 4 : 2;
    s.pointFormat = fmt;
    for (std::int32_t i = 0; i < 9; ++i) s.points.push_back({i, 2 * i, 3 * i});
    std::string b = testing::buildLas(s);
    for (std::size_t i : {0u, 3u, 8u}) testing::setLasClass(b, s, i, 7, testing::kLasWithheld);
    const auto path = dir / ("w" + std::to_string(fmt) + ".las");
    test::writeText(path, b);
    const FileInfo info = inspectFile(path);
    EXPECT_EQ(detail(info, "header point count"), "9") << fmt;
    EXPECT_EQ(detail(info, "withheld points"), "3 (dropped on read)") << fmt;
    EXPECT_EQ(info.cloud.size(), 6u) << fmt;
  }
}

}  // namespace
}  // namespace treesketch::io
