#include "treesketch/io/xyz.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "io_test_util.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch::io {
namespace {

using testing::expectError;

geom::PointCloud readText(const std::string& text, const CloudReadOptions& opt = {}) {
  std::istringstream in(text);
  return readXyz(in, "mem.xyz", opt);
}

TEST(Xyz, RoundTripIsExactForUtmCoordinates) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  geom::PointCloud c;
  for (int i = 0; i < 500; ++i) c.positions.emplace_back(5e5 + 1000 * u(rng), 5.4e6 + 1000 * u(rng), 250 + u(rng));
  c.positions.emplace_back(-1e-300, 1e300, 0.1);
  std::stringstream ss;
  writeXyz(ss, c);
  geom::PointCloud back = readXyz(ss, "mem");
  ASSERT_EQ(back.size(), c.size());
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_EQ(back.positions[i], c.positions[i]) << i;
}

TEST(Xyz, PathRoundTripGoesThroughTheFile) {
  test::TempDir dir;
  geom::PointCloud c;
  for (int i = 0; i < 5; ++i) c.positions.emplace_back(i, 2 * i, 0.5 * i);
  writeXyz(dir / "a.xyz", c);
  EXPECT_EQ(test::readText(dir / "a.xyz").substr(0, 6), "0 0 0\n");
  EXPECT_EQ(readXyz(dir / "a.xyz").positions, c.positions);
}

TEST(Xyz, AcceptsSeparatorsHeadersCommentsCrlfAndExtraColumns) {
  std::string text =
      "X,Y,Z,intensity\r\n"
      "# a comment\r\n"
      "1,2,3,99\r\n"
      "\r\n"
      "4;5;6\r\n"
      "  7\t8 9 extra words here   \r\n"
      "// another comment\n"
      "+1e1 -2.5e-1 .5   \n"
      "11 12 13";  // no final newline
  geom::PointCloud c = readText(text);
  ASSERT_EQ(c.size(), 5u);
  EXPECT_EQ(c.positions[0], geom::Vec3(1, 2, 3));
  EXPECT_EQ(c.positions[1], geom::Vec3(4, 5, 6));
  EXPECT_EQ(c.positions[2], geom::Vec3(7, 8, 9));
  EXPECT_EQ(c.positions[3], geom::Vec3(10, -0.25, 0.5));
  EXPECT_EQ(c.positions[4], geom::Vec3(11, 12, 13));
}

TEST(Xyz, QuotedHeaderOfCloudCompareAsciiExport) {
  geom::PointCloud c = readText("\"x\" \"y\" \"z\" \"Intensity\"\r\n1 2 3 7\r\n4 5 6 8\r\n7 8 9 9\r\n0 0 1 10\r\n");
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c.positions[1], geom::Vec3(4, 5, 6));
  ASSERT_EQ(c.intensity.size(), 4u);
  EXPECT_EQ(c.intensity[3], 10.0f);
}

TEST(Xyz, HeaderPlacesCoordinatesAndAttributesWhereItNamesThem) {
  // Semicolons, an id before the coordinates, a text label and classification after them.
  std::string text =
      "id;Classification;X;Y;Z;label;Red;Green;Blue\n"
      "1;2;500000.125;5400000.0625;251.5;stem;255;0;0\n"
      "2;5;500001.25;5400001.5;252.75;leaf;0;255;0\n"
      "3;5;500002.5;5400002.75;253;leaf;0;0;255\n"
      "4;2;500003.75;5400003.875;254.25;stem;10;20;30\n";
  geom::PointCloud c = readText(text);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c.positions[0], geom::Vec3(500000.125, 5400000.0625, 251.5));
  EXPECT_EQ(c.positions[3], geom::Vec3(500003.75, 5400003.875, 254.25));
  ASSERT_EQ(c.classification.size(), 4u);
  EXPECT_EQ(c.classification[1], 5);
  ASSERT_EQ(c.color.size(), 4u);
  EXPECT_EQ(c.color[3], (std::array<std::uint8_t, 3>{10, 20, 30}));
  EXPECT_TRUE(c.intensity.empty());
}

TEST(Xyz, TabsAndCrlfWithUnnamedExtraColumnsIgnored) {
  geom::PointCloud c = readText(
      "X\tY\tZ\tlabel\tscore\r\n1\t2\t3\tA\t0.5\r\n4\t5\t6\tB\t0.25\r\n"
      "7\t8\t9\tC\t1\r\n1\t1\t1\tD\t0\r\n");
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c.positions[2], geom::Vec3(7, 8, 9));
  EXPECT_TRUE(c.intensity.empty());
  EXPECT_TRUE(c.color.empty());
}

