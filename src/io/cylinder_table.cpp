// Cylinder table reader: finds the columns by name (or TreeQSM's fixed order when there is no
// header), reads every row strictly, then resolves the parents.
#include "treesketch/io/cylinder_table.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/io_util.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

/// Fields of a line. `delimiter` 0 = runs of whitespace; otherwise that character, fields trimmed.
std::vector<std::string_view> split(std::string_view line, char delimiter) {
  std::vector<std::string_view> out;
  if (delimiter == 0) {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i == line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      out.push_back(line.substr(start, i - start));
    }
    return out;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t at = line.find(delimiter, start);
    out.push_back(trim(line.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start)));
    if (at == std::string_view::npos) break;
    start = at + 1;
  }
  // A trailing delimiter (TreeQSM's text export ends rows with one in some versions) adds no field.
  if (out.size() > 1 && out.back().empty()) out.pop_back();
  return out;
}

bool isNumber(std::string_view s) {
  double v;
  return detail::parseDouble(s.data(), s.data() + s.size(), v);
}

/// Lower case, without anything in parentheses (a unit) and without non-alphanumeric characters:
/// "start_X (m)" → "startx".
std::string normalizedName(std::string_view s) {
  std::string out;
  int depth = 0;
  for (char ch : s) {
    if (ch == '(') ++depth;
    if (ch == ')') depth = std::max(0, depth - 1);
    if (depth > 0) continue;
    if (std::isalnum(static_cast<unsigned char>(ch)))
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  }
  return out;
}

struct Line {
  std::size_t number = 0;  // 1-based
  std::string_view text;
};

/// The content lines: not blank, not '#' comments; '\r' removed.
std::vector<Line> contentLines(std::string_view text) {
  std::vector<Line> lines;
  std::size_t pos = 0, number = 0;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string_view t = trim(line);
    if (!t.empty() && t.front() != '#') lines.push_back({number, line});
    if (nl == std::string_view::npos) break;
    pos = nl + 1;
  }
  return lines;
}

char detectDelimiter(std::string_view line) {
  for (char d : {',', '\t', ';'})
    if (line.find(d) != std::string_view::npos) return d;
  return 0;
}

/// Column of each quantity (-1 when absent).
struct Columns {
  int id = -1, parent = -1, radius = -1, startRadius = -1, length = -1, branchOrder = -1;
  std::array<int, 3> start{-1, -1, -1}, end{-1, -1, -1}, axis{-1, -1, -1};
  std::vector<std::string> names;  // per field, as written (for messages)
  std::size_t count = 0;           // fields a row must have
};

bool complete(const std::array<int, 3>& a) { return a[0] >= 0 && a[1] >= 0 && a[2] >= 0; }

Columns headerColumns(const std::vector<std::string_view>& fields) {
  Columns c;
  auto set = [](int& slot, int column) {
    if (slot < 0) slot = column;  // the first column of a name wins
  };
  for (std::string_view raw : fields) {
    const std::string name = normalizedName(raw);
    const int col = static_cast<int>(c.names.size());
    // TreeQSM's text export names a three-column quantity once.
    if (name == "startpoint" || name == "axisdirection") {
      std::array<int, 3>& target = name == "startpoint" ? c.start : c.axis;
      for (int k = 0; k < 3; ++k) {
        set(target[k], col + k);
        c.names.push_back(std::string(raw) + "[" + "xyz"[k] + "]");
      }
      continue;
    }
    c.names.emplace_back(raw);
    if (name == "id" || name == "cylinderid")
      set(c.id, col);
    else if (name == "parent" || name == "parentid")
      set(c.parent, col);
    else if (name == "radius")
      set(c.radius, col);
    else if (name == "startradius")
      set(c.startRadius, col);
    else if (name == "length")
      set(c.length, col);
    else if (name == "branchorder")
      set(c.branchOrder, col);
    else if (name.size() == 6 && name.starts_with("start") && name[5] >= 'x' && name[5] <= 'z')
      set(c.start[name[5] - 'x'], col);
    else if (name.size() == 4 && name.starts_with("end") && name[3] >= 'x' && name[3] <= 'z')
      set(c.end[name[3] - 'x'], col);
    else if (name.size() == 5 && name.starts_with("axis") && name[4] >= 'x' && name[4] <= 'z')
      set(c.axis[name[4] - 'x'], col);
  }
  c.count = c.names.size();
  return c;
}

