// PLY reader and writer. Format reference: Greg Turk, "The PLY Polygon File Format" (1994), and
// the type aliases (int8 ... float64) written by later tools such as VTK and Open3D.
#include "treesketch/io/ply.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "io/io_util.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

namespace {

using detail::quoted;

std::size_t typeSize(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

bool isIntegerType(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

bool parseType(std::string_view s, PlyType& t) {
  struct Name {
    const char* a;
    const char* b;
    PlyType t;
  };
  static const Name kNames[] = {{"char", "int8", PlyType::Int8},        {"uchar", "uint8", PlyType::UInt8},
                                {"short", "int16", PlyType::Int16},     {"ushort", "uint16", PlyType::UInt16},
                                {"int", "int32", PlyType::Int32},       {"uint", "uint32", PlyType::UInt32},
                                {"float", "float32", PlyType::Float32}, {"double", "float64", PlyType::Float64}};
  for (const auto& n : kNames) {
    if (s == n.a || s == n.b) {
      t = n.t;
      return true;
    }
  }
  return false;
}

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i == line.size()) break;
    std::size_t s = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    words.push_back(line.substr(s, i - s));
  }
  return words;
}

/// Reads values of a PLY body, ascii or binary, and reports errors at the current line (ascii)
/// or byte offset (binary), naming the element and record being read.
class Cursor {
 public:
  Cursor(std::string_view data, const PlyHeader& header, const std::string& source)
      : data_(data),
        pos_(header.dataOffset),
        ascii_(header.format == PlyFormat::Ascii),
        big_(header.format == PlyFormat::BinaryBigEndian),
        line_(header.headerLines + 1),
        source_(source) {}

  bool ascii() const { return ascii_; }
  std::size_t bytesLeft() const { return data_.size() - pos_; }

  void beginElement(const PlyElement& e) { element_ = &e; }
  void beginRecord(std::uint64_t index) {
    if (ascii_) skipSpace();
    record_ = index;
    recordPos_ = pos_;
    recordLine_ = line_;
  }

  /// One scalar value of type `t`, as a double (exact for every PLY integer type).
  double scalar(PlyType t) {
    if (ascii_) {
      std::string_view tok = token();
      double v;
      if (!detail::parseDouble(tok.data(), tok.data() + tok.size(), v))
        failHere("expected a number (" + std::string(toString(t)) + "), got " + quoted(tok));
      return v;
    }
    std::size_t sz = typeSize(t);
    if (bytesLeft() < sz) failHere("unexpected end of file (truncated data), expected " + std::string(toString(t)));
    const char* q = data_.data() + pos_;
    pos_ += sz;
    switch (t) {
      case PlyType::Int8:
        return static_cast<std::int8_t>(*q);
      case PlyType::UInt8:
        return static_cast<std::uint8_t>(*q);
      case PlyType::Int16:
        return detail::load<std::int16_t>(q, big_);
      case PlyType::UInt16:
        return detail::load<std::uint16_t>(q, big_);
      case PlyType::Int32:
        return detail::load<std::int32_t>(q, big_);
      case PlyType::UInt32:
        return detail::load<std::uint32_t>(q, big_);
      case PlyType::Float32:
        return detail::load<float>(q, big_);
      case PlyType::Float64:
        return detail::load<double>(q, big_);
    }
    return 0;
  }

  /// A list length: a non-negative integer.
  std::uint64_t listCount(PlyType t) {
    double v = scalar(t);
    if (!(v >= 0) || v != std::floor(v) || v > 4294967295.0)
      failHere("expected a list length (a non-negative integer), got " + std::to_string(v));
    return static_cast<std::uint64_t>(v);
  }

  void skipValues(PlyType t, std::uint64_t n) {
    if (ascii_) {
      for (std::uint64_t i = 0; i < n; ++i) scalar(t);
      return;
    }
    std::size_t sz = typeSize(t);
    if (n > bytesLeft() / sz) failHere("unexpected end of file (truncated list of " + std::to_string(n) + " values)");
    pos_ += static_cast<std::size_t>(n) * sz;
  }

  void skipProperty(const PlyProperty& p) {
    if (p.isList)
      skipValues(p.type, listCount(p.countType));
    else
      skipValues(p.type, 1);
  }

  /// Binary only: skips `n` records of `recordSize` bytes.
  void skipBytes(std::uint64_t n, std::size_t recordSize) { pos_ += static_cast<std::size_t>(n) * recordSize; }

