// Test trees with a known answer for the evaluation: a branch mesh (the reference surface), an
// optional leaf mesh (occlusion and noise in leaf-on scans) and the true branch axes (what a
// careful user would trace). Two sources: the built-in generator (always available) and a folder
// of third-party trees in the ez-tree layout (<name>.branches.obj, <name>.leaves.obj,
// <name>.json with a "skeleton.limbs" list; see ../shared/data/trees/README.md).
#pragma once

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "treesketch/eval/condition_matrix.h"
#include "treesketch/gen/tree_generator.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/geom/types.h"
#include "treesketch/sketch/polyline_sketch.h"

namespace treesketch::eval {

struct TreeCase {
  std::string name;
  geom::TriMesh branches;                      ///< reference surface (trunk and branches)
  geom::TriMesh leaves;                        ///< may be empty
  std::vector<sketch::BranchPolyline> axes;    ///< true branch axes, trunk first
  std::vector<std::vector<double>> axisRadii;  ///< radius at each axis vertex (same shape as axes)
  geom::UpAxis up = geom::UpAxis::Y;
  /// Physical scale: metres per scene unit (the scan conditions' millimetres and metres are
  /// converted with it). The built-in generator works in metres (1); the ez-tree trees have no
  /// unit and are taken as decimetres (kEzTreeMetresPerUnit, 0.1).
  double metresPerUnit = 1.0;
  /// The exact wood volume of `branches`, scene units³: per branch, the frustums between its
  /// consecutive sections scaled by the share of its circles that its polygonal rings cover
  /// (gen::inscribedPolygonShare), the wood a scan of the mesh can see. NaN when unknown (a tree
  /// folder whose JSON has no skeleton.branches).
  double woodVolume = std::numeric_limits<double>::quiet_NaN();
};

/// A generated tree as a test case (axes = the skeleton's branch centre lines; woodVolume =
/// gen::branchMeshVolume of its skeleton and mesh).
TreeCase treeCaseFromGenerated(const std::string& name, const gen::GeneratedTree& tree);

/// `count` trees from the built-in generator: presets "default", "sparse", "conifer" cycling,
/// seeds 1, 2, 3...; with leaves. Deterministic.
std::vector<TreeCase> builtinTrees(int count);

/// Reads every <name>.json in `folder` that has a matching <name>.branches.obj: the branch mesh,
/// the leaf mesh when <name>.leaves.obj exists, the limbs of the JSON skeleton as axes
/// (each limb's parent vertex = its parent limb's section nearest to the limb's first centre) and
/// the wood volume of its tubes (readEzTreeWoodVolume).
/// Sorted by name. Throws InputError naming the file for a malformed JSON or mesh, and when the
/// folder holds no tree. Scale: `metresPerUnit` for every tree (default: decimetres, the
/// convention for ez-tree trees); throws OptionsError when it is not positive.
std::vector<TreeCase> loadTreeFolder(const std::filesystem::path& folder, double metresPerUnit = kEzTreeMetresPerUnit);

/// Reads one ez-tree JSON skeleton's limbs as axes (and radii). Throws InputError naming the file.
void readEzTreeAxes(const std::filesystem::path& json, std::vector<sketch::BranchPolyline>& axes,
                    std::vector<std::vector<double>>& radii);

/// The wood volume of an ez-tree JSON's branch mesh, scene units³: over skeleton.branches, the
/// frustums between consecutive sections (center, radius) times n/(2π)·sin(2π/n) for the branch's
/// `segment_count` n (its rings are polygons of n vertices inscribed in the section circles).
/// NaN when the JSON has no skeleton.branches. Throws InputError naming the file and the branch
/// (or section) for a malformed entry: a segment count below 3, a missing or non-finite centre,
/// a negative or non-finite radius.
double readEzTreeWoodVolume(const std::filesystem::path& json);

}  // namespace treesketch::eval
