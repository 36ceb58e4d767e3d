// LAZ files: the LASzip VLR, the chunk table, and the chunks decoded in parallel into plain LAS
// records (the items' decoding is in laz_items.cpp and laz_items14.cpp). File layout (LASzip):
// the point data starts with the int64 offset of the chunk table (-1 when the writer could not
// seek back: then the file's last 8 bytes hold it), then the chunks back to back; the chunk
// table is a uint32 version (0), a uint32 chunk count and, arithmetic-coded, each chunk's point
// count (variable chunks only) and byte size.
#include "treesketch/io/laz.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <optional>

#include "io/io_util.h"
#include "io/laz_arith.h"
#include "io/laz_items.h"
#include "treesketch/io/las.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

namespace {

constexpr char kLaszipUserId[] = "laszip encoded";
constexpr std::uint16_t kLaszipRecordId = 22204;
constexpr std::size_t kVlrHeaderSize = 54;
constexpr std::size_t kLazVlrFixedSize = 34, kLazItemSize = 6;
/// Most points a chunk may claim per compressed byte. The adaptive models cap a symbol's
/// probability (bits at 8191/8192, symbols near 1 - n/32768), so a record costs at least about
/// 0.008 bit (a change symbol and three corrections) even when all records are identical: under
/// 1000 points a byte. Real scans take 3–10 bytes a point. The bound stops a damaged count from
/// allocating memory the data could never fill.
constexpr std::uint64_t kMaxPointsPerByte = 1024;

/// Throws unless `count` points can come from `bytes` compressed bytes (see kMaxPointsPerByte).
void checkPlausible(std::uint64_t count, std::uint64_t bytes, std::uint64_t at, const std::string& source) {
  if (count > 1 + bytes * kMaxPointsPerByte)
    throw InputError(atOffset(source, at,
                              std::to_string(count) + " points cannot come from " + std::to_string(bytes) +
                                  " compressed bytes, expected at most " +
                                  std::to_string(1 + bytes * kMaxPointsPerByte) + " (damaged point count?)"));
}

/// The size an item type must have (0: any non-zero size, the extra bytes).
std::uint16_t itemFixedSize(std::uint16_t type) {
  switch (type) {
    case laz::kPoint10:
      return 20;
    case laz::kGpsTime11:
      return 8;
    case laz::kRgb12:
    case laz::kRgb14:
      return 6;
    case laz::kPoint14:
      return 30;
    case laz::kRgbNir14:
      return 8;
    default:
      return 0;
  }
}

/// Checks the item list against the compressor and the point format; `at` is the list's offset.
void checkItems(const LazInfo& info, int pointFormat, std::uint16_t recordLength, std::uint64_t at,
                const std::string& source) {
  const bool layered = info.compressor == 3;
  std::uint32_t total = 0;
  for (std::size_t i = 0; i < info.items.size(); ++i) {
    const LazItem& it = info.items[i];
    const std::uint64_t off = at + i * kLazItemSize;
    const bool pointwiseType =
        it.type == laz::kPoint10 || it.type == laz::kGpsTime11 || it.type == laz::kRgb12 || it.type == laz::kByte;
    const bool layeredType =
        it.type == laz::kPoint14 || it.type == laz::kRgb14 || it.type == laz::kRgbNir14 || it.type == laz::kByte14;
    if (it.type == laz::kWavePacket13 || it.type == laz::kWavePacket14)
      throw InputError(atOffset(source, off,
                                "LAZ item " + it.name +
                                    " (waveform packets) is not supported, expected "
                                    "point formats 0-3 or 6-8"));
    if (!pointwiseType && !layeredType)
      throw InputError(atOffset(source, off,
                                "unknown LAZ item " + it.name +
                                    ", expected POINT10, GPSTIME11, RGB12, BYTE, POINT14, RGB14, "
                                    "RGBNIR14 or BYTE14"));
    if (layered != layeredType)
      throw InputError(
          atOffset(source, off,
                   "LAZ item " + it.name + " does not belong to compressor " + info.compressorName() + ", expected " +
                       (layered ? "POINT14, RGB14, RGBNIR14 or BYTE14" : "POINT10, GPSTIME11, RGB12 or BYTE")));
    const std::uint16_t wantVersion = layered ? 3 : 2;
    if (it.version != wantVersion)
      throw InputError(atOffset(source, off + 4,
                                "LAZ item " + it.name + " has coding version " + std::to_string(it.version) +
                                    ", expected version " + std::to_string(wantVersion) + " (the only one supported)"));
    const std::uint16_t want = itemFixedSize(it.type);
    if ((want && it.size != want) || it.size == 0)
      throw InputError(atOffset(source, off + 2,
                                "LAZ item " + it.name + " has size " + std::to_string(it.size) + ", expected " +
                                    (want ? std::to_string(want) : "at least 1")));
    if ((i == 0) != (it.type == laz::kPoint10 || it.type == laz::kPoint14))
      throw InputError(atOffset(source, off,
                                "LAZ item " + it.name + " at position " + std::to_string(i + 1) +
                                    ", expected POINT10 or POINT14 first and only first"));
    total += it.size;
  }
  if (info.items.empty()) throw InputError(atOffset(source, at, "LASzip VLR lists no items, expected at least one"));
  if (pointFormat >= 0 && (info.items[0].type == laz::kPoint14) != (pointFormat >= 6))
    throw InputError(atOffset(source, at,
                              "LAZ item " + info.items[0].name + " does not code point format " +
                                  std::to_string(pointFormat) + ", expected " +
                                  (pointFormat >= 6 ? "POINT14" : "POINT10")));
  if (total != recordLength)
    throw InputError(atOffset(source, at,
                              "LAZ items add up to " + std::to_string(total) +
                                  " bytes, expected the point record length " + std::to_string(recordLength)));
}

struct Chunk {
  std::uint64_t begin = 0, end = 0;  // byte range in the file
  std::uint64_t firstPoint = 0, count = 0;
};

/// The byte offset of the chunk table, read from the 8 bytes at the start of the point data (or
/// from the file's last 8 bytes when those say -1); checks that it lies inside the file after them.
std::uint64_t chunkTableOffset(std::string_view file, std::uint64_t pointData, const std::string& source) {
  const std::uint64_t size = file.size();
  if (size < pointData + 8)
    throw InputError(atOffset(
        source, size, "truncated: expected the 8-byte chunk table offset at byte " + std::to_string(pointData)));
  auto tableAt = detail::loadLE<std::int64_t>(file.data() + pointData);
  std::uint64_t tableFieldAt = pointData;
  if (tableAt == -1) {  // not written back: the file's last 8 bytes hold it
    tableFieldAt = size - 8;
    tableAt = detail::loadLE<std::int64_t>(file.data() + size - 8);
  }
  if (tableAt < static_cast<std::int64_t>(pointData + 8) || static_cast<std::uint64_t>(tableAt) + 8 > size)
    throw InputError(atOffset(source, tableFieldAt,
                              "chunk table offset " + std::to_string(tableAt) +
                                  " lies outside the point data, "
                                  "expected " +
                                  std::to_string(pointData + 8) + " to " + std::to_string(size >= 8 ? size - 8 : 0) +
                                  " (truncated file?)"));
  return static_cast<std::uint64_t>(tableAt);
}

/// Reads the chunk table; checks that the chunks lie inside the point data and hold exactly the
/// header's point count.
std::vector<Chunk> readChunkTable(std::string_view file, const LasHeader& h, const LazInfo& info,
                                  const std::string& source) {
  const std::uint64_t pointData = h.offsetToPointData;
  const std::uint64_t size = file.size();
  std::vector<Chunk> chunks;
  if (info.compressor == 1) {  // one stream, no table
    if (size < pointData)
      throw InputError(
          atOffset(source, size, "truncated: point data should start at byte " + std::to_string(pointData)));
    checkPlausible(h.pointCount, size - pointData, pointData, source);
    if (h.pointCount) chunks.push_back({pointData, size, 0, h.pointCount});
    return chunks;
  }
  const std::uint64_t table = chunkTableOffset(file, pointData, source);
  const auto version = detail::loadLE<std::uint32_t>(file.data() + table);
  const auto count = detail::loadLE<std::uint32_t>(file.data() + table + 4);
  if (version != 0)
    throw InputError(atOffset(source, table, "chunk table version " + std::to_string(version) + ", expected 0"));
  const bool variable = info.chunkSize == kLazVariableChunkSize;
  if (!variable && info.chunkSize == 0)
    throw InputError(atOffset(source, table, "chunk size 0 in the LASzip VLR, expected a positive point count"));
  // Every chunk takes at least one byte, so a count beyond the table's position is damage.
  if (count > table - pointData)
    throw InputError(
        atOffset(source, table + 4,
                 "chunk table lists " + std::to_string(count) + " chunks, more than the point data can hold"));
  const auto* bytes = reinterpret_cast<const unsigned char*>(file.data());
  laz::ArithmeticDecoder dec(bytes + table + 8, bytes + size, table + 8, source);
  if (count) dec.start();
  laz::IntegerDecompressor ic(32, 2);
  chunks.resize(count);
  std::uint64_t at = pointData + 8, first = 0, left = h.pointCount;
  std::int32_t prevCount = 0, prevSize = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    Chunk& c = chunks[i];
    if (variable) {
      prevCount = ic.decompress(dec, prevCount, 0);
      c.count = static_cast<std::uint32_t>(prevCount);
    } else {
      c.count = std::min<std::uint64_t>(info.chunkSize, left);
    }
    prevSize = ic.decompress(dec, prevSize, 1);
    c.begin = at;
    c.end = at + static_cast<std::uint32_t>(prevSize);
    c.firstPoint = first;
    if (c.end > table)
      throw InputError(atOffset(source, c.begin,
                                "chunk " + std::to_string(i + 1) + " of " + std::to_string(count) + " (" +
                                    std::to_string(static_cast<std::uint32_t>(prevSize)) +
                                    " bytes) runs past the chunk table at byte " + std::to_string(table) +
                                    ", expected it before"));
    if (c.count > left || c.count == 0)
      throw InputError(atOffset(source, c.begin,
                                "chunk " + std::to_string(i + 1) + " holds " + std::to_string(c.count) +
                                    " points, expected 1 to the " + std::to_string(left) + " the header has left"));
    checkPlausible(c.count, c.end - c.begin, c.begin, source);
    at = c.end;
    first += c.count;
    left -= c.count;
  }
  if (left != 0)
    throw InputError(atOffset(source, table,
                              "the chunk table covers " + std::to_string(first) + " points, expected " +
                                  "the header's " + std::to_string(h.pointCount)));
  return chunks;
}