  /// Binary, fixed-size records: throws unless `count` records of `recordSize` bytes follow.
  void requireRecords(std::uint64_t count, std::size_t recordSize) {
    if (recordSize > 0 && count > bytesLeft() / recordSize) {
      throw InputError(atOffset(source_, pos_,
                                "truncated: the header promises " + std::to_string(count) + " '" + element_->name +
                                    "' records of " + std::to_string(recordSize) + " bytes, but only " +
                                    std::to_string(bytesLeft()) + " bytes follow"));
    }
  }

  [[noreturn]] void failHere(const std::string& what) const { fail(ascii_ ? line_ : 0, pos_, what); }
  [[noreturn]] void failAtRecord(const std::string& what) const { fail(recordLine_, recordPos_, what); }

 private:
  void skipSpace() {
    const char* p = data_.data() + pos_;
    const char* e = data_.data() + data_.size();
    while (p < e && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')) {
      if (*p == '\n') ++line_;
      ++p;
    }
    pos_ = static_cast<std::size_t>(p - data_.data());
  }

  std::string_view token() {
    skipSpace();
    const char* p = data_.data() + pos_;
    const char* e = data_.data() + data_.size();
    if (p == e) failHere("unexpected end of file (truncated data), expected another value");
    const char* s = p;
    while (p < e && !(*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')) ++p;
    pos_ = static_cast<std::size_t>(p - data_.data());
    return std::string_view(s, static_cast<std::size_t>(p - s));
  }

  [[noreturn]] void fail(std::size_t line, std::size_t pos, const std::string& what) const {
    std::string ctx = element_ ? "in '" + element_->name + "' record " + std::to_string(record_) + " of " +
                                     std::to_string(element_->count) + ": "
                               : std::string();
    if (ascii_) throw InputError(atLine(source_, line, ctx + what));
    throw InputError(atOffset(source_, pos, ctx + what));
  }

  std::string_view data_;
  std::size_t pos_;
  bool ascii_;
  bool big_;
  std::size_t line_;
  const std::string& source_;
  const PlyElement* element_ = nullptr;
  std::uint64_t record_ = 0;
  std::size_t recordPos_ = 0;
  std::size_t recordLine_ = 0;
};

/// Bytes of a record with no lists (binary); 0 when the element has a list property.
std::size_t fixedRecordSize(const PlyElement& e) {
  std::size_t s = 0;
  for (const auto& p : e.properties) {
    if (p.isList) return 0;
    s += typeSize(p.type);
  }
  return s;
}

/// The fewest bytes a record can take: caps reservations by what the file can hold.
std::size_t minRecordBytes(const PlyElement& e, bool ascii) {
  std::size_t s = 0;
  for (const auto& p : e.properties) s += ascii ? 2 : typeSize(p.isList ? p.countType : p.type);
  return std::max<std::size_t>(s, 1);
}

std::size_t cappedReserve(std::uint64_t count, const Cursor& c, const PlyElement& e) {
  std::uint64_t cap = c.bytesLeft() / minRecordBytes(e, c.ascii()) + 1;
  return static_cast<std::size_t>(std::min(count, cap));
}

void skipElement(Cursor& c, const PlyElement& e) {
  c.beginElement(e);
  if (e.properties.empty()) return;  // records of nothing: there is nothing to skip, whatever the count
  std::size_t rs = c.ascii() ? 0 : fixedRecordSize(e);
  if (rs > 0) {
    c.requireRecords(e.count, rs);
    c.skipBytes(e.count, rs);
    return;
  }
  for (std::uint64_t i = 0; i < e.count; ++i) {
    c.beginRecord(i);
    for (const auto& p : e.properties) c.skipProperty(p);
  }
}

struct VertexData {
  std::vector<geom::Vec3> positions;
  std::vector<std::int32_t> station, meshId;
  std::vector<geom::Vec3> scanner;
  std::vector<std::array<std::uint8_t, 3>> colors;
  std::vector<double> quality;
};

enum Role {
  kNone,
  kX,
  kY,
  kZ,
  kStation,
  kMesh,
  kScannerX,
  kScannerY,
  kScannerZ,
  kRed,
  kGreen,
  kBlue,
  kQuality,
  kRoles
};

std::int32_t toInt32(Cursor& c, double v, const char* name) {
  if (!std::isfinite(v) || v < -2147483648.0 || v > 2147483647.0 || v != std::floor(v))
    c.failAtRecord(std::string("property '") + name + "' must be a 32-bit integer, got " + std::to_string(v));
  return static_cast<std::int32_t>(v);
}

std::uint8_t toColor(double v, PlyType t) {
  if (!isIntegerType(t)) v *= 255.0;
  if (!(v > 0)) return 0;
  if (v > 255) return 255;
  return static_cast<std::uint8_t>(std::lround(v));
}

VertexData readVertices(Cursor& c, const PlyElement& e, bool cloudAttributes, bool meshAttributes) {
  c.beginElement(e);
  std::vector<Role> roles(e.properties.size(), kNone);
  bool has[kRoles] = {};
  for (std::size_t i = 0; i < e.properties.size(); ++i) {
    const PlyProperty& p = e.properties[i];
    if (p.isList) continue;
    Role r = kNone;
    if (p.name == "x")
      r = kX;
    else if (p.name == "y")
      r = kY;
    else if (p.name == "z")
      r = kZ;
    else if (cloudAttributes && p.name == "station")
      r = kStation;
    else if (cloudAttributes && p.name == "mesh")
      r = kMesh;
    else if (cloudAttributes && p.name == "scanner_x")
      r = kScannerX;
    else if (cloudAttributes && p.name == "scanner_y")
      r = kScannerY;
    else if (cloudAttributes && p.name == "scanner_z")
      r = kScannerZ;
    else if (meshAttributes && (p.name == "red" || p.name == "r"))
      r = kRed;
    else if (meshAttributes && (p.name == "green" || p.name == "g"))
      r = kGreen;
    else if (meshAttributes && (p.name == "blue" || p.name == "b"))
      r = kBlue;
    else if (meshAttributes && p.name == "quality")
      r = kQuality;
    if (r != kNone && has[r]) r = kNone;  // a repeated name: the first one counts
    roles[i] = r;
    has[r] = true;
  }
  VertexData out;
  std::size_t reserve = cappedReserve(e.count, c, e);
  out.positions.reserve(reserve);
  bool wantColors = has[kRed] && has[kGreen] && has[kBlue];
  // The scanner position is kept only when all three coordinates are there.
  bool wantScanner = has[kScannerX] && has[kScannerY] && has[kScannerZ];
  if (has[kStation]) out.station.reserve(reserve);
  if (has[kMesh]) out.meshId.reserve(reserve);
  if (wantColors) out.colors.reserve(reserve);
  if (wantScanner) out.scanner.reserve(reserve);
  if (has[kQuality]) out.quality.reserve(reserve);
  std::size_t rs = c.ascii() ? 0 : fixedRecordSize(e);
  if (rs > 0) c.requireRecords(e.count, rs);
  for (std::uint64_t i = 0; i < e.count; ++i) {
    c.beginRecord(i);
    geom::Vec3 pt, sc;
    std::array<std::uint8_t, 3> rgb{};
    for (std::size_t k = 0; k < roles.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      if (p.isList) {
        c.skipProperty(p);
        continue;
      }
      double v = c.scalar(p.type);
      switch (roles[k]) {
        case kX:
          pt.x() = v;
          break;
        case kY:
          pt.y() = v;
          break;
        case kZ:
          pt.z() = v;
          break;
        case kStation:
          out.station.push_back(toInt32(c, v, "station"));
          break;
        case kMesh:
          out.meshId.push_back(toInt32(c, v, "mesh"));
          break;
        case kScannerX:
          sc.x() = v;
          break;
        case kScannerY:
          sc.y() = v;
          break;
        case kScannerZ:
          sc.z() = v;
          break;
        case kRed:
          rgb[0] = toColor(v, p.type);
          break;
        case kGreen:
          rgb[1] = toColor(v, p.type);
          break;
        case kBlue:
          rgb[2] = toColor(v, p.type);
          break;
        case kQuality:
          out.quality.push_back(v);
          break;
        case kNone:
        case kRoles:
          break;
      }
    }
    if (!pt.allFinite()) c.failAtRecord("non-finite vertex coordinate (NaN or Inf), expected finite x, y, z");
    out.positions.push_back(pt);
    if (wantColors) out.colors.push_back(rgb);
    if (wantScanner) {
      if (!sc.allFinite()) c.failAtRecord("non-finite scanner position (NaN or Inf), expected finite scanner_x, y, z");
      out.scanner.push_back(sc);
    }
  }
  return out;
}

void requireXyz(const PlyElement& e, const std::string& source) {
  for (const char* n : {"x", "y", "z"}) {
    int k = e.find(n);
    if (k < 0 || e.properties[static_cast<std::size_t>(k)].isList)
      throw InputError(source + ": the 'vertex' element has no scalar property '" + n + "', expected x, y and z");
  }
}

const PlyElement& vertexElement(const PlyHeader& h, const std::string& source) {
  const PlyElement* v = h.find("vertex");
  if (!v) throw InputError(source + ": PLY header has no 'vertex' element, expected one with x, y, z");
  requireXyz(*v, source);
  return *v;
}

/// Reads the face element, fan-triangulating the list property at `listIndex`.
void readFaces(Cursor& c, const PlyElement& e, int listIndex, std::size_t vertexCount,
               std::vector<std::array<std::uint32_t, 3>>& tris) {
  c.beginElement(e);
  tris.reserve(cappedReserve(e.count, c, e));
  for (std::uint64_t i = 0; i < e.count; ++i) {
    c.beginRecord(i);
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      if (static_cast<int>(k) != listIndex) {
        c.skipProperty(p);
        continue;
      }
      std::uint64_t n = c.listCount(p.countType);
      if (n < 3) c.failAtRecord("face with " + std::to_string(n) + " vertices, expected at least 3");
      auto index = [&]() -> std::uint32_t {
        double v = c.scalar(p.type);
        if (!(v >= 0) || v != std::floor(v) || v >= static_cast<double>(vertexCount))
          c.failHere("face index " + std::to_string(v) + " out of range, expected an integer in [0, " +
                     std::to_string(vertexCount) + ")");
        return static_cast<std::uint32_t>(v);
      };
      std::uint32_t first = index();
      std::uint32_t prev = index();
      for (std::uint64_t j = 2; j < n; ++j) {
        std::uint32_t cur = index();
        tris.push_back({first, prev, cur});
        prev = cur;
      }
    }
  }
}

}  // namespace

