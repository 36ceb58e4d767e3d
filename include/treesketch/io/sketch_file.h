// Sketch files (JSON) and camera files: saving a sketch with its cameras and sampling sizes, and
// loading it back bit-exactly. Format (version 1):
//   {"format":"treesketch-sketch","version":1,"up":"y","defaults":{PARAMS},
//    "cameras":[{"view":[16 numbers, row-major],"projection":[16],"viewport":[x,y,w,h]}],
//    "nodes":[{"id":0,"parent":-1,"camera":0,"screen":[x,y],"params":{PARAMS}},
//             {"id":1,"parent":0,"point":[x,y,z],"normal":[x,y,z],"params":{PARAMS}
//              [,"circle":{"centre":[x,y,z],"radius":r}]}]}
//   PARAMS = {"sliceHalfThickness":..,"lineEpsilon":..,"lineEpsilonStep":..,"enabled":true
//             [,"maxGrowthSteps":N]}   (absent = -1 = unlimited, as the thesis)
// A node has either "camera"+"screen" (screen node) or "point"+"normal" (point node). Missing
// "params" fields take the file's "defaults" (and missing defaults the SamplingParams defaults).
// "circle" (point nodes only, optional) is the node's kept circle (sketch::KeptCircle: used
// instead of a fit); it was added within version 1 (older files have none, older readers ignore
// it and fit the node).
// "notWood" (optional, added within version 1 like "circle"): the not-wood lassos
// (sketch::NotWoodLasso), [{"camera":i,"polygon":[[x,y],[x,y],[x,y],...]}], written only when the
// sketch has any, so files without lassos are byte-identical to before; older readers ignore it.
// "cloud" (optional, added within version 1 like "circle"): the cloud the sketch was made for,
// {"path": "tree.las", "points": N, "hash": "fnv1a64:..."}: the path relative to the sketch
// file's folder when it can be (else as given), the point count and cloudContentHash. Files
// without it still load (SketchFile::cloud is then empty); older readers ignore it.
// A camera file holds one camera object: {"view":[16],"projection":[16],"viewport":[4]}.
// Dependency direction: io reads and writes the sketch model, so io includes sketch/sketch.h and
// nothing in sketch/ includes io (whatever reads a file, such as io/view_camera.h, lives here).
#pragma once

#include <cstdint>
#include <filesystem>
#include <istream>
#include <optional>
#include <ostream>
#include <string>

#include "treesketch/geom/camera.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::io {

/// Reads a sketch file. `source` names the stream in error messages. Throws InputError naming
/// the source and, where it applies, the node ("sketch.json: node 7: parent 12 does not exist")
/// or the byte offset of malformed JSON, for: malformed JSON, wrong "format", unsupported
/// "version", a missing or non-numeric field (JSON has no NaN: null and strings are rejected),
/// a camera index out of range, a degenerate camera, an unknown parent, two roots, a cycle, a
/// duplicate id, non-positive sampling sizes, a zero normal, a kept circle on a screen node or
/// with a radius that is not > 0. The result passes Sketch::validate.
sketch::Sketch readSketch(std::istream& in, const std::string& source);
sketch::Sketch readSketch(const std::filesystem::path& path);

/// Writes a sketch (nodes in parent-before-child order, so child order survives a round trip;
/// doubles in shortest round-trip form, so reading gives back bit-identical values). Throws
/// OptionsError if the sketch fails Sketch::validate (nothing is written), OutputError if the
/// file cannot be written. The path version writes atomically (temporary file + rename).
void writeSketch(std::ostream& out, const sketch::Sketch& sketch);
void writeSketch(const std::filesystem::path& path, const sketch::Sketch& sketch);

/// The cloud a sketch was made for, as its file records it.
struct SketchCloudRecord {
  std::string path;          ///< as written (relative to the sketch file's folder when it could be)
  std::uint64_t points = 0;  ///< the cloud's point count
  std::string hash;          ///< cloudContentHash of the cloud
  /// Same points and hash (the path is only a name: a moved cloud is the same cloud).
  bool sameCloud(const SketchCloudRecord& other) const { return points == other.points && hash == other.hash; }
};

/// A content hash of a cloud's positions ("fnv1a64:" and 16 hex digits; FNV-1a over the bits of
/// every coordinate, in order): two clouds with the same points in the same order hash alike, and
/// a cloud changed by one coordinate bit does not. One pass over the positions.
std::string cloudContentHash(const geom::PointCloud& cloud);
/// The record of `cloud` read from `cloudPath`, for a sketch file to be written at `sketchPath`.
SketchCloudRecord makeCloudRecord(const geom::PointCloud& cloud, const std::filesystem::path& cloudPath,
                                  const std::filesystem::path& sketchPath);

/// A sketch file with the record of its cloud (nullopt for a file written without one).
struct SketchFile {
  sketch::Sketch sketch;
  std::optional<SketchCloudRecord> cloud;
};
/// As readSketch, and the "cloud" record (a malformed one is an InputError naming the file).
SketchFile readSketchFile(std::istream& in, const std::string& source);
SketchFile readSketchFile(const std::filesystem::path& path);
/// As writeSketch, with the "cloud" record.
void writeSketch(const std::filesystem::path& path, const sketch::Sketch& sketch, const SketchCloudRecord& cloud);

/// Reads / writes a camera file (see above). readCamera throws InputError for malformed JSON,
/// missing or non-numeric entries, or a degenerate camera (zero viewport, singular matrices).
geom::Camera readCamera(std::istream& in, const std::string& source);
geom::Camera readCamera(const std::filesystem::path& path);
void writeCamera(std::ostream& out, const geom::Camera& camera);
void writeCamera(const std::filesystem::path& path, const geom::Camera& camera);

}  // namespace treesketch::io
