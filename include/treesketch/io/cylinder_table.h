// Reading published cylinder tables (QSMs) into a geom::CylinderModel, so that a model made by
// another tool can be measured against its cloud (compare/model_fit.h) beside treesketch's own.
//
// Recognised (comma, tab, semicolon or whitespace separated; '#' lines and blank lines skipped):
// - treesketch's cylinder CSV (skeleton/skeleton_export.h): id, parent, start_x/y/z, end_x/y/z,
//   radius, length, branch_order[, start_radius]. Each row is the segment from the parent node to
//   the row's node, with the node's radius at its end; its start radius is `start_radius`, or, in
//   tables written before that column existed, the parent row's radius (its own for a row whose
//   parent is the root) — the frustums the swept mesh follows.
// - SimpleForest's QSM CSV (as published with rTwig): ID, parentID, startX..endZ, radius, length,
//   ..., branchOrder, ... — plain cylinders.
// - TreeQSM's cylinder table with a header: columns named radius, length, start_x/y/z (or one
//   `start_point` name for three columns, as TreeQSM's text export writes it), axis_x/y/z (or
//   `axis_direction`), parent, BranchOrder (or branch_order); the end is start + axis · length.
// - TreeQSM's table without a header (the cylinder matrix saved as numbers, TreeQSM 2.3 order):
//   radius, length, start x y z, axis x y z[, parent, extension, added, UnmodRadius, branch,
//   BranchOrder, PositionInBranch]; the branch order is taken when a row has those 15 columns.
// Any other header works when it names a radius, the start, and the end or the axis and length.
// Column names are matched case-insensitively, ignoring spaces, underscores and a trailing unit
// in parentheses ("radius (m)"). With an id column, `parent` holds ids (negative or absent = none);
// without one, it holds 1-based row numbers (0 = none), TreeQSM's convention.
#pragma once

#include <filesystem>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "treesketch/geom/cylinder_model.h"

namespace treesketch::io {

enum class CylinderTableFormat { Treesketch, SimpleForest, TreeQsm, TreeQsmNoHeader, Generic };

/// "treesketch", "SimpleForest", "TreeQSM", "TreeQSM (no header)", "cylinder table".
const char* toString(CylinderTableFormat format);

struct CylinderTable {
  geom::CylinderModel model;
  CylinderTableFormat format = CylinderTableFormat::Generic;
};

/// Reads a cylinder table. Throws InputError naming the source, the line and what was expected
/// (a missing column, a field that is not a number, a row with the wrong number of fields, a
/// negative radius or length, a zero axis, a parent that names no row). A header with no rows
/// gives an empty model.
CylinderTable readCylinderTable(const std::filesystem::path& path);
CylinderTable readCylinderTable(std::istream& in, const std::string& source);
CylinderTable parseCylinderTable(std::string_view text, const std::string& source);

/// Header line of treesketch's cylinder table (CSV).
inline constexpr const char* kCylinderCsvHeader =
    "id,parent,start_x,start_y,start_z,end_x,end_y,end_z,radius,length,branch_order,start_radius";
/// The column writeCylinderCsv adds after start_radius when it is given the measured flags.
inline constexpr const char* kCylinderCsvMeasuredColumn = "measured";

/// Writes `model` as treesketch's cylinder table: one row per piece, in model order: its id, its
/// parent's id (-1 for none), start and end points, radius (the end's), length, branch order and
/// start radius, and whether its end radius was measured (1: a circle fitted to the points) or
/// inferred (0: from the tree's allometry, the pipe model, its neighbours) — that column only when
/// `measured` is given. `ids` gives each piece's id (an automatic model uses the node each piece ends at);
/// empty = the piece's index. Numbers with 9 significant digits; readCylinderTable reads it back to
/// the same frustums. Throws OptionsError when `ids` has the wrong size or a parent index is out of
/// range or `measured` is neither empty nor one flag per piece; the path form writes atomically
/// (OutputError).
void writeCylinderCsv(std::ostream& out, const geom::CylinderModel& model, const std::vector<std::int64_t>& ids = {},
                      const std::vector<char>& measured = {});
void writeCylinderCsv(const std::filesystem::path& path, const geom::CylinderModel& model,
                      const std::vector<std::int64_t>& ids = {}, const std::vector<char>& measured = {});

/// Header of TreeQSM's cylinder text export (tab separated; start_point and axis_direction are
/// three columns each, so a row has 17 numbers).
inline constexpr const char* kTreeQsmCylinderHeader =
    "radius (m)\tlength (m)\tstart_point\taxis_direction\tparent\textension\tbranch\tbranch_order\t"
    "position_in_branch\tmad\tSurfCov\tadded\tUnmodRadius (m)";

/// Writes `model` in the column layout of TreeQSM's cylinder text export (the layout R and MATLAB
/// tools that read TreeQSM models take): one row per piece, in model order, tab separated:
/// radius, length, start x y z, unit axis x y z, parent (1-based row, 0 = none), extension (the
/// 1-based row of the child continuing the branch, 0 = none), branch (1-based, 1 = the stem),
/// branch_order (0 = stem), position_in_branch (1-based), mad and SurfCov (0: not measured by
/// treesketch), added (0), UnmodRadius (= radius). Branches come from geom::branchStructure with
/// `up`. TreeQSM's cylinders are plain: a frustum is written with the radius that keeps its
/// volume, √((r0² + r0 r1 + r1²) / 3). Units are the model's (TreeQSM's are metres). Numbers with
/// 9 significant digits. A piece of zero length gets axis (0, 0, 1) along z (or y for up y).
/// Throws OptionsError for bad parent links; the path form writes atomically (OutputError).
void writeTreeQsmCylinders(std::ostream& out, const geom::CylinderModel& model, geom::UpAxis up);
void writeTreeQsmCylinders(const std::filesystem::path& path, const geom::CylinderModel& model, geom::UpAxis up);

}  // namespace treesketch::io
