#include "treesketch/io/las.h"

#include <gtest/gtest.h>

#include <sstream>

#include "io_test_util.h"
#include "test_support.h"

namespace treesketch::io {
namespace {

using testing::buildLas;
using testing::expectError;
using testing::LasSpec;

geom::PointCloud lasFrom(const std::string& bytes, LasHeader* h = nullptr, const CloudReadOptions& opt = {}) {
  std::istringstream in(bytes);
  return readLas(in, "mem.las", opt, h);
}

std::vector<std::array<std::int32_t, 3>> somePoints() {
  return {{0, 0, 0}, {1000, -2000, 3000}, {-2147483647, 2147483647, 5}, {123456, 654321, -999}, {7, 8, 9}};
}

int versionFor(int format) { return format <= 1 ? 0 : format <= 3 ? 2 : format <= 5 ? 3 : 4; }

TEST(Las, EveryPointFormatReadsScaledCoordinates) {
  for (int fmt = 0; fmt <= 10; ++fmt) {
    for (int extra : {0, 5}) {
      LasSpec s;
      s.versionMinor = versionFor(fmt);
      s.pointFormat = fmt;
      s.recordLength = lasMinRecordLength(fmt) + extra;
      s.scale = {0.01, 0.001, 0.0001};
      s.offset = {500000, 5400000, 200};
      s.points = somePoints();
      s.vlrBytes = extra * 10;
      LasHeader h;
      geom::PointCloud c = lasFrom(buildLas(s), &h);
      EXPECT_EQ(h.pointFormat, fmt);
      EXPECT_EQ(h.versionMinor, s.versionMinor);
      ASSERT_EQ(c.size(), s.points.size()) << "format " << fmt;
      for (std::size_t i = 0; i < c.size(); ++i) {
        for (int k = 0; k < 3; ++k)
          EXPECT_EQ(c.positions[i][k], s.points[i][k] * s.scale[k] + s.offset[k]) << "format " << fmt << " point " << i;
      }
    }
  }
}

TEST(Las, EveryVersionReadsFormatZeroAndOne) {
  for (int minor = 0; minor <= 4; ++minor) {
    for (int fmt : {0, 1}) {
      LasSpec s;
      s.versionMinor = minor;
      s.pointFormat = fmt;
      s.points = somePoints();
      LasHeader h;
      EXPECT_EQ(lasFrom(buildLas(s), &h).size(), 5u) << minor;
      EXPECT_EQ(h.pointCount, 5u);
    }
  }
}

TEST(Las, Las14UsesThe64BitCountWhenTheLegacyOneIsZero) {
  LasSpec s;
  s.versionMinor = 4;
  s.pointFormat = 1;
  s.points = somePoints();
  s.legacyCount = 0;
  LasHeader h;
  EXPECT_EQ(lasFrom(buildLas(s), &h).size(), 5u);
  EXPECT_EQ(h.legacyPointCount, 0u);
  EXPECT_EQ(h.pointCount, 5u);
}

TEST(Las, HeaderFieldsAndBounds) {
  LasSpec s;
  s.points = somePoints();
  s.offset = {1, 2, 3};
  LasHeader h;
  geom::PointCloud c = lasFrom(buildLas(s), &h);
  EXPECT_EQ(h.systemId, "treesketch test");
  EXPECT_EQ(h.generatingSoftware, "io_test_util");
  EXPECT_EQ(h.headerSize, 227);
  EXPECT_EQ(h.offsetToPointData, 227u);
  EXPECT_EQ(h.recordLength, 20);
  EXPECT_EQ(h.scale, geom::Vec3(0.001, 0.001, 0.001));
  EXPECT_EQ(h.offset, geom::Vec3(1, 2, 3));
  geom::BBox b = c.bounds();
  EXPECT_EQ(b.min, h.min);
  EXPECT_EQ(b.max, h.max);
}

TEST(Las, RejectsBadHeaders) {
  LasSpec s;
  s.points = somePoints();
  std::string good = buildLas(s);
  expectError([] { lasFrom(""); }, {"mem.las", "empty"});
  expectError([] { lasFrom("PK\x03\x04 this is a zip"); }, {"mem.las: byte offset 0", "signature", "LASF"});
  expectError([&] { lasFrom(good.substr(0, 100)); }, {"mem.las", "truncated header"});
  std::string v = good;
  v[24] = 2;
  expectError([&] { lasFrom(v); }, {"byte offset 24", "version 2.2", "1.0 to 1.4"});
  v = good;
  v[25] = 5;
  expectError([&] { lasFrom(v); }, {"version 1.5"});
  LasSpec small = s;
  small.headerSizeOverride = 200;
  expectError([&] { lasFrom(buildLas(small)); }, {"byte offset 94", "header size 200"});
  LasSpec shortRec = s;
  shortRec.pointFormat = 3;
  shortRec.recordLength = 28;
  expectError([&] { lasFrom(buildLas(shortRec)); }, {"byte offset 105", "record length 28", "format 3", "at least 34"});
  v = good;
  v[104] = static_cast<char>(0x40);  // compressed (the old writers' bit), but no LASzip VLR
  expectError([&] { lasFrom(v); }, {"byte offset 227", "LASzip VLR"});
  v = good;
  v[104] = 11;
  expectError([&] { lasFrom(v); }, {"byte offset 104", "format 11"});
  LasSpec zeroScale = s;
  zeroScale.scale = {0.001, 0, 0.001};
  expectError([&] { lasFrom(buildLas(zeroScale)); }, {"byte offset 139", "scale"});
}

TEST(Las, RejectsTruncatedPointsAndHugeCounts) {
  LasSpec s;
  s.points = somePoints();
  std::string bytes = buildLas(s);
  expectError([&] { lasFrom(bytes.substr(0, bytes.size() - 3)); },
              {"mem.las: byte offset " + std::to_string(227 + 4 * 20), "truncated", "promises 5 points", "only 4"});
  LasSpec huge = s;
  huge.legacyCount = 4000000000;
  expectError([&] { lasFrom(buildLas(huge)); }, {"truncated", "4000000000"});
  LasSpec huge14 = s;
  huge14.versionMinor = 4;
  huge14.count64 = 1000000000000;
  expectError([&] { lasFrom(buildLas(huge14)); }, {"truncated", "1000000000000"});
  LasSpec three = s;
  three.points.resize(3);
  expectError([&] { lasFrom(buildLas(three)); }, {"mem.las", "only 3 points"});
  CloudReadOptions any;
  any.minPoints = 1;
  EXPECT_EQ(lasFrom(buildLas(three), nullptr, any).size(), 3u);
}

TEST(Las, TheFormatByteNotTheExtensionSaysCompressed) {
  test::TempDir dir;
  LasSpec s;
  s.points = somePoints();
  test::writeText(dir / "a.laz", buildLas(s));  // plain LAS named .laz
  EXPECT_EQ(readLas(dir / "a.laz").size(), 5u);
  EXPECT_FALSE(readLasHeader(dir / "a.laz").compressed);
  std::string flagged = buildLas(s);
  flagged[104] = static_cast<char>(0x80);  // compression bit, point format 0, and no LASzip VLR
  test::writeText(dir / "b.las", flagged);
  EXPECT_TRUE(readLasHeader(dir / "b.las").compressed);
  EXPECT_EQ(readLasHeader(dir / "b.las").pointFormat, 0);
  expectError([&] { readLas(dir / "b.las"); }, {"b.las", "byte offset 227", "no LASzip VLR", "expected one"});
}

TEST(Las, RealArchiTreeMatchesItsHeader) {
  auto path = test::sharedDataDir() / "real" / "archi_Tree_2_point_cloud.las";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no shared data";
  LasHeader h;
  geom::PointCloud c = readLas(path, {}, &h);
  EXPECT_EQ(h.versionMajor, 1);
  EXPECT_EQ(h.versionMinor, 2);
  EXPECT_EQ(h.pointFormat, 0);
  EXPECT_EQ(h.pointCount, 58219u);
  ASSERT_EQ(c.size(), 58219u);
  geom::BBox b = c.bounds();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b.min[k], h.min[k], 0.5 * h.scale[k]);
    EXPECT_NEAR(b.max[k], h.max[k], 0.5 * h.scale[k]);
  }
  EXPECT_NEAR(b.extent().z(), 6.20, 0.01);
}

TEST(Las, DamagedFilesGiveInputErrorsOnly) {
  for (int fmt : {0, 6}) {
    LasSpec s;
    s.versionMinor = fmt == 0 ? 2 : 4;
    s.pointFormat = fmt;
    s.points = somePoints();
    testing::expectOnlyInputErrors(
        buildLas(s), [](const std::string& b) { lasFrom(b); }, 1000);
  }
}

}  // namespace
}  // namespace treesketch::io
