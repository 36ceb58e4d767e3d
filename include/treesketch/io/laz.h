// LASzip-compressed LAS (LAZ), read by a decoder of this project written from the published
// format (M. Isenburg, "LASzip: lossless compression of LiDAR data", 2013, and the LASzip
// source documentation; LAS 1.4 R15 for the records). Supported: point formats 0–3 (point-wise
// items POINT10, GPSTIME11, RGB12 and BYTE, version 2) and 6–8 (layered items POINT14, RGB14,
// RGBNIR14 and BYTE14, version 3), with extra bytes, fixed or variable chunks. Chunks are
// independent and decoded in parallel. Waveform items (formats 4, 5, 9, 10) and the version-1
// items of LASzip 1.x are refused with a message.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace treesketch::io {

struct LasHeader;

/// One entry of the LASzip VLR's item list: what part of a record it codes, its size in bytes,
/// its coding version.
struct LazItem {
  std::uint16_t type = 0, size = 0, version = 0;
  std::string name;  ///< "POINT10", "BYTE14", ...
};

/// Chunk size of files whose chunk table gives each chunk's point count.
inline constexpr std::uint32_t kLazVariableChunkSize = 0xFFFFFFFFu;

/// What the LASzip VLR (user id "laszip encoded", record 22204) says.
struct LazInfo {
  std::uint16_t compressor = 0;                          ///< 1 point-wise, 2 point-wise chunked, 3 layered chunked
  std::uint16_t coder = 0;                               ///< 0: arithmetic (the only one)
  int versionMajor = 0, versionMinor = 0, revision = 0;  ///< of the LASzip that wrote the file
  std::uint32_t options = 0;
  std::uint32_t chunkSize = 0;  ///< points a chunk, or kLazVariableChunkSize
  std::vector<LazItem> items;
  std::uint64_t chunkCount = 0;  ///< from the chunk table (set by decompressLaz)

  /// "point-wise", "point-wise chunked", "layered chunked" or "compressor N".
  std::string compressorName() const;
  /// "POINT10 v2, GPSTIME11 v2".
  std::string itemList() const;
};

/// Finds and checks the LASzip VLR among the VLRs that follow the header in `file` (the whole
/// file). Throws InputError naming `source`, the byte offset and what was expected for: no such
/// VLR, a VLR running past the point data, an unknown compressor or coder, an unknown item type
/// or version, items whose sizes do not add up to the record length or do not fit the point
/// format.
LazInfo parseLazVlr(std::string_view file, const LasHeader& header, const std::string& source);

/// Decompresses every point of `file` into uncompressed LAS records (header.pointCount records
/// of header.recordLength bytes, the layout of header.pointFormat), decoding the chunks on up to
/// `threads` threads (0: all cores). `info`, when given, receives the VLR and the chunk count.
/// Throws InputError naming `source`, the byte offset and what was expected for a bad VLR (see
/// parseLazVlr), a missing or damaged chunk table, chunks that run past the data or disagree
/// with the header's point count, and compressed data that ends early. Corrupted data inside a
/// chunk that still parses yields wrong values, never a crash.
std::string decompressLaz(std::string_view file, const LasHeader& header, const std::string& source,
                          LazInfo* info = nullptr, int threads = 0);

/// Decodes one chunk as stored in a LAZ file (`chunk`: its bytes, from its raw first record to
/// its end) into `count` uncompressed records of `recordLength` bytes, coded with `info`'s
/// compressor and items (for tools that locate chunks themselves, and the fuzz harness).
/// `fileOffset`: where the chunk starts in `source`, for messages. Throws InputError for items
/// that do not fit the compressor or do not add up to `recordLength`, and for data that ends early.
std::string decompressLazChunk(std::string_view chunk, const LazInfo& info, std::uint16_t recordLength,
                               std::uint64_t count, const std::string& source, std::uint64_t fileOffset = 0);

}  // namespace treesketch::io
