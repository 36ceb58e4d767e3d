#include "treesketch/io/laz.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "io_test_util.h"
#include "test_support.h"
#include "treesketch/io/file_info.h"
#include "treesketch/io/las.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/xyz.h"

namespace treesketch::io {
namespace {

namespace fs = std::filesystem;
using testing::expectError;

template <class T>
T load(const std::string& s, std::size_t at) {
  T v;
  std::memcpy(&v, s.data() + at, sizeof(T));
  return v;
}
template <class T>
void store(std::string& s, std::size_t at, T v) {
  std::memcpy(s.data() + at, &v, sizeof(T));
}

// ---------------------------------------------------------------------------------------------
// A tiny LAZ built in code: one point, compressor "point-wise" (no chunk table), so its point is
// stored raw. Enough to test the LASzip VLR without third-party data.

constexpr std::size_t kVlrAt = 227, kVlrBody = kVlrAt + 54, kItemsAt = kVlrBody + 34;

std::string tinyLaz(int items = 1) {
  testing::LasSpec s;
  s.points = {{1000, -2000, 3000}};
  s.vlrBytes = 54 + 34 + 6 * items;
  std::string f = testing::buildLas(s);
  f[104] = static_cast<char>(0x80);  // compressed, format 0
  std::string vlr(static_cast<std::size_t>(s.vlrBytes), '\0');
  std::memcpy(vlr.data() + 2, "laszip encoded", 14);
  store<std::uint16_t>(vlr, 18, 22204);
  store<std::uint16_t>(vlr, 20, static_cast<std::uint16_t>(34 + 6 * items));
  std::string body(34 + 6 * items, '\0');
  store<std::uint16_t>(body, 0, 1);  // compressor: point-wise
  body[4] = 3;                       // LASzip 3.4
  body[5] = 4;
  store<std::uint32_t>(body, 12, 50000);
  store<std::uint16_t>(body, 32, static_cast<std::uint16_t>(items));
  store<std::uint16_t>(body, 34, 6);  // POINT10, 20 bytes, version 2
  store<std::uint16_t>(body, 36, 20);
  store<std::uint16_t>(body, 38, 2);
  std::memcpy(vlr.data() + 54, body.data(), body.size());
  f.replace(kVlrAt, vlr.size(), vlr);
  f += std::string(4, '\0');  // the coder's first bytes (nothing is coded after a chunk's first point)
  return f;
}

geom::PointCloud readLazBytes(const std::string& bytes, LasHeader* h = nullptr) {
  std::istringstream in(bytes);
  CloudReadOptions any;
  any.minPoints = 1;
  return readLas(in, "mem.laz", any, h);
}

TEST(Laz, TinyPointwiseFileReadsItsRawPoint) {
  LasHeader h;
  geom::PointCloud c = readLazBytes(tinyLaz(), &h);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c.positions[0], geom::Vec3(1.0, -2.0, 3.0));
  EXPECT_TRUE(h.compressed);
  EXPECT_EQ(h.laz.compressorName(), "point-wise");
  EXPECT_EQ(h.laz.itemList(), "POINT10 v2");
  EXPECT_EQ(h.laz.chunkCount, 1u);
}

TEST(Laz, BadLaszipVlrNamesOffsetAndExpectation) {
  std::string f = tinyLaz();
  f[kVlrBody] = 7;
  expectError([&] { readLazBytes(f); },
              {"mem.laz", "byte offset " + std::to_string(kVlrBody), "unknown LAZ compressor 7", "expected 1"});
  f = tinyLaz();
  f[kVlrBody + 2] = 1;
  expectError([&] { readLazBytes(f); }, {"byte offset " + std::to_string(kVlrBody + 2), "coder 1", "arithmetic"});
  f = tinyLaz();
  f[kItemsAt + 4] = 1;
  expectError([&] { readLazBytes(f); },
              {"byte offset " + std::to_string(kItemsAt + 4), "POINT10 has coding version 1", "expected version 2"});
  f = tinyLaz();
  f[kItemsAt] = 99;
  expectError([&] { readLazBytes(f); }, {"byte offset " + std::to_string(kItemsAt), "unknown LAZ item type 99"});
  f = tinyLaz();
  f[kItemsAt] = 9;
  expectError([&] { readLazBytes(f); }, {"WAVEPACKET13", "not supported"});
  f = tinyLaz();
  f[kItemsAt] = 10;  // POINT14 under a point-wise compressor
  expectError([&] { readLazBytes(f); }, {"POINT14", "does not belong", "POINT10"});
  f = tinyLaz();
  f[kItemsAt + 2] = 19;
  expectError([&] { readLazBytes(f); }, {"POINT10 has size 19", "expected 20"});
  f = tinyLaz();
  f[kVlrBody + 32] = 5;  // five items in a VLR that holds one
  expectError([&] { readLazBytes(f); }, {"lists 5 items", "more than"});
  f = tinyLaz();
  f[kVlrAt + 2] = 'X';  // not the LASzip user id
  expectError([&] { readLazBytes(f); }, {"byte offset 227", "no LASzip VLR", "expected one"});
}

TEST(Laz, DamagedTinyFilesGiveInputErrorsOnly) {
  testing::expectOnlyInputErrors(
      tinyLaz(), [](const std::string& b) { readLazBytes(b); }, 2000);
}

// ---------------------------------------------------------------------------------------------
// The LAZ files of ../shared/data/real (skipped when absent).

fs::path realDir() { return test::sharedDataDir() / "real"; }

std::vector<fs::path> realLazFiles() {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(realDir(), ec))
    if (e.path().extension() == ".laz") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string slurp(const fs::path& p) { return test::readText(p); }

/// The records of `file` decoded by treesketch (threads: 0 = all cores).
std::string decodeRecords(const fs::path& file, LasHeader& h, int threads = 0) {
  std::string bytes = slurp(file);
  h = parseLasHeader(bytes, file.string());
  return decompressLaz(bytes, h, file.string(), &h.laz, threads);
}

TEST(Laz, SpruceMatchesItsCopyDecodedByAnotherTool) {
  const fs::path laz = realDir() / "treels_spruce.laz", xyz = realDir() / "treels_spruce_decoded.xyz";
  if (!fs::exists(laz) || !fs::exists(xyz)) GTEST_SKIP() << "no shared data at " << realDir();
  geom::PointCloud a = readPointCloud(laz), b = readXyz(xyz);
  ASSERT_EQ(a.size(), 83392u);
  ASSERT_EQ(b.size(), a.size());
  std::size_t off = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) off += std::abs(a.positions[i][k] - b.positions[i][k]) > 0.5e-4 + 1e-9;
  EXPECT_EQ(off, 0u) << "coordinates differing beyond the copy's 4 decimals";
}

