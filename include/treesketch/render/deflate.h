// A small zlib/deflate compressor (RFC 1950/1951) for the PNG writer, with no dependency:
// LZ77 matching over a 32 KiB window with hash chains, coded with the fixed Huffman tables
// (or stored blocks). Also the CRC-32 (PNG, ISO 3309) and Adler-32 (zlib) checksums.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace treesketch::render {

struct DeflateOptions {
  /// false: stored (uncompressed) blocks only — larger output, trivially decodable.
  bool compress = true;
  /// Longest hash chain followed per position (more = smaller output, slower). zlib's level 6 uses 128.
  int maxChainLength = 64;
  /// A match at least this long is taken without looking further (zlib level 6: "nice_length" 128).
  int niceLength = 128;
};

/// CRC-32 (polynomial 0xEDB88320, reflected, as in PNG and zlib) of `n` bytes, continuing from
/// `crc` (pass the previous result to checksum data in pieces; 0 to start). Empty data returns `crc`.
std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0);

/// Adler-32 of `n` bytes, continuing from `adler` (1 to start). Empty data returns `adler`.
std::uint32_t adler32(const std::uint8_t* data, std::size_t n, std::uint32_t adler = 1);

/// A complete zlib stream (2-byte header, deflate blocks, Adler-32) holding `n` bytes of `data`.
/// Empty input gives a valid stream of one empty final block.
std::vector<std::uint8_t> zlibCompress(const std::uint8_t* data, std::size_t n, const DeflateOptions& options = {});

}  // namespace treesketch::render
