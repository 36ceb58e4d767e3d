#include "treesketch/io/xyz.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <vector>

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

/// Which columns hold the coordinates and which attribute (-1: none).
struct ColumnMap {
  int x = 0, y = 1, z = 2;
  int intensity = -1, red = -1, green = -1, blue = -1, classification = -1;
  bool namesXyz = false;  ///< a header named all three coordinates
  bool any() const { return intensity >= 0 || red >= 0 || classification >= 0; }
  bool defaultXyz() const { return x == 0 && y == 1 && z == 2; }
  int needed() const { return std::max({intensity, red, green, blue, classification}) + 1; }
  int neededXyz() const { return std::max({x, y, z}) + 1; }
};

constexpr int kMaxFields = 32;

/// The fields of a header line. A line with commas, semicolons or tabs is split at each one, so
/// an empty name keeps its column (pandas writes ",x,y,z" over an unnamed index column); other
/// lines at runs of spaces. Returns how many fields were found (at most kMaxFields).
int splitHeader(std::string_view line, std::string_view* fields) {
  char sep = 0;
  for (char c : {',', ';', '\t'})
    if (line.find(c) != std::string_view::npos) {
      sep = c;
      break;
    }
  if (sep == 0) return splitFields(line.data(), line.data() + line.size(), fields, kMaxFields);
  int n = 0;
  std::size_t start = 0;
  while (n < kMaxFields && start <= line.size()) {
    std::size_t end = line.find(sep, start);
    if (end == std::string_view::npos) end = line.size();
    std::string_view f = line.substr(start, end - start);
    while (!f.empty() && (f.front() == ' ' || isSeparator(f.front()))) f.remove_prefix(1);
    while (!f.empty() && (f.back() == ' ' || isSeparator(f.back()))) f.remove_suffix(1);
    fields[n++] = f;
    start = end + 1;
  }
  while (n > 0 && fields[n - 1].empty()) --n;  // a trailing separator names nothing
  return n;
}

/// Columns named by a header line ("X,Y,Z,Intensity,R,G,B", "//X Y Z Rf Gf Bf Classification",
/// CloudCompare's ASCII export '"x" "y" "z"', "id;x;y;z;label", pandas' ",x,y,z"): names are
/// matched case-insensitively, without quotes, with CloudCompare's "scalar_" prefix and "f"
/// suffix on colour names dropped; other names (an id or index column, a label) are ignored.
/// x, y and z stay the first three columns unless the line names all three (namesXyz).
ColumnMap columnsFromHeader(std::string_view header) {
  std::string_view f[kMaxFields];
  int n = splitHeader(header, f);
  ColumnMap m;
  int xyz[3] = {-1, -1, -1};
  for (int i = 0; i < n; ++i) {
    std::string name;
    for (char c : f[i])
      if (c != '/' && c != '#' && c != '"' && c != '\'')
        name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (name.rfind("scalar_", 0) == 0) name = name.substr(7);
    if ((name == "x" || name == "y" || name == "z") && xyz[name[0] - 'x'] < 0)
      xyz[name[0] - 'x'] = i;
    else if (name == "intensity" || name == "i" || name == "reflectance")
      m.intensity = i;
    else if (name == "r" || name == "red" || name == "rf")
      m.red = i;
    else if (name == "g" || name == "green" || name == "gf")
      m.green = i;
    else if (name == "b" || name == "blue" || name == "bf")
      m.blue = i;
    else if (name == "classification" || name == "class")
      m.classification = i;
  }
  if (m.red < 0 || m.green < 0 || m.blue < 0) m.red = m.green = m.blue = -1;  // colour needs all three
  if (xyz[0] >= 0 && xyz[1] >= 0 && xyz[2] >= 0) m.x = xyz[0], m.y = xyz[1], m.z = xyz[2], m.namesXyz = true;
  return m;
}

