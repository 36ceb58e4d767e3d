// Polyline OBJ reader: `v` and `l` statements of the Wavefront OBJ format (Wavefront Technologies,
// "Object Files (.obj)", Appendix B1 of the Advanced Visualizer manual).
#include "treesketch/render/polyline_obj.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "treesketch/util/error.h"

namespace treesketch::render {

namespace {

bool parseDouble(const std::string& token, double& out) {
  std::istringstream ss(token);
  ss >> out;
  return !ss.fail() && ss.eof();
}

}  // namespace

std::vector<std::vector<geom::Vec3>> readObjPolylines(std::istream& in, const std::string& source) {
  std::vector<geom::Vec3> vertices;
  std::vector<std::vector<geom::Vec3>> lines;
  std::string text;
  std::size_t lineNo = 0;
  while (std::getline(in, text)) {
    ++lineNo;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    std::istringstream ss(text);
    std::string kind;
    if (!(ss >> kind) || kind[0] == '#') continue;
    if (kind == "v") {
      std::string tok[3];
      geom::Vec3 p;
      for (int k = 0; k < 3; ++k) {
        if (!(ss >> tok[k]) || !parseDouble(tok[k], p[k]))
          throw InputError(atLine(source, lineNo, "expected 'v x y z' with three numbers"));
      }
      if (!p.allFinite()) throw InputError(atLine(source, lineNo, "vertex has NaN or Inf"));
      vertices.push_back(p);
    } else if (kind == "l") {
      std::vector<geom::Vec3> pts;
      std::string tok;
      while (ss >> tok) {
        std::string idx = tok.substr(0, tok.find('/'));
        long long i = 0;
        auto [end, ec] = std::from_chars(idx.data(), idx.data() + idx.size(), i);
        if (ec != std::errc() || end != idx.data() + idx.size() || i == 0)
          throw InputError(atLine(source, lineNo, "expected a vertex index (a non-zero integer), got '" + tok + "'"));
        long long n = static_cast<long long>(vertices.size());
        long long zeroBased = i > 0 ? i - 1 : n + i;
        if (zeroBased < 0 || zeroBased >= n)
          throw InputError(
              atLine(source, lineNo,
                     "vertex index " + idx + " out of range (" + std::to_string(n) + " vertices defined so far)"));
        pts.push_back(vertices[static_cast<std::size_t>(zeroBased)]);
      }
      if (pts.size() < 2) throw InputError(atLine(source, lineNo, "expected 'l' with at least two vertex indices"));
      lines.push_back(std::move(pts));
    }
  }
  if (in.bad()) throw InputError(source + ": read error");
  if (lines.empty()) throw InputError(source + ": expected at least one 'l' (polyline) element, found none");
  return lines;
}

std::vector<std::vector<geom::Vec3>> readObjPolylines(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  return readObjPolylines(in, path.string());
}

}  // namespace treesketch::render