/// TreeQSM 2.3's column order, for tables saved without a header.
Columns treeQsmColumns(std::size_t count) {
  Columns c;
  c.radius = 0;
  c.length = 1;
  c.start = {2, 3, 4};
  c.axis = {5, 6, 7};
  if (count >= 9) c.parent = 8;
  if (count == 15) c.branchOrder = 13;
  static const char* kNames[15] = {"radius", "length",      "start_x", "start_y",     "start_z",
                                   "axis_x", "axis_y",      "axis_z",  "parent",      "extension",
                                   "added",  "UnmodRadius", "branch",  "BranchOrder", "PositionInBranch"};
  for (std::size_t i = 0; i < count; ++i) c.names.push_back(i < 15 ? kNames[i] : "column " + std::to_string(i + 1));
  c.count = count;
  return c;
}

struct Row {
  std::size_t line = 0;
  double id = 0, parent = 0;
  bool hasParent = false;
};

class TableReader {
 public:
  TableReader(const std::string& source) : source_(source) {}

  CylinderTable read(std::string_view text) {
    if (trim(text).empty()) throw InputError(source_ + ": file is empty, expected a cylinder table");
    const std::vector<Line> lines = contentLines(text);
    if (lines.empty()) throw InputError(source_ + ": no table lines (only comments), expected a cylinder table");
    delimiter_ = detectDelimiter(lines[0].text);
    const std::vector<std::string_view> first = split(lines[0].text, delimiter_);
    const bool header = !std::all_of(first.begin(), first.end(), isNumber);
    CylinderTable table;
    std::size_t firstRow = 0;
    if (header) {
      cols_ = headerColumns(first);
      table.format = formatOf(first);
      checkColumns(lines[0].number);
      firstRow = 1;
    } else {
      if (first.size() < 8)
        throw InputError(atLine(source_, lines[0].number,
                                "expected a header line naming the columns, or TreeQSM's numeric table (at least 8 "
                                "columns: radius, length, start x y z, axis x y z), got " +
                                    std::to_string(first.size()) + " numbers"));
      cols_ = treeQsmColumns(first.size());
      table.format = CylinderTableFormat::TreeQsmNoHeader;
    }

    std::vector<Row> rows;
    std::vector<double> ownRadius;
    for (std::size_t li = firstRow; li < lines.size(); ++li) {
      const Line& line = lines[li];
      const std::vector<std::string_view> f = split(line.text, delimiter_);
      if (f.size() != cols_.count)
        throw InputError(atLine(source_, line.number,
                                "expected " + std::to_string(cols_.count) + " fields (" +
                                    (header ? "the header's columns" : "as on the first row") + "), got " +
                                    std::to_string(f.size())));
      geom::ModelCylinder c;
      Row row;
      row.line = line.number;
      c.endRadius = number(f, cols_.radius, line.number);
      if (c.endRadius < 0) fail(line.number, cols_.radius, "expected a radius >= 0");
      c.startRadius = cols_.startRadius >= 0 ? number(f, cols_.startRadius, line.number) : c.endRadius;
      if (c.startRadius < 0) fail(line.number, cols_.startRadius, "expected a radius >= 0");
      for (int k = 0; k < 3; ++k) c.start[k] = number(f, cols_.start[k], line.number);
      if (complete(cols_.end)) {
        for (int k = 0; k < 3; ++k) c.end[k] = number(f, cols_.end[k], line.number);
      } else {
        const double length = number(f, cols_.length, line.number);
        if (length < 0) fail(line.number, cols_.length, "expected a length >= 0");
        geom::Vec3 axis;
        for (int k = 0; k < 3; ++k) axis[k] = number(f, cols_.axis[k], line.number);
        const double norm = axis.norm();
        if (!(norm > 0))
          throw InputError(atLine(source_, line.number, "the axis direction is zero, expected a non-zero vector"));
        c.end = c.start + axis * (length / norm);
      }
      if (cols_.branchOrder >= 0) {
        const double o = integer(f, cols_.branchOrder, line.number);
        if (o > 1e9) fail(line.number, cols_.branchOrder, "expected a branch order (at most 10^9)");
        c.branchOrder = o >= 0 ? static_cast<std::int32_t>(o) : -1;
      }
      if (cols_.id >= 0) row.id = integer(f, cols_.id, line.number);
      if (cols_.parent >= 0) {
        row.parent = integer(f, cols_.parent, line.number);
        row.hasParent = true;
      }
      table.model.cylinders.push_back(c);
      rows.push_back(row);
    }
    resolveParents(table.model, rows);
    if (table.format == CylinderTableFormat::Treesketch && cols_.startRadius < 0) {
      // Written before start_radius existed: a row starts at its parent node, whose radius is
      // its parent row's (a row whose parent is the root keeps its own: the root's is not saved).
      for (auto& c : table.model.cylinders)
        if (c.parent >= 0) c.startRadius = table.model.cylinders[c.parent].endRadius;
    }
    return table;
  }