TEST(Laz, RealFilesDecodeWithinTheirHeaderBounds) {
  const auto files = realLazFiles();
  if (files.empty()) GTEST_SKIP() << "no shared data at " << realDir();
  for (const auto& f : files) {
    LasHeader h;
    geom::PointCloud c = readLas(f, {}, &h);
    EXPECT_EQ(c.size(), h.pointCount) << f;
    geom::BBox b = c.bounds();
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(b.min[k], h.min[k], h.scale[k]) << f << " axis " << k;
      EXPECT_NEAR(b.max[k], h.max[k], h.scale[k]) << f << " axis " << k;
    }
  }
}

TEST(Laz, ChunksDecodeTheSameOnOneThreadAsOnAll) {
  const fs::path f = realDir() / "spanner_TLS_Clip.laz";
  if (!fs::exists(f)) GTEST_SKIP() << "no shared data at " << realDir();
  LasHeader h1, h2;
  const std::string one = decodeRecords(f, h1, 1), all = decodeRecords(f, h2, 0);
  EXPECT_GT(h1.laz.chunkCount, 1u);
  EXPECT_EQ(one.size(), h1.pointCount * h1.recordLength);
  EXPECT_TRUE(one == all);
}

TEST(Laz, InfoNamesCompressorItemsAndChunkSize) {
  const fs::path f = realDir() / "treels_spruce.laz";
  if (!fs::exists(f)) GTEST_SKIP() << "no shared data at " << realDir();
  FileInfo info = inspectFile(f);
  EXPECT_EQ(info.format, "LAZ (compressed LAS) 1.2");
  auto detail = [&](const std::string& key) {
    for (const auto& [k, v] : info.details)
      if (k == key) return v;
    return std::string("(missing)");
  };
  EXPECT_EQ(detail("point data format"), "0");
  EXPECT_NE(detail("compressor").find("point-wise chunked"), std::string::npos) << detail("compressor");
  EXPECT_EQ(detail("compressed items"), "POINT10 v2");
  EXPECT_EQ(detail("chunk size"), "50000 points");
  EXPECT_EQ(detail("chunks"), "2");
  EXPECT_EQ(info.cloud.size(), 83392u);
}

