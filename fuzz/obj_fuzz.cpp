// Fuzz harness: the OBJ reader (as a mesh and as a cloud of its vertices). Contract checked: bad
// input throws InputError and nothing else; an accepted mesh is valid, and writing it as OBJ and
// reading that back gives the same vertices and triangles.
#include <sstream>

#include "fuzz_support.h"
#include "treesketch/io/obj.h"
#include "treesketch/util/error.h"

using namespace treesketch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(fuzz::asText(data, size));
  try {
    std::istringstream in(text);
    fuzz::checkCloud(io::readObjVertices(in, "fuzz.obj"), 0);
  } catch (const InputError&) {
  }
  std::istringstream in(text);
  io::ObjStats stats;
  geom::TriMesh mesh;
  try {
    mesh = io::readObj(in, "fuzz.obj", &stats);
  } catch (const InputError&) {
    return 0;
  }
  fuzz::checkMesh(mesh);
  FUZZ_CHECK(stats.polygons > 0 && stats.nonTriangles <= stats.polygons, "OBJ: inconsistent statistics");
  FUZZ_CHECK(mesh.triangles.size() >= stats.polygons, "OBJ: fewer triangles than faces");
  std::ostringstream out;
  io::writeObj(out, mesh);
  std::istringstream back(out.str());
  const geom::TriMesh again = io::readObj(back, "written.obj");
  FUZZ_CHECK(again.vertices == mesh.vertices, "OBJ write/read: vertices changed");
  FUZZ_CHECK(again.triangles == mesh.triangles, "OBJ write/read: triangles changed");
  return 0;
}