int PlyElement::find(std::string_view n) const {
  for (std::size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == n) return static_cast<int>(i);
  return -1;
}

const PlyElement* PlyHeader::find(std::string_view n) const {
  for (const auto& e : elements)
    if (e.name == n) return &e;
  return nullptr;
}

const char* toString(PlyFormat f) {
  switch (f) {
    case PlyFormat::Ascii:
      return "ascii";
    case PlyFormat::BinaryLittleEndian:
      return "binary_little_endian";
    case PlyFormat::BinaryBigEndian:
      return "binary_big_endian";
  }
  return "?";
}

const char* toString(PlyType t) {
  switch (t) {
    case PlyType::Int8:
      return "char";
    case PlyType::UInt8:
      return "uchar";
    case PlyType::Int16:
      return "short";
    case PlyType::UInt16:
      return "ushort";
    case PlyType::Int32:
      return "int";
    case PlyType::UInt32:
      return "uint";
    case PlyType::Float32:
      return "float";
    case PlyType::Float64:
      return "double";
  }
  return "?";
}

PlyHeader parsePlyHeader(std::string_view data, const std::string& source) {
  if (data.empty()) throw InputError(source + ": file is empty, expected a PLY header starting with 'ply'");
  PlyHeader h;
  std::size_t pos = 0, lineNo = 0;
  bool haveFormat = false;
  auto fail = [&](const std::string& what) { throw InputError(atLine(source, lineNo, what)); };
  while (true) {
    if (pos >= data.size())
      throw InputError(atLine(source, lineNo, "header not terminated: expected an 'end_header' line"));
    std::size_t nl = data.find('\n', pos);
    std::size_t end = nl == std::string_view::npos ? data.size() : nl;
    std::string_view line = data.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = nl == std::string_view::npos ? data.size() : nl + 1;
    ++lineNo;
    auto w = splitWords(line);
    if (lineNo == 1) {
      if (w.size() != 1 || w[0] != "ply") fail("not a PLY file: expected 'ply' on the first line, got " + quoted(line));
      continue;
    }
    if (w.empty()) continue;
    std::string_view key = w[0];
    if (key == "comment" || key == "obj_info") {
      std::string_view rest = line.substr(std::min(line.size(), key.size() + 1));
      h.comments.emplace_back(rest);
    } else if (key == "format") {
      if (w.size() != 3) fail("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      if (w[1] == "ascii")
        h.format = PlyFormat::Ascii;
      else if (w[1] == "binary_little_endian")
        h.format = PlyFormat::BinaryLittleEndian;
      else if (w[1] == "binary_big_endian")
        h.format = PlyFormat::BinaryBigEndian;
      else
        fail("unsupported PLY format " + quoted(w[1]) + ", expected ascii, binary_little_endian or binary_big_endian");
      if (w[2].substr(0, 2) != "1." && w[2] != "1") fail("unsupported PLY version " + quoted(w[2]) + ", expected 1.0");
      haveFormat = true;
    } else if (key == "element") {
      if (w.size() != 3) fail("expected 'element <name> <count>'");
      PlyElement e;
      e.name = std::string(w[1]);
      auto r = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (r.ec != std::errc() || r.ptr != w[2].data() + w[2].size())
        fail("element count " + quoted(w[2]) + " is not a non-negative integer");
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) fail("'property' before any 'element' line");
      PlyProperty p;
      if (w.size() >= 2 && w[1] == "list") {
        if (w.size() != 5) fail("expected 'property list <count type> <item type> <name>'");
        if (!parseType(w[2], p.countType) || !isIntegerType(p.countType))
          fail("list count type " + quoted(w[2]) + " is not an integer PLY type");
        if (!parseType(w[3], p.type))
          fail("unknown PLY type " + quoted(w[3]) +
               ", expected char, uchar, short, ushort, int, uint, float, double (or int8 ... float64)");
        p.isList = true;
        p.name = std::string(w[4]);
      } else {
        if (w.size() != 3) fail("expected 'property <type> <name>'");
        if (!parseType(w[1], p.type))
          fail("unknown PLY type " + quoted(w[1]) +
               ", expected char, uchar, short, ushort, int, uint, float, double (or int8 ... float64)");
        p.name = std::string(w[2]);
      }
      h.elements.back().properties.push_back(std::move(p));
    } else if (key == "end_header") {
      if (!haveFormat) fail("'end_header' before any 'format' line");
      break;
    } else {
      fail("unknown PLY header keyword " + quoted(key) + ", expected format, comment, element, property or end_header");
    }
  }
  h.dataOffset = pos;
  h.headerLines = lineNo;
  return h;
}