/// The records of one chunk, grown as they are decoded: damaged data fails after a few records,
/// so a damaged point count never allocates what the data could not fill.
class ChunkRecords {
 public:
  ChunkRecords(std::string& out, std::uint16_t length, std::uint64_t count)
      : out_(out), length_(length), total_(static_cast<std::size_t>(count) * length) {}
  /// Record `i` (< count), valid until the next call.
  unsigned char* operator[](std::uint64_t i) {
    const std::size_t need = static_cast<std::size_t>(i + 1) * length_;
    if (need > out_.size()) out_.resize(std::min(total_, std::max(need, 2 * out_.size())));
    return reinterpret_cast<unsigned char*>(out_.data()) + i * length_;
  }

 private:
  std::string& out_;
  std::size_t length_, total_;
};

/// Decodes one point-wise chunk into `records` (c.count records).
void decodePointwise(std::string_view file, const Chunk& c, const LazInfo& info, std::uint16_t recordLength,
                     std::string& records, const std::string& source, std::uint64_t base = 0) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(file.data());
  laz::ArithmeticDecoder dec(bytes + c.begin, bytes + c.end, base + c.begin, source);
  ChunkRecords rec(records, recordLength, c.count);
  unsigned char* out = rec[0];
  std::vector<std::unique_ptr<laz::PointwiseItem>> items;
  std::size_t off = 0;
  for (const LazItem& it : info.items) {
    items.push_back(laz::makePointwiseItem({it.type, it.size, it.version}));
    dec.readRaw(out + off, it.size);
    items.back()->first(out + off);
    off += it.size;
  }
  dec.start();
  for (std::uint64_t p = 1; p < c.count; ++p) {
    unsigned char* r = rec[p];
    std::size_t o = 0;
    for (std::size_t i = 0; i < items.size(); ++i) {
      items[i]->next(dec, r + o);
      o += info.items[i].size;
    }
  }
}

