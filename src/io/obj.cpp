// OBJ reader and writer. Format reference: Wavefront "Object Files (.obj)", Advanced
// Visualizer manual, appendix B1 (polygonal subset: v, f, and the lines that may be ignored).
#include "treesketch/io/obj.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/io_util.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

namespace {

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Next whitespace-separated word of [p, e), advancing p; empty at the end of the line.
inline std::string_view nextWord(const char*& p, const char* e) {
  while (p < e && isSpace(*p)) ++p;
  const char* s = p;
  while (p < e && !isSpace(*p)) ++p;
  return std::string_view(s, static_cast<std::size_t>(p - s));
}

bool isIgnorable(std::string_view k) {
  static const char* kIgnored[] = {"vt",   "vn",     "vp",     "usemtl",     "mtllib",    "g",        "o",
                                   "s",    "l",      "p",      "cstype",     "deg",       "bmat",     "step",
                                   "curv", "curv2",  "surf",   "parm",       "trim",      "hole",     "scrv",
                                   "sp",   "end",    "con",    "mg",         "bevel",     "c_interp", "d_interp",
                                   "lod",  "maplib", "usemap", "shadow_obj", "trace_obj", "ctech",    "stech"};
  for (const char* s : kIgnored)
    if (k == s) return true;
  return false;
}

struct ObjData {
  std::vector<geom::Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

ObjData parseObj(std::string_view data, const std::string& source, ObjStats* statsOut) {
  if (data.empty()) throw InputError(source + ": file is empty, expected OBJ 'v' and 'f' lines");
  ObjData out;
  ObjStats stats;
  auto shown = [](const char* b, const char* e) {
    return detail::quoted(std::string_view(b, static_cast<std::size_t>(e - b)));
  };
  detail::Lines lines(data);
  std::string_view line;
  while (lines.next(line)) {
    const std::size_t lineNo = lines.number();
    const char* ls = line.data();
    const char* le = ls + line.size();
    const char* q = ls;
    std::string_view key = nextWord(q, le);
    if (key.empty() || key[0] == '#') continue;
    if (key == "v") {
      double v[3];
      for (int k = 0; k < 3; ++k) {
        std::string_view w = nextWord(q, le);
        if (!detail::parseDouble(w.data(), w.data() + w.size(), v[k]))
          throw InputError(atLine(source, lineNo, "expected 'v x y z' with 3 numbers, got " + shown(ls, le)));
      }
      if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
        throw InputError(atLine(source, lineNo, "non-finite vertex coordinate (NaN or Inf), expected finite numbers"));
      if (out.vertices.size() >= std::numeric_limits<std::uint32_t>::max())
        throw InputError(atLine(source, lineNo, "more than 2^32-1 vertices are not supported"));
      out.vertices.emplace_back(v[0], v[1], v[2]);
    } else if (key == "f") {
      ++stats.polygons;
      const auto nv = static_cast<long long>(out.vertices.size());
      std::uint32_t first = 0, prev = 0;
      int corners = 0;
      while (true) {
        std::string_view w = nextWord(q, le);
        if (w.empty()) break;
        std::size_t slash = w.find('/');
        std::string_view num = w.substr(0, slash);
        const char* b = num.data();
        const char* e = b + num.size();
        if (b < e && *b == '+') ++b;
        long long idx = 0;
        auto r = std::from_chars(b, e, idx);
        if (b == e || r.ec != std::errc() || r.ptr != e)
          throw InputError(atLine(source, lineNo, "expected a vertex index in face corner " + detail::quoted(w)));
        long long zeroBased = idx > 0 ? idx - 1 : nv + idx;
        if (idx == 0 || zeroBased < 0 || zeroBased >= nv)
          throw InputError(atLine(source, lineNo,
                                  "face index " + std::to_string(idx) + " out of range, expected 1.." +
                                      std::to_string(nv) + " or -1..-" + std::to_string(nv) +
                                      " (vertices defined so far)"));
        auto cur = static_cast<std::uint32_t>(zeroBased);
        if (corners == 0)
          first = cur;
        else if (corners >= 2)
          out.triangles.push_back({first, prev, cur});
        prev = cur;
        ++corners;
      }
      if (corners < 3)
        throw InputError(
            atLine(source, lineNo, "face with " + std::to_string(corners) + " corners, expected at least 3"));
      if (corners > 3) ++stats.nonTriangles;
    } else if (isIgnorable(key)) {
      ++stats.ignoredLines;
    } else {
      throw InputError(atLine(source, lineNo,
                              "unknown OBJ keyword " + detail::quoted(key) +
                                  ", expected v, f, vt, vn, g, o, s, usemtl, mtllib, l or a comment"));
    }
  }
  if (statsOut) *statsOut = stats;
  return out;
}

}  // namespace

geom::TriMesh readObj(std::istream& in, const std::string& source, ObjStats* stats) {
  std::string data = detail::readAll(in, source);
  ObjData d = parseObj(data, source, stats);
  if (d.triangles.empty()) throw InputError(source + ": OBJ has no faces ('f' lines), expected a triangle mesh");
  geom::TriMesh m;
  m.vertices = std::move(d.vertices);
  m.triangles = std::move(d.triangles);
  return m;
}

geom::TriMesh readObj(const std::filesystem::path& path, ObjStats* stats) {
  std::string data = detail::readFile(path);
  ObjData d = parseObj(data, path.string(), stats);
  if (d.triangles.empty()) throw InputError(path.string() + ": OBJ has no faces ('f' lines), expected a triangle mesh");
  geom::TriMesh m;
  m.vertices = std::move(d.vertices);
  m.triangles = std::move(d.triangles);
  return m;
}

geom::PointCloud readObjVertices(std::istream& in, const std::string& source) {
  ObjData d = parseObj(detail::readAll(in, source), source, nullptr);
  geom::PointCloud c;
  c.positions = std::move(d.vertices);
  return c;
}

void writeObj(std::ostream& out, const geom::TriMesh& mesh) {
  mesh.checkConsistent();
  std::string buf = "# written by treesketch\n# " + std::to_string(mesh.vertices.size()) + " vertices, " +
                    std::to_string(mesh.triangles.size()) + " triangles\n";
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const geom::Vec3& v = mesh.vertices[i];
    if (!v.allFinite()) throw OutputError("obj writer: vertex " + std::to_string(i) + " has a non-finite coordinate");
    buf += "v ";
    detail::appendXyz(buf, v.x(), v.y(), v.z());
    buf += '\n';
    detail::flushIfFull(out, buf);
  }
  for (const auto& t : mesh.triangles) {
    buf += 'f';
    for (auto idx : t) {
      buf += ' ';
      detail::appendNumber(buf, static_cast<std::uint64_t>(idx) + 1);
    }
    buf += '\n';
    detail::flushIfFull(out, buf);
  }
  detail::writeAll(out, buf);
}

void writeObj(const std::filesystem::path& path, const geom::TriMesh& mesh) {
  writeFileAtomically(
      path, [&](std::ostream& out) { writeObj(out, mesh); }, true);
}

}  // namespace treesketch::io