PlyHeader readPlyHeader(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path.string() + ": file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  std::string head(1 << 16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return parsePlyHeader(head, path.string());
}

namespace {

geom::PointCloud parsePlyCloud(std::string_view data, const std::string& source, const CloudReadOptions& options) {
  PlyHeader h = parsePlyHeader(data, source);
  const PlyElement& ve = vertexElement(h, source);
  Cursor c(data, h, source);
  geom::PointCloud cloud;
  for (const auto& e : h.elements) {
    if (&e == &ve) {
      VertexData v = readVertices(c, e, true, false);
      cloud.positions = std::move(v.positions);
      cloud.station = std::move(v.station);
      cloud.meshId = std::move(v.meshId);
      cloud.scanner = std::move(v.scanner);
      break;  // nothing after the vertices is needed
    }
    skipElement(c, e);
  }
  checkCloudSize(cloud, source, options.minPoints);
  return cloud;
}

geom::TriMesh parsePlyMesh(std::string_view data, const std::string& source) {
  PlyHeader h = parsePlyHeader(data, source);
  const PlyElement& ve = vertexElement(h, source);
  const PlyElement* fe = h.find("face");
  if (!fe) throw InputError(source + ": PLY has no 'face' element: a point cloud, not a mesh");
  int li = fe->find("vertex_indices");
  if (li < 0) li = fe->find("vertex_index");
  if (li < 0 || !fe->properties[static_cast<std::size_t>(li)].isList)
    throw InputError(source + ": the 'face' element has no list property 'vertex_indices' (or 'vertex_index')");
  if (ve.count > std::numeric_limits<std::uint32_t>::max())
    throw InputError(source + ": " + std::to_string(ve.count) + " vertices, at most 2^32-1 are supported");
  Cursor c(data, h, source);
  geom::TriMesh mesh;
  bool haveVertices = false, haveFaces = false;
  for (const auto& e : h.elements) {
    if (&e == &ve) {
      VertexData v = readVertices(c, e, false, true);
      mesh.vertices = std::move(v.positions);
      mesh.colors = std::move(v.colors);
      mesh.quality = std::move(v.quality);
      haveVertices = true;
    } else if (&e == fe) {
      readFaces(c, e, li, static_cast<std::size_t>(ve.count), mesh.triangles);
      haveFaces = true;
    } else {
      skipElement(c, e);
    }
    if (haveVertices && haveFaces) break;  // later elements (edges, materials) are not needed
  }
  if (mesh.triangles.empty()) throw InputError(source + ": PLY mesh has no faces, expected at least one triangle");
  return mesh;
}

}  // namespace