 private:
  [[noreturn]] void fail(std::size_t line, int col, const std::string& what) const {
    throw InputError(
        atLine(source_, line, "column '" + cols_.names[col] + "' (field " + std::to_string(col + 1) + "): " + what));
  }

  double number(const std::vector<std::string_view>& f, int col, std::size_t line) const {
    double v;
    const std::string_view s = f[col];
    if (!detail::parseDouble(s.data(), s.data() + s.size(), v))
      fail(line, col, "expected a number, got " + detail::quoted(s));
    if (!std::isfinite(v)) fail(line, col, "expected a finite number, got " + detail::quoted(s));
    return v;
  }

  double integer(const std::vector<std::string_view>& f, int col, std::size_t line) const {
    const double v = number(f, col, line);
    if (v != std::round(v) || std::abs(v) > 9.0e15)
      fail(line, col, "expected an integer, got " + detail::quoted(f[col]));
    return v;
  }

  void checkColumns(std::size_t line) const {
    auto missing = [&](const std::string& what) {
      throw InputError(atLine(source_, line,
                              "no " + what +
                                  " column in the header; expected a cylinder table naming radius, start_x/y/z, and "
                                  "end_x/y/z or axis_x/y/z with length (treesketch, TreeQSM or SimpleForest)"));
    };
    if (cols_.radius < 0) missing("'radius'");
    for (int k = 0; k < 3; ++k)
      if (cols_.start[k] < 0) missing(std::string("'start_") + "xyz"[k] + "'");
    if (!complete(cols_.end)) {
      if (!complete(cols_.axis)) missing("end point (end_x/y/z) or axis (axis_x/y/z)");
      if (cols_.length < 0) missing("'length' (needed with an axis)");
    }
  }

  CylinderTableFormat formatOf(const std::vector<std::string_view>& fields) const {
    static const char* kTreesketch[] = {"id",   "parent", "startx", "starty", "startz",     "endx",
                                        "endy", "endz",   "radius", "length", "branchorder"};
    std::vector<std::string> names;
    for (auto f : fields) names.push_back(normalizedName(f));
    bool treesketch = names.size() >= 11;
    for (int i = 0; treesketch && i < 11; ++i) treesketch = names[i] == kTreesketch[i];
    if (treesketch) return CylinderTableFormat::Treesketch;
    auto has = [&](const char* n) { return std::find(names.begin(), names.end(), n) != names.end(); };
    if (has("parentid") && has("growthlength")) return CylinderTableFormat::SimpleForest;
    if (complete(cols_.axis) && !complete(cols_.end)) return CylinderTableFormat::TreeQsm;
    return CylinderTableFormat::Generic;
  }

