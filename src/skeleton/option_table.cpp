// The automatic model's settings by name (see option_table.h). Each row binds a name to a field
// through a getter and a setter; the ranges are those the option checks of the stages accept
// (skeleton.cpp, voxel_graph.cpp, skeleton_sketch.cpp), so a value refused here would be refused
// there too, only later and without the setting's name.
#include "treesketch/skeleton/option_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "treesketch/util/error.h"
#include "treesketch/util/text.h"

namespace treesketch::skeleton {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct SettingRow {
  SettingInfo info;
  double (*get)(const AutoSkeletonOptions&);
  void (*set)(AutoSkeletonOptions&, double);
};

// One row: the field path is both the name and the member access.
#define TS_SETTING(path, type, lo, hi, help)                                                \
  SettingRow {                                                                              \
    SettingInfo{#path, SettingType::type, lo, hi, help},                                    \
        [](const AutoSkeletonOptions& o) { return static_cast<double>(o.path); },           \
        [](AutoSkeletonOptions& o, double v) { o.path = static_cast<decltype(o.path)>(v); } \
  }

std::vector<SettingRow> graphRows() {
  return {
      TS_SETTING(skeleton.graph.voxelSize, Real, 0, kInf, "voxel edge, cloud units (0 = automatic)"),
      TS_SETTING(skeleton.graph.autoDiagonalFraction, Real, 1e-6, 1, "automatic voxel: fraction of the bbox diagonal"),
      TS_SETTING(skeleton.graph.autoSpacingFactor, Real, 1e-3, 1e3, "automatic voxel: multiple of the point spacing"),
      TS_SETTING(skeleton.graph.maxVoxels, Integer, 1, 1e9, "most occupied voxels for the automatic size"),
      TS_SETTING(skeleton.graph.reach, Integer, 1, 3, "edges join voxels this many steps apart per axis"),
      TS_SETTING(skeleton.graph.sparseLinkNeighbours, Integer, 0, 26,
                 "links to nearest voxels of other pieces (0 = off)"),
      TS_SETTING(skeleton.graph.shapeCellVoxels, Real, 1e-3, 1e3, "cell of the local shape (PCA), voxels"),
      TS_SETTING(skeleton.graph.maxGapVoxels, Real, 0, 1e6, "longest occlusion gap bridged, voxels"),
      TS_SETTING(skeleton.graph.coneAngleDeg, Real, 1e-3, 180, "bridge cone about the piece's axis, degrees"),
      TS_SETTING(skeleton.graph.freeGapVoxels, Real, 0, 1e6, "gaps always bridged, voxels"),
      TS_SETTING(skeleton.graph.coneRadiusVoxels, Real, 1e-3, 1e6, "radius the bridge axis is measured over, voxels"),
      TS_SETTING(skeleton.graph.minBridgeLinearity, Real, 0, 1, "linearity a bridged piece needs (0 = any)"),
      TS_SETTING(skeleton.graph.minBridgePoints, Integer, 0, 1e9, "fewest points of a bridged piece"),
  };
}

std::vector<SettingRow> levelSetRows() {
  return {
      TS_SETTING(skeleton.binWidthVoxels, Real, 1e-3, 1e3, "level set width, voxels"),
      TS_SETTING(skeleton.rootHeightVoxels, Real, 0, 1e6, "root region height, voxels"),
      TS_SETTING(skeleton.minRadiusVoxels, Real, 1e-3, 1e3, "smallest node radius, voxels"),
      TS_SETTING(skeleton.trackStem, Boolean, 0, 1, "track the stem by circle fits"),
      TS_SETTING(skeleton.splitMergedForks, Boolean, 0, 1, "cut merged pieces below a fork along its limbs"),
  };
}

std::vector<SettingRow> pruningRows() {
  return {
      TS_SETTING(skeleton.spurLengthRadii, Real, 0, 1e3, "spur length, fork radii (0 = by level sets only)"),
      TS_SETTING(skeleton.spurLengthBins, Real, 0, 1e3, "spur length, level sets"),
      TS_SETTING(skeleton.twigOutBins, Real, 0, 1e3, "a spur standing out this far is a twig, level sets (0 = off)"),
      TS_SETTING(skeleton.minEndSupportFraction, Real, 0, 1e3, "end nodes below this share of the parent's points go"),
      TS_SETTING(skeleton.forkZoneRadii, Real, 0, 1e3, "fork zone moved onto the parent's line, radii"),
      TS_SETTING(skeleton.collinearToleranceRadii, Real, 0, 1e3, "chain simplification tolerance, radii"),
      TS_SETTING(skeleton.collinearToleranceVoxels, Real, 0, 1e3, "chain simplification tolerance, voxels"),
      TS_SETTING(skeleton.maxSegmentRadii, Real, 1e-3, 1e6, "longest segment, radii"),
      TS_SETTING(skeleton.maxSegmentBins, Real, 1e-3, 1e6, "longest segment, level sets"),
      TS_SETTING(skeleton.radiusMedianWindow, Integer, 1, 1001, "running median of raw radii, nodes (1 = off)"),
  };
}

std::vector<SettingRow> leafRows() {
  return {
      TS_SETTING(skeleton.leafEntryPositions, Boolean, 0, 1, "leaf-entry positions (leaf-on)"),
      TS_SETTING(skeleton.leafPlaneRadiusVoxels, Real, 1e-3, 1e3, "leaf plane test radius, voxels"),
      TS_SETTING(skeleton.leafPlaneBandVoxels, Real, 1e-6, 1e3, "leaf plane inlier band, voxels"),
      TS_SETTING(skeleton.leafPlaneHypotheses, Integer, 1, 1e6, "leaf plane RANSAC hypotheses per voxel"),
      TS_SETTING(skeleton.leafPlaneMinInliers, Real, 0, 1, "share of points a flat voxel holds in the band"),
      TS_SETTING(skeleton.leafPlaneMinSpread, Real, 0, 1e3, "in-plane spread of a flat voxel, radii"),
      TS_SETTING(skeleton.leafPlaneMaxAngleDeg, Real, 0, 90, "planes of one patch within this angle, degrees"),
      TS_SETTING(skeleton.leafPatchMaxOffsetVoxels, Real, 0, 1e3, "step off a patch's plane, voxels"),
      TS_SETTING(skeleton.leafPlaneMaxPointsPerVoxel, Integer, 0, 1e9,
                 "points per voxel the plane test reads (0 = all)"),
      TS_SETTING(skeleton.leafConvergenceWeight, Real, 0, 1, "plane convergence weight (0 = off)"),
      TS_SETTING(skeleton.leafConvergenceRadiusVoxels, Real, 0, 1e3,
                 "plane convergence radius, voxels (0 = automatic)"),
      TS_SETTING(skeleton.leafConvergenceAutoScale, Real, 1e-3, 1e3, "automatic convergence radius scale"),
      TS_SETTING(skeleton.leafConvergenceMinRadiusVoxels, Real, 1e-3, 1e3, "automatic convergence radius, lowest"),
      TS_SETTING(skeleton.leafConvergenceMaxRadiusVoxels, Real, 1e-3, 1e3, "automatic convergence radius, highest"),
      TS_SETTING(skeleton.leafConvergenceFreeShare, Real, 0, 1, "directions left free by the planes"),
  };
}

std::vector<SettingRow> modelRows() {
  return {
      TS_SETTING(sketch.sliceRadii, Real, 0, 1e3, "slice half-thickness, radii"),
      TS_SETTING(sketch.sliceVoxels, Real, 0, 1e3, "slice half-thickness, voxels"),
      TS_SETTING(sketch.lineRadii, Real, 0, 1e3, "initial test radius, radii"),
      TS_SETTING(sketch.lineVoxels, Real, 0, 1e3, "initial test radius, voxels"),
      TS_SETTING(sketch.stepRadii, Real, 0, 1e3, "test radius growth, radii"),
      TS_SETTING(sketch.stepVoxels, Real, 0, 1e3, "test radius growth, voxels"),
      TS_SETTING(fit.maxGrowthSteps, Integer, 0, 1e6, "test radius growth steps per node"),
      TS_SETTING(fit.circle.maxIterations, Integer, 1, 1e7, "RANSAC samples per fit"),
      TS_SETTING(fit.circle.minInliers, Integer, 3, 1e9, "fewest inliers of a circle"),
      TS_SETTING(fit.circle.minArcDegrees, Real, 0, 360, "arc a circle's inliers must cover, degrees"),
      TS_SETTING(radii.maxRadiusRatio, Real, 1e-3, 1e6, "a fit's radius at most this x the skeleton's"),
      TS_SETTING(radii.maxCentreShiftRadii, Real, 1e-3, 1e6, "a fit's centre within this many radii"),
      TS_SETTING(radii.maxRelativeRms, Real, 1e-3, 1e6, "a fit's RMS at most this x its radius"),
      TS_SETTING(radii.slackVoxels, Real, 0, 1e6, "slack of those checks, voxels"),
      TS_SETTING(radii.rmsFloorVoxels, Real, 0, 1e6, "RMS floor, voxels"),
      TS_SETTING(radii.medianWindow, Integer, 1, 1001, "running median of fitted radii, nodes (1 = off)"),
      TS_SETTING(radii.childNotThicker, Boolean, 0, 1, "radii never grow towards a tip"),
      TS_SETTING(radii.pipeModel, Boolean, 0, 1, "grow forks to carry their children (pipe model)"),
      TS_SETTING(radii.allometryMaxRatio, Real, 0, 1e6, "pipe-model bound factor (0 = off, else >= 1)"),
      TS_SETTING(radii.maxGrowthRatio, Real, 0, 1e6, "fits over this x the fits below and the pipe law set aside (0 = off)"),
      TS_SETTING(radii.surfaceBound, Boolean, 0, 1, "no tube thicker than its points allow"),
      TS_SETTING(axes.halfWindowNodes, Integer, 0, 1000, "axis smoothing half-window, nodes (0 = off)"),
      TS_SETTING(axes.unfittedWeight, Real, 1e-6, 1,
                 "weight of a node without a fit (1: such nodes stay, no smoothing)"),
      TS_SETTING(axes.maxShiftRadii, Real, 0, 1e6, "largest axis move, radii"),
      TS_SETTING(maxFitFlatFraction, Real, 0, 1, "pieces flatter than this are not fitted (1 = fit all)"),
      TS_SETTING(minInlierBandVoxels, Real, 0, 1e6, "least inlier band of the fits, voxels"),
      TS_SETTING(contractionNoises, Real, 0, 1e3,
                 "noisy scans: skeleton on the points drawn together by this x the noise (0 = off)"),
  };
}

std::vector<SettingRow> completionRows() {
  return {
      TS_SETTING(completion.enabled, Boolean, 0, 1, "model the points the model leaves out"),
      TS_SETTING(completion.marginVoxels, Real, 0, 1e6, "a point this far outside is unexplained, voxels"),
      TS_SETTING(completion.minPoints, Integer, 1, 1e9, "fewest points of a part"),
      TS_SETTING(completion.maxGapVoxels, Real, 0, 1e6, "a part's greatest distance from the model, voxels"),
      TS_SETTING(completion.maxParts, Integer, 0, 1e9, "most parts modelled a round"),
      TS_SETTING(completion.maxRounds, Integer, 0, 1000, "most rounds (0 = off)"),
      TS_SETTING(strays.enabled, Boolean, 0, 1, "set aside points far from the tree"),
      TS_SETTING(strays.linkSpacings, Real, 1e-3, 1e6, "linking distance, point spacings"),
      TS_SETTING(strays.bulkShare, Real, 0, 1, "a component this share of the points is the tree"),
      TS_SETTING(strays.nearLinks, Real, 0, 1e6, "smaller components kept within this many links"),
      TS_SETTING(strays.minComponentPoints, Integer, 1, 1e9, "components of fewer points go (1 = off)"),
      TS_SETTING(strays.maxShare, Real, 0, 1, "set nothing aside past this share"),
      TS_SETTING(ground.enabled, Boolean, 0, 1, "set aside the ground under the tree"),
      TS_SETTING(ground.columnSpacings, Real, 1e-3, 1e6, "ground columns' side, point spacings"),
      TS_SETTING(markedNoise.enabled, Boolean, 0, 1, "set aside the points the file classifies as noise (7, 18)"),
  };
}

#undef TS_SETTING

const std::vector<SettingRow>& rows() {
  static const std::vector<SettingRow> all = [] {
    std::vector<SettingRow> r;
    for (auto part : {graphRows(), levelSetRows(), pruningRows(), leafRows(), modelRows(), completionRows()})
      r.insert(r.end(), part.begin(), part.end());
    return r;
  }();
  return all;
}

const SettingRow& findRow(const std::string& name) {
  for (const SettingRow& r : rows())
    if (r.info.name == name) return r;
  std::string msg = "unknown setting '" + name + "'";
  const std::string near = nearestSettingName(name);
  if (!near.empty()) msg += " (nearest: " + near + "; --set help lists them all)";
  throw OptionsError(msg);
}

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

double parseValue(const SettingInfo& s, const std::string& text) {
  const std::string t = lowercase(text);
  if (s.type == SettingType::Boolean) {
    if (t == "true" || t == "on" || t == "1") return 1.0;
    if (t == "false" || t == "off" || t == "0") return 0.0;
    throw OptionsError("setting " + s.name + ": '" + text + "' is not a boolean (true/false, on/off, 1/0)");
  }
  double v = 0;
  std::size_t used = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw OptionsError("setting " + s.name + ": '" + text + "' is not a finite number");
  if (s.type == SettingType::Integer && v != std::floor(v))
    throw OptionsError("setting " + s.name + ": '" + text + "' is not a whole number");
  return v;
}

std::string formatNumber(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

const char* typeName(SettingType t) {
  return t == SettingType::Real ? "real" : t == SettingType::Integer ? "integer" : "boolean";
}

}  // namespace

const std::vector<SettingInfo>& settingTable() {
  static const std::vector<SettingInfo> table = [] {
    std::vector<SettingInfo> t;
    for (const SettingRow& r : rows()) t.push_back(r.info);
    return t;
  }();
  return table;
}

double settingValue(const AutoSkeletonOptions& options, const std::string& name) { return findRow(name).get(options); }

void applySetting(AutoSkeletonOptions& options, const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == assignment.size())
    throw OptionsError("setting '" + assignment + "': expected NAME=VALUE");
  const SettingRow& row = findRow(assignment.substr(0, eq));
  const double v = parseValue(row.info, assignment.substr(eq + 1));
  if (v < row.info.min || v > row.info.max)
    throw OptionsError("setting " + row.info.name + ": " + assignment.substr(eq + 1) + " is outside [" +
                       formatNumber(row.info.min) + ", " + formatNumber(row.info.max) + "]");
  row.set(options, v);
}

std::string nearestSettingName(const std::string& name) {
  const std::string key = lowercase(name);
  std::string best;
  std::size_t bestCost = std::numeric_limits<std::size_t>::max();
  for (const SettingRow& r : rows()) {
    const std::string full = lowercase(r.info.name);
    const std::string last = full.substr(full.rfind('.') + 1);
    // A bare field name ("medianwindow") is as near as its full path: the cost of the prefix is waived.
    const std::size_t cost = std::min(editDistance(key, full), editDistance(key, last));
    if (cost < bestCost) bestCost = cost, best = r.info.name;
  }
  return best;
}

std::string formatSettingTable(const AutoSkeletonOptions& options) {
  std::ostringstream s;
  std::size_t width = 0;
  for (const SettingRow& r : rows()) width = std::max(width, r.info.name.size());
  for (const SettingRow& r : rows()) {
    const SettingInfo& i = r.info;
    const std::string range =
        i.type == SettingType::Boolean ? "true/false" : "[" + formatNumber(i.min) + ", " + formatNumber(i.max) + "]";
    char line[512];
    std::snprintf(line, sizeof line, "%-*s  %-7s  %-18s  = %-8s  %s\n", static_cast<int>(width), i.name.c_str(),
                  typeName(i.type), range.c_str(), formatSettingValue(i, r.get(options)).c_str(), i.help.c_str());
    s << line;
  }
  return s.str();
}

std::string formatSettingValue(const SettingInfo& setting, double value) {
  if (setting.type == SettingType::Boolean) return value != 0 ? "true" : "false";
  return formatNumber(value);
}

}  // namespace treesketch::skeleton
