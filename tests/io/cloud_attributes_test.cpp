// Intensity, RGB and classification read into geom::PointCloud by the LAS, text and PLY readers.
#include <gtest/gtest.h>

#include <sstream>

#include "io_test_util.h"
#include "treesketch/io/las.h"
#include "treesketch/io/ply.h"
#include "treesketch/io/xyz.h"
#include "treesketch/util/error.h"

namespace treesketch::io {
namespace {

using testing::buildLas;
using testing::LasSpec;

/// Overwrites `bytes` (an uncompressed LAS) at `offset` inside record `i`.
template <class T>
void poke(std::string& las, const LasSpec& s, std::size_t i, int offset, T value) {
  std::size_t header = s.versionMinor >= 4 ? 375 : s.versionMinor == 3 ? 235 : 227;
  static const int kMin[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  std::size_t at = header + i * static_cast<std::size_t>(kMin[s.pointFormat]) + static_cast<std::size_t>(offset);
  for (std::size_t b = 0; b < sizeof(T); ++b)
    las[at + b] = static_cast<char>((static_cast<std::uint64_t>(value) >> (8 * b)) & 0xFF);
}

geom::PointCloud las(const std::string& bytes) {
  std::istringstream in(bytes);
  return readLas(in, "mem.las");
}

LasSpec fourPoints(int format, int minor = 2) {
  LasSpec s;
  s.pointFormat = format;
  s.versionMinor = minor;
  s.points = {{0, 0, 0}, {1000, 0, 0}, {0, 1000, 0}, {0, 0, 1000}};
  return s;
}

TEST(CloudAttributes, LasFormat0IntensityAndClassInTheLowFiveBits) {
  LasSpec s = fourPoints(0);
  std::string b = buildLas(s);
  for (std::size_t i = 0; i < 4; ++i) {
    poke<std::uint16_t>(b, s, i, 12, static_cast<std::uint16_t>(100 * i + 7));
    poke<std::uint8_t>(b, s, i, 15, static_cast<std::uint8_t>(0x60 | (i + 2)));  // flags in bits 5-6
  }
  geom::PointCloud c = las(b);
  ASSERT_EQ(c.intensity.size(), 4u);
  ASSERT_EQ(c.classification.size(), 4u);
  EXPECT_TRUE(c.color.empty());  // format 0 has no colour
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(c.intensity[i], static_cast<float>(100 * i + 7));
    EXPECT_EQ(c.classification[i], i + 2);
  }
  EXPECT_NO_THROW(c.checkConsistent());
}

TEST(CloudAttributes, LasAllZeroAttributesAreDropped) {
  LasSpec s = fourPoints(2);
  std::string b = buildLas(s);
  for (std::size_t i = 0; i < 4; ++i) {
    poke<std::uint16_t>(b, s, i, 12, 0);
    poke<std::uint8_t>(b, s, i, 15, 0);
    for (int k = 0; k < 3; ++k) poke<std::uint16_t>(b, s, i, 20 + 2 * k, 0);
  }
  geom::PointCloud c = las(b);
  EXPECT_TRUE(c.intensity.empty());
  EXPECT_TRUE(c.classification.empty());
  EXPECT_TRUE(c.color.empty());
}

TEST(CloudAttributes, LasColourSixteenBitScaledEightBitKept) {
  for (bool wide : {true, false}) {
    LasSpec s = fourPoints(3);  // RGB at byte 28
    std::string b = buildLas(s);
    for (std::size_t i = 0; i < 4; ++i) {
      std::uint16_t v = static_cast<std::uint16_t>(wide ? 65535 / (i + 1) : 50 * i);
      poke<std::uint16_t>(b, s, i, 28, v);
      poke<std::uint16_t>(b, s, i, 30, static_cast<std::uint16_t>(wide ? 0 : 1));
      poke<std::uint16_t>(b, s, i, 32, static_cast<std::uint16_t>(wide ? 65535 : 255));
    }
    geom::PointCloud c = las(b);
    ASSERT_EQ(c.color.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
      int expectRed = wide ? static_cast<int>((65535 / (i + 1) + 128) / 257) : static_cast<int>(50 * i);
      EXPECT_EQ(c.color[i][0], expectRed) << wide << " " << i;
      EXPECT_EQ(c.color[i][1], wide ? 0 : 1);
      EXPECT_EQ(c.color[i][2], 255);
    }
  }
}

TEST(CloudAttributes, LasFormat7ClassIsAWholeByteAndRgbAt30) {
  LasSpec s = fourPoints(7, 4);
  std::string b = buildLas(s);
  for (std::size_t i = 0; i < 4; ++i) {
    poke<std::uint8_t>(b, s, i, 15, 0xFB);  // classification flags (not withheld), scanner channel: not the class
    poke<std::uint8_t>(b, s, i, 16, static_cast<std::uint8_t>(64 + i));  // user-defined classes
    for (int k = 0; k < 3; ++k) poke<std::uint16_t>(b, s, i, 30 + 2 * k, static_cast<std::uint16_t>(10 * k + i));
  }
  geom::PointCloud c = las(b);
  ASSERT_EQ(c.classification.size(), 4u);
  ASSERT_EQ(c.color.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(c.classification[i], 64 + i);
    EXPECT_EQ(c.color[i][2], 20 + i);
  }
}

geom::PointCloud text(const std::string& t) {
  std::istringstream in(t);
  return readXyz(in, "mem.xyz");
}

TEST(CloudAttributes, TextColumnsNamedByTheHeader) {
  geom::PointCloud c = text(
      "X,Y,Z,Classification,R,G,B,Intensity\n"
      "0,0,0,2,10,20,30,0.5\n1,0,0,5,40,50,60,0.25\n0,1,0,5,70,80,90,1\n0,0,1,6,1,2,3,0\n");
  ASSERT_EQ(c.size(), 4u);
  ASSERT_EQ(c.classification.size(), 4u);
  ASSERT_EQ(c.intensity.size(), 4u);
  ASSERT_EQ(c.color.size(), 4u);
  EXPECT_EQ(c.classification[0], 2);
  EXPECT_EQ(c.classification[3], 6);
  EXPECT_FLOAT_EQ(c.intensity[1], 0.25f);
  EXPECT_EQ(c.color[1][0], 40);
  EXPECT_EQ(c.color[2][2], 90);
}

TEST(CloudAttributes, TextCloudCompareHeaderWithFloatColours) {
  geom::PointCloud c =
      text("//X Y Z Rf Gf Bf scalar_Intensity\n0 0 0 1 0 0.5 3\n1 0 0 0 1 0 4\n0 1 0 0 0 1 5\n0 0 1 1 1 1 6\n");
  ASSERT_EQ(c.color.size(), 4u);
  EXPECT_EQ(c.color[0][0], 255);
  EXPECT_EQ(c.color[0][2], 128);  // 0.5 * 255 rounded
  ASSERT_EQ(c.intensity.size(), 4u);
  EXPECT_FLOAT_EQ(c.intensity[3], 6.0f);
}

TEST(CloudAttributes, TextColumnsByCountWithoutAHeader) {
  geom::PointCloud i4 = text("0 0 0 7\n1 0 0 8\n0 1 0 9\n0 0 1 10\n");
  EXPECT_EQ(i4.intensity.size(), 4u);
  EXPECT_TRUE(i4.color.empty());
  geom::PointCloud c6 = text("0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n0 0 1 9 9 9\n");
  EXPECT_TRUE(c6.intensity.empty());
  ASSERT_EQ(c6.color.size(), 4u);
  EXPECT_EQ(c6.color[1][1], 255);
  EXPECT_EQ(c6.color[3][0], 9);
  geom::PointCloud pts = text("4\n0 0 0 -5 255 0 0\n1 0 0 12 0 255 0\n0 1 0 3 0 0 255\n0 0 1 1 9 9 9\n");  // Leica PTS
  ASSERT_EQ(pts.intensity.size(), 4u);
  EXPECT_FLOAT_EQ(pts.intensity[0], -5.0f);
  ASSERT_EQ(pts.color.size(), 4u);
  EXPECT_EQ(pts.color[2][2], 255);
  geom::PointCloud five = text("0 0 0 1 2\n1 0 0 1 2\n0 1 0 1 2\n0 0 1 1 2\n");  // we do not guess
  EXPECT_TRUE(five.intensity.empty() && five.color.empty() && five.classification.empty());
}

TEST(CloudAttributes, TextLineWithoutTheColumnsDropsThemNotTheFile) {
  geom::PointCloud c = text("0 0 0 7\n1 0 0 8\n0 1 0\n0 0 1 10\n");
  EXPECT_EQ(c.size(), 4u);
  EXPECT_TRUE(c.intensity.empty());
  geom::PointCloud bad = text("x y z classification\n0 0 0 2\n1 0 0 300\n0 1 0 2\n0 0 1 2\n");  // not a class
  EXPECT_EQ(bad.size(), 4u);
  EXPECT_TRUE(bad.classification.empty());
}

TEST(CloudAttributes, PlyIntensityColourAndClassification) {
  std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float scalar_Intensity\n"
      "property uchar classification\nend_header\n"
      "0 0 0 1 2 3 0.5 2\n1 0 0 4 5 6 1.5 5\n0 1 0 7 8 9 2.5 5\n0 0 1 10 11 12 3.5 6\n";
  std::istringstream in(ply);
  geom::PointCloud c = readPlyPointCloud(in, "mem.ply");
  ASSERT_EQ(c.color.size(), 4u);
  ASSERT_EQ(c.intensity.size(), 4u);
  ASSERT_EQ(c.classification.size(), 4u);
  EXPECT_EQ(c.color[3][2], 12);
  EXPECT_FLOAT_EQ(c.intensity[2], 2.5f);
  EXPECT_EQ(c.classification[3], 6);
  std::string badClass = ply;
  badClass.replace(badClass.rfind(" 6\n"), 3, " 6.5\n");
  std::istringstream in2(badClass);
  EXPECT_THROW(readPlyPointCloud(in2, "mem.ply"), InputError);
}

TEST(CloudAttributes, AppendKeepsAttributesOnlyWhenBothHaveThem) {
  geom::PointCloud a = text("0 0 0 7\n1 0 0 8\n0 1 0 9\n0 0 1 10\n");
  geom::PointCloud b = a;
  a.append(b);
  EXPECT_EQ(a.intensity.size(), 8u);
  geom::PointCloud plain = text("0 0 0\n1 0 0\n0 1 0\n0 0 1\n");
  a.append(plain);
  EXPECT_TRUE(a.intensity.empty());
  EXPECT_NO_THROW(a.checkConsistent());
  a.classification.resize(3);
  EXPECT_THROW(a.checkConsistent(), OptionsError);
}

}  // namespace
}  // namespace treesketch::io