  void resolveParents(geom::CylinderModel& model, const std::vector<Row>& rows) const {
    if (cols_.parent < 0) return;
    const std::size_t n = rows.size();
    std::unordered_map<std::int64_t, std::int64_t> byId;
    if (cols_.id >= 0) {
      byId.reserve(n);
      for (std::size_t i = 0; i < n; ++i)
        if (!byId.emplace(static_cast<std::int64_t>(rows[i].id), static_cast<std::int64_t>(i)).second)
          fail(rows[i].line, cols_.id,
               "id " + std::to_string(static_cast<std::int64_t>(rows[i].id)) +
                   " was used by an earlier row, expected unique ids");
    }
    for (std::size_t i = 0; i < n; ++i) {
      const auto p = static_cast<std::int64_t>(rows[i].parent);
      std::int64_t index = -1;
      if (cols_.id >= 0) {
        if (p < 0) continue;  // a root: -1 (SimpleForest, treesketch)
        auto it = byId.find(p);
        if (it == byId.end()) fail(rows[i].line, cols_.parent, "parent " + std::to_string(p) + " is no row's id");
        index = it->second;
      } else {
        if (p <= 0) continue;  // TreeQSM: 0 = no parent
        if (p > static_cast<std::int64_t>(n))
          fail(rows[i].line, cols_.parent,
               "parent " + std::to_string(p) + " is past the last row (" + std::to_string(n) +
                   "), expected a 1-based row number or 0");
        index = p - 1;
      }
      if (index == static_cast<std::int64_t>(i)) fail(rows[i].line, cols_.parent, "a row cannot be its own parent");
      model.cylinders[i].parent = index;
    }
  }

  std::string source_;
  char delimiter_ = 0;
  Columns cols_;
};

}  // namespace

const char* toString(CylinderTableFormat format) {
  switch (format) {
    case CylinderTableFormat::Treesketch:
      return "treesketch";
    case CylinderTableFormat::SimpleForest:
      return "SimpleForest";
    case CylinderTableFormat::TreeQsm:
      return "TreeQSM";
    case CylinderTableFormat::TreeQsmNoHeader:
      return "TreeQSM (no header)";
    case CylinderTableFormat::Generic:
      break;
  }
  return "cylinder table";
}

CylinderTable parseCylinderTable(std::string_view text, const std::string& source) {
  CylinderTable table = TableReader(source).read(text);
  // Parent links that form a cycle or point past the table are the file's fault: say so here,
  // naming it (exit 3), not later as a bad option.
  try {
    geom::branchStructure(table.model, geom::UpAxis::Z);
  } catch (const OptionsError& e) {
    throw InputError(source + ": " + e.what());
  }
  return table;
}

CylinderTable readCylinderTable(std::istream& in, const std::string& source) {
  return parseCylinderTable(detail::readAll(in, source), source);
}

CylinderTable readCylinderTable(const std::filesystem::path& path) {
  return parseCylinderTable(detail::readFile(path), path.string());
}

}  // namespace treesketch::io

