#include "treesketch/render/deflate.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "inflate_for_tests.h"

namespace treesketch::render {
namespace {

std::vector<std::uint8_t> bytesOf(const std::string& s) { return {s.begin(), s.end()}; }

TEST(Crc32, KnownValuesAndPieces) {
  auto v = bytesOf("123456789");
  EXPECT_EQ(crc32(v.data(), v.size()), 0xCBF43926u);  // the standard check value
  EXPECT_EQ(crc32(v.data() + 4, 5, crc32(v.data(), 4)), 0xCBF43926u);
  EXPECT_EQ(crc32(nullptr, 0), 0u);
  std::mt19937 rng(7);
  std::vector<std::uint8_t> r(1000);
  for (auto& b : r) b = static_cast<std::uint8_t>(rng());
  EXPECT_EQ(crc32(r.data(), r.size()), test::bitwiseCrc32(r.data(), r.size()));
}

TEST(Adler32, KnownValueAndLongInput) {
  auto v = bytesOf("Wikipedia");
  EXPECT_EQ(adler32(v.data(), v.size()), 0x11E60398u);
  EXPECT_EQ(adler32(nullptr, 0), 1u);
  std::vector<std::uint8_t> ones(100000, 255);  // long enough to need the modulo inside the loop
  EXPECT_EQ(adler32(ones.data(), ones.size()), test::slowAdler32(ones.data(), ones.size()));
}

void expectRoundTrip(const std::vector<std::uint8_t>& data, const DeflateOptions& opt) {
  std::vector<std::uint8_t> z = zlibCompress(data.data(), data.size(), opt);
  std::vector<std::uint8_t> back = test::inflateZlib(z);
  ASSERT_EQ(back.size(), data.size());
  EXPECT_TRUE(back == data);
}

TEST(ZlibCompress, RoundTripsThroughAnIndependentInflater) {
  std::mt19937 rng(42);
  std::vector<std::uint8_t> random(5000);
  for (auto& b : random) b = static_cast<std::uint8_t>(rng());
  std::vector<std::uint8_t> runs;
  for (int i = 0; i < 200000; ++i) runs.push_back(static_cast<std::uint8_t>((i / 997) % 3 == 0 ? 255 : i % 7));
  std::vector<std::uint8_t> farRepeat(random);  // a repeat 5000 bytes back and one beyond the window
  farRepeat.insert(farRepeat.end(), random.begin(), random.end());
  farRepeat.resize(40000, 9);
  farRepeat.insert(farRepeat.end(), random.begin(), random.begin() + 300);
  for (bool compress : {true, false}) {
    DeflateOptions opt;
    opt.compress = compress;
    SCOPED_TRACE(compress ? "fixed Huffman" : "stored");
    expectRoundTrip({}, opt);
    expectRoundTrip(bytesOf("a"), opt);
    expectRoundTrip(bytesOf("abcabcabcabcabcabcabcabcabcabcabcabcabcX"), opt);
    expectRoundTrip(random, opt);
    expectRoundTrip(runs, opt);
    expectRoundTrip(farRepeat, opt);
  }
}

TEST(ZlibCompress, CompressesRepetitiveDataAndStoresVerbatim) {
  std::vector<std::uint8_t> flat(300000, 255);
  DeflateOptions opt;
  EXPECT_LT(zlibCompress(flat.data(), flat.size(), opt).size(), flat.size() / 100);
  opt.compress = false;
  std::vector<std::uint8_t> stored = zlibCompress(flat.data(), flat.size(), opt);
  // 2-byte header, 5 bytes per block of at most 65535 bytes, 4-byte Adler-32.
  EXPECT_EQ(stored.size(), 2 + flat.size() + 5 * 5 + 4);
  EXPECT_EQ(stored[0], 0x78);
  EXPECT_EQ(((stored[0] << 8) | stored[1]) % 31, 0);
}

}  // namespace
}  // namespace treesketch::render
