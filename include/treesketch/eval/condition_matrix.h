// The evaluation's scan conditions: one named row per scan setting, varied one factor
// at a time around a realistic terrestrial scan, plus the evaluation's former favourable setting
// ("reference"); and the split of the test trees into a tuning half and a held-out half.
//
// Physical scale. Scanner settings are physical (a tripod is 1.5 m high, ranging noise is a few
// millimetres) but the test trees have no unit: each TreeCase carries `metresPerUnit`, and every
// physical setting here is converted with it (mmToUnits, metresToUnits). The ez-tree trees of
// ../shared/data/trees are taken as decimetres (1 unit = 0.1 m: a tree 25-65 units tall is
// 2.5-6.5 m, a small garden tree); the built-in generator's trees are in metres.
//
// The full matrix (fullMatrix(), listed by `treesketch evaluate --matrix full --list`):
//  - base "tls-base": TLS, 4 stations on a ring one scene diagonal from the tree, 1.5 m above
//    its base, 0.2° step, 5 mm range noise (a quick survey of one tree);
//  - stations 1, 2, 8; step 0.1° and 0.5°; range noise 0, 2 and 10 mm: each alone, the rest as the
//    base;
//  - the thesis's sphere pattern at 73,728 / 294,912 / 1,179,648 rays (subdivisions 6/7/8), aimed
//    at the centre with a 1° jitter and no point-count scaling: the trunk base and the crown's
//    edge get few points;
//  - the former setting "reference" (sphere pattern, jitter cone covering the tree, ~160k points)
//    and the same with 5k, 20k, 50k, 400k and 1M wood points: the point-count factor. (A TLS
//    sweep cannot be the base here: at the step that gives 1M points on the smallest tree it
//    would cast ~500M rays per tree.)
// Leaf state is the user's flag, not a scan setting: every row runs leaf-off; the leaf-on scans
// (4-11 % wood, and the leaf-on skeleton is ~10x slower) run on the rows that matter for them
// (reference, sphere 73k and 295k, tls-base, 1 and 8 stations, 10 mm noise).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "treesketch/geom/tri_mesh.h"
#include <vector>

namespace treesketch::eval {

/// Metres per scene unit of the ez-tree trees (taken as decimetres, see above).
inline constexpr double kEzTreeMetresPerUnit = 0.1;
/// A case with fewer wood points than this is reported but flagged "sparse" and left out of
/// the means and worst cases (the accuracy targets are stated for cases with >= 5k wood points).
inline constexpr std::size_t kSparseWoodPoints = 5000;
/// Root check: the method's sketch root lies at the trunk base when it is within this distance
/// of the reference trunk base (the first centre of the reference skeleton's root limb), as % of
/// the reference bounding-box diagonal (2 % = 14 cm on a 5 m tree with a 7 m diagonal: about
/// two trunk diameters; a root put on the lowest branch tips or half a metre up a sparse trunk
/// fails it).
inline constexpr double kRootAtBasePct = 2.0;
/// Tips vs limbs: the target band (tips of the sketch / limbs of the reference).
inline constexpr double kTipsRatioMin = 0.8;
inline constexpr double kTipsRatioMax = 1.3;

/// One row of the matrix: a complete scan setting, applied to every tree.
struct ScanCondition {
  std::string name;
  /// The factor this row varies from its base: "reference", "base", "stations", "step",
  /// "noise", "sphere rays" or "wood points" (plots and the evaluation report group by it).
  std::string factor;
  /// "sphere" (thesis, origins on a sphere aimed at the centre) or "tls" (stations on a ring).
  std::string pattern = "tls";
  /// Leaf states this row is scanned in.
  bool leafOn = true;
  bool leafOff = true;
  /// Run the simulated user's node-count sweep (thesis figure 5.14) here.
  bool sweep = false;

  // -- sphere pattern
  /// > 0: exactly 18 * 4^k rays (the thesis's 6/7/8 give 73,728 / 294,912 / 1,179,648).
  int sphereSubdivisions = 0;
  /// When no subdivision or target is set: about this many rays.
  std::uint64_t sphereRays = 0;
  /// Half-angle of the aim jitter, degrees; 0 = the cone that covers the model's bounding
  /// sphere (the former reference: samples the whole tree evenly).
  double sphereJitterDeg = 0.0;
  /// Sphere: > 0 scales the ray count from a 100k-ray pilot scan so that the cloud has about this
  /// many points. TLS: with stepDeg 0, the step is chosen for about this many points.
  std::uint64_t targetPoints = 0;
  /// Sphere: > 0 scales the ray count so that about this many points are on the wood (the
  /// branch mesh); rays are capped at 5e7 (the wood_points column says what was reached).
  std::uint64_t targetWoodPoints = 0;