// ---------------------------------------------------------------------------------------------
// Damaged copies of the real files: clear errors, never a crash.

std::string pathMessageCheck(const fs::path& f) { return f.filename().string(); }

TEST(Laz, TruncatedAndDamagedChunkTablesAreClearErrors) {
  const fs::path f = realDir() / "treels_spruce.laz";
  if (!fs::exists(f)) GTEST_SKIP() << "no shared data at " << realDir();
  const std::string good = slurp(f);
  const auto h = parseLasHeader(good, "spruce.laz");
  const std::size_t pointData = h.offsetToPointData;
  const auto table = static_cast<std::size_t>(load<std::int64_t>(good, pointData));
  auto read = [](const std::string& b) {
    std::istringstream in(b);
    readLas(in, "spruce.laz");
  };
  // Truncated: the chunk table (at the end) is gone.
  expectError([&] { read(good.substr(0, good.size() / 2)); },
              {"spruce.laz", "byte offset " + std::to_string(pointData), "chunk table offset", "truncated"});
  expectError([&] { read(good.substr(0, pointData + 4)); }, {"spruce.laz", "truncated", "chunk table offset"});
  std::string b = good;
  store<std::uint32_t>(b, table, 1);
  expectError([&] { read(b); }, {"byte offset " + std::to_string(table), "chunk table version 1", "expected 0"});
  b = good;
  store<std::uint32_t>(b, table + 4, 1);  // one chunk listed, two needed
  expectError([&] { read(b); }, {"byte offset " + std::to_string(table), "covers 50000 points", "83392"});
  b = good;
  store<std::uint32_t>(b, table + 4, 3);  // three listed: the table's coded part ends early
  expectError([&] { read(b); }, {"spruce.laz", "byte offset"});
  b = good;
  store<std::int64_t>(b, pointData, static_cast<std::int64_t>(good.size()) + 100);
  expectError([&] { read(b); }, {"byte offset " + std::to_string(pointData), "outside the point data"});
  b = good;
  store<std::int64_t>(b, pointData, -1);  // "not written": the last 8 bytes are not an offset here
  expectError([&] { read(b); }, {"spruce.laz", "chunk table"});
}

TEST(Laz, LayeredChunkWithAWrongPointCountIsAClearError) {
  const fs::path f = realDir() / "spanner_TLS_Clip.laz";
  if (!fs::exists(f)) GTEST_SKIP() << "no shared data at " << realDir();
  std::string b = slurp(f);
  const auto h = parseLasHeader(b, "clip.laz");
  const std::size_t countAt = h.offsetToPointData + 8 + 30;  // after the first chunk's raw point
  ASSERT_EQ(load<std::uint32_t>(b, countAt), 50000u);
  store<std::uint32_t>(b, countAt, 49999);
  std::istringstream in(b);
  expectError([&] { readLas(in, "clip.laz"); },
              {"clip.laz", "byte offset " + std::to_string(countAt), "chunk holds 49999 points", "expected 50000"});
}

TEST(Laz, DamagedRealFilesGiveInputErrorsOnly) {
  const auto files = realLazFiles();
  if (files.empty()) GTEST_SKIP() << "no shared data at " << realDir();
  for (const auto& f : files) {
    const std::string bytes = slurp(f);
    SCOPED_TRACE(f.string());
    testing::expectOnlyInputErrors(
        bytes,
        [](const std::string& b) {
          std::istringstream in(b);
          readLas(in, "damaged.laz");
        },
        20, 10);
  }
}

// ---------------------------------------------------------------------------------------------
// The oracle: laz-perf (npm) decodes the same files; every field of every point must agree.