TEST(Xyz, ManyDigitsFarFromTheOriginKeepDoublePrecision) {
  geom::PointCloud c = readText(
      "x y z\n512345.678901234 5412345.987654321 254.123456789\n"
      "512345.678901235 5412345.987654322 254.123456790\n0 0 0\n1 1 1\n");
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c.positions[0].x(), 512345.678901234);
  EXPECT_EQ(c.positions[0].y(), 5412345.987654321);
  EXPECT_NE(c.positions[0].x(), c.positions[1].x());  // 1e-9 apart: a float would merge them
}

TEST(Xyz, BadLineAfterNamedColumnsSaysWhichColumns) {
  expectError([] { readText("id x y z\n1 0 0 0\n2 1 1 1\n3 2 2 2\n4 3 oops 3\n"); },
              {"mem.xyz:5:", "columns 2, 3 and 4"});
  expectError([] { readText("1 2 3\n4 5 6\n7 8 nine\n"); }, {"mem.xyz:3:", "expected 'x y z'"});
}

TEST(Xyz, PointCountLineOfPtsFilesIsSkippedAsHeader) {
  geom::PointCloud c = readText("4\n0 0 0 1 255 0 0\n1 0 0 1 255 0 0\n0 1 0 1 0 0 0\n0 0 1 1 0 0 0\n");
  EXPECT_EQ(c.size(), 4u);
}

TEST(Xyz, RejectsEmptyAndBlankFiles) {
  expectError([] { readText(""); }, {"mem.xyz", "empty"});
  expectError([] { readText("\n\n  \n"); }, {"mem.xyz", "no point lines"});
}

TEST(Xyz, RejectsGarbageTextWithItsLine) {
  CloudReadOptions opt;
  opt.maxHeaderLines = 2;
  expectError([&] { readText("hello\nworld\nthis is\nnot a cloud\n", opt); }, {"mem.xyz:1:", "'hello'"});
  expectError([&] { readText("x y z\nworld\nthis is\nnot a cloud\n", opt); }, {"mem.xyz:2:", "'world'"});
  expectError([] { readText("0 0 0\n1 1 1\n2 2\n3 3 3\n4 4 4\n"); }, {"mem.xyz:3:", "'2 2'"});
  expectError([] { readText("0 0 0\n1 1 1\nx y z\n3 3 3\n"); }, {"mem.xyz:3:"});
  expectError([] { readText("0 0 0\n1 1 1e999\n"); }, {"mem.xyz:2:"});
  std::string binary("\x01\x02\xff\x00\x10", 5);
  expectError([&] { readText(binary + "\n" + binary + "\n", opt); }, {"mem.xyz"});
}

TEST(Xyz, AUtf8ByteOrderMarkIsSkipped) {
  geom::PointCloud c = readText("\xEF\xBB\xBF" "1 2 3\n4 5 6\n7 8 9\n0 0 1\n");
  ASSERT_EQ(c.size(), 4u);  // the first point is not taken for a header
  EXPECT_EQ(c.positions[0], geom::Vec3(1, 2, 3));
  c = readText("\xEF\xBB\xBF" "Z,Y,X\n3,2,1\n6,5,4\n9,8,7\n1,0,0\n");
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c.positions[0], geom::Vec3(1, 2, 3));
  expectError([] { readText(std::string("\xFF\xFE" "1\0 \0" "2\0", 8)); }, {"mem.xyz", "UTF-16", "UTF-8"});
}

TEST(Xyz, HeaderColumnsAreUsedByNameInAnyOrderAndCase) {
  // pandas' to_csv: an unnamed index column first
  geom::PointCloud c = readText(",x,y,z\n0,1.5,2.5,3.5\n1,4,5,6\n2,7,8,9\n3,1,1,1\n");
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c.positions[0], geom::Vec3(1.5, 2.5, 3.5));
  EXPECT_EQ(c.positions[3], geom::Vec3(1, 1, 1));
  c = readText("id,x,y,z\n10,1,2,3\n11,4,5,6\n12,7,8,9\n13,0,0,1\n");
  EXPECT_EQ(c.positions[0], geom::Vec3(1, 2, 3));
  c = readText("Z Y X\n3 2 1\n6 5 4\n9 8 7\n1 0 0\n");  // the tree does not lie on its side
  EXPECT_EQ(c.positions[0], geom::Vec3(1, 2, 3));
  EXPECT_EQ(c.positions[3], geom::Vec3(0, 0, 1));
  c = readText("index\ty\tZ\tX\n0\t2\t3\t1\n1\t5\t6\t4\n2\t8\t9\t7\n3\t0\t1\t0\n");
  EXPECT_EQ(c.positions[1], geom::Vec3(4, 5, 6));
}