namespace treesketch::io {

namespace {

void checkIds(const geom::CylinderModel& model, const std::vector<std::int64_t>& ids,
              const std::vector<char>& measured) {
  if (!ids.empty() && ids.size() != model.size())
    throw OptionsError("cylinder table: " + std::to_string(ids.size()) + " ids for " + std::to_string(model.size()) +
                       " pieces");
  if (!measured.empty() && measured.size() != model.size())
    throw OptionsError("cylinder table: " + std::to_string(measured.size()) + " measured flags for " +
                       std::to_string(model.size()) + " pieces");
  for (const geom::ModelCylinder& c : model.cylinders)
    if (c.parent >= static_cast<std::int64_t>(model.size()))
      throw OptionsError("cylinder table: parent index " + std::to_string(c.parent) + " out of range (" +
                         std::to_string(model.size()) + " pieces)");
}

}  // namespace

namespace {

/// A coordinate with nine significant digits, and more where the number is large, so that it
/// keeps a micrometre-scale absolute precision: a LAS file's coordinates 1e6 m from its origin
/// (projected coordinates) written with nine digits alone would be rounded to the centimetre.
std::string coordinate(double v) {
  const double magnitude = std::abs(v);
  const int integerDigits = magnitude >= 1 ? static_cast<int>(std::floor(std::log10(magnitude))) + 1 : 0;
  const int digits = std::clamp(integerDigits + 6, 9, 17);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace

void writeCylinderCsv(std::ostream& out, const geom::CylinderModel& model, const std::vector<std::int64_t>& ids,
                      const std::vector<char>& measured) {
  checkIds(model, ids, measured);
  const auto id = [&](std::int64_t i) { return ids.empty() ? i : ids[static_cast<std::size_t>(i)]; };
  std::string buf = std::string(kCylinderCsvHeader);
  if (!measured.empty()) buf += std::string(",") + kCylinderCsvMeasuredColumn;
  buf += "\n";
  char line[512];
  for (std::size_t i = 0; i < model.size(); ++i) {
    const geom::ModelCylinder& c = model.cylinders[i];
    const char* source = measured.empty() ? "" : (measured[i] ? ",1" : ",0");
    std::snprintf(line, sizeof line, "%lld,%lld,%s,%s,%s,%s,%s,%s,%.9g,%.9g,%d,%.9g%s\n",
                  static_cast<long long>(id(static_cast<std::int64_t>(i))),
                  static_cast<long long>(c.parent < 0 ? -1 : id(c.parent)), coordinate(c.start.x()).c_str(),
                  coordinate(c.start.y()).c_str(), coordinate(c.start.z()).c_str(), coordinate(c.end.x()).c_str(),
                  coordinate(c.end.y()).c_str(), coordinate(c.end.z()).c_str(), c.endRadius, c.length(),
                  c.branchOrder, c.startRadius, source);
    buf += line;
  }
  out << buf;
  if (!out) throw OutputError("cylinder table: write failed");
}

void writeCylinderCsv(const std::filesystem::path& path, const geom::CylinderModel& model,
                      const std::vector<std::int64_t>& ids, const std::vector<char>& measured) {
  checkIds(model, ids, measured);  // bad input fails before the file
  writeFileAtomically(
      path, [&](std::ostream& out) { writeCylinderCsv(out, model, ids, measured); }, false);
}

void writeTreeQsmCylinders(std::ostream& out, const geom::CylinderModel& model, geom::UpAxis up) {
  const geom::BranchStructure b = geom::branchStructure(model, up);
  std::string buf = std::string(kTreeQsmCylinderHeader) + "\n";
  char line[512];
  for (std::size_t i = 0; i < model.size(); ++i) {
    const geom::ModelCylinder& c = model.cylinders[i];
    const double r0 = c.startRadius, r1 = c.endRadius;
    const double r = std::sqrt((r0 * r0 + r0 * r1 + r1 * r1) / 3.0);
    const double len = c.length();
    const geom::Vec3 axis = len > 0 ? geom::Vec3((c.end - c.start) / len) : geom::upVector(up);
    std::snprintf(line, sizeof line,
                  "%.9g\t%.9g\t%s\t%s\t%s\t%.9g\t%.9g\t%.9g\t%lld\t%lld\t%lld\t%d\t%lld\t0\t0\t0\t%.9g\n", r, len,
                  coordinate(c.start.x()).c_str(), coordinate(c.start.y()).c_str(), coordinate(c.start.z()).c_str(),
                  axis.x(), axis.y(), axis.z(),
                  static_cast<long long>(c.parent + 1), static_cast<long long>(b.extension[i] + 1),
                  static_cast<long long>(b.branch[i] + 1), b.order[i], static_cast<long long>(b.position[i] + 1), r);
    buf += line;
  }
  out << buf;
  if (!out) throw OutputError("TreeQSM cylinder table: write failed");
}

void writeTreeQsmCylinders(const std::filesystem::path& path, const geom::CylinderModel& model, geom::UpAxis up) {
  const geom::BranchStructure check = geom::branchStructure(model, up);  // bad links fail before the file
  (void)check;
  writeFileAtomically(
      path, [&](std::ostream& out) { writeTreeQsmCylinders(out, model, up); }, false);
}

}  // namespace treesketch::io