/// Decodes one layered chunk into `records` (c.count records).
void decodeLayered(std::string_view file, const Chunk& c, const LazInfo& info, std::uint16_t recordLength,
                   std::string& records, const std::string& source, std::uint64_t base = 0) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(file.data());
  laz::ArithmeticDecoder in(bytes + c.begin, bytes + c.end, base + c.begin, source);
  ChunkRecords rec(records, recordLength, c.count);
  unsigned char* out = rec[0];
  std::vector<std::unique_ptr<laz::LayeredItem>> items;
  std::size_t off = 0;
  unsigned channel = 0;
  for (const LazItem& it : info.items) {
    items.push_back(laz::makeLayeredItem({it.type, it.size, it.version}));
    in.readRaw(out + off, it.size);
    items.back()->first(out + off, channel);
    off += it.size;
  }
  const std::uint64_t countAt = in.offset();
  const std::uint32_t count = in.readRawU32();
  if (count != c.count)
    throw InputError(atOffset(source, countAt,
                              "chunk holds " + std::to_string(count) + " points, expected " + std::to_string(c.count) +
                                  " as the chunk table says"));
  for (auto& item : items) item->readSizes(in);
  for (auto& item : items) item->startLayers(in);
  for (std::uint64_t p = 1; p < c.count; ++p) {
    unsigned char* r = rec[p];
    std::size_t o = 0;
    channel = 0;  // as the format's reference decoder: set by POINT14 only when it changes
    for (std::size_t i = 0; i < items.size(); ++i) {
      items[i]->next(r + o, channel);
      o += info.items[i].size;
    }
  }
}

}  // namespace

