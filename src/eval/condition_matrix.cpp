#include "treesketch/eval/condition_matrix.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "treesketch/util/error.h"

namespace treesketch::eval {

double mmToUnits(double mm, double metresPerUnit) { return metresToUnits(mm * 1e-3, metresPerUnit); }

double metresToUnits(double metres, double metresPerUnit) {
  if (!(metresPerUnit > 0) || !std::isfinite(metresPerUnit))
    throw OptionsError("metres per scene unit must be positive and finite (got " + std::to_string(metresPerUnit) + ")");
  return metres / metresPerUnit;
}

ScanCondition referenceCondition() {
  ScanCondition c;
  c.name = "reference";
  c.factor = "reference";
  c.pattern = "sphere";
  c.targetPoints = 160000;
  c.sphereJitterDeg = 0.0;
  c.sweep = true;
  return c;
}

namespace {

ScanCondition tlsBase() {
  ScanCondition c;
  c.name = "tls-base";
  c.factor = "base";
  c.pattern = "tls";
  c.stations = 4;
  c.stepDeg = 0.2;
  c.stationHeightM = 1.5;
  c.rangeNoiseMm = 5.0;
  return c;
}

ScanCondition tlsVariant(const std::string& name, const std::string& factor, bool leafOn) {
  ScanCondition c = tlsBase();
  c.name = name;
  c.factor = factor;
  c.leafOn = leafOn;
  return c;
}

ScanCondition thesisSphere(const std::string& name, int subdivisions, bool leafOn) {
  ScanCondition c;
  c.name = name;
  c.factor = "sphere rays";
  c.pattern = "sphere";
  c.sphereSubdivisions = subdivisions;
  c.sphereJitterDeg = 1.0;  // the thesis's "small amount"; every ray passes near the centre
  c.leafOn = leafOn;
  return c;
}

ScanCondition woodCount(const std::string& name, std::uint64_t woodPoints) {
  ScanCondition c = referenceCondition();
  c.name = name;
  c.factor = "wood points";
  c.targetPoints = 0;
  c.targetWoodPoints = woodPoints;
  c.sweep = false;
  c.leafOn = false;  // 1M wood points leaf-on would be a 10-25M-point cloud
  return c;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string count(std::uint64_t v) {
  if (v >= 1000000 && v % 100000 == 0) return num(v / 1e6) + "M";
  if (v >= 1000 && v % 1000 == 0) return num(v / 1e3) + "k";
  return std::to_string(v);
}

}  // namespace

geom::TriMesh terrainUnder(const geom::BBox& tree, geom::UpAxis up, double metresPerUnit, double halfWidth,
                           double slopeDeg) {
  constexpr int kCells = 120;
  const int a = 0, b = up == geom::UpAxis::Y ? 2 : 1, h = up == geom::UpAxis::Y ? 1 : 2;
  const geom::Vec3 centre = tree.centre();
  const double bottom = tree.min[h], rise = std::tan(slopeDeg * M_PI / 180.0);
  const double bump = metresToUnits(0.02, metresPerUnit), wave = 2 * M_PI / metresToUnits(1.0, metresPerUnit);
  geom::TriMesh m;
  for (int i = 0; i <= kCells; ++i)
    for (int j = 0; j <= kCells; ++j) {
      const double x = -halfWidth + 2 * halfWidth * i / kCells, y = -halfWidth + 2 * halfWidth * j / kCells;
      geom::Vec3 p;
      p[a] = centre[a] + x;
      p[b] = centre[b] + y;
      // The foot stands on the terrain: level with the tree's bottom under it, a bump's depth below.
      p[h] = bottom - bump + rise * x + bump * std::sin(wave * x) * std::cos(0.7 * wave * y);
      m.vertices.push_back(p);
    }
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      const auto v = static_cast<std::uint32_t>(i * (kCells + 1) + j), w = v + kCells + 1;
      m.triangles.push_back({v, w, v + 1});
      m.triangles.push_back({v + 1, w, w + 1});
    }
  return m;
}

std::vector<ScanCondition> fullMatrix() {
  std::vector<ScanCondition> m;
  m.push_back(referenceCondition());
  m.push_back(tlsBase());
  {
    auto c = tlsVariant("tls-1-station", "stations", true);
    c.stations = 1;
    m.push_back(c);
    c = tlsVariant("tls-2-stations", "stations", false);
    c.stations = 2;
    m.push_back(c);
    c = tlsVariant("tls-8-stations", "stations", true);
    c.stations = 8;
    m.push_back(c);
  }
  {
    auto c = tlsVariant("tls-step-0.1", "step", false);
    c.stepDeg = 0.1;
    m.push_back(c);
    c = tlsVariant("tls-step-0.5", "step", false);
    c.stepDeg = 0.5;
    m.push_back(c);
  }
  // 25 mm: a mobile scanner's range noise (its trajectory and registration), leaf-off.
  for (double mm : {0.0, 2.0, 10.0, 25.0}) {
    auto c = tlsVariant("tls-noise-" + num(mm) + "mm", "noise", mm == 10.0);
    c.rangeNoiseMm = mm;
    m.push_back(c);
  }
  {
    // A terrestrial scan keeps the terrain round the stem: the tree on level, bumpy ground, clipped
    // to the square under its crown (a tree cut out of a plot's scan).
    auto c = tlsVariant("tls-terrain", "terrain", false);
    c.terrainSlopeDeg = 0.0;
    m.push_back(c);
  }
  m.push_back(thesisSphere("sphere-73k", 6, true));
  m.push_back(thesisSphere("sphere-295k", 7, true));
  m.push_back(thesisSphere("sphere-1180k", 8, false));
  m.push_back(woodCount("wood-5k", 5000));
  m.push_back(woodCount("wood-20k", 20000));
  m.push_back(woodCount("wood-50k", 50000));
  m.push_back(woodCount("wood-400k", 400000));
  m.push_back(woodCount("wood-1m", 1000000));
  return m;
}

std::vector<ScanCondition> quickMatrix() {
  std::vector<ScanCondition> m =
      selectConditions(fullMatrix(), {"sphere-73k", "tls-1-station", "tls-step-0.5", "tls-noise-10mm", "wood-5k"});
  // Leaf-on (the slow skeleton settings) on the sphere row only.
  for (auto& c : m)
    if (c.name != "sphere-73k") c.leafOn = false;
  return m;
}

std::vector<ScanCondition> conditionMatrix(const std::string& name) {
  if (name == "full") return fullMatrix();
  if (name == "quick") return quickMatrix();
  throw OptionsError("unknown condition matrix '" + name + "' (known: quick, full)");
}

std::vector<ScanCondition> selectConditions(const std::vector<ScanCondition>& matrix,
                                            const std::vector<std::string>& names) {
  for (const auto& n : names) {
    if (std::none_of(matrix.begin(), matrix.end(), [&](const ScanCondition& c) { return c.name == n; })) {
      std::string known;
      for (const auto& c : matrix) known += (known.empty() ? "" : ", ") + c.name;
      throw OptionsError("unknown condition '" + n + "' (known: " + known + ")");
    }
  }
  std::vector<ScanCondition> out;
  for (const auto& c : matrix)
    if (std::find(names.begin(), names.end(), c.name) != names.end()) out.push_back(c);
  return out;
}

std::string describeCondition(const ScanCondition& c) {
  std::ostringstream s;
  if (c.pattern == "sphere") {
    s << "sphere, ";
    if (c.targetWoodPoints > 0)
      s << "~" << count(c.targetWoodPoints) << " wood points";
    else if (c.targetPoints > 0)
      s << "~" << count(c.targetPoints) << " points";
    else if (c.sphereSubdivisions > 0)
      s << count(18ull << (2 * c.sphereSubdivisions)) << " rays (subdivision " << c.sphereSubdivisions << ")";
    else
      s << "~" << count(c.sphereRays) << " rays";
    if (c.sphereJitterDeg > 0)
      s << ", " << num(c.sphereJitterDeg) << "° jitter";
    else
      s << ", jitter cone over the tree";
  } else {
    s << "tls, " << c.stations << (c.stations == 1 ? " station" : " stations") << ", ";
    if (c.stepDeg > 0)
      s << num(c.stepDeg) << "° step";
    else
      s << "step for ~" << count(c.targetPoints) << " points";
    if (c.stationHeightDiagonal > 0)
      s << ", " << num(c.stationHeightDiagonal) << " × diagonal high";
    else
      s << ", " << num(c.stationHeightM) << " m high";
  }
  if (c.rangeNoiseDiagonal > 0)
    s << ", noise " << num(c.rangeNoiseDiagonal) << " × diagonal";
  else if (c.pattern == "tls" || c.rangeNoiseMm > 0)
    s << ", " << num(c.rangeNoiseMm) << " mm noise";
  if (c.terrainSlopeDeg >= 0) s << ", on terrain at " << num(c.terrainSlopeDeg) << "°";
  return s.str();
}

std::string conditionTable(const std::vector<ScanCondition>& matrix) {
  std::ostringstream s;
  s << "| condition | factor | scan | leaf states | flags |\n|---|---|---|---|---|\n";
  for (const auto& c : matrix) {
    std::string leaf = c.leafOn && c.leafOff ? "on, off" : c.leafOn ? "on" : "off";
    std::string flags;
    if (c.backwardOnly()) flags = "backward only";
    if (c.sweep) flags += std::string(flags.empty() ? "" : "; ") + "node sweep";
    s << "| " << c.name << " | " << c.factor << " | " << describeCondition(c) << " | " << leaf << " | " << flags
      << " |\n";
  }
  return s.str();
}

// -- split ---------------------------------------------------------------------------------------

const char* halfName(TreeHalf half) { return half == TreeHalf::Tune ? "tune" : "held-out"; }

const std::vector<std::string>& developerTuneTrees() {
  // The four original trees, plus one further tree of the aspen, pine and ash families.
  static const std::vector<std::string> names = {"aspen_medium_s101", "pine_medium_s13977", "oak_medium_s35729",
                                                 "bush_2_s45590",     "aspen_small_s914",   "pine_small_s3391",
                                                 "ash_small_s2203"};
  return names;
}

const std::vector<std::string>& developerHeldOutTrees() {
  // Other seeds of the four original presets, and size variants (large aspen, small oak, medium
  // ash): what generalisation means here.
  static const std::vector<std::string> names = {"aspen_medium_s4409", "pine_medium_s8817", "oak_medium_s1290",
                                                 "bush_2_s6644",       "aspen_large_s5521", "oak_small_s6120",
                                                 "ash_medium_s7781"};
  return names;
}

TreeHalf treeHalf(const std::string& name) {
  const auto& tune = developerTuneTrees();
  const auto& held = developerHeldOutTrees();
  if (std::find(tune.begin(), tune.end(), name) != tune.end()) return TreeHalf::Tune;
  if (std::find(held.begin(), held.end(), name) != held.end()) return TreeHalf::HeldOut;
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a, 64 bits
  for (unsigned char ch : name) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  // FNV-1a mixes its high bits poorly for names that differ only at the end ("tree_1", "tree_2"),
  // and its low bit is the parity of the odd characters: finish with the splitmix64 mixer.
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  h ^= h >> 31;
  return (h & 1) == 0 ? TreeHalf::Tune : TreeHalf::HeldOut;
}

bool splitSelects(const std::string& split, TreeHalf half) {
  if (split == "all") return true;
  if (split == "tune") return half == TreeHalf::Tune;
  if (split == "held-out") return half == TreeHalf::HeldOut;
  throw OptionsError("unknown split '" + split + "' (known: tune, held-out, all)");
}

}  // namespace treesketch::eval
