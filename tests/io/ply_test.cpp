#include "treesketch/io/ply.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "io_test_util.h"
#include "test_support.h"

namespace treesketch::io {
namespace {

using testing::expectError;
using testing::put;

geom::PointCloud cloudFrom(const std::string& bytes, const CloudReadOptions& opt = {}) {
  std::istringstream in(bytes);
  return readPlyPointCloud(in, "mem.ply", opt);
}
geom::TriMesh meshFrom(const std::string& bytes) {
  std::istringstream in(bytes);
  return readPlyMesh(in, "mem.ply");
}

/// Appends value `v` as PLY type `t`.
void putAs(std::string& s, PlyType t, double v, bool big) {
  switch (t) {
    case PlyType::Int8:
      put(s, static_cast<std::int8_t>(v), big);
      break;
    case PlyType::UInt8:
      put(s, static_cast<std::uint8_t>(v), big);
      break;
    case PlyType::Int16:
      put(s, static_cast<std::int16_t>(v), big);
      break;
    case PlyType::UInt16:
      put(s, static_cast<std::uint16_t>(v), big);
      break;
    case PlyType::Int32:
      put(s, static_cast<std::int32_t>(v), big);
      break;
    case PlyType::UInt32:
      put(s, static_cast<std::uint32_t>(v), big);
      break;
    case PlyType::Float32:
      put(s, static_cast<float>(v), big);
      break;
    case PlyType::Float64:
      put(s, v, big);
      break;
  }
}

geom::PointCloud randomCloud(int n, bool attributes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  geom::PointCloud c;
  for (int i = 0; i < n; ++i) {
    c.positions.emplace_back(5e5 + u(rng), 5.4e6 + u(rng), 250 + u(rng));
    if (attributes) {
      c.station.push_back(i % 3);
      c.meshId.push_back(-i);
    }
  }
  return c;
}

TEST(Ply, CloudRoundTripKeepsPositionsAndAttributesExactly) {
  geom::PointCloud c = randomCloud(300, true);
  std::stringstream ss;
  writePlyPointCloud(ss, c);
  geom::PointCloud back = readPlyPointCloud(ss, "mem");
  EXPECT_EQ(back.positions, c.positions);
  EXPECT_EQ(back.station, c.station);
  EXPECT_EQ(back.meshId, c.meshId);
}

TEST(Ply, CloudRoundTripWithoutAttributesThroughAFile) {
  test::TempDir dir;
  geom::PointCloud c = randomCloud(50, false);
  writePlyPointCloud(dir / "c.ply", c);
  geom::PointCloud back = readPlyPointCloud(dir / "c.ply");
  EXPECT_EQ(back.positions, c.positions);
  EXPECT_TRUE(back.station.empty());
  EXPECT_TRUE(back.meshId.empty());
  PlyHeader h = readPlyHeader(dir / "c.ply");
  EXPECT_EQ(h.format, PlyFormat::BinaryLittleEndian);
  ASSERT_NE(h.find("vertex"), nullptr);
  EXPECT_EQ(h.find("vertex")->count, 50u);
}

TEST(Ply, EveryScalarTypeInBothByteOrders) {
  const PlyType types[] = {PlyType::Int8,  PlyType::UInt8,  PlyType::Int16,   PlyType::UInt16,
                           PlyType::Int32, PlyType::UInt32, PlyType::Float32, PlyType::Float64};
  const char* aliases[] = {"int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  for (bool big : {false, true}) {
    for (int ti = 0; ti < 8; ++ti) {
      for (bool alias : {false, true}) {
        PlyType t = types[ti];
        std::string name = alias ? aliases[ti] : toString(t);
        std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                        " 1.0\nelement vertex 4\nproperty " + name + " x\nproperty " + name + " y\nproperty " + name +
                        " z\nend_header\n";
        for (int i = 0; i < 4; ++i) {
          putAs(s, t, i + 1, big);
          putAs(s, t, 2 * i + 3, big);
          putAs(s, t, 100 + i, big);
        }
        geom::PointCloud c = cloudFrom(s);
        ASSERT_EQ(c.size(), 4u) << name;
        for (int i = 0; i < 4; ++i) EXPECT_EQ(c.positions[i], geom::Vec3(i + 1, 2 * i + 3, 100 + i)) << name << big;
      }
    }
  }
}

TEST(Ply, BigEndianWithMixedTypesExtraPropertiesAndElements) {
  const bool big = true;
  std::string s =
      "ply\nformat binary_big_endian 1.0\ncomment made in code\nobj_info nothing\n"
      "element camera 2\nproperty float view_px\nproperty list uchar int ids\n"
      "element vertex 5\nproperty uchar flags\nproperty float x\nproperty double y\nproperty short z\n"
      "property list ushort float normals\nproperty int station\nproperty uint mesh\n"
      "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  for (int i = 0; i < 2; ++i) {
    put(s, 1.5f, big);
    put<std::uint8_t>(s, static_cast<std::uint8_t>(i + 1), big);
    for (int k = 0; k <= i; ++k) put<std::int32_t>(s, k, big);
  }
  for (int i = 0; i < 5; ++i) {
    put<std::uint8_t>(s, 9, big);
    put(s, 0.25f * static_cast<float>(i), big);
    put(s, -1.0 / 3.0 * i, big);
    put<std::int16_t>(s, static_cast<std::int16_t>(-1000 + i), big);
    put<std::uint16_t>(s, 2, big);
    put(s, 7.f, big);
    put(s, 8.f, big);
    put<std::int32_t>(s, i * 10, big);
    put<std::uint32_t>(s, 3, big);
  }
  put<std::uint8_t>(s, 3, big);
  for (std::uint32_t k : {0u, 1u, 2u}) put(s, k, big);
  geom::PointCloud c = cloudFrom(s);
  ASSERT_EQ(c.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(c.positions[i], geom::Vec3(0.25 * i, -1.0 / 3.0 * i, -1000 + i));
    EXPECT_EQ(c.station[i], i * 10);
    EXPECT_EQ(c.meshId[i], 3);
  }
  geom::TriMesh m = meshFrom(s);
  EXPECT_EQ(m.vertices.size(), 5u);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
}

TEST(Ply, AsciiMeshWithPolygonsCrlfHeaderAndColors) {
  std::string s =
      "ply\r\nformat ascii 1.0\r\ncomment quads and a pentagon\r\nelement vertex 6\r\nproperty float32 x\r\n"
      "property float32 y\r\nproperty float32 z\r\nproperty uchar red\r\nproperty uchar green\r\nproperty uchar "
      "blue\r\n"
      "element face 3\r\nproperty list uint8 int32 vertex_indices\r\nproperty int flags\r\nend_header\r\n"
      "0 0 0 255 0 0\r\n1 0 0 0 255 0\r\n1 1 0 0 0 255\r\n0 1 0 1 2 3\r\n0.5 1.5 0 4 5 6\r\n-1 0.5 1e-1 7 8 9\r\n"
      "3 0 1 2 0\r\n4 0 1 2 3 0\r\n5 0 1 4 3 5 1\r\n";
  geom::TriMesh m = meshFrom(s);
  ASSERT_EQ(m.vertices.size(), 6u);
  EXPECT_EQ(m.vertices[5], geom::Vec3(-1, 0.5, 0.1));  // ascii values are read as written
  ASSERT_EQ(m.triangles.size(), 1u + 2u + 3u);
  EXPECT_EQ(m.triangles[1], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[2], (std::array<std::uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(m.triangles[5], (std::array<std::uint32_t, 3>{0, 3, 5}));
  ASSERT_EQ(m.colors.size(), 6u);
  EXPECT_EQ(m.colors[1], (std::array<std::uint8_t, 3>{0, 255, 0}));
  EXPECT_TRUE(m.quality.empty());
  // The same file read as a cloud gives its vertices.
  EXPECT_EQ(cloudFrom(s).size(), 6u);
}

TEST(Ply, MeshRoundTripWithColourAndQuality) {
  geom::TriMesh m;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 10);
  for (int i = 0; i < 20; ++i) {
    m.vertices.emplace_back(u(rng), u(rng), u(rng));
    m.colors.push_back({static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(2 * i), 255});
    m.quality.push_back(u(rng));
  }
  for (std::uint32_t i = 0; i + 2 < 20; ++i) m.triangles.push_back({i, i + 1, i + 2});
  std::stringstream ss;
  writePlyMesh(ss, m);
  std::string bytes = ss.str();
  EXPECT_NE(bytes.find("property float quality\n"), std::string::npos);
  EXPECT_NE(bytes.find("property uchar red\n"), std::string::npos);
  geom::TriMesh back = meshFrom(bytes);
  EXPECT_EQ(back.vertices, m.vertices);
  EXPECT_EQ(back.triangles, m.triangles);
  EXPECT_EQ(back.colors, m.colors);
  ASSERT_EQ(back.quality.size(), m.quality.size());
  for (std::size_t i = 0; i < m.quality.size(); ++i) EXPECT_EQ(back.quality[i], static_cast<float>(m.quality[i]));
}

TEST(Ply, MeshRoundTripWithoutAttributesThroughAFile) {
  test::TempDir dir;
  geom::TriMesh m;
  m.vertices = {geom::Vec3(0, 0, 0), geom::Vec3(1, 0, 0), geom::Vec3(0, 1, 0), geom::Vec3(0, 0, 1)};
  m.triangles = {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}};
  writePlyMesh(dir / "m.ply", m);
  geom::TriMesh back = readPlyMesh(dir / "m.ply");
  EXPECT_EQ(back.vertices, m.vertices);
  EXPECT_EQ(back.triangles, m.triangles);
  EXPECT_TRUE(back.colors.empty());
  EXPECT_TRUE(back.quality.empty());
}

const std::string kAsciiHead =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n";

TEST(Ply, RejectsBadHeaders) {
  expectError([] { cloudFrom(""); }, {"mem.ply", "empty"});
  expectError([] { cloudFrom("plyx\nformat ascii 1.0\nend_header\n"); }, {"mem.ply:1:", "'ply'"});
  expectError([] { cloudFrom("ply\nelement vertex 1\nproperty float x\nend_header\n"); }, {"mem.ply:4:", "format"});
  expectError([] { cloudFrom("ply\nformat binary_middle_endian 1.0\nend_header\n"); },
              {"mem.ply:2:", "unsupported PLY format", "binary_middle_endian"});
  expectError([] { cloudFrom("ply\nformat ascii 2.0\nend_header\n"); }, {"mem.ply:2:", "version"});
  expectError([] { cloudFrom("ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n"); },
              {"mem.ply:4:", "unknown PLY type", "float128"});
  expectError([] { cloudFrom("ply\nformat ascii 1.0\nproperty float x\nend_header\n"); }, {"mem.ply:3:", "before any"});
  expectError([] { cloudFrom("ply\nformat ascii 1.0\nelement vertex -3\nend_header\n"); }, {"mem.ply:3:", "count"});
  expectError([] { cloudFrom(kAsciiHead + "0 0 0\n"); }, {"end_header"});
  expectError(
      [] {
        cloudFrom("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n");
      },
      {"mem.ply", "'z'"});
  expectError([] { cloudFrom("ply\nformat ascii 1.0\nelement point 1\nproperty float x\nend_header\n0\n"); },
              {"mem.ply", "no 'vertex' element"});
  expectError([] { cloudFrom("ply\nformat ascii 1.0\nbogus line\nend_header\n"); }, {"mem.ply:3:", "bogus"});
}

TEST(Ply, ElementsWithoutPropertiesAreSkippedWhateverTheirCount) {
  for (const char* fmt : {"ascii", "binary_little_endian"}) {
    std::string s = std::string("ply\nformat ") + fmt +
                    " 1.0\nelement nothing 1000000000000\nelement vertex 4\nproperty uchar x\nproperty uchar y\n"
                    "property uchar z\nend_header\n";
    s += std::string(fmt) == "ascii" ? "1 2 3\n4 5 6\n7 8 9\n10 11 12\n"
                                     : "\x01\x02\x03\x04\x05\x06\x07\x08\x09\x0a\x0b\x0c";
    geom::PointCloud c = cloudFrom(s);
    ASSERT_EQ(c.size(), 4u) << fmt;
    EXPECT_EQ(c.positions[3], geom::Vec3(10, 11, 12)) << fmt;
  }
}

TEST(Ply, RejectsTruncatedAndBadAsciiData) {
  expectError([] { cloudFrom(kAsciiHead + "end_header\n0 0 0\n1 1 1\n2 2\n"); },
              {"mem.ply:", "truncated", "'vertex' record 2"});
  expectError([] { cloudFrom(kAsciiHead + "end_header\n0 0 0\n1 1 1\n2 2 2\n3 zz 3\n"); }, {"mem.ply:11:", "'zz'"});
  expectError([] { cloudFrom(kAsciiHead + "end_header\n0 0 0\n1 1 1\n2 nan 2\n3 3 3\n"); },
              {"mem.ply:10:", "non-finite"});
  expectError(
      [] {
        cloudFrom(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n0 0 0\n1 1 1\n2 2 2\n");
      },
      {"mem.ply", "only 3 points"});
  // A header claiming 10^12 vertices fails cleanly (no huge allocation).
  expectError(
      [] {
        cloudFrom(
            "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n0 0 0\n");
      },
      {"mem.ply:", "truncated"});
}

std::string binaryCloudHeader(std::uint64_t n) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
         "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
}

TEST(Ply, RejectsTruncatedAndNonFiniteBinaryDataWithOffsets) {
  std::string s = binaryCloudHeader(10);
  std::size_t dataStart = s.size();
  for (int i = 0; i < 3 * 3; ++i) put(s, 1.0f);
  expectError([&] { cloudFrom(s); }, {"mem.ply: byte offset " + std::to_string(dataStart), "truncated", "10 'vertex'"});
  expectError([] { cloudFrom(binaryCloudHeader(1000000000000ull) + std::string(24, '\0')); }, {"truncated"});
  std::string n = binaryCloudHeader(4);
  std::size_t start = n.size();
  for (int i = 0; i < 12; ++i) put(n, i == 7 ? std::numeric_limits<float>::infinity() : 1.0f);
  expectError([&] { cloudFrom(n); }, {"byte offset " + std::to_string(start + 2 * 12), "non-finite"});
}

std::string faceFile(const std::string& faces, int nFaces) {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement "
         "face " +
         std::to_string(nFaces) + "\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n" +
         faces;
}

TEST(Ply, RejectsBadFaces) {
  EXPECT_EQ(meshFrom(faceFile("3 0 1 2\n", 1)).triangles.size(), 1u);
  expectError([] { meshFrom(faceFile("3 0 1 4\n", 1)); }, {"mem.ply:14:", "out of range", "[0, 4)"});
  expectError([] { meshFrom(faceFile("3 0 -1 2\n", 1)); }, {"mem.ply:14:", "out of range"});
  expectError([] { meshFrom(faceFile("2 0 1\n", 1)); }, {"mem.ply:14:", "at least 3"});
  expectError([] { meshFrom(faceFile("3 0 1 2\n3 0 1\n", 2)); }, {"truncated"});
  expectError([] { meshFrom(faceFile("3 0 1 2\n", 0)); }, {"no faces"});
  expectError([] { meshFrom(kAsciiHead + "end_header\n0 0 0\n1 1 1\n2 2 2\n3 3 3\n"); }, {"no 'face' element"});
  // Binary: a face list claiming 4 billion indices stops at the end of the data.
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1000000000\nproperty list uint int vertex_indices\nend_header\n";
  for (int i = 0; i < 9; ++i) put(s, static_cast<float>(i));
  put<std::uint32_t>(s, 4000000000u);
  for (int i = 0; i < 3; ++i) put<std::int32_t>(s, i);
  expectError([&] { meshFrom(s); }, {"byte offset", "truncated"});
}

TEST(Ply, WritersRejectBadData) {
  geom::PointCloud c = randomCloud(4, false);
  c.positions[2].y() = std::numeric_limits<double>::infinity();
  std::ostringstream out;
  expectError<OutputError>([&] { writePlyPointCloud(out, c); }, {"point 2"});
  geom::PointCloud bad = randomCloud(4, true);
  bad.station.pop_back();
  expectError<OptionsError>([&] { writePlyPointCloud(out, bad); }, {"station"});
  geom::TriMesh m;
  m.vertices = {geom::Vec3(0, 0, 0)};
  m.triangles = {{0, 0, 1}};
  expectError<OptionsError>([&] { writePlyMesh(out, m); }, {"vertex 1"});
}

TEST(Ply, DamagedFilesGiveInputErrorsOnly) {
  geom::TriMesh m;
  for (int i = 0; i < 12; ++i) {
    m.vertices.emplace_back(i, i % 3, i % 5);
    m.colors.push_back({1, 2, 3});
    m.quality.push_back(i);
  }
  for (std::uint32_t i = 0; i + 2 < 12; ++i) m.triangles.push_back({i, i + 1, i + 2});
  std::stringstream binary;
  writePlyMesh(binary, m);
  auto readBoth = [](const std::string& b) {
    try {
      meshFrom(b);
    } catch (const InputError&) {
    }
    CloudReadOptions any;
    any.minPoints = 0;
    cloudFrom(b, any);
  };
  testing::expectOnlyInputErrors(binary.str(), readBoth);
  std::string ascii = faceFile("3 0 1 2\n4 0 1 2 3\n", 2);
  testing::expectOnlyInputErrors(ascii, readBoth);
  std::stringstream cloud;
  writePlyPointCloud(cloud, randomCloud(10, true));
  std::string big = cloud.str();
  big.replace(big.find("binary_little_endian"), 20, "binary_big_endian   ");
  testing::expectOnlyInputErrors(big, readBoth);
}

}  // namespace
}  // namespace treesketch::io