TEST(Xyz, AnUnrecognisedHeaderIsAnErrorNamingIt) {
  expectError([] { readText("a b c\n1 2 3\n4 5 6\n7 8 9\n0 0 1\n"); },
              {"mem.xyz:1:", "'a b c'", "does not name the coordinate columns"});
  expectError([] { readText("easting,northing,height\n1,2,3\n4,5,6\n7,8,9\n0,0,1\n"); },
              {"mem.xyz:1:", "easting"});
  // a point count (PTS) and comments are not headers to check
  EXPECT_EQ(readText("# made by hand\n4\n1 2 3\n4 5 6\n7 8 9\n0 0 1\n").size(), 4u);
}

TEST(Xyz, RejectsDecimalCommas) {
  expectError([] { readText("x;y;z\n1,5;2,5;3,5\n"); }, {"mem.xyz:2:", "decimal"});
}

TEST(Xyz, RejectsNanAndInfWithTheirLine) {
  expectError([] { readText("0 0 0\n1 1 1\n2 nan 2\n3 3 3\n"); }, {"mem.xyz:3:", "non-finite"});
  expectError([] { readText("0 0 0\n1 1 1\n2 2 2\n3 3 -inf\n"); }, {"mem.xyz:4:", "non-finite"});
}

TEST(Xyz, RejectsCloudsSmallerThanTheMinimumUnlessAllowed) {
  expectError([] { readText("0 0 0\n1 0 0\n0 1 0\n"); }, {"mem.xyz", "only 3 points", "at least 4"});
  CloudReadOptions opt;
  opt.minPoints = 1;
  EXPECT_EQ(readText("0 0 0\n1 0 0\n0 1 0\n", opt).size(), 3u);
}

TEST(Xyz, MissingFileIsAnInputError) {
  test::TempDir dir;
  expectError([&] { readXyz(dir / "none.xyz"); }, {"none.xyz", "not found"});
  expectError([&] { readXyz(dir.path()); }, {"directory"});
}

TEST(Xyz, WriterRejectsNonFinitePoints) {
  geom::PointCloud c;
  c.positions.emplace_back(0, std::numeric_limits<double>::quiet_NaN(), 0);
  std::ostringstream out;
  expectError<OutputError>([&] { writeXyz(out, c); }, {"point 0", "non-finite"});
}

TEST(Xyz, RealAdTreeCloudWithTrailingSpaces) {
  auto path = test::sharedDataDir() / "real" / "adtree_tree7.xyz";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no shared data";
  geom::PointCloud c = readXyz(path);
  ASSERT_EQ(c.size(), 15130u);
  EXPECT_EQ(c.positions[0], geom::Vec3(-9.679, -9.128, 3.152));
  geom::Vec3 e = c.bounds().extent();
  EXPECT_NEAR(e.x(), 3.06, 0.01);
  EXPECT_NEAR(e.y(), 3.21, 0.01);
  EXPECT_NEAR(e.z(), 5.23, 0.01);
}

TEST(Xyz, RealRTwigCloud) {
  auto path = test::sharedDataDir() / "real" / "rtwig_cloud.txt";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no shared data";
  geom::PointCloud c = readXyz(path);
  ASSERT_EQ(c.size(), 14667u);
  EXPECT_EQ(c.positions[0], geom::Vec3(0.73229748, -16.39104271, 253.89553833));
  EXPECT_GT(c.bounds().min.z(), 253.0);
  EXPECT_LT(c.bounds().max.z(), 259.0);
}

// The text clouds of ../shared/data/real as they come: CloudCompare's .asc with a quoted header,
// a header-less .asc, a tab-separated table with an "X Y Z" header.
TEST(Xyz, RealTextVariantsLoadWithTheirPointCounts) {
  const auto real = test::sharedDataDir() / "real";
  if (!std::filesystem::exists(real / "voxr_Tree_t0.asc")) GTEST_SKIP() << "no shared data at " << real;
  struct Case {
    const char* name;
    std::size_t points;
    geom::Vec3 first;
  };
  const Case cases[] = {
      {"voxr_Tree_t0.asc", 49054, {-0.21034623, -0.25578769, 5.42987073}},
      {"plantscan3d_A3B4.asc", 20903, {-6.44799995, 3.90499997, 7.92000008}},
      {"rtls_pc_tree.txt", 75812, {9.149, -1.110, 0.001}},
  };
  for (const Case& k : cases) {
    geom::PointCloud c = readPointCloud(real / k.name);
    EXPECT_EQ(c.size(), k.points) << k.name;
    if (!c.empty()) EXPECT_EQ(c.positions[0], k.first) << k.name;
  }
}

TEST(Xyz, DamagedFilesGiveInputErrorsOnly) {
  std::string text = "x,y,z\n0 0 0\n1.5,2,3\n4;5;6 7\n-1e3 2e-3 +7\n8 9 10\n";
  testing::expectOnlyInputErrors(
      text, [](const std::string& b) { readText(b); }, 1000);
}

}  // namespace
}  // namespace treesketch::io
