// Fuzz harness: the PLY readers (ascii, binary little and big endian; header, point cloud, mesh).
// Contract checked: bad input throws InputError and nothing else; what is accepted is a valid
// cloud or mesh, and writing it as binary PLY and reading that back gives the same data.
#include <sstream>

#include "fuzz_support.h"
#include "treesketch/io/ply.h"
#include "treesketch/util/error.h"

using namespace treesketch;

namespace {

void cloudRoundTrip(std::string_view bytes) {
  io::CloudReadOptions options;
  options.minPoints = 1;
  std::istringstream in{std::string(bytes)};
  geom::PointCloud cloud;
  try {
    cloud = io::readPlyPointCloud(in, "fuzz.ply", options);
  } catch (const InputError&) {
    return;
  }
  fuzz::checkCloud(cloud, 1);
  std::ostringstream out;
  io::writePlyPointCloud(out, cloud);
  std::istringstream back(out.str());
  fuzz::checkSameCloud(cloud, io::readPlyPointCloud(back, "written.ply", options), "PLY cloud write/read");
}

void meshRoundTrip(std::string_view bytes) {
  std::istringstream in{std::string(bytes)};
  geom::TriMesh mesh;
  try {
    mesh = io::readPlyMesh(in, "fuzz.ply");
  } catch (const InputError&) {
    return;
  }
  fuzz::checkMesh(mesh);
  std::ostringstream out;
  io::writePlyMesh(out, mesh);
  std::istringstream back(out.str());
  const geom::TriMesh again = io::readPlyMesh(back, "written.ply");
  FUZZ_CHECK(again.vertices == mesh.vertices, "PLY mesh write/read: vertices changed");
  FUZZ_CHECK(again.triangles == mesh.triangles, "PLY mesh write/read: triangles changed");
  FUZZ_CHECK(again.colors == mesh.colors, "PLY mesh write/read: colours changed");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = fuzz::asText(data, size);
  try {
    io::parsePlyHeader(bytes, "fuzz.ply");
  } catch (const InputError&) {
  }
  cloudRoundTrip(bytes);
  meshRoundTrip(bytes);
  return 0;
}
