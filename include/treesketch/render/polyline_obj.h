// Reading polylines (skeletons) from OBJ files: `v x y z` vertices and `l i j k ...` line
// elements. io::readObj wants faces, so this small reader lives beside the renderer.
#pragma once

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "treesketch/geom/types.h"

namespace treesketch::render {

/// The `l` elements of an OBJ file as point lists (world units as stored), in file order.
/// Indices are 1-based, negative ones count back from the last vertex read so far, and `i/t`
/// forms use the part before the slash. Other statements (`f`, `vn`, `o`, comments...) are
/// ignored. Throws InputError naming `source` and the line for: a malformed or non-finite `v`,
/// an `l` with fewer than two indices, an index that is not an integer or out of range, and a
/// file with no `l` element at all.
std::vector<std::vector<geom::Vec3>> readObjPolylines(std::istream& in, const std::string& source);
/// As above from a file; throws InputError if it cannot be opened.
std::vector<std::vector<geom::Vec3>> readObjPolylines(const std::filesystem::path& path);

}  // namespace treesketch::render