/// The text tests/io/laz_oracle.js prints, made from treesketch's records.
std::string recordsAsText(const std::string& rec, const LasHeader& h) {
  const int fmt = h.pointFormat;
  const std::size_t len = h.recordLength;
  std::string out = "format " + std::to_string(fmt) + " length " + std::to_string(len) + " count " +
                    std::to_string(h.pointCount) + "\n";
  char buf[64];
  auto u8 = [&](std::size_t at) { return static_cast<unsigned>(static_cast<unsigned char>(rec[at])); };
  for (std::size_t i = 0; i < h.pointCount; ++i) {
    const std::size_t p = i * len;
    std::string line =
        std::to_string(load<std::int32_t>(rec, p)) + " " + std::to_string(load<std::int32_t>(rec, p + 4)) + " " +
        std::to_string(load<std::int32_t>(rec, p + 8)) + " " + std::to_string(load<std::uint16_t>(rec, p + 12));
    auto add = [&](long long v) { line += " " + std::to_string(v); };
    auto addHex64 = [&](std::size_t at) {
      std::snprintf(buf, sizeof buf, " %016llx", static_cast<unsigned long long>(load<std::uint64_t>(rec, at)));
      line += buf;
    };
    std::size_t next;
    if (fmt >= 6) {
      add(u8(p + 14) & 15), add(u8(p + 14) >> 4), add(u8(p + 15)), add(u8(p + 16)), add(u8(p + 17));
      add(load<std::int16_t>(rec, p + 18)), add(load<std::uint16_t>(rec, p + 20));
      addHex64(p + 22);
      next = 30;
    } else {
      add(u8(p + 14) & 7), add((u8(p + 14) >> 3) & 7), add(u8(p + 14) >> 6), add(u8(p + 15)), add(u8(p + 17));
      add(static_cast<signed char>(rec[p + 16])), add(load<std::uint16_t>(rec, p + 18));
      next = 20;
      if (fmt == 1 || fmt == 3) {
        addHex64(p + 20);
        next = 28;
      }
    }
    if (fmt == 2 || fmt == 3 || fmt == 7 || fmt == 8) {
      for (int k = 0; k < 3; ++k) add(load<std::uint16_t>(rec, p + next + 2 * k));
      next += 6;
    }
    if (fmt == 8) {
      add(load<std::uint16_t>(rec, p + next));
      next += 2;
    }
    if (next < len) {
      line += ' ';
      for (std::size_t k = next; k < len; ++k) {
        std::snprintf(buf, sizeof buf, "%02x", u8(p + k));
        line += buf;
      }
    }
    out += line + "\n";
  }
  return out;
}

/// Runs the oracle on `file`; empty when it fails.
std::string oracleDecode(const fs::path& file) {
  const fs::path script = fs::path(TS_TESTS_DIR) / "io" / "laz_oracle.js";
  const std::string cmd =
      "node '" + script.string() + "' '" + std::string(TS_LAZ_ORACLE_DIR) + "' '" + file.string() + "'";
  std::string out;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return out;
  char buf[1 << 16];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  if (pclose(pipe) != 0) out.clear();
  return out;
}

TEST(Laz, EveryFieldOfEveryPointMatchesLazPerf) {
  const auto files = realLazFiles();
  if (files.empty()) GTEST_SKIP() << "no shared data at " << realDir();
  if (std::system("node --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "node is not installed (scripts/install_deps.sh installs nodejs and laz-perf)";
  if (!fs::exists(fs::path(TS_LAZ_ORACLE_DIR) / "node_modules" / "laz-perf"))
    GTEST_SKIP() << "laz-perf is not installed in " << TS_LAZ_ORACLE_DIR << " (scripts/install_deps.sh installs it)";
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    const std::string theirs = oracleDecode(f);
    ASSERT_FALSE(theirs.empty()) << "laz-perf failed on " << f;
    LasHeader h;
    const std::string ours = recordsAsText(decodeRecords(f, h), h);
    ASSERT_EQ(std::count(ours.begin(), ours.end(), '\n'), static_cast<long>(h.pointCount) + 1);
    if (ours == theirs) continue;
    std::istringstream a(ours), b(theirs);
    std::string la, lb;
    std::size_t line = 0, differing = 0;
    std::string first;
    while (std::getline(a, la)) {
      ++line;
      if (!std::getline(b, lb)) lb = "(missing)";
      if (la != lb && differing++ == 0)
        first = "line " + std::to_string(line) + ": ours '" + la + "', laz-perf '" + lb + "'";
    }
    ADD_FAILURE() << differing << " of " << line << " lines differ; first at " << first;
  }
}

}  // namespace
}  // namespace treesketch::io