std::string LazInfo::compressorName() const {
  switch (compressor) {
    case 1:
      return "point-wise";
    case 2:
      return "point-wise chunked";
    case 3:
      return "layered chunked";
    default:
      return "compressor " + std::to_string(compressor);
  }
}

std::string LazInfo::itemList() const {
  std::string s;
  for (const LazItem& it : items) {
    if (!s.empty()) s += ", ";
    s += it.name + " v" + std::to_string(it.version);
    if (it.type == laz::kByte || it.type == laz::kByte14) s += " (" + std::to_string(it.size) + " bytes)";
  }
  return s;
}

LazInfo parseLazVlr(std::string_view file, const LasHeader& h, const std::string& source) {
  std::uint64_t at = h.headerSize;
  for (std::uint32_t v = 0; v < h.numVlrs; ++v) {
    if (at + kVlrHeaderSize > h.offsetToPointData || at + kVlrHeaderSize > file.size())
      throw InputError(atOffset(source, at,
                                "VLR " + std::to_string(v + 1) + " of " + std::to_string(h.numVlrs) +
                                    " runs past the start of the point data, expected the LASzip VLR"));
    const char* p = file.data() + at;
    std::string userId(p + 2, 16);
    userId.resize(std::strlen(userId.c_str()));
    const auto recordId = detail::loadLE<std::uint16_t>(p + 18);
    const auto length = detail::loadLE<std::uint16_t>(p + 20);
    const std::uint64_t body = at + kVlrHeaderSize;
    if (body + length > h.offsetToPointData || body + length > file.size())
      throw InputError(atOffset(source, at + 20,
                                "VLR " + std::to_string(v + 1) + " of " + std::to_string(length) +
                                    " bytes runs past the start of the point data"));
    if (userId == kLaszipUserId && recordId == kLaszipRecordId) {
      if (length < kLazVlrFixedSize)
        throw InputError(atOffset(source, at + 20,
                                  "LASzip VLR of " + std::to_string(length) + " bytes, expected at least " +
                                      std::to_string(kLazVlrFixedSize)));
      const char* b = file.data() + body;
      LazInfo info;
      info.compressor = detail::loadLE<std::uint16_t>(b);
      info.coder = detail::loadLE<std::uint16_t>(b + 2);
      info.versionMajor = static_cast<std::uint8_t>(b[4]);
      info.versionMinor = static_cast<std::uint8_t>(b[5]);
      info.revision = detail::loadLE<std::uint16_t>(b + 6);
      info.options = detail::loadLE<std::uint32_t>(b + 8);
      info.chunkSize = detail::loadLE<std::uint32_t>(b + 12);
      const auto numItems = detail::loadLE<std::uint16_t>(b + 32);
      if (info.compressor < 1 || info.compressor > 3)
        throw InputError(atOffset(source, body,
                                  "unknown LAZ compressor " + std::to_string(info.compressor) +
                                      ", expected 1 (point-wise), 2 (point-wise chunked) or 3 "
                                      "(layered chunked)"));
      if (info.coder != 0)
        throw InputError(atOffset(source, body + 2,
                                  "unknown LAZ coder " + std::to_string(info.coder) + ", expected 0 (arithmetic)"));
      if (kLazVlrFixedSize + std::size_t(numItems) * kLazItemSize > length)
        throw InputError(atOffset(source, body + 32,
                                  "LASzip VLR lists " + std::to_string(numItems) + " items, more than its " +
                                      std::to_string(length) + " bytes hold"));
      for (std::uint16_t i = 0; i < numItems; ++i) {
        const char* q = b + kLazVlrFixedSize + i * kLazItemSize;
        LazItem it;
        it.type = detail::loadLE<std::uint16_t>(q);
        it.size = detail::loadLE<std::uint16_t>(q + 2);
        it.version = detail::loadLE<std::uint16_t>(q + 4);
        it.name = laz::itemName(it.type);
        info.items.push_back(it);
      }
      checkItems(info, h.pointFormat, h.recordLength, body + kLazVlrFixedSize, source);
      return info;
    }
    at = body + length;
  }
  throw InputError(atOffset(source, h.headerSize,
                            "compressed point data (LAZ) but no LASzip VLR (user id 'laszip encoded', record " +
                                std::to_string(kLaszipRecordId) + ") among the " + std::to_string(h.numVlrs) +
                                " VLRs, expected one"));
}