geom::PointCloud readPlyPointCloud(std::istream& in, const std::string& source, const CloudReadOptions& options) {
  return parsePlyCloud(detail::readAll(in, source), source, options);
}
geom::PointCloud readPlyPointCloud(const std::filesystem::path& path, const CloudReadOptions& options) {
  return parsePlyCloud(detail::readFile(path), path.string(), options);
}
geom::TriMesh readPlyMesh(std::istream& in, const std::string& source) {
  return parsePlyMesh(detail::readAll(in, source), source);
}
geom::TriMesh readPlyMesh(const std::filesystem::path& path) {
  return parsePlyMesh(detail::readFile(path), path.string());
}

namespace {

void flushIfFull(std::ostream& out, std::string& buf) {
  if (buf.size() >= (1u << 20)) {
    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    buf.clear();
  }
}

}  // namespace

void writePlyPointCloud(std::ostream& out, const geom::PointCloud& cloud) {
  cloud.checkConsistent();
  bool st = !cloud.station.empty(), me = !cloud.meshId.empty(), sc = !cloud.scanner.empty();
  std::string buf = "ply\nformat binary_little_endian 1.0\ncomment written by treesketch\nelement vertex " +
                    std::to_string(cloud.size()) + "\nproperty double x\nproperty double y\nproperty double z\n";
  if (st) buf += "property int station\n";
  if (me) buf += "property int mesh\n";
  if (sc) buf += "property double scanner_x\nproperty double scanner_y\nproperty double scanner_z\n";
  buf += "end_header\n";
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const geom::Vec3& p = cloud.positions[i];
    if (!p.allFinite()) throw OutputError("ply writer: point " + std::to_string(i) + " has a non-finite coordinate");
    detail::storeLE(buf, p.x());
    detail::storeLE(buf, p.y());
    detail::storeLE(buf, p.z());
    if (st) detail::storeLE(buf, cloud.station[i]);
    if (me) detail::storeLE(buf, cloud.meshId[i]);
    if (sc) {
      const geom::Vec3& o = cloud.scanner[i];
      if (!o.allFinite())
        throw OutputError("ply writer: point " + std::to_string(i) + " has a non-finite scanner position");
      detail::storeLE(buf, o.x());
      detail::storeLE(buf, o.y());
      detail::storeLE(buf, o.z());
    }
    flushIfFull(out, buf);
  }
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
}