/// A header line before the first point must name the x, y and z columns, or be a point count
/// (one number, as PTS files start); anything else would leave the columns to a guess.
void checkHeaderLine(std::string_view line, const ColumnMap& columns, const std::string& source, std::size_t lineNo) {
  if (columns.namesXyz) return;
  std::string_view f[2];
  double count = 0;
  if (splitFields(line.data(), line.data() + line.size(), f, 2) == 1 &&
      detail::parseDouble(f[0].data(), f[0].data() + f[0].size(), count))
    return;
  throw InputError(atLine(source, lineNo,
                          "header line " + detail::quoted(line) +
                              " does not name the coordinate columns; expected a header naming x, y and z (in any "
                              "order and case; other columns such as an id are ignored), a point count, or none"));
}

/// Columns by count when no header names them: 4 = x y z intensity; 6 = x y z r g b; 7 = x y z
/// intensity r g b (Leica PTS). Any other count: no attributes (we do not guess).
ColumnMap columnsFromCount(int n) {
  ColumnMap m;
  if (n == 4 || n == 7) m.intensity = 3;
  if (n == 6) m.red = 3, m.green = 4, m.blue = 5;
  if (n == 7) m.red = 4, m.green = 5, m.blue = 6;
  return m;
}

/// Appends the attributes of one point line (its `n` fields in `f`) to `cloud` and `colors`.
/// Extra columns are optional: a line without them (or with text there) drops the attributes of
/// the whole file rather than failing, as before they were read. Returns false when it dropped them.
bool appendAttributes(const std::string_view* f, int n, const ColumnMap& columns, geom::PointCloud& cloud,
                      std::vector<std::array<double, 3>>& colors) {
  double a[kMaxFields];
  auto number = [&](int col) {
    return col < n && detail::parseDouble(f[col].data(), f[col].data() + f[col].size(), a[col]) &&
           std::isfinite(a[col]);
  };
  bool ok = n >= columns.needed();
  if (ok && columns.intensity >= 0)
    ok = number(columns.intensity) && std::abs(a[columns.intensity]) <= std::numeric_limits<float>::max();
  if (ok && columns.red >= 0) ok = number(columns.red) && number(columns.green) && number(columns.blue);
  if (ok && columns.classification >= 0)
    ok = number(columns.classification) && a[columns.classification] >= 0 && a[columns.classification] <= 255;
  if (!ok) {
    cloud.intensity.clear();
    cloud.classification.clear();
    colors.clear();
    return false;
  }
  if (columns.intensity >= 0) cloud.intensity.push_back(static_cast<float>(a[columns.intensity]));
  if (columns.red >= 0) colors.push_back({a[columns.red], a[columns.green], a[columns.blue]});
  if (columns.classification >= 0)
    cloud.classification.push_back(static_cast<std::uint8_t>(std::lround(a[columns.classification])));
  return true;
}

/// Sets the cloud's colours from the columns read: colours in [0, 1] (CloudCompare's "Rf Gf Bf")
/// are scaled to bytes; others are clamped to 0–255.
void setColors(geom::PointCloud& cloud, const std::vector<std::array<double, 3>>& colors) {
  double top = 0.0;
  for (const auto& c : colors) top = std::max({top, c[0], c[1], c[2]});
  const double scale = top <= 1.0 ? 255.0 : 1.0;
  cloud.color.resize(colors.size());
  for (std::size_t i = 0; i < colors.size(); ++i)
    for (int k = 0; k < 3; ++k)
      cloud.color[i][k] = static_cast<std::uint8_t>(std::lround(std::clamp(colors[i][k] * scale, 0.0, 255.0)));
}

/// Drops a UTF-8 byte-order mark (Windows tools write one; it would make the first point a header);
/// refuses UTF-16 text, whose every other byte is zero.
std::string_view withoutByteOrderMark(std::string_view data, const std::string& source) {
  if (data.substr(0, 3) == "\xEF\xBB\xBF") return data.substr(3);
  if (data.substr(0, 2) == "\xFF\xFE" || data.substr(0, 2) == "\xFE\xFF")
    throw InputError(source + ": byte offset 0: UTF-16 text (byte-order mark " +
                     (data[0] == '\xFF' ? std::string("FF FE") : std::string("FE FF")) +
                     "); expected ASCII or UTF-8: save the file as UTF-8");
  return data;
}

