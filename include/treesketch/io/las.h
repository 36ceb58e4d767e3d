// ASPRS LAS 1.0–1.4 point clouds, point data record formats 0–10, and LAZ (LASzip-compressed
// LAS, formats 0–3 and 6–8: see laz.h), told apart by the format byte's compression bit rather
// than the extension. Read: the coordinates (X, Y, Z int32 at the start of every record, times
// scale plus offset), intensity, classification and, in the formats that have it, RGB
// (geom::PointCloud's optional attributes; one that is 0 in every record is dropped as "not
// recorded"). Records flagged withheld (LAS 1.0–1.3 formats 0–5: bit 7 of the classification
// byte; formats 6–10: bit 2 of the classification flags) are dropped on read, as the
// specification asks ("should be considered deleted"), and counted (LasHeader::withheld).
#pragma once

#include <cstdint>
#include <filesystem>
#include <istream>
#include <string>
#include <string_view>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"
#include "treesketch/io/laz.h"
#include "treesketch/io/read_options.h"

namespace treesketch::io {

struct LasHeader {
  int versionMajor = 1;
  int versionMinor = 2;
  std::string systemId;
  std::string generatingSoftware;
  std::uint16_t headerSize = 0;
  std::uint32_t offsetToPointData = 0;
  std::uint32_t numVlrs = 0;
  std::uint8_t pointFormat = 0;  ///< 0..10 (the compression bits masked off)
  bool compressed = false;       ///< LAZ: the format byte had a compression bit set
  std::uint16_t recordLength = 0;
  std::uint32_t legacyPointCount = 0;
  std::uint64_t pointCount = 0;  ///< the 64-bit count for LAS 1.4 when set, else the legacy count
  geom::Vec3 scale = geom::Vec3::Ones();
  geom::Vec3 offset = geom::Vec3::Zero();
  geom::Vec3 min = geom::Vec3::Zero();  ///< header bounds (world units, as stored)
  geom::Vec3 max = geom::Vec3::Zero();
  LazInfo laz;  ///< compressed files: the LASzip VLR and chunk count (filled by readLas)
  /// Records flagged withheld, dropped on read (filled by readLas; the cloud holds
  /// pointCount − withheld points).
  std::uint64_t withheld = 0;
};

/// Smallest record length of each point data record format 0..10, in bytes (LAS 1.4 R15 table).
std::uint16_t lasMinRecordLength(int pointFormat);

/// Parses the public header block at the start of `data` (the whole file or at least its
/// header). Throws InputError with the byte offset for: a signature other than "LASF", a version
/// other than 1.0–1.4, a header size too small for its version, a point format above 10, a record length too short for
/// its format, a zero or non-finite scale, an offset to point data inside the header.
LasHeader parseLasHeader(std::string_view data, const std::string& source);
/// Reads the header of a LAS or LAZ file (the LASzip VLR is read by readLas only).
LasHeader readLasHeader(const std::filesystem::path& path);

/// Reads all points but the withheld: X/Y/Z * scale + offset (world units, usually metres; Z up),
/// decompressing LAZ on all cores. Throws InputError for a bad header (above), data shorter than
/// pointCount records (naming the offset where it ends), bad LAZ data (see decompressLaz), fewer
/// than options.minPoints points once the withheld are dropped (saying how many were withheld).
/// Allocation is capped by the bytes present.
geom::PointCloud readLas(std::istream& in, const std::string& source, const CloudReadOptions& options = {},
                         LasHeader* header = nullptr);
/// Same, from a file (.las or .laz).
geom::PointCloud readLas(const std::filesystem::path& path, const CloudReadOptions& options = {},
                         LasHeader* header = nullptr);

}  // namespace treesketch::io
