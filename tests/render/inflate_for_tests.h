// Independent decoders for the render tests: a bitwise CRC-32, Adler-32, and an inflater for
// stored and fixed-Huffman deflate blocks (RFC 1951), written from the RFC without sharing code
// with src/render, so the tests check the writer against a second implementation.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace treesketch::test {

inline std::uint32_t bitwiseCrc32(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

inline std::uint32_t slowAdler32(const std::uint8_t* p, std::size_t n) {
  std::uint64_t a = 1, b = 0;
  for (std::size_t i = 0; i < n; ++i) {
    a = (a + p[i]) % 65521;
    b = (b + a) % 65521;
  }
  return static_cast<std::uint32_t>((b << 16) | a);
}

/// Decodes a zlib stream made of stored and fixed-Huffman blocks; throws std::runtime_error on
/// anything else or on a bad header/checksum.
inline std::vector<std::uint8_t> inflateZlib(const std::vector<std::uint8_t>& z) {
  if (z.size() < 6) throw std::runtime_error("zlib: too short");
  if ((z[0] & 0x0F) != 8 || ((z[0] << 8) | z[1]) % 31 != 0) throw std::runtime_error("zlib: bad header");
  std::size_t bytePos = 2;
  int bitPos = 0;
  auto bit = [&]() -> std::uint32_t {
    if (bytePos >= z.size()) throw std::runtime_error("deflate: out of data");
    std::uint32_t b = (z[bytePos] >> bitPos) & 1u;
    if (++bitPos == 8) {
      bitPos = 0;
      ++bytePos;
    }
    return b;
  };
  auto bits = [&](int n) {
    std::uint32_t v = 0;
    for (int i = 0; i < n; ++i) v |= bit() << i;
    return v;
  };
  // Fixed code (RFC 1951 3.2.6), decoded by reading the code MSB first and comparing ranges.
  auto literalLength = [&]() -> int {
    std::uint32_t code = 0;
    for (int len = 1; len <= 9; ++len) {
      code = (code << 1) | bit();
      if (len == 7 && code <= 0x17) return static_cast<int>(256 + code);
      if (len == 8 && code >= 0x30 && code <= 0xBF) return static_cast<int>(code - 0x30);
      if (len == 8 && code >= 0xC0 && code <= 0xC7) return static_cast<int>(280 + code - 0xC0);
      if (len == 9 && code >= 0x190) return static_cast<int>(144 + code - 0x190);
    }
    throw std::runtime_error("deflate: bad literal/length code");
  };
  static const int lenBase[] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
  std::vector<std::uint8_t> out;
  for (bool last = false; !last;) {
    last = bit() != 0;
    std::uint32_t type = bits(2);
    if (type == 0) {
      if (bitPos != 0) {
        bitPos = 0;
        ++bytePos;
      }
      if (bytePos + 4 > z.size()) throw std::runtime_error("stored: truncated header");
      std::uint32_t len = z[bytePos] | (z[bytePos + 1] << 8), nlen = z[bytePos + 2] | (z[bytePos + 3] << 8);
      if ((len ^ 0xFFFFu) != nlen) throw std::runtime_error("stored: LEN/NLEN mismatch");
      bytePos += 4;
      if (bytePos + len > z.size()) throw std::runtime_error("stored: truncated data");
      out.insert(out.end(), z.begin() + bytePos, z.begin() + bytePos + len);
      bytePos += len;
    } else if (type == 1) {
      for (;;) {
        int sym = literalLength();
        if (sym < 256) {
          out.push_back(static_cast<std::uint8_t>(sym));
          continue;
        }
        if (sym == 256) break;
        int li = sym - 257;
        if (li > 28) throw std::runtime_error("deflate: bad length symbol");
        int extra = (li < 8 || li == 28) ? 0 : (li - 4) / 4;
        std::size_t length = lenBase[li] + bits(extra);
        std::uint32_t dcode = 0;
        for (int i = 0; i < 5; ++i) dcode = (dcode << 1) | bit();
        if (dcode > 29) throw std::runtime_error("deflate: bad distance code");
        int dextra = dcode < 4 ? 0 : static_cast<int>(dcode / 2 - 1);
        std::size_t dbase = dcode < 4 ? dcode + 1 : ((2u + (dcode & 1u)) << dextra) + 1;
        std::size_t dist = dbase + bits(dextra);
        if (dist > out.size()) throw std::runtime_error("deflate: distance before the start");
        for (std::size_t i = 0; i < length; ++i) out.push_back(out[out.size() - dist]);
      }
    } else {
      throw std::runtime_error("deflate: block type not supported by this test decoder");
    }
  }
  if (bitPos != 0) ++bytePos;
  if (bytePos + 4 != z.size()) throw std::runtime_error("zlib: trailing or missing bytes");
  std::uint32_t adler =
      (std::uint32_t(z[bytePos]) << 24) | (z[bytePos + 1] << 16) | (z[bytePos + 2] << 8) | z[bytePos + 3];
  if (adler != slowAdler32(out.data(), out.size())) throw std::runtime_error("zlib: Adler-32 mismatch");
  return out;
}

}  // namespace treesketch::test
