// PLY bodies: reading the vertex element (a point cloud, or a mesh's vertices with colour and
// quality) and the face element (fan-triangulated polygons), ascii or binary of either byte
// order, after the header (ply_header.cpp). Writing is in ply_write.cpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "io/io_util.h"
#include "treesketch/io/ply.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

namespace {

using detail::quoted;

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
  std::vector<float> intensity;
  std::vector<std::uint8_t> classification;
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
  kIntensity,
  kClass,
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

/// What a scalar vertex property holds, by its name (kNone: read and ignored). Station, mesh,
/// scanner position, intensity and classification count only with `cloudAttributes`, quality
/// only with `meshAttributes`.
Role roleOf(const PlyProperty& p, bool cloudAttributes, bool meshAttributes) {
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
  else if (p.name == "red" || p.name == "r" || p.name == "diffuse_red")
    r = kRed;  // clouds (CloudCompare, PDAL) and meshes (MeshLab) alike
  else if (p.name == "green" || p.name == "g" || p.name == "diffuse_green")
    r = kGreen;
  else if (p.name == "blue" || p.name == "b" || p.name == "diffuse_blue")
    r = kBlue;
  else if (cloudAttributes && (p.name == "intensity" || p.name == "scalar_intensity" || p.name == "scalar_Intensity"))
    r = kIntensity;
  else if (cloudAttributes &&
           (p.name == "classification" || p.name == "scalar_classification" || p.name == "scalar_Classification"))
    r = kClass;
  else if (meshAttributes && p.name == "quality")
    r = kQuality;
  return r;
}

/// Puts the value `v` of property `p`, which has role `role`, in place: in the point, the scanner
/// position or the colour of the record being read, or appended to its column of `out`.
void storeValue(Cursor& c, Role role, const PlyProperty& p, double v, VertexData& out, geom::Vec3& pt, geom::Vec3& sc,
                std::array<std::uint8_t, 3>& rgb) {
  switch (role) {
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
    case kIntensity:
      if (!(std::abs(v) <= std::numeric_limits<float>::max()))
        c.failAtRecord("intensity " + std::to_string(v) + " is not a finite single-precision number");
      out.intensity.push_back(static_cast<float>(v));
      break;
    case kClass:
      if (!(v >= 0 && v <= 255 && v == std::floor(v)))
        c.failAtRecord("classification must be an integer 0 to 255, got " + std::to_string(v));
      out.classification.push_back(static_cast<std::uint8_t>(v));
      break;
    case kNone:
    case kRoles:
      break;
  }
}

VertexData readVertices(Cursor& c, const PlyElement& e, bool cloudAttributes, bool meshAttributes) {
  c.beginElement(e);
  std::vector<Role> roles(e.properties.size(), kNone);
  bool has[kRoles] = {};
  for (std::size_t i = 0; i < e.properties.size(); ++i) {
    const PlyProperty& p = e.properties[i];
    if (p.isList) continue;
    Role r = roleOf(p, cloudAttributes, meshAttributes);
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
  if (has[kIntensity]) out.intensity.reserve(reserve);
  if (has[kClass]) out.classification.reserve(reserve);
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
      storeValue(c, roles[k], p, v, out, pt, sc, rgb);
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
      cloud.intensity = std::move(v.intensity);
      cloud.classification = std::move(v.classification);
      cloud.color = std::move(v.colors);
      break;  // nothing after the vertices is needed
    }
    skipElement(c, e);
  }
  checkCloudSize(cloud, source, options.minPoints);
  cloud.up = declaredUpAxis(h);
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

}  // namespace treesketch::io
