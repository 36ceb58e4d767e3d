// Classified clouds: PLY and LAS 1.4 written with a class code and a probability read back by the
// project's own readers, the LAS extra byte where its VLR says, and bad arrays or extensions refused.
#include "treesketch/io/classified_cloud.h"

#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

#include "test_support.h"
#include "treesketch/io/las.h"
#include "treesketch/io/ply.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/util/error.h"

namespace treesketch::io {
namespace {

geom::PointCloud cloud() {
  geom::PointCloud c;
  for (int i = 0; i < 50; ++i) c.positions.emplace_back(500000.0 + 0.013 * i, 5400000.25 - 0.007 * i, 250.0 + 0.1 * i);
  return c;
}

TEST(ClassifiedCloud, PlyAndLasRoundTrip) {
  test::TempDir dir;
  const geom::PointCloud c = cloud();
  std::vector<std::uint8_t> codes(c.size());
  std::vector<float> p(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) {
    codes[i] = i % 3 == 0 ? 64 : 65;
    p[i] = static_cast<float>(i) / c.size();
  }
  for (const char* name : {"a.ply", "a.las"}) {
    writeClassifiedCloud(dir / name, c, codes, p);
    const geom::PointCloud back = readPointCloud(dir / name);
    ASSERT_EQ(back.size(), c.size()) << name;
    ASSERT_EQ(back.classification.size(), c.size()) << name;
    for (std::size_t i = 0; i < c.size(); ++i) {
      EXPECT_EQ(back.classification[i], codes[i]) << name << " " << i;
      EXPECT_NEAR((back.positions[i] - c.positions[i]).norm(), 0.0, 1e-4) << name << " " << i;  // LAS: 0.1 mm
    }
  }
  // LAS: version 1.4, format 6, one float after the 30 bytes of each record.
  const LasHeader h = readLasHeader(dir / "a.las");
  EXPECT_EQ(h.versionMinor, 4);
  EXPECT_EQ(h.pointFormat, 6);
  EXPECT_EQ(h.recordLength, 34);
  EXPECT_EQ(h.pointCount, c.size());
  const std::string bytes = test::readText(dir / "a.las");
  EXPECT_NE(bytes.find("wood_probability"), std::string::npos);
  for (std::size_t i = 0; i < c.size(); ++i) {
    float v;
    std::memcpy(&v, bytes.data() + h.offsetToPointData + i * h.recordLength + 30, 4);
    EXPECT_FLOAT_EQ(v, p[i]) << i;
  }
  // PLY: the probability property by name in the header.
  const PlyHeader ph = readPlyHeader(dir / "a.ply");
  ASSERT_NE(ph.find("vertex"), nullptr);
  EXPECT_GE(ph.find("vertex")->find("wood_probability"), 0);
}

TEST(ClassifiedCloud, BadArraysAndExtensionsAreRefused) {
  test::TempDir dir;
  const geom::PointCloud c = cloud();
  EXPECT_THROW(writeClassifiedCloud(dir / "a.ply", c, std::vector<std::uint8_t>(3), std::vector<float>(c.size())),
               OptionsError);
  EXPECT_THROW(
      writeClassifiedCloud(dir / "a.xyz", c, std::vector<std::uint8_t>(c.size()), std::vector<float>(c.size())),
      OutputError);
  geom::PointCloud bad = c;
  bad.positions[7].x() = NAN;
  std::ostringstream out;
  EXPECT_THROW(writeClassifiedCloud(out, true, bad, std::vector<std::uint8_t>(c.size()), std::vector<float>(c.size())),
               OutputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "a.ply"));
}

}  // namespace
}  // namespace treesketch::io
