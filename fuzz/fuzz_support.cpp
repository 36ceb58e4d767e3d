#include "fuzz_support.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>

namespace treesketch::fuzz {

void fail(const char* file, int line, const std::string& what) {
  std::fprintf(stderr, "fuzz check failed: %s (%s:%d)\n", what.c_str(), file, line);
  std::fflush(stderr);
  std::abort();
}

namespace {
// The temporary files of this process, removed when it exits normally.
struct TempFiles {
  std::set<std::filesystem::path> paths;
  ~TempFiles() {
    std::error_code ignored;
    for (const auto& p : paths) std::filesystem::remove(p, ignored);
  }
};
TempFiles tempFiles;
}  // namespace

std::filesystem::path writeTempFile(std::string_view extension, std::string_view bytes) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("treesketch_fuzz_" + std::to_string(::getpid()) + std::string(extension));
  tempFiles.paths.insert(path);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  FUZZ_CHECK(out.good(), "cannot write the temporary file " + path.string());
  return path;
}

namespace {
bool finite(const geom::Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
bool sameBits(const geom::Vec3& a, const geom::Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}
}  // namespace

void checkCloud(const geom::PointCloud& cloud, std::size_t minPoints) {
  const std::size_t n = cloud.size();
  FUZZ_CHECK(n >= minPoints, "reader returned " + std::to_string(n) + " points, fewer than the minimum");
  for (const auto& p : cloud.positions) FUZZ_CHECK(finite(p), "reader returned a NaN/Inf position");
  for (const auto& p : cloud.scanner) FUZZ_CHECK(finite(p), "reader returned a NaN/Inf scanner position");
  FUZZ_CHECK(cloud.station.empty() || cloud.station.size() == n, "station array of the wrong size");
  FUZZ_CHECK(cloud.meshId.empty() || cloud.meshId.size() == n, "mesh id array of the wrong size");
  FUZZ_CHECK(cloud.scanner.empty() || cloud.scanner.size() == n, "scanner array of the wrong size");
}

void checkMesh(const geom::TriMesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  FUZZ_CHECK(!mesh.triangles.empty(), "reader returned a mesh with no triangle");
  for (const auto& v : mesh.vertices) FUZZ_CHECK(finite(v), "reader returned a NaN/Inf vertex");
  for (const auto& t : mesh.triangles)
    for (std::uint32_t i : t) FUZZ_CHECK(i < n, "reader returned a triangle index out of range");
  FUZZ_CHECK(mesh.colors.empty() || mesh.colors.size() == n, "colour array of the wrong size");
  FUZZ_CHECK(mesh.quality.empty() || mesh.quality.size() == n, "quality array of the wrong size");
}

void checkSameCloud(const geom::PointCloud& a, const geom::PointCloud& b, const char* what) {
  FUZZ_CHECK(a.size() == b.size(), std::string(what) + ": point count changed");
  for (std::size_t i = 0; i < a.size(); ++i)
    FUZZ_CHECK(sameBits(a.positions[i], b.positions[i]), std::string(what) + ": position changed");
  FUZZ_CHECK(a.station == b.station && a.meshId == b.meshId, std::string(what) + ": attributes changed");
  FUZZ_CHECK(a.scanner.size() == b.scanner.size(), std::string(what) + ": scanner positions changed");
  for (std::size_t i = 0; i < a.scanner.size(); ++i)
    FUZZ_CHECK(sameBits(a.scanner[i], b.scanner[i]), std::string(what) + ": scanner position changed");
}

namespace {
template <class M>
bool sameMatrix(const M& a, const M& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}
bool sameCamera(const geom::Camera& a, const geom::Camera& b) {
  const auto& u = a.viewport;
  const auto& v = b.viewport;
  return sameMatrix(a.view, b.view) && sameMatrix(a.projection, b.projection) && u.x == v.x && u.y == v.y &&
         u.width == v.width && u.height == v.height;
}
// The first field in which two nodes differ, or nullptr.
const char* nodeDifference(const sketch::Node& a, const sketch::Node& b) {
  if (a.id != b.id || a.parent != b.parent) return "id or parent";
  if (a.children != b.children) return "children";
  if (a.camera != b.camera || !sameMatrix(a.screen, b.screen)) return "camera or screen position";
  if (!sameMatrix(a.point, b.point) || !sameMatrix(a.normal, b.normal)) return "point or normal";
  if (!(a.params == b.params)) return "params";
  if (a.kept.has_value() != b.kept.has_value()) return "kept circle presence";
  if (a.kept && (!sameMatrix(a.kept->centre, b.kept->centre) || a.kept->radius != b.kept->radius)) return "kept circle";
  return nullptr;
}
}  // namespace

void checkSameSketch(const sketch::Sketch& a, const sketch::Sketch& b, const char* what) {
  const std::string w(what);
  FUZZ_CHECK(a.up == b.up, w + ": up axis changed");
  FUZZ_CHECK(a.defaults == b.defaults, w + ": defaults changed");
  FUZZ_CHECK(a.cameras().size() == b.cameras().size(), w + ": camera count changed");
  for (std::size_t i = 0; i < a.cameras().size(); ++i)
    FUZZ_CHECK(sameCamera(a.cameras()[i], b.cameras()[i]), w + ": camera " + std::to_string(i) + " changed");
  FUZZ_CHECK(a.size() == b.size(), w + ": node count changed");
  for (const auto& [id, node] : a.nodes()) {
    FUZZ_CHECK(b.contains(id), w + ": node " + std::to_string(id) + " lost");
    const char* difference = nodeDifference(node, b.node(id));
    FUZZ_CHECK(!difference, w + ": node " + std::to_string(id) + " changed: " + (difference ? difference : ""));
  }
}

double nextDouble(ByteSource& in, bool allowNonFinite) {
  const std::uint8_t mode = in.next<std::uint8_t>();
  double v = 0;
  if (mode < 128) {
    v = static_cast<std::int8_t>(in.next<std::uint8_t>()) / 16.0;
  } else if (mode < 224) {
    const int exponent = static_cast<int>(in.next<std::uint8_t>()) * 640 / 255 - 330;
    v = static_cast<std::int16_t>(in.next<std::uint16_t>()) * std::pow(10.0, exponent);
  } else {
    v = in.next<double>();
  }
  return std::isfinite(v) || allowNonFinite ? v : 0.0;
}

}  // namespace treesketch::fuzz
