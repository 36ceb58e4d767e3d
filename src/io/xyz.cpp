#include "treesketch/io/xyz.h"

#include <algorithm>
#include <cmath>

#include "io/io_util.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

namespace {

inline bool isSeparator(char c) {
  return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r' || c == '\v' || c == '\f';
}

/// Splits [b, e) into at most `maxFields` fields; returns how many were found.
int splitFields(const char* b, const char* e, std::string_view* fields, int maxFields) {
  int n = 0;
  const char* p = b;
  while (n < maxFields) {
    while (p < e && isSeparator(*p)) ++p;
    if (p == e) break;
    const char* start = p;
    while (p < e && !isSeparator(*p)) ++p;
    fields[n++] = std::string_view(start, static_cast<std::size_t>(p - start));
  }
  return n;
}

geom::PointCloud parseXyz(std::string_view data, const std::string& source, const CloudReadOptions& options) {
  geom::PointCloud cloud;
  // One point a line, and a point line takes at least 6 bytes ("0 0 0\n").
  const std::size_t lineCount = static_cast<std::size_t>(std::count(data.begin(), data.end(), '\n')) + 1;
  cloud.positions.reserve(std::min(lineCount, data.size() / 6 + 1));
  std::size_t headerLines = 0;
  std::string_view f[3];
  detail::Lines lines(data);
  std::string_view line;
  while (lines.next(line)) {
    const std::size_t lineNo = lines.number();
    const char* lineStart = line.data();
    const char* lineEnd = lineStart + line.size();
    int n = splitFields(lineStart, lineEnd, f, 3);
    if (n == 0) continue;                                                             // blank line
    if (f[0][0] == '#' || (f[0].size() >= 2 && f[0].substr(0, 2) == "//")) continue;  // comment
    double v[3];
    bool numeric = n == 3;
    for (int i = 0; numeric && i < 3; ++i) numeric = detail::parseDouble(f[i].data(), f[i].data() + f[i].size(), v[i]);
    if (!numeric) {
      if (cloud.empty() && headerLines < options.maxHeaderLines) {
        ++headerLines;
        continue;
      }
      throw InputError(atLine(
          source, lineNo,
          "expected 'x y z' (3 numbers separated by spaces, commas or semicolons), got " + detail::quoted(line)));
    }
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      throw InputError(atLine(source, lineNo, "non-finite coordinate (NaN or Inf), expected finite numbers"));
    if (cloud.empty()) {
      // "1,5;2,5;3,5" would silently read as 1 5 2: refuse decimal commas on the first point line.
      if (line.find(';') != std::string_view::npos && line.find(',') != std::string_view::npos)
        throw InputError(
            atLine(source, lineNo, "line mixes ';' and ',' (decimal commas?); expected '.' as the decimal separator"));
    }
    cloud.positions.emplace_back(v[0], v[1], v[2]);
  }
  if (cloud.empty()) {
    if (data.empty()) throw InputError(source + ": file is empty, expected lines of 'x y z' numbers");
    throw InputError(source + ": no point lines found in " + std::to_string(lines.number()) +
                     " lines, expected lines of 'x y z' numbers");
  }
  checkCloudSize(cloud, source, options.minPoints);
  return cloud;
}

}  // namespace

geom::PointCloud readXyz(std::istream& in, const std::string& source, const CloudReadOptions& options) {
  return parseXyz(detail::readAll(in, source), source, options);
}

geom::PointCloud readXyz(const std::filesystem::path& path, const CloudReadOptions& options) {
  return parseXyz(detail::readFile(path), path.string(), options);
}

void writeXyz(std::ostream& out, const geom::PointCloud& cloud) {
  std::string buf;
  buf.reserve(detail::kWriteBlock + 100);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const geom::Vec3& q = cloud.positions[i];
    if (!q.allFinite()) throw OutputError("xyz writer: point " + std::to_string(i) + " has a non-finite coordinate");
    detail::appendXyz(buf, q.x(), q.y(), q.z());
    buf += '\n';
    detail::flushIfFull(out, buf);
  }
  detail::writeAll(out, buf);
}

void writeXyz(const std::filesystem::path& path, const geom::PointCloud& cloud) {
  writeFileAtomically(path, [&](std::ostream& out) { writeXyz(out, cloud); });
}

}  // namespace treesketch::io
