// A seeded procedural tree: a trunk and 2-3 levels of branches grown as random walks with
// gnarl and tropism, radii following a pipe-model flavour (a child is never thicker than its
// parent where it starts), optional leaf quads near the twig tips. Gives the exact ground-truth
// skeleton, the branch mesh (the reference surface) and the leaf mesh, in metres, Y or Z up.
// Deterministic: same options -> bit-identical output (single-threaded, portable random numbers).
// The growth scheme follows the spirit of ez-tree (D. Greenheck, MIT) and Weber & Penn 1995;
// no code was taken from either.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "treesketch/gen/branch_mesh.h"
#include "treesketch/gen/skeleton.h"
#include "treesketch/geom/tri_mesh.h"

namespace treesketch::gen {

/// Growth parameters of one branch level (0 = trunk). Angles in degrees, lengths in metres.
struct LevelOptions {
  /// Trunk: length in m. Other levels: the longest child's length as a fraction of its parent's.
  double length = 0.45;
  /// Trunk: base radius in m. Other levels: base radius as a fraction of the parent's radius at the
  /// attachment section, in (0, 1] (pipe-model flavour: a child is never thicker than its parent).
  double radius = 0.6;
  /// Tip radius as a fraction of the base radius, in (0, 1].
  double tipRadius = 0.25;
  /// Sections (rings) per branch before refinement, >= 2.
  int sections = 8;
  /// Vertices per ring of the mesh, >= 3 (before the detail multiplier).
  int segments = 6;
  /// Angle between a branch and its parent's axis at the attachment, and its std dev (not used for
  /// the trunk).
  double angleDeg = 45;
  double angleJitterDeg = 10;
  /// Random bending: std dev of the direction change over one metre of growth, in degrees per
  /// sqrt(metre) (a random walk of the direction, so independent of the section count).
  double gnarlDeg = 15;
  /// Bending towards up (+) or down (-), in radians per metre of growth (gravitropism /
  /// phototropism).
  double tropism = 0.1;
  /// Relative std dev of the branch length.
  double lengthJitter = 0.15;
  /// Number of children of the next level grown on each branch of this level (0 = none).
  int children = 0;
  /// Children start at this fraction of the branch length, in [0, 1).
  double childStart = 0.3;
  /// Children towards the tip are shorter by up to this fraction, in [0, 1) (crown shape).
  double childLengthTaper = 0.5;
};

/// The "default" preset's levels: trunk + 3 branch levels, ~8 m tall, trunk base radius 0.15 m,
/// ~14 first-order branches. Numbers chosen by eye for a small broadleaf tree.
std::vector<LevelOptions> defaultLevels();

struct TreeOptions {
  std::uint64_t seed = 1;
  /// World up axis of all outputs; the trunk base is at the origin and grows along it.
  geom::UpAxis up = geom::UpAxis::Y;
  /// Per level, trunk first; 1 to 5 levels.
  std::vector<LevelOptions> levels = defaultLevels();
  /// Detail multiplier, >= 1: every branch segment is split into `detail` (Catmull–Rom) and ring
  /// vertex counts are multiplied by it; triangles grow ~ detail^2. The tree itself does not change.
  int detail = 1;
  /// Smallest radius any section may have, m (a child is clamped to its parent's radius first).
  double minRadius = 0.0015;
  /// Leaf quads: on branches of the `leafLevels` highest levels, `leavesPerBranch` square quads of
  /// side `leafSize` (m), beyond `leafStart` (fraction of the branch length).
  bool leaves = true;
  int leafLevels = 1;
  int leavesPerBranch = 8;
  double leafSize = 0.08;
  double leafStart = 0.4;

  /// Throws OptionsError naming the first field out of range.
  void validate() const;
};

/// Names of the built-in presets: "default" (a ~8 m broadleaf tree), "conifer" (a straight
/// trunk with many short, near-horizontal branches), "sparse" (few, long branches; quick to scan).
std::vector<std::string> presetNames();
/// The options of a preset (seed 1, Y up). Throws OptionsError for an unknown name.
TreeOptions presetOptions(const std::string& name);

struct GeneratedTree {
  Skeleton skeleton;     ///< ground truth (refined by `detail`), frame of options.up
  BranchMesh branches;   ///< trunk and branches: the reference surface
  geom::TriMesh leaves;  ///< leaf quads, 2 triangles each (empty when options.leaves is false)
};

/// Grows the tree of `options`. Levels are grown breadth-first, so branch ids increase with level.
/// Each branch draws from its own random sub-stream (seed, branch id), leaves from another, so the
/// branches do not change when leaf options do. Throws OptionsError for invalid options.
GeneratedTree generateTree(const TreeOptions& options);

/// The skeleton alone (no meshes), as in generateTree.
Skeleton generateSkeleton(const TreeOptions& options);

}  // namespace treesketch::gen
