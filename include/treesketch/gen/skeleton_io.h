// Reading and writing skeletons as JSON ("treesketch-skeleton" version 1):
//   {"format": "treesketch-skeleton", "version": 1, "up": "y" | "z", "units": "m",
//    "branches": [{"id": 0, "parent": -1, "parent_section": -1, "level": 0,
//                  "sections": [{"center": [x, y, z], "radius": r, "axis": [x, y, z]}, ...]}, ...]}
// Numbers are written in the shortest form that reads back to the same double, so a write/read
// round trip is exact. Unknown keys are ignored (room for metadata such as "generator").
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>

#include <nlohmann/json_fwd.hpp>
#include "treesketch/gen/skeleton.h"

namespace treesketch::gen {

/// The skeleton as a JSON value in the format above.
nlohmann::json skeletonToJson(const Skeleton& skeleton);
/// Parses a JSON value in the format above. `source` names the input in error messages. Throws
/// InputError (naming source, the JSON path, e.g. branches[3].sections[2].radius, and what was
/// expected) on a wrong format/version, missing or mistyped fields, NaN/Inf, or a malformed
/// hierarchy (see findSkeletonProblem).
Skeleton skeletonFromJson(const nlohmann::json& json, const std::string& source);

/// Writes `skeleton` as JSON text to `out` (indented when `pretty`). Throws OutputError if the
/// stream fails.
void writeSkeletonJson(std::ostream& out, const Skeleton& skeleton, bool pretty = false);
/// Writes to `path` atomically (temporary file renamed on success). Throws OutputError.
void writeSkeletonJson(const std::filesystem::path& path, const Skeleton& skeleton, bool pretty = false);
/// Reads a skeleton from JSON text. Throws InputError (with the byte offset for syntax errors).
Skeleton readSkeletonJson(std::istream& in, const std::string& source);
/// Reads a skeleton file. Throws InputError when it cannot be opened or parsed.
Skeleton readSkeletonJson(const std::filesystem::path& path);

}  // namespace treesketch::gen
