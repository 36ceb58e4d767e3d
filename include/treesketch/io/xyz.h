// Plain-text point clouds (.xyz .txt .csv .pts .asc): one point a line, "x y z" followed by any
// extra columns. A header line naming the columns, quoted or not ("X Y Z Intensity R G B
// Classification", CloudCompare's "//X Y Z Rf Gf Bf scalar_Intensity" or '"x" "y" "z"',
// "id;x;y;z;label") places x, y and z where it names them; intensity, RGB and classification are
// read into the cloud's attributes where named, other columns (labels, ids) are ignored. With no
// such header, attributes go by the column count: x y z i; x y z r g b; x y z i r g b (Leica
// PTS). A line without the attribute columns drops them for the file. Fields are separated by spaces, tabs, commas or
// semicolons. Header lines at the top ("X,Y,Z", a point count, "# comment") are skipped; CRLF is accepted.
#pragma once

#include <filesystem>
#include <istream>
#include <ostream>
#include <string>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/io/read_options.h"

namespace treesketch::io {

/// Reads a text cloud from `in`; `source` names it in error messages. Coordinates are taken as
/// they are (metres in the file's frame). Lines starting with '#' or "//" and blank lines are
/// skipped anywhere; up to `options.maxHeaderLines` non-numeric lines are taken as a header before
/// the first point: each must name the x, y and z columns (any order and case; other columns such
/// as an id are ignored, an unnamed first column of pandas' ",x,y,z" too) or be a point count,
/// else InputError names it. A UTF-8 byte-order mark is skipped; UTF-16 text is refused. Decimal separators must be '.'; a first point line mixing ';' and ',' (decimal
/// commas, "1,5;2,5;3,5") is rejected rather than misread.
/// Throws InputError naming the line for: a line with fewer than 3 numbers after the data
/// started, NaN/Inf, a number out of range, no points at all, fewer than options.minPoints.
geom::PointCloud readXyz(std::istream& in, const std::string& source, const CloudReadOptions& options = {});
/// Same, from a file (InputError if it cannot be opened).
geom::PointCloud readXyz(const std::filesystem::path& path, const CloudReadOptions& options = {});

/// Writes "x y z\n" per point with the shortest decimal form that reads back to the same double
/// (exact round trip, so UTM coordinates keep far better than millimetres). Attributes are not
/// written (use PLY for those). Throws OutputError for a non-finite coordinate.
void writeXyz(std::ostream& out, const geom::PointCloud& cloud);
/// Same, to a file, through writeFileAtomically.
void writeXyz(const std::filesystem::path& path, const geom::PointCloud& cloud);

}  // namespace treesketch::io
