// LAS reader. Format reference: ASPRS "LAS Specification 1.4 – R15" (2019) and the 1.0–1.3
// specifications it supersedes; the public header block and, of each record, X/Y/Z, intensity,
// classification, the withheld flag and RGB are used.
#include "treesketch/io/las.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "io/io_util.h"
#include "treesketch/io/laz.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

namespace {

// Byte offsets in the public header block.
constexpr std::size_t kOffVersionMajor = 24, kOffVersionMinor = 25, kOffSystemId = 26, kOffSoftware = 58,
                      kOffHeaderSize = 94, kOffPointDataOffset = 96, kOffNumVlrs = 100, kOffPointFormat = 104,
                      kOffRecordLength = 105, kOffLegacyCount = 107, kOffScale = 131, kOffOffset = 155, kOffMaxX = 179,
                      kOffPointCount64 = 247;
constexpr std::size_t kHeaderSize12 = 227, kHeaderSize13 = 235, kHeaderSize14 = 375;

std::string fixedString(std::string_view data, std::size_t off, std::size_t n) {
  std::string s(data.substr(off, n));
  s.resize(std::strlen(s.c_str()));
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

std::uint16_t lasMinRecordLength(int pointFormat) {
  static const std::uint16_t kLengths[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  if (pointFormat < 0 || pointFormat > 10) return 0;
  return kLengths[pointFormat];
}

LasHeader parseLasHeader(std::string_view data, const std::string& source) {
  if (data.empty()) throw InputError(source + ": file is empty, expected a LAS file starting with 'LASF'");
  if (data.size() < 4 || data.substr(0, 4) != "LASF")
    throw InputError(atOffset(
        source, 0, "bad signature " + detail::quoted(data.substr(0, 4)) + ", expected 'LASF' (not a LAS file)"));
  if (data.size() < kHeaderSize12)
    throw InputError(atOffset(source, data.size(),
                              "truncated header: " + std::to_string(data.size()) + " bytes, expected at least " +
                                  std::to_string(kHeaderSize12)));
  LasHeader h;
  h.versionMajor = static_cast<std::uint8_t>(data[kOffVersionMajor]);
  h.versionMinor = static_cast<std::uint8_t>(data[kOffVersionMinor]);
  if (h.versionMajor != 1 || h.versionMinor > 4)
    throw InputError(atOffset(source, kOffVersionMajor,
                              "unsupported LAS version " + std::to_string(h.versionMajor) + "." +
                                  std::to_string(h.versionMinor) + ", expected 1.0 to 1.4"));
  h.systemId = fixedString(data, kOffSystemId, 32);
  h.generatingSoftware = fixedString(data, kOffSoftware, 32);
  h.headerSize = detail::loadLE<std::uint16_t>(data.data() + kOffHeaderSize);
  std::size_t need = h.versionMinor >= 4 ? kHeaderSize14 : h.versionMinor == 3 ? kHeaderSize13 : kHeaderSize12;
  if (h.headerSize < need)
    throw InputError(atOffset(source, kOffHeaderSize,
                              "header size " + std::to_string(h.headerSize) + " too small for LAS 1." +
                                  std::to_string(h.versionMinor) + ", expected at least " + std::to_string(need)));
  if (data.size() < h.headerSize)
    throw InputError(atOffset(source, data.size(),
                              "truncated header: expected " + std::to_string(h.headerSize) + " bytes of header"));
  h.offsetToPointData = detail::loadLE<std::uint32_t>(data.data() + kOffPointDataOffset);
  h.numVlrs = detail::loadLE<std::uint32_t>(data.data() + kOffNumVlrs);
  std::uint8_t fmt = static_cast<std::uint8_t>(data[kOffPointFormat]);
  // LASzip sets bit 7 (and bit 6 in old writers) of the format byte for compressed points.
  h.compressed = (fmt & 0xC0) != 0;
  fmt &= 0x3F;
  if (fmt > 10)
    throw InputError(atOffset(source, kOffPointFormat,
                              "unsupported point data record format " + std::to_string(fmt) + ", expected 0 to 10"));
  h.pointFormat = fmt;
  h.recordLength = detail::loadLE<std::uint16_t>(data.data() + kOffRecordLength);
  if (h.recordLength < lasMinRecordLength(fmt))
    throw InputError(atOffset(source, kOffRecordLength,
                              "point record length " + std::to_string(h.recordLength) +
                                  " is too short for point format " + std::to_string(fmt) + ", expected at least " +
                                  std::to_string(lasMinRecordLength(fmt))));
  h.legacyPointCount = detail::loadLE<std::uint32_t>(data.data() + kOffLegacyCount);
  h.pointCount = h.legacyPointCount;
  if (h.versionMinor >= 4) {
    std::uint64_t c64 = detail::loadLE<std::uint64_t>(data.data() + kOffPointCount64);
    if (c64 != 0) h.pointCount = c64;
  }
  for (int k = 0; k < 3; ++k) {
    h.scale[k] = detail::loadLE<double>(data.data() + kOffScale + 8 * k);
    h.offset[k] = detail::loadLE<double>(data.data() + kOffOffset + 8 * k);
    h.max[k] = detail::loadLE<double>(data.data() + kOffMaxX + 16 * k);
    h.min[k] = detail::loadLE<double>(data.data() + kOffMaxX + 16 * k + 8);
  }
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(h.scale[k]) || h.scale[k] == 0)
      throw InputError(atOffset(source, kOffScale + 8 * k, "scale factor must be finite and non-zero"));
    if (!std::isfinite(h.offset[k])) throw InputError(atOffset(source, kOffOffset + 8 * k, "offset must be finite"));
  }
  if (h.offsetToPointData < h.headerSize)
    throw InputError(atOffset(source, kOffPointDataOffset,
                              "offset to point data " + std::to_string(h.offsetToPointData) +
                                  " lies inside the header, expected at least " + std::to_string(h.headerSize)));
  return h;
}

LasHeader readLasHeader(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path.string() + ": file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  std::string head(kHeaderSize14, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return parseLasHeader(head, path.string());
}

namespace {

/// Byte offset of the RGB triple in a record of `format`, or -1 when the format has none (LAS 1.4
/// R15, tables 7–17).
int rgbOffset(int format) {
  switch (format) {
    case 2:
      return 20;
    case 3:
    case 5:
      return 28;
    case 7:
    case 8:
    case 10:
      return 30;
    default:
      return -1;
  }
}

/// Reads intensity, classification and RGB of every record into `cloud` (positions already read).
/// Decisions, as CloudCompare does: an attribute that is 0 in every record is the writer's "not
/// recorded" and is dropped; colours are 16-bit by the specification, but many writers store 8-bit
/// values in them, so they are divided by 257 (65535 -> 255) only when some channel exceeds 255.
/// Formats 0–5 keep the class in the low 5 bits of byte 15 (the others are flags); 6–10 give it a
/// whole byte (16).
void readLasAttributes(const char* records, const LasHeader& h, geom::PointCloud& cloud) {
  const std::size_t n = cloud.size();
  const bool extended = h.pointFormat >= 6;
  const int rgb = rgbOffset(h.pointFormat);
  cloud.intensity.resize(n);
  cloud.classification.resize(n);
  if (rgb >= 0) cloud.color.resize(n);
  bool anyIntensity = false, anyClass = false, anyColor = false, wideColor = false;
  std::vector<std::array<std::uint16_t, 3>> wide(rgb >= 0 ? n : 0);
  const char* p = records;
  for (std::size_t i = 0; i < n; ++i, p += h.recordLength) {
    std::uint16_t intensity = detail::loadLE<std::uint16_t>(p + 12);
    std::uint8_t cls = extended ? static_cast<std::uint8_t>(p[16]) : static_cast<std::uint8_t>(p[15] & 0x1F);
    cloud.intensity[i] = static_cast<float>(intensity);
    cloud.classification[i] = cls;
    anyIntensity |= intensity != 0;
    anyClass |= cls != 0;
    if (rgb >= 0) {
      for (int k = 0; k < 3; ++k) {
        wide[i][k] = detail::loadLE<std::uint16_t>(p + rgb + 2 * k);
        anyColor |= wide[i][k] != 0;
        wideColor |= wide[i][k] > 255;
      }
    }
  }
  for (std::size_t i = 0; i < wide.size(); ++i)
    for (int k = 0; k < 3; ++k)
      cloud.color[i][k] = static_cast<std::uint8_t>(wideColor ? (wide[i][k] + 128) / 257 : wide[i][k]);
  if (!anyIntensity) cloud.intensity.clear();
  if (!anyClass) cloud.classification.clear();
  if (!anyColor) cloud.color.clear();
}

/// Whether a record is flagged withheld: bit 7 of the classification byte (15) in formats 0–5,
/// bit 2 of the classification flags (the low nibble of byte 15) in formats 6–10 (LAS 1.4 R15,
/// tables 7 and 12).
bool isWithheld(const char* record, bool extended) {
  const auto flags = static_cast<std::uint8_t>(record[15]);
  return extended ? (flags & 0x04) != 0 : (flags & 0x80) != 0;
}

/// Drops the points whose records are flagged withheld from `cloud` (positions and attributes read
/// from `records`, one per record); returns how many there were.
std::uint64_t dropWithheld(const char* records, const LasHeader& h, geom::PointCloud& cloud) {
  const std::size_t n = cloud.size();
  const bool extended = h.pointFormat >= 6;
  std::vector<char> drop(n, 0);
  std::uint64_t count = 0;
  const char* p = records;
  for (std::size_t i = 0; i < n; ++i, p += h.recordLength)
    if (isWithheld(p, extended)) {
      drop[i] = 1;
      ++count;
    }
  if (count == 0) return 0;
  auto compact = [&](auto& values) {
    if (values.size() != n) return;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (!drop[i]) values[kept++] = values[i];
    values.resize(kept);
  };
  compact(cloud.positions);
  compact(cloud.intensity);
  compact(cloud.classification);
  compact(cloud.color);
  return count;
}

geom::PointCloud parseLas(std::string_view file, const std::string& source, const CloudReadOptions& options,
                          LasHeader* headerOut, int threads) {
  LasHeader h = parseLasHeader(file, source);
  // Compressed points are decompressed into plain records first, then read as any LAS records.
  std::string decompressed;
  std::string_view data = file;
  std::size_t start = h.offsetToPointData;  // where the records start in `data`
  if (h.compressed) {
    decompressed = decompressLaz(file, h, source, &h.laz, threads);
    data = decompressed;
    start = 0;
  }
  if (headerOut) *headerOut = h;
  if (start > data.size())
    throw InputError(atOffset(source, data.size(),
                              "truncated: point data should start at byte " + std::to_string(h.offsetToPointData)));
  std::size_t avail = (data.size() - start) / h.recordLength;
  if (h.pointCount > avail)
    throw InputError(atOffset(source, start + avail * h.recordLength,
                              "truncated: the header promises " + std::to_string(h.pointCount) + " points of " +
                                  std::to_string(h.recordLength) + " bytes, but only " + std::to_string(avail) +
                                  " complete records follow"));
  geom::PointCloud cloud;
  auto n = static_cast<std::size_t>(h.pointCount);
  cloud.positions.resize(n);
  const char* p = data.data() + start;
  for (std::size_t i = 0; i < n; ++i, p += h.recordLength) {
    for (int k = 0; k < 3; ++k)
      cloud.positions[i][k] = detail::loadLE<std::int32_t>(p + 4 * k) * h.scale[k] + h.offset[k];
    if (!cloud.positions[i].allFinite()) {
      const std::string what = "coordinate overflows to Inf after scale and offset, expected finite";
      if (h.compressed) throw InputError(source + ": point " + std::to_string(i + 1) + ": " + what);
      throw InputError(atOffset(source, static_cast<std::uint64_t>(p - data.data()), what));
    }
  }
  readLasAttributes(data.data() + start, h, cloud);
  h.withheld = dropWithheld(data.data() + start, h, cloud);
  if (headerOut) headerOut->withheld = h.withheld;
  if (h.withheld > 0 && cloud.size() < options.minPoints)
    throw InputError(source + ": holds " + std::to_string(cloud.size()) + " point" + (cloud.size() == 1 ? "" : "s") +
                     " not withheld (" + std::to_string(h.withheld) + " of its " + std::to_string(h.pointCount) +
                     " are flagged withheld, which the LAS specification says are deleted), expected at least " +
                     std::to_string(options.minPoints));
  checkCloudSize(cloud, source, options.minPoints);
  cloud.up = geom::UpAxis::Z;  // LAS coordinates are Z-up by the format's specification
  return cloud;
}

}  // namespace

geom::PointCloud readLas(std::istream& in, const std::string& source, const CloudReadOptions& options,
                         LasHeader* header) {
  return parseLas(detail::readAll(in, source), source, options, header, 0);
}

geom::PointCloud readLas(const std::filesystem::path& path, const CloudReadOptions& options, LasHeader* header) {
  return parseLas(detail::readFile(path), path.string(), options, header, 0);
}

}  // namespace treesketch::io
