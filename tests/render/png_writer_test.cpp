#include "treesketch/render/png_writer.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <string>

#include "inflate_for_tests.h"
#include "test_support.h"
#include "treesketch/util/error.h"

namespace treesketch::render {
namespace {

struct Chunk {
  std::string type;
  std::vector<std::uint8_t> data;
};

std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

/// Splits a PNG into chunks, checking the signature and every chunk's CRC with the test's own CRC.
std::vector<Chunk> parsePng(const std::vector<std::uint8_t>& png) {
  const std::uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  EXPECT_GE(png.size(), 8u);
  EXPECT_TRUE(std::equal(sig, sig + 8, png.begin()));
  std::vector<Chunk> chunks;
  std::size_t pos = 8;
  while (pos + 12 <= png.size()) {
    std::uint32_t len = be32(&png[pos]);
    EXPECT_LE(pos + 12 + len, png.size());
    if (pos + 12 + len > png.size()) break;
    Chunk c{std::string(png.begin() + pos + 4, png.begin() + pos + 8),
            std::vector<std::uint8_t>(png.begin() + pos + 8, png.begin() + pos + 8 + len)};
    EXPECT_EQ(be32(&png[pos + 8 + len]), test::bitwiseCrc32(&png[pos + 4], 4 + len)) << "chunk " << c.type;
    chunks.push_back(std::move(c));
    pos += 12 + len;
  }
  EXPECT_EQ(pos, png.size());
  return chunks;
}

/// Undoes the PNG scanline filters (spec §9.2) written independently of the encoder.
std::vector<std::uint8_t> unfilter(const std::vector<std::uint8_t>& raw, int w, int h, int bpp) {
  const std::size_t rowLen = static_cast<std::size_t>(w) * bpp;
  std::vector<std::uint8_t> out(rowLen * h);
  for (int y = 0; y < h; ++y) {
    int type = raw[y * (rowLen + 1)];
    EXPECT_LE(type, 4);
    for (std::size_t i = 0; i < rowLen; ++i) {
      int x = raw[y * (rowLen + 1) + 1 + i];
      int a = i >= std::size_t(bpp) ? out[y * rowLen + i - bpp] : 0;
      int b = y > 0 ? out[(y - 1) * rowLen + i] : 0;
      int c = (y > 0 && i >= std::size_t(bpp)) ? out[(y - 1) * rowLen + i - bpp] : 0;
      int pred = 0;
      if (type == 1) pred = a;
      if (type == 2) pred = b;
      if (type == 3) pred = (a + b) / 2;
      if (type == 4) {
        int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
        pred = (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
      }
      out[y * rowLen + i] = static_cast<std::uint8_t>(x + pred);
    }
  }
  return out;
}

Image testImage(int w, int h, int channels) {
  Image img(w, h, {255, 255, 255}, channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::size_t o = img.offset(x, y);
      img.pixels[o] = static_cast<std::uint8_t>(x * 7 + y);
      img.pixels[o + 1] = static_cast<std::uint8_t>(x < w / 2 ? 255 : y * 13);
      img.pixels[o + 2] = static_cast<std::uint8_t>((x * y) % 251);
      if (channels == 4) img.pixels[o + 3] = static_cast<std::uint8_t>(x * 3);
    }
  return img;
}

void expectPixelsBack(const Image& img, const PngOptions& opt) {
  std::vector<Chunk> chunks = parsePng(encodePng(img, opt));
  ASSERT_EQ(chunks.size(), 3u);
  EXPECT_EQ(chunks[0].type, "IHDR");
  EXPECT_EQ(chunks[1].type, "IDAT");
  EXPECT_EQ(chunks[2].type, "IEND");
  ASSERT_EQ(chunks[0].data.size(), 13u);
  EXPECT_EQ(be32(&chunks[0].data[0]), std::uint32_t(img.width));
  EXPECT_EQ(be32(&chunks[0].data[4]), std::uint32_t(img.height));
  EXPECT_EQ(chunks[0].data[8], 8);                          // bit depth
  EXPECT_EQ(chunks[0].data[9], img.channels == 4 ? 6 : 2);  // colour type
  std::vector<std::uint8_t> raw = test::inflateZlib(chunks[1].data);
  ASSERT_EQ(raw.size(), (std::size_t(img.width) * img.channels + 1) * img.height);
  EXPECT_TRUE(unfilter(raw, img.width, img.height, img.channels) == img.pixels);
}

TEST(PngWriter, RoundTripsRgbAndRgbaWithEveryEncoderSetting) {
  for (int channels : {3, 4}) {
    for (bool compress : {true, false}) {
      for (bool adaptive : {true, false}) {
        PngOptions opt;
        opt.deflate.compress = compress;
        opt.adaptiveFilter = adaptive;
        SCOPED_TRACE(std::to_string(channels) + " channels, compress " + std::to_string(compress) + ", adaptive " +
                     std::to_string(adaptive));
        expectPixelsBack(testImage(37, 23, channels), opt);
        expectPixelsBack(testImage(1, 1, channels), opt);
      }
    }
  }
}

TEST(PngWriter, StoredRowsAreThePixelsVerbatim) {
  Image img = testImage(5, 3, 3);
  PngOptions opt;
  opt.deflate.compress = false;
  opt.adaptiveFilter = false;
  std::vector<Chunk> chunks = parsePng(encodePng(img, opt));
  ASSERT_EQ(chunks.size(), 3u);
  // zlib header (2), one stored block header (5), then filter byte 0 + 15 pixel bytes per row.
  const auto& z = chunks[1].data;
  ASSERT_EQ(z.size(), 2u + 5u + 3u * 16u + 4u);
  for (int y = 0; y < 3; ++y) {
    EXPECT_EQ(z[7 + y * 16], 0);
    for (int i = 0; i < 15; ++i) EXPECT_EQ(z[7 + y * 16 + 1 + i], img.pixels[y * 15 + i]);
  }
}

TEST(PngWriter, FlatPictureCompressesWell) {
  Image img(900, 900, {255, 255, 255});
  for (int x = 100; x < 800; ++x) img.set(x, 450, {200, 20, 20});
  std::vector<std::uint8_t> png = encodePng(img);
  EXPECT_LT(png.size(), 30000u);
  expectPixelsBack(img, {});
}

TEST(PngWriter, RejectsInvalidImages) {
  EXPECT_THROW(encodePng(Image(0, 10)), OptionsError);
  EXPECT_THROW(encodePng(Image(10, 0)), OptionsError);
  Image bad(4, 4);
  bad.pixels.pop_back();
  EXPECT_THROW(encodePng(bad), OptionsError);
  Image gray(4, 4);
  gray.channels = 1;
  EXPECT_THROW(encodePng(gray), OptionsError);
}

TEST(PngWriter, WritesFilesAtomicallyAndReportsBadPaths) {
  test::TempDir dir;
  Image img = testImage(8, 8, 3);
  writePng(dir / "a.png", img);
  std::string text = test::readText(dir / "a.png");
  std::vector<std::uint8_t> bytes(text.begin(), text.end());
  EXPECT_TRUE(bytes == encodePng(img));
  EXPECT_THROW(writePng(dir / "missing" / "a.png", img), OutputError);
  EXPECT_THROW(writePng(dir / "b.png", Image(0, 0)), OptionsError);
  EXPECT_FALSE(std::filesystem::exists(dir / "b.png"));
  std::ostringstream out;
  writePng(out, img);
  EXPECT_EQ(out.str(), text);
}

}  // namespace
}  // namespace treesketch::render
