#include "treesketch/io/las.h"

#include <gtest/gtest.h>

#include <set>
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

// Withheld records ("should be considered deleted", LAS 1.4 R15) are dropped on read and
// counted; the other flags keep their points; the attributes stay with their points.
TEST(Las, WithheldRecordsAreDroppedAndCounted) {
  struct Case {
    int minor, format;
  };
  for (const Case c : {Case{2, 0}, Case{2, 1}, Case{3, 3}, Case{4, 6}, Case{4, 7}}) {
    LasSpec s;
    s.versionMinor = c.minor;
    s.pointFormat = c.format;
    for (std::int32_t i = 0; i < 12; ++i) s.points.push_back({1000 * i, -7 * i, 3 * i});
    const std::set<std::size_t> withheld{1, 4, 5, 11};
    std::string b = buildLas(s);
    const std::uint8_t others = c.format >= 6 ? testing::kLasSynthetic | testing::kLasKeyPoint | testing::kLasOverlap
                                              : testing::kLasSynthetic | testing::kLasKeyPoint;
    for (std::size_t i = 0; i < s.points.size(); ++i)
      testing::setLasClass(b, s, i, static_cast<std::uint8_t>(i + 1),
                           withheld.count(i) ? testing::kLasWithheld : (i % 2 ? others : 0));
    LasHeader h;
    const geom::PointCloud cloud = lasFrom(b, &h);
    EXPECT_EQ(h.pointCount, s.points.size()) << c.format;
    EXPECT_EQ(h.withheld, withheld.size()) << c.format;
    ASSERT_EQ(cloud.size(), s.points.size() - withheld.size()) << c.format;
    ASSERT_EQ(cloud.classification.size(), cloud.size()) << c.format;
    EXPECT_NO_THROW(cloud.checkConsistent());
    std::size_t k = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      if (withheld.count(i)) continue;
      EXPECT_DOUBLE_EQ(cloud.positions[k].x(), s.points[i][0] * s.scale[0]) << c.format << " " << i;
      EXPECT_EQ(cloud.classification[k], i + 1) << c.format << " " << i;
      ++k;
    }
    // The same file with no record withheld: every point, none counted.
    std::string none = buildLas(s);
    LasHeader h0;
    EXPECT_EQ(lasFrom(none, &h0).size(), s.points.size());
    EXPECT_EQ(h0.withheld, 0u);
  }
}

TEST(Las, AFileOfWithheldPointsOnlyIsAClearError) {
  for (int fmt : {1, 6}) {
    LasSpec s;
    s.versionMinor = fmt >= 6 ? 4 : 2;
    s.pointFormat = fmt;
    s.points = somePoints();
    std::string b = buildLas(s);
    for (std::size_t i = 0; i < s.points.size(); ++i) testing::setLasClass(b, s, i, 1, testing::kLasWithheld);
    expectError([&] { lasFrom(b); }, {"mem.las", "holds 0 points not withheld", "5 of its 5", "deleted"});
    // One left: a clear error at the default minimum, a cloud of one point when any count will do.
    testing::setLasClass(b, s, 2, 1, 0);
    expectError([&] { lasFrom(b); }, {"mem.las", "holds 1 point not withheld", "4 of its 5"});
    CloudReadOptions any;
    any.minPoints = 1;
    LasHeader h;
    const geom::PointCloud one = lasFrom(b, &h, any);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(h.withheld, 4u);
    EXPECT_DOUBLE_EQ(one.positions[0].z(), s.points[2][2] * s.scale[2]);
  }
}

// The ASPRS noise classes are read as the file gives them (7 in every format; 18, a LAS 1.4 class,
// fits in the five bits of formats 0-5 too); setting them aside is the modelling's business.
TEST(Las, NoiseClassesAreReadAsTheFileGivesThem) {
  for (int fmt : {0, 6}) {
    LasSpec s;
    s.versionMinor = fmt >= 6 ? 4 : 2;
    s.pointFormat = fmt;
    s.points = somePoints();
    std::string b = buildLas(s);
    const std::uint8_t classes[] = {7, 1, 18, 2, 7};
    for (std::size_t i = 0; i < 5; ++i) testing::setLasClass(b, s, i, classes[i]);
    const geom::PointCloud c = lasFrom(b);
    ASSERT_EQ(c.classification.size(), 5u);
    for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(c.classification[i], classes[i]) << fmt << " " << i;
  }
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
