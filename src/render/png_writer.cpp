// PNG encoder after the PNG specification (W3C, 2nd ed.): chunk layout §5, IHDR §11.2.2, filters
// §9 with the adaptive choice heuristic of §12.8; compression by render/deflate.cpp.
#include "treesketch/render/png_writer.h"

#include <cstdlib>
#include <string>

#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::render {

namespace {

void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

void putChunk(std::vector<std::uint8_t>& out, const char type[4], const std::vector<std::uint8_t>& data) {
  putU32(out, static_cast<std::uint32_t>(data.size()));
  std::size_t typeAt = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  putU32(out, crc32(out.data() + typeAt, 4 + data.size()));  // the CRC covers type and data
}

std::uint8_t paeth(int a, int b, int c) {
  int p = a + b - c;
  int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return static_cast<std::uint8_t>(a);
  if (pb <= pc) return static_cast<std::uint8_t>(b);
  return static_cast<std::uint8_t>(c);
}

/// Filters one row with filter `type` into `out` (bpp bytes per pixel; `prior` is the row above
/// or null for the first row).
void filterRow(int type, const std::uint8_t* row, const std::uint8_t* prior, std::size_t len, int bpp,
               std::uint8_t* out) {
  for (std::size_t i = 0; i < len; ++i) {
    int a = i >= static_cast<std::size_t>(bpp) ? row[i - bpp] : 0;
    int b = prior ? prior[i] : 0;
    int c = (prior && i >= static_cast<std::size_t>(bpp)) ? prior[i - bpp] : 0;
    int pred = 0;
    if (type == 1)
      pred = a;
    else if (type == 2)
      pred = b;
    else if (type == 3)
      pred = (a + b) / 2;
    else if (type == 4)
      pred = paeth(a, b, c);
    out[i] = static_cast<std::uint8_t>(row[i] - pred);
  }
}

std::size_t sumAbs(const std::uint8_t* bytes, std::size_t len) {
  std::size_t s = 0;
  for (std::size_t i = 0; i < len; ++i) s += bytes[i] < 128 ? bytes[i] : 256 - bytes[i];  // as signed bytes
  return s;
}

std::vector<std::uint8_t> filteredScanlines(const Image& image, bool adaptive) {
  const std::size_t rowLen = static_cast<std::size_t>(image.width) * image.channels;
  std::vector<std::uint8_t> out((rowLen + 1) * image.height);
  std::vector<std::uint8_t> trial(rowLen);
  for (int y = 0; y < image.height; ++y) {
    const std::uint8_t* row = image.pixels.data() + y * rowLen;
    const std::uint8_t* prior = y > 0 ? row - rowLen : nullptr;
    std::uint8_t* dst = out.data() + y * (rowLen + 1);
    int bestType = 0;
    if (adaptive) {
      std::size_t bestSum = SIZE_MAX;
      for (int type = 0; type <= 4; ++type) {
        filterRow(type, row, prior, rowLen, image.channels, trial.data());
        std::size_t s = sumAbs(trial.data(), rowLen);
        if (s < bestSum) {
          bestSum = s;
          bestType = type;
        }
      }
    }
    dst[0] = static_cast<std::uint8_t>(bestType);
    filterRow(bestType, row, prior, rowLen, image.channels, dst + 1);
  }
  return out;
}

}  // namespace

std::vector<std::uint8_t> encodePng(const Image& image, const PngOptions& options) {
  if (image.width <= 0 || image.height <= 0)
    throw OptionsError("PNG writer: empty image (" + std::to_string(image.width) + " x " +
                       std::to_string(image.height) + " pixels)");
  if (image.channels != 3 && image.channels != 4)
    throw OptionsError("PNG writer: expected 3 or 4 channels, got " + std::to_string(image.channels));
  if (image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
    throw OptionsError("PNG writer: pixel buffer holds " + std::to_string(image.pixels.size()) +
                       " bytes, expected width * height * channels");
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> ihdr;
  putU32(ihdr, static_cast<std::uint32_t>(image.width));
  putU32(ihdr, static_cast<std::uint32_t>(image.height));
  ihdr.push_back(8);                            // bit depth
  ihdr.push_back(image.channels == 4 ? 6 : 2);  // colour type: truecolour (+ alpha)
  ihdr.push_back(0);                            // compression: deflate
  ihdr.push_back(0);                            // filter method 0
  ihdr.push_back(0);                            // no interlace
  putChunk(png, "IHDR", ihdr);
  std::vector<std::uint8_t> raw = filteredScanlines(image, options.adaptiveFilter);
  putChunk(png, "IDAT", zlibCompress(raw.data(), raw.size(), options.deflate));
  putChunk(png, "IEND", {});
  return png;
}

void writePng(std::ostream& out, const Image& image, const PngOptions& options) {
  std::vector<std::uint8_t> bytes = encodePng(image, options);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw OutputError("PNG writer: the output stream failed");
}

void writePng(const std::filesystem::path& path, const Image& image, const PngOptions& options) {
  std::vector<std::uint8_t> bytes = encodePng(image, options);  // validate before creating any file
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw OutputError(path.string() + ": could not write the PNG data");
  });
}

}  // namespace treesketch::render
