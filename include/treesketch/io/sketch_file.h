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
// A camera file holds one camera object: {"view":[16],"projection":[16],"viewport":[4]}.
// Dependency direction: io reads and writes the sketch model, so io includes sketch/sketch.h and
// nothing in sketch/ includes io (whatever reads a file, such as io/view_camera.h, lives here).
#pragma once

#include <filesystem>
#include <istream>
#include <ostream>
#include <string>

#include "treesketch/geom/camera.h"
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

/// Reads / writes a camera file (see above). readCamera throws InputError for malformed JSON,
/// missing or non-numeric entries, or a degenerate camera (zero viewport, singular matrices).
geom::Camera readCamera(std::istream& in, const std::string& source);
geom::Camera readCamera(const std::filesystem::path& path);
void writeCamera(std::ostream& out, const geom::Camera& camera);
void writeCamera(const std::filesystem::path& path, const geom::Camera& camera);

}  // namespace treesketch::io