geom::PointCloud parseXyz(std::string_view data, const std::string& source, const CloudReadOptions& options) {
  data = withoutByteOrderMark(data, source);
  geom::PointCloud cloud;
  // One point a line, and a point line takes at least 6 bytes ("0 0 0\n").
  const std::size_t lineCount = static_cast<std::size_t>(std::count(data.begin(), data.end(), '\n')) + 1;
  cloud.positions.reserve(std::min(lineCount, data.size() / 6 + 1));
  std::size_t headerLines = 0;
  std::string_view lastHeader;
  std::string_view f[kMaxFields];
  ColumnMap columns;        // from the last header line until the first point, then fixed
  bool attributes = false;  // every line so far had the attribute columns as numbers
  std::vector<std::array<double, 3>> colors;
  detail::Lines lines(data);
  std::string_view line;
  while (lines.next(line)) {
    const std::size_t lineNo = lines.number();
    const char* lineStart = line.data();
    const char* lineEnd = lineStart + line.size();
    int n = splitFields(lineStart, lineEnd, f, kMaxFields);
    if (n == 0) continue;  // blank line
    if (f[0][0] == '#' || (f[0].size() >= 2 && f[0].substr(0, 2) == "//")) {
      if (cloud.empty()) {  // "//X Y Z Rf Gf Bf" names columns
        lastHeader = line;
        columns = columnsFromHeader(lastHeader);
      }
      continue;  // comment
    }
    double v[3];
    const int xyz[3] = {columns.x, columns.y, columns.z};
    bool numeric = n >= columns.neededXyz();
    for (int i = 0; numeric && i < 3; ++i)
      numeric = detail::parseDouble(f[xyz[i]].data(), f[xyz[i]].data() + f[xyz[i]].size(), v[i]);
    if (!numeric) {
      if (cloud.empty() && headerLines < options.maxHeaderLines) {
        ++headerLines;
        lastHeader = line;
        columns = columnsFromHeader(lastHeader);
        checkHeaderLine(line, columns, source, lineNo);
        continue;
      }
      throw InputError(atLine(source, lineNo,
                              columns.defaultXyz()
                                  ? "expected 'x y z' (3 numbers separated by spaces, tabs, commas or semicolons), "
                                    "got " +
                                        detail::quoted(line)
                                  : "expected numbers in columns " + std::to_string(columns.x + 1) + ", " +
                                        std::to_string(columns.y + 1) + " and " + std::to_string(columns.z + 1) +
                                        " (x y z, as the header names them), got " + detail::quoted(line)));
    }
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      throw InputError(atLine(source, lineNo, "non-finite coordinate (NaN or Inf), expected finite numbers"));
    if (cloud.empty()) {
      // "1,5;2,5;3,5" would silently read as 1 5 2: refuse decimal commas on the first point line.
      if (line.find(';') != std::string_view::npos && line.find(',') != std::string_view::npos)
        throw InputError(
            atLine(source, lineNo, "line mixes ';' and ',' (decimal commas?); expected '.' as the decimal separator"));
      if (!columns.any() && columns.defaultXyz()) columns = columnsFromCount(n);
      attributes = columns.any();
    }
    cloud.positions.emplace_back(v[0], v[1], v[2]);
    if (attributes) attributes = appendAttributes(f, n, columns, cloud, colors);
  }
  if (cloud.empty()) {
    if (data.empty()) throw InputError(source + ": file is empty, expected lines of 'x y z' numbers");
    throw InputError(source + ": no point lines found in " + std::to_string(lines.number()) +
                     " lines, expected lines of 'x y z' numbers");
  }
  checkCloudSize(cloud, source, options.minPoints);
  if (!colors.empty()) setColors(cloud, colors);
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