  // -- TLS pattern
  int stations = 4;
  /// Angular step, degrees; 0 = chosen from targetPoints (the former TLS reference).
  double stepDeg = 0.2;
  /// Station height above the bottom of the tree's bounding box, metres.
  double stationHeightM = 1.5;
  /// > 0: the height is this fraction of the branch bounding-box diagonal instead (the former
  /// TLS reference, which had no physical scale).
  double stationHeightDiagonal = 0.0;

  // -- both patterns
  /// Gaussian range noise sigma along each ray, millimetres.
  double rangeNoiseMm = 0.0;
  /// > 0: the noise sigma is this fraction of the branch bounding-box diagonal instead (former
  /// TLS reference).
  double rangeNoiseDiagonal = 0.0;
  /// >= 0: the scan also sees a terrain under the tree, rising at this slope (degrees), with bumps
  /// (terrainUnder); < 0: the tree alone.
  double terrainSlopeDeg = -1.0;

  /// Forward error is not judged: one TLS station cannot see the far side of the tree.
  bool backwardOnly() const { return pattern == "tls" && stations == 1; }
};

/// Scene units for a length in millimetres / metres at a scale of `metresPerUnit` (> 0).
double mmToUnits(double mm, double metresPerUnit);
double metresToUnits(double metres, double metresPerUnit);

/// A square of terrain under a tree of bounds `tree` (its foot at the bounds' bottom, centred
/// across `up`), out to `halfWidth` each way, rising at `slopeDeg` along the first axis across up,
/// with bumps of 2 cm (at `metresPerUnit`) about a metre apart: a grid of triangles, 120 a side.
geom::TriMesh terrainUnder(const geom::BBox& tree, geom::UpAxis up, double metresPerUnit, double halfWidth,
                           double slopeDeg);

/// The former evaluation setting, sphere pattern: jitter cone over the tree, ~160k points,
/// node-count sweep on. Named "reference".
ScanCondition referenceCondition();
/// The whole matrix described above (names unique, reference first).
std::vector<ScanCondition> fullMatrix();
/// The subset that runs under `make test`: rows of fullMatrix() (same names and settings) that
/// scan cheaply — the 73k-ray sphere (both leaf states), 0.5° TLS, one station, 10 mm noise and
/// 5k wood points (leaf-off) — so every factor and both flags are exercised.
std::vector<ScanCondition> quickMatrix();
/// "quick" or "full"; throws OptionsError naming the known matrices otherwise.
std::vector<ScanCondition> conditionMatrix(const std::string& name);
/// The rows of `matrix` named in `names`, in the matrix's order; throws OptionsError for an
/// unknown name (listing the known ones).
std::vector<ScanCondition> selectConditions(const std::vector<ScanCondition>& matrix,
                                            const std::vector<std::string>& names);
/// Markdown table of the rows' settings (name, factor, pattern, settings, leaf states).
std::string conditionTable(const std::vector<ScanCondition>& matrix);
/// One-line summary of a row's settings ("tls, 4 stations, 0.2°, 1.5 m high, 5 mm noise").
std::string describeCondition(const ScanCondition& condition);

// -- the tuning / held-out split -------------------------------------------------------------------

/// The half of the test trees a tree belongs to. Methods are tuned on "tune" only; "held-out"
/// reports how they do on trees they were not tuned on.
enum class TreeHalf { Tune, HeldOut };

/// "tune" or "held-out".
const char* halfName(TreeHalf half);
/// The fixed split of the 14 developer trees (../shared/data/trees): 7 each, the four original
/// trees in the tuning half; every preset family (aspen, pine, oak, bush, ash) in both halves.
const std::vector<std::string>& developerTuneTrees();
const std::vector<std::string>& developerHeldOutTrees();
/// The half of a tree by name: the fixed lists above, and for any other name (built-in trees, a
/// user's folder) the low bit of the name's 64-bit FNV-1a hash passed through the splitmix64
/// finaliser (0: tune). Depends only on the name, so adding a tree never moves another.
TreeHalf treeHalf(const std::string& name);
/// Parses --split: "tune", "held-out" or "all" (true when the half is selected). Throws
/// OptionsError for another value.
bool splitSelects(const std::string& split, TreeHalf half);

}  // namespace treesketch::eval
