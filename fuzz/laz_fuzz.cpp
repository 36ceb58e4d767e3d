// Fuzz harness: the LAZ decoder (LASzip VLR, chunk table, arithmetic decoder, point-wise and
// layered items). Each input is used twice:
//  - as a whole file (the seeds include small valid LAZ files): readLas;
//  - as one chunk: the first bytes choose the point format (0-3 or 6-8), the extra bytes (0-3),
//    the items' order variant and the record count (< 4096); the rest is the chunk's bytes,
//    decoded by decompressLazChunk, so random data reaches the item decoders rather than
//    stopping at a header or chunk table (a fuzzer cannot forge their arithmetic-coded sizes).
// Contract checked: bad input throws InputError and nothing else; an accepted file gives exactly
// the header's point count of finite points and decodes the same on one thread as on all; an
// accepted chunk gives count records, its first record being the chunk's first bytes.
#include <sstream>

#include "fuzz_support.h"
#include "treesketch/io/las.h"
#include "treesketch/io/laz.h"
#include "treesketch/util/error.h"

using namespace treesketch;

namespace {

void readFile(const std::string& bytes) {
  io::CloudReadOptions options;
  options.minPoints = 1;
  std::istringstream in(bytes);
  io::LasHeader header;
  geom::PointCloud cloud;
  try {
    cloud = io::readLas(in, "fuzz.laz", options, &header);
  } catch (const InputError&) {
    return;
  }
  fuzz::checkCloud(cloud, 1);
  FUZZ_CHECK(cloud.size() + header.withheld == header.pointCount, "LAZ: point count differs from the header's");
  if (header.compressed) {
    const std::string all = io::decompressLaz(bytes, header, "fuzz.laz", nullptr, 0);
    const std::string one = io::decompressLaz(bytes, header, "fuzz.laz", nullptr, 1);
    FUZZ_CHECK(all == one, "LAZ: one thread and all threads decode differently");
  }
}

io::LazItem item(std::uint16_t type, std::uint16_t size, std::uint16_t version) {
  return {type, size, version, "item"};
}

void readChunk(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteSource in(data, size);
  static const int kFormats[] = {0, 1, 2, 3, 6, 7, 8};
  const int format = kFormats[in.next<std::uint8_t>() % 7];
  const auto extra = static_cast<std::uint16_t>(in.next<std::uint8_t>() % 4);
  const auto variant = in.next<std::uint8_t>();
  const std::uint64_t count = in.next<std::uint16_t>() % 4096;
  io::LazInfo info;
  if (format >= 6) {
    info.compressor = 3;
    info.items.push_back(item(10, 30, 3));
    if (format == 7) info.items.push_back(item(11, 6, 3));
    if (format == 8) info.items.push_back(item(12, 8, 3));
    if (extra) info.items.push_back(item(14, extra, 3));
  } else {
    info.compressor = static_cast<std::uint16_t>(1 + (variant & 1));
    info.items.push_back(item(6, 20, 2));
    const bool gps = format == 1 || format == 3, rgb = format == 2 || format == 3;
    // Both orders of GPS time and colour occur in files; the decoder must not care.
    if ((variant & 2) && rgb) info.items.push_back(item(8, 6, 2));
    if (gps) info.items.push_back(item(7, 8, 2));
    if (!(variant & 2) && rgb) info.items.push_back(item(8, 6, 2));
    if (extra) info.items.push_back(item(0, extra, 2));
  }
  std::uint16_t length = 0;
  for (const auto& it : info.items) length = static_cast<std::uint16_t>(length + it.size);
  const std::string_view chunk = fuzz::asText(data + (size - in.remaining()), in.remaining());
  std::string records;
  try {
    records = io::decompressLazChunk(chunk, info, length, count, "fuzz.laz", 100);
  } catch (const InputError&) {
    return;
  }
  FUZZ_CHECK(records.size() == count * length, "LAZ chunk: wrong number of record bytes");
  if (count) FUZZ_CHECK(records.compare(0, length, chunk.substr(0, length)) == 0, "LAZ chunk: first record not raw");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  readFile(std::string(fuzz::asText(data, size)));
  readChunk(data, size);
  return 0;
}