std::string decompressLazChunk(std::string_view chunk, const LazInfo& info, std::uint16_t recordLength,
                               std::uint64_t count, const std::string& source, std::uint64_t fileOffset) {
  if (info.compressor < 1 || info.compressor > 3)
    throw InputError(source + ": unknown LAZ compressor " + std::to_string(info.compressor) + ", expected 1, 2 or 3");
  checkItems(info, -1, recordLength, fileOffset, source);
  // The chunk's bytes sit at offset 0 of their own view; messages add fileOffset.
  checkPlausible(count, chunk.size(), fileOffset, source);
  std::string out;
  if (count == 0) return out;
  const Chunk c{0, chunk.size(), 0, count};
  if (info.compressor == 3)
    decodeLayered(chunk, c, info, recordLength, out, source, fileOffset);
  else
    decodePointwise(chunk, c, info, recordLength, out, source, fileOffset);
  return out;
}

std::string decompressLaz(std::string_view file, const LasHeader& h, const std::string& source, LazInfo* infoOut,
                          int threads) {
  LazInfo info = parseLazVlr(file, h, source);
  if (h.offsetToPointData > file.size())
    throw InputError(atOffset(source, file.size(),
                              "truncated: point data should start at byte " + std::to_string(h.offsetToPointData)));
  std::vector<Chunk> chunks = readChunkTable(file, h, info, source);
  info.chunkCount = chunks.size();
  if (infoOut) *infoOut = info;
  // Each chunk is decoded on its own into its own records; the first failing chunk (in file
  // order) names the error.
  std::vector<std::string> parts(chunks.size());
  std::vector<std::optional<InputError>> errors(chunks.size());
  auto decodeRange = [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      try {
        if (info.compressor == 3)
          decodeLayered(file, chunks[i], info, h.recordLength, parts[i], source);
        else
          decodePointwise(file, chunks[i], info, h.recordLength, parts[i], source);
      } catch (const InputError& e) {
        errors[i] = e;
      }
    }
  };
  const tbb::blocked_range<std::size_t> all(0, chunks.size(), 1);
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute([&] { tbb::parallel_for(all, decodeRange); });
  } else {
    tbb::parallel_for(all, decodeRange);
  }
  for (const auto& e : errors)
    if (e) throw *e;
  if (parts.size() == 1) return std::move(parts[0]);
  std::string out;
  out.reserve(static_cast<std::size_t>(h.pointCount) * h.recordLength);
  for (std::string& p : parts) {
    out += p;
    std::string().swap(p);
  }
  return out;
}

}  // namespace treesketch::io
