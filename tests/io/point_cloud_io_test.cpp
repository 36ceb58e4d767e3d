#include "treesketch/io/point_cloud_io.h"

#include <gtest/gtest.h>

#include <sstream>

#include "io_test_util.h"
#include "test_support.h"
#include "treesketch/io/ply.h"

namespace treesketch::io {
namespace {

using testing::expectError;

geom::PointCloud smallCloud() {
  geom::PointCloud c;
  for (int i = 0; i < 6; ++i) c.positions.emplace_back(0.5 * i, 1.25 * i, 600000.0 + i);
  return c;
}

TEST(PointCloudIo, FormatFromExtension) {
  EXPECT_EQ(cloudFormatFromPath("a.ply"), CloudFormat::Ply);
  EXPECT_EQ(cloudFormatFromPath("dir/a.PLY"), CloudFormat::Ply);
  EXPECT_EQ(cloudFormatFromPath("a.xyz"), CloudFormat::Xyz);
  EXPECT_EQ(cloudFormatFromPath("a.txt"), CloudFormat::Xyz);
  EXPECT_EQ(cloudFormatFromPath("a.csv"), CloudFormat::Xyz);
  EXPECT_EQ(cloudFormatFromPath("a.pts"), CloudFormat::Xyz);
  EXPECT_EQ(cloudFormatFromPath("a.ASC"), CloudFormat::Xyz);
  EXPECT_EQ(cloudFormatFromPath("a.las"), CloudFormat::Las);
  EXPECT_EQ(cloudFormatFromPath("a.obj"), CloudFormat::Obj);
  expectError([] { cloudFormatFromPath("a.e57"); }, {"a.e57", "unknown point cloud extension", ".ply", ".las", ".xyz"});
  expectError([] { cloudFormatFromPath("noext"); }, {"noext"});
  EXPECT_EQ(cloudFormatFromPath("a.LAZ"), CloudFormat::Las);
}

TEST(PointCloudIo, WriteAndReadBackByExtension) {
  test::TempDir dir;
  geom::PointCloud c = smallCloud();
  c.station = {0, 0, 1, 1, 2, 2};
  for (const char* name : {"c.ply", "c.xyz", "c.txt"}) {
    writePointCloud(dir / name, c);
    geom::PointCloud back = readPointCloud(dir / name);
    EXPECT_EQ(back.positions, c.positions) << name;
    if (std::string(name) == "c.ply") EXPECT_EQ(back.station, c.station);
  }
  expectError<OutputError>([&] { writePointCloud(dir / "c.las", c); }, {"c.las", ".ply"});
  expectError<OutputError>([&] { writePointCloud(dir / "missing" / "c.ply", c); }, {"does not exist"});
  EXPECT_FALSE(std::filesystem::exists(dir / "c.las"));
}

TEST(PointCloudIo, StreamVersionsDispatchOnFormat) {
  geom::PointCloud c = smallCloud();
  for (CloudFormat f : {CloudFormat::Ply, CloudFormat::Xyz}) {
    std::stringstream ss;
    writePointCloud(ss, f, c);
    EXPECT_EQ(readPointCloud(ss, "mem", f).positions, c.positions);
  }
  std::ostringstream out;
  expectError<OutputError>([&] { writePointCloud(out, CloudFormat::Las, c); }, {"PLY or XYZ"});
}

TEST(PointCloudIo, MeshFilesReadAsTheirVertices) {
  test::TempDir dir;
  geom::TriMesh m;
  m.vertices = {geom::Vec3(0, 0, 0), geom::Vec3(1, 0, 0), geom::Vec3(0, 1, 0), geom::Vec3(0, 0, 1)};
  m.triangles = {{0, 1, 2}, {0, 1, 3}};
  writePlyMesh(dir / "m.ply", m);
  EXPECT_EQ(readPointCloud(dir / "m.ply").positions, m.vertices);
  test::writeText(dir / "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n");
  EXPECT_EQ(readPointCloud(dir / "m.obj").positions, m.vertices);
  test::writeText(dir / "small.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expectError([&] { readPointCloud(dir / "small.obj"); }, {"small.obj", "only 3 points"});
}

TEST(PointCloudIo, BadFilesAreInputErrorsNamingTheFile) {
  test::TempDir dir;
  expectError([&] { readPointCloud(dir / "none.ply"); }, {"none.ply", "not found"});
  test::writeText(dir / "empty.ply", "");
  expectError([&] { readPointCloud(dir / "empty.ply"); }, {"empty.ply", "empty"});
  test::writeText(dir / "empty.las", "");
  expectError([&] { readPointCloud(dir / "empty.las"); }, {"empty.las", "empty"});
  test::writeText(dir / "three.xyz", "0 0 0\n1 0 0\n0 1 0\n");
  expectError([&] { readPointCloud(dir / "three.xyz"); }, {"three.xyz", "only 3 points"});
  CloudReadOptions any;
  any.minPoints = 1;
  EXPECT_EQ(readPointCloud(dir / "three.xyz", any).size(), 3u);
}

TEST(PointCloudIo, CheckCloudSize) {
  geom::PointCloud c = smallCloud();
  EXPECT_NO_THROW(checkCloudSize(c, "x"));
  expectError([&] { checkCloudSize(c, "x", 7); }, {"x:", "only 6 points", "at least 7"});
  expectError([] { checkCloudSize(geom::PointCloud{}, "x"); }, {"x:", "no points"});
  EXPECT_NO_THROW(checkCloudSize(geom::PointCloud{}, "x", 0));
}

}  // namespace
}  // namespace treesketch::io