void writePlyPointCloud(const std::filesystem::path& path, const geom::PointCloud& cloud) {
  writeFileAtomically(path, [&](std::ostream& out) { writePlyPointCloud(out, cloud); });
}

void writePlyMesh(std::ostream& out, const geom::TriMesh& mesh) {
  mesh.checkConsistent();
  bool col = !mesh.colors.empty(), qual = !mesh.quality.empty();
  std::string buf = "ply\nformat binary_little_endian 1.0\ncomment written by treesketch\nelement vertex " +
                    std::to_string(mesh.vertices.size()) +
                    "\nproperty double x\nproperty double y\nproperty double z\n";
  if (col) buf += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (qual) buf += "property float quality\n";
  buf += "element face " + std::to_string(mesh.triangles.size()) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const geom::Vec3& p = mesh.vertices[i];
    if (!p.allFinite()) throw OutputError("ply writer: vertex " + std::to_string(i) + " has a non-finite coordinate");
    detail::storeLE(buf, p.x());
    detail::storeLE(buf, p.y());
    detail::storeLE(buf, p.z());
    if (col) buf.append(reinterpret_cast<const char*>(mesh.colors[i].data()), 3);
    if (qual) detail::storeLE(buf, static_cast<float>(mesh.quality[i]));
    flushIfFull(out, buf);
  }
  for (const auto& t : mesh.triangles) {
    buf += static_cast<char>(3);
    for (auto idx : t) detail::storeLE(buf, static_cast<std::int32_t>(idx));
    flushIfFull(out, buf);
  }
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
}

void writePlyMesh(const std::filesystem::path& path, const geom::TriMesh& mesh) {
  writeFileAtomically(path, [&](std::ostream& out) { writePlyMesh(out, mesh); });
}

}  // namespace treesketch::io
