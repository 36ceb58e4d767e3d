// The evaluation's report: its tables as Markdown and CSV, its plots, and the folder that holds
// them all (see evaluation.h for the rows).
#include "treesketch/eval/evaluation_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "treesketch/eval/svg_plot.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::eval {

namespace fs = std::filesystem;

namespace {

std::string f2(double v) {
  if (!std::isfinite(v)) return std::isinf(v) ? "∞" : "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}
std::string f3(double v) {
  if (!std::isfinite(v)) return std::isinf(v) ? "∞" : "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

/// A fraction as a percentage with one decimal ("12.3"), "—" when unknown.
std::string pct1(double fraction) {
  if (!std::isfinite(fraction)) return "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", 100.0 * fraction);
  return buf;
}
/// The same with its sign ("+12.3", "-4.0").
std::string signedPct1(double fraction) {
  if (!std::isfinite(fraction)) return "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.1f", 100.0 * fraction);
  return buf;
}

/// "+3.2 (81)": the model's volume error and its measured share, % ("—" without a volume error).
std::string volumeCell(const EvalRow& r) {
  if (!std::isfinite(r.volumeError)) return "—";
  return signedPct1(r.volumeError) + " (" + pct1(r.measuredVolumeShare) + ")";
}

std::string flagsOf(const EvalRow& r) {
  std::string f;
  if (r.sparse) f = "sparse";
  if (r.backwardOnly) f += std::string(f.empty() ? "" : ", ") + "backward only";
  return f;
}

/// (condition, leaf) groups of the main rows, in first-seen order.
std::vector<std::pair<std::string, std::string>> conditionGroups(const std::vector<EvalRow>& rows) {
  std::vector<std::pair<std::string, std::string>> groups;
  for (const auto& r : rows) {
    auto key = std::make_pair(r.condition, r.leaf);
    if (std::find(groups.begin(), groups.end(), key) == groups.end()) groups.push_back(key);
  }
  return groups;
}

/// The rows' scales as text ("1 unit = 0.1 m (14 trees)").
std::string scaleText(const std::vector<EvalRow>& rows) {
  std::map<double, std::set<std::string>> trees;
  for (const auto& r : rows) trees[r.metresPerUnit].insert(r.tree);
  std::string s;
  for (const auto& [mpu, names] : trees) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "1 scene unit = %g m (%zu tree%s)", mpu, names.size(), names.size() == 1 ? "" : "s");
    s += (s.empty() ? "" : "; ") + std::string(buf);
  }
  return s;
}

}  // namespace

std::string markdownTable(const std::vector<EvalRow>& rows) {
  std::ostringstream s;
  const auto summaries = summarize(rows);
  if (!rows.empty()) s << "Scale: " << scaleText(rows) << ".\n\n";
  for (const auto& [condition, leaf] : conditionGroups(rows)) {
    s << "### " << condition << ", " << leaf << "\n\n";
    s << "| tree | half | method | nodes (fitted) | tips (limbs) | root offset % | reconstruct ms | points | wood "
         "points "
         "| wood % | samples | bbox diag | back max % | back mean % | back RMS % | fwd max % | fwd mean % | fwd RMS % "
         "| volume error % (measured %) | flags |\n";
    s << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const auto& r : rows) {
      if (r.condition != condition || r.leaf != leaf || r.sweep) continue;
      s << "| " << r.tree << " | " << r.half << " | " << r.method << " | " << r.nodes << " (" << r.fitted << ") | "
        << r.tips << " (" << r.referenceLimbs << ") | " << f2(r.rootOffsetPct) << " | " << f2(r.reconstructMs) << " | "
        << r.points << " | " << r.woodPoints << " | " << f2(100.0 * r.woodFraction) << " | " << r.samples << " | "
        << f2(r.bboxDiagonal) << " | " << f3(r.backwardMax) << " | " << f3(r.backwardMean) << " | " << f3(r.backwardRms)
        << " | " << f3(r.forwardMax) << " | " << f3(r.forwardMean) << " | " << f3(r.forwardRms) << " | "
        << volumeCell(r) << " | " << flagsOf(r) << " |\n";
    }
    s << "\nMean and worst case over the judged trees of each half (sparse cases and cases without a mesh left out, "
         "counted):\n\n| method | half | judged (sparse, no mesh) | back RMS mean % | back RMS worst % | fwd RMS mean "
         "% "
         "| fwd RMS worst % | volume error mean abs. % | volume error worst % |\n|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& m : summaries) {
      if (m.condition != condition || m.leaf != leaf) continue;
      std::string open = m.forwardJudged ? "" : "(", close = m.forwardJudged ? "" : ")";
      s << "| " << m.method << " | " << m.half << " | " << m.judged << " of " << m.cases << " (" << m.sparse << ", "
        << m.noMesh << ") | " << f3(m.backwardMean) << " | " << f3(m.backwardWorst) << " | " << open
        << f3(m.forwardMean) << close << " | " << open << f3(m.forwardWorst) << close << " | "
        << pct1(m.volumeErrorMeanAbs) << " | " << signedPct1(m.volumeErrorWorst) << " |\n";
    }
    s << "\n";
  }
  return s.str();
}

namespace {

// The summary's opening notes: scale, split, what the cells mean, the judging rules.
void writeSummaryNotes(std::ostream& s, const std::vector<EvalRow>& rows, const std::vector<std::string>& tune,
                       const std::vector<std::string>& held, const std::string& cellHalves,
                       const std::vector<ScanCondition>& conditions) {
  s << "# Evaluation summary\n\n";
  const bool ezTree =
      std::any_of(rows.begin(), rows.end(), [](const EvalRow& r) { return r.metresPerUnit == kEzTreeMetresPerUnit; });
  s << "- Scale: " << (rows.empty() ? std::string("no rows") : scaleText(rows))
    << ". Physical scan settings (station height, range noise in mm) are converted with it"
    << (ezTree ? "; the ez-tree trees are taken as decimetres (a tree 25-65 units tall is 2.5-6.5 m)" : "") << ".\n";
  s << "- Split: tuning half (" << tune.size() << "): " << (tune.empty() ? "—" : "");
  for (std::size_t i = 0; i < tune.size(); ++i) s << (i ? ", " : "") << tune[i];
  s << "; held-out half (" << held.size() << "): " << (held.empty() ? "—" : "");
  for (std::size_t i = 0; i < held.size(); ++i) s << (i ? ", " : "") << held[i];
  s << ". Every cell below is `" << cellHalves << "`.\n";
  s << "- RMS distances are % of the reference (branch mesh) bounding-box diagonal; backward: the reconstruction "
       "sampled against the branch mesh, forward: the branch mesh against the reconstruction. Worst = max over "
       "the trees of the half.\n";
  s << "- Judged cases: a case with fewer than " << kSparseWoodPoints
    << " wood points is flagged sparse and left out (counted); so is a case without a mesh. One-station TLS cannot "
       "see the far side: its forward RMS and tips ratio are shown in parentheses, not judged.\n";
  s << "- Tips / limbs: the method's sketch tips over the reference's limbs, min–max over the judged trees (target "
    << kTipsRatioMin << "–" << kTipsRatioMax << ").\n";
  s << "- Root at base: judged trees whose sketch root lies within " << kRootAtBasePct
    << " % of the diagonal of the reference trunk base (the first centre of the reference skeleton's root limb), "
       "and the largest such distance (∞: no root located).\n\n";
  if (!conditions.empty()) s << "## Conditions\n\n" << conditionTable(conditions) << "\n";
}

// One table cell: the halves' values of f for (condition, leaf, method), "tune / held-out".
std::string summaryCell(const std::vector<ConditionSummary>& summaries, const std::vector<std::string>& halves,
                        const std::string& condition, const std::string& leaf, const std::string& method,
                        const std::function<std::string(const ConditionSummary&)>& f) {
  std::string out;
  for (const auto& h : halves) {
    std::string v = "—";
    for (const auto& m : summaries)
      if (m.condition == condition && m.leaf == leaf && m.method == method && m.half == h) v = f(m);
    out += (out.empty() ? "" : " / ") + v;
  }
  return out;
}

// The table of one method and leaf state: a row per condition.
void writeMethodTable(std::ostream& s, const std::vector<ConditionSummary>& summaries,
                      const std::vector<std::string>& halves, const std::string& leaf, const std::string& method) {
  auto cell = [&](const std::string& condition, const std::function<std::string(const ConditionSummary&)>& f) {
    return summaryCell(summaries, halves, condition, leaf, method, f);
  };
  std::vector<std::string> conds;
  for (const auto& m : summaries)
    if (m.leaf == leaf && m.method == method && std::find(conds.begin(), conds.end(), m.condition) == conds.end())
      conds.push_back(m.condition);
  if (conds.empty()) return;
  s << "## " << method << ", " << leaf << "\n\n";
  s << "| condition | factor | wood points | judged (sparse, no mesh) | back RMS mean % | back RMS worst % | fwd "
       "RMS "
       "mean % | fwd RMS worst % | tips / limbs | root at base (max offset %) |\n";
  s << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& cond : conds) {
    std::string factor;
    for (const auto& m : summaries)
      if (m.condition == cond) factor = m.factor;
    s << "| " << cond << " | " << factor << " | "
      << cell(cond,
              [](const ConditionSummary& m) {
                return m.woodPointsMin == m.woodPointsMax
                           ? std::to_string(m.woodPointsMin)
                           : std::to_string(m.woodPointsMin) + "–" + std::to_string(m.woodPointsMax);
              })
      << " | "
      << cell(cond,
              [](const ConditionSummary& m) {
                return std::to_string(m.judged) + " (" + std::to_string(m.sparse) + ", " + std::to_string(m.noMesh) +
                       ")";
              })
      << " | " << cell(cond, [](const ConditionSummary& m) { return f3(m.backwardMean); }) << " | "
      << cell(cond, [](const ConditionSummary& m) { return f3(m.backwardWorst); }) << " | "
      << cell(cond,
              [](const ConditionSummary& m) {
                return m.forwardJudged || m.judged == 0 ? f3(m.forwardMean) : "(" + f3(m.forwardMean) + ")";
              })
      << " | "
      << cell(cond,
              [](const ConditionSummary& m) {
                return m.forwardJudged || m.judged == 0 ? f3(m.forwardWorst) : "(" + f3(m.forwardWorst) + ")";
              })
      << " | "
      << cell(cond,
              [](const ConditionSummary& m) {
                if (m.judged == 0) return std::string("—");
                std::string v = m.tipsRatioMin == m.tipsRatioMax ? f2(m.tipsRatioMin)
                                                                 : f2(m.tipsRatioMin) + "–" + f2(m.tipsRatioMax);
                return m.forwardJudged ? v : "(" + v + ")";
              })
      << " | "
      << cell(cond,
              [](const ConditionSummary& m) {
                if (m.judged == 0) return std::string("—");
                return std::to_string(m.rootAtBase) + "/" + std::to_string(m.judged) + " (" + f2(m.rootOffsetWorst) +
                       ")";
              })
      << " |\n";
  }
  s << "\n";
}

// The volume table of one method and leaf state (methods with a cylinder model and trees with a
// known volume only): a row per condition.
void writeVolumeTable(std::ostream& s, const std::vector<ConditionSummary>& summaries,
                      const std::vector<std::string>& halves, const std::string& leaf, const std::string& method) {
  std::vector<std::string> conds;
  for (const auto& m : summaries)
    if (m.leaf == leaf && m.method == method && m.volumeJudged > 0 &&
        std::find(conds.begin(), conds.end(), m.condition) == conds.end())
      conds.push_back(m.condition);
  if (conds.empty()) return;
  auto cell = [&](const std::string& condition, const std::function<std::string(const ConditionSummary&)>& f) {
    return summaryCell(summaries, halves, condition, leaf, method, f);
  };
  s << "## Volume, " << method << ", " << leaf << "\n\n";
  s << "The model's wood volume against the tree's (its branch mesh's exact volume), judged cases: mean of the "
       "absolute relative error, the worst case with its tree, and the mean share of the model's volume on "
       "fitted circles; then how many of the cases with a volume range (`reconstruct --report`'s) have the true "
       "volume inside it, and how many the model's verdict calls trusted, with the worst of those.\n\n";
  s << "| condition | judged | volume error mean abs. % | volume error worst % (tree) | measured share % | range holds "
       "the truth | trusted: cases, worst % (tree) |\n";
  s << "|---|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& cond : conds) {
    s << "| " << cond << " | " << cell(cond, [](const ConditionSummary& m) { return std::to_string(m.volumeJudged); })
      << " | " << cell(cond, [](const ConditionSummary& m) { return pct1(m.volumeErrorMeanAbs); }) << " | "
      << cell(cond,
              [](const ConditionSummary& m) {
                return m.volumeJudged == 0 ? std::string("—")
                                           : signedPct1(m.volumeErrorWorst) + " (" + m.volumeWorstTree + ")";
              })
      << " | " << cell(cond, [](const ConditionSummary& m) { return pct1(m.measuredVolumeShareMean); }) << " | "
      << cell(cond,
              [](const ConditionSummary& m) {
                return m.volumeRanged == 0 ? std::string("—")
                                           : std::to_string(m.volumeRangeHolds) + " of " + std::to_string(m.volumeRanged);
              })
      << " | "
      << cell(cond,
              [](const ConditionSummary& m) {
                return m.verdictTrusted == 0 ? std::string("0")
                                             : std::to_string(m.verdictTrusted) + ", " +
                                                   signedPct1(m.volumeErrorWorstTrusted) + " (" +
                                                   m.volumeWorstTrustedTree + ")";
              })
      << " |\n";
  }
  s << "\n";
}

}  // namespace

std::string markdownSummary(const std::vector<EvalRow>& rows, const std::vector<ScanCondition>& conditions) {
  std::ostringstream s;
  const auto summaries = summarize(rows);
  std::vector<std::string> halves, methods, tune, held;
  for (const char* h : {"tune", "held-out"})
    if (std::any_of(rows.begin(), rows.end(), [&](const EvalRow& r) { return r.half == h; })) halves.push_back(h);
  if (std::any_of(rows.begin(), rows.end(), [](const EvalRow& r) { return r.method == "skeleton"; }))
    methods.push_back("skeleton");
  for (const auto& r : rows) {
    if (std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
    auto& list = r.half == "tune" ? tune : held;
    if (std::find(list.begin(), list.end(), r.tree) == list.end()) list.push_back(r.tree);
  }
  std::string cellHalves;
  for (const auto& h : halves) cellHalves += (cellHalves.empty() ? "" : " / ") + h;

  writeSummaryNotes(s, rows, tune, held, cellHalves, conditions);
  for (const auto& leaf : {std::string("leaf-off"), std::string("leaf-on")})
    for (const auto& method : methods) writeMethodTable(s, summaries, halves, leaf, method);
  for (const auto& leaf : {std::string("leaf-off"), std::string("leaf-on")})
    for (const auto& method : methods) writeVolumeTable(s, summaries, halves, leaf, method);
  return s.str();
}

std::string csvTable(const std::vector<EvalRow>& rows) {
  std::ostringstream s;
  s << "tree,half,condition,factor,pattern,leaf,method,sweep,nodes,fitted,points,wood_points,wood_fraction,rays,"
       "stations,step_deg,range_noise_mm,metres_per_unit,reconstruct_ms,samples,bbox_diagonal,backward_max_pct,"
       "backward_mean_pct,backward_rms_pct,forward_max_pct,forward_mean_pct,forward_rms_pct,mesh_triangles,tips,"
       "reference_limbs,root_offset_pct,root_at_base,sparse,backward_only,true_volume,model_volume,volume_error,"
       "measured_volume_share,rejected_by,skipped_off_limb,skipped_hidden,skipped_classed_leaf,skipped_rejected,"
       "fitted_on_limb,verdict,volume_low,volume_high\n";
  s.precision(9);
  for (const auto& r : rows) {
    s << r.tree << "," << r.half << "," << r.condition << "," << r.factor << "," << r.pattern << "," << r.leaf << ","
      << r.method << "," << (r.sweep ? 1 : 0) << "," << r.nodes << "," << r.fitted << "," << r.points << ","
      << r.woodPoints << "," << r.woodFraction << "," << r.rays << "," << r.stations << "," << r.stepDeg << ","
      << r.rangeNoiseMm << "," << r.metresPerUnit << "," << r.reconstructMs << "," << r.samples << "," << r.bboxDiagonal
      << "," << r.backwardMax << "," << r.backwardMean << "," << r.backwardRms << "," << r.forwardMax << ","
      << r.forwardMean << "," << r.forwardRms << "," << r.meshTriangles << "," << r.tips << "," << r.referenceLimbs
      << "," << r.rootOffsetPct << "," << (r.rootAtBase ? 1 : 0) << "," << (r.sparse ? 1 : 0) << ","
      << (r.backwardOnly ? 1 : 0) << "," << r.trueVolume << "," << r.modelVolume << "," << r.volumeError << ","
      << r.measuredVolumeShare << "," << r.rejectedBy << "," << r.skippedOffLimb << "," << r.skippedHidden << ","
      << r.skippedClassedLeaf << "," << r.skippedRejected << "," << r.fittedOnLimb << "," << r.verdict << ","
      << r.volumeLow << "," << r.volumeHigh << "\n";
  }
  return s.str();
}

std::string csvSummary(const std::vector<ConditionSummary>& summaries) {
  std::ostringstream s;
  s << "condition,factor,leaf,method,half,cases,sparse,no_mesh,judged,forward_judged,wood_points_min,wood_points_max,"
       "backward_rms_mean_pct,backward_rms_worst_pct,backward_worst_tree,forward_rms_mean_pct,forward_rms_worst_pct,"
       "forward_worst_tree,tips_ratio_min,tips_ratio_max,tips_ratio_in_band,root_at_base,root_offset_worst_pct,"
       "volume_judged,volume_error_mean_abs_pct,volume_error_worst_pct,volume_worst_tree,measured_volume_share_mean,"
       "volume_ranged,volume_range_holds,verdict_trusted,volume_error_worst_trusted_pct,volume_worst_trusted_tree\n";
  s.precision(9);
  for (const auto& m : summaries) {
    s << m.condition << "," << m.factor << "," << m.leaf << "," << m.method << "," << m.half << "," << m.cases << ","
      << m.sparse << "," << m.noMesh << "," << m.judged << "," << (m.forwardJudged ? 1 : 0) << "," << m.woodPointsMin
      << "," << m.woodPointsMax << "," << m.backwardMean << "," << m.backwardWorst << "," << m.backwardWorstTree << ","
      << m.forwardMean << "," << m.forwardWorst << "," << m.forwardWorstTree << "," << m.tipsRatioMin << ","
      << m.tipsRatioMax << "," << m.tipsRatioInBand << "," << m.rootAtBase << "," << m.rootOffsetWorst << ","
      << m.volumeJudged << "," << 100.0 * m.volumeErrorMeanAbs << "," << 100.0 * m.volumeErrorWorst << ","
      << m.volumeWorstTree << "," << m.measuredVolumeShareMean << "," << m.volumeRanged << "," << m.volumeRangeHolds
      << "," << m.verdictTrusted << "," << 100.0 * m.volumeErrorWorstTrusted << "," << m.volumeWorstTrustedTree << "\n";
  }
  return s.str();
}

namespace {

/// The thesis's figures 5.12-5.14 from the first condition (leaf-on when it has it).
void writeThesisPlots(const fs::path& folder, const std::vector<EvalRow>& rows) {
  const std::string condition = rows.front().condition;
  std::string leaf = "leaf-off";
  for (const auto& r : rows)
    if (r.condition == condition && r.leaf == "leaf-on") leaf = "leaf-on";
  const std::string label = condition + ", " + leaf;
  std::vector<std::string> trees, methods;
  for (const auto& r : rows) {
    if (std::find(trees.begin(), trees.end(), r.tree) == trees.end()) trees.push_back(r.tree);
    if (!r.sweep && std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
  }
  auto find = [&](const std::string& tree, const std::string& method) -> const EvalRow* {
    for (const auto& r : rows)
      if (!r.sweep && r.tree == tree && r.method == method && r.condition == condition && r.leaf == leaf) return &r;
    return nullptr;
  };
  std::string userMethod = std::find(methods.begin(), methods.end(), "user") != methods.end() ? "user" : methods[0];

  BarChart f12;
  f12.title = "Backward vs forward RMS per tree (" + userMethod + ", " + label + ")";
  f12.yLabel = "RMS, % of bbox diagonal";
  f12.groups = trees;
  f12.series = {"backward", "forward"};
  f12.values.assign(2, std::vector<double>(trees.size(), NAN));
  for (std::size_t t = 0; t < trees.size(); ++t) {
    if (const EvalRow* r = find(trees[t], userMethod)) {
      f12.values[0][t] = r->backwardRms;
      f12.values[1][t] = r->forwardRms;
    }
  }
  writeSvg(folder / "fig_5_12_backward_vs_forward.svg", renderSvg(f12));

  BarChart f13;
  f13.title = "Backward RMS per tree and method (" + label + ")";
  f13.yLabel = "backward RMS, % of bbox diagonal";
  f13.groups = trees;
  f13.series = methods;
  f13.values.assign(methods.size(), std::vector<double>(trees.size(), NAN));
  for (std::size_t m = 0; m < methods.size(); ++m)
    for (std::size_t t = 0; t < trees.size(); ++t)
      if (const EvalRow* r = find(trees[t], methods[m])) f13.values[m][t] = r->backwardRms;
  writeSvg(folder / "fig_5_13_user_vs_auto.svg", renderSvg(f13));

  LineChart f14;
  f14.title = "Backward RMS vs sketch nodes (simulated user, " + label + ")";
  f14.xLabel = "sketch nodes";
  f14.yLabel = "backward RMS, % of bbox diagonal";
  for (const auto& tree : trees) {
    std::vector<std::pair<double, double>> pts;
    for (const auto& r : rows)
      if (r.sweep && r.tree == tree && r.condition == condition && r.leaf == leaf)
        pts.emplace_back(r.nodes, r.backwardRms);
    if (pts.empty()) continue;
    std::sort(pts.begin(), pts.end());
    f14.series.push_back(tree);
    f14.xs.emplace_back();
    f14.ys.emplace_back();
    for (auto [x, y] : pts) {
      f14.xs.back().push_back(x);
      f14.ys.back().push_back(y);
    }
  }
  writeSvg(folder / "fig_5_14_rms_vs_nodes.svg", renderSvg(f14));
}

/// The robustness plots: RMS against wood points (every case) and against range noise (means).
void writeRobustnessPlots(const fs::path& folder, const std::vector<EvalRow>& rows) {
  std::string leaf = "leaf-on";
  for (const auto& r : rows)
    if (r.leaf == "leaf-off") leaf = "leaf-off";
  std::vector<std::string> methods;
  for (const auto& r : rows)
    if (!r.sweep && std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
  const std::vector<std::string> halves = {"tune", "held-out"};

  for (bool backward : {true, false}) {
    const std::string dir = backward ? "backward" : "forward";
    LineChart c;
    c.title = dir + " RMS vs wood points, every case (" + leaf + "; hollow: held-out trees)";
    c.xLabel = "wood points in the scan";
    c.yLabel = dir + " RMS, % of bbox diagonal";
    c.logX = c.logY = true;
    for (std::size_t m = 0; m < methods.size(); ++m) {
      for (std::size_t h = 0; h < halves.size(); ++h) {
        std::vector<double> xs, ys;
        for (const auto& r : rows) {
          if (r.sweep || r.leaf != leaf || r.method != methods[m] || r.half != halves[h]) continue;
          if (!backward && r.backwardOnly) continue;  // not judged
          xs.push_back(static_cast<double>(r.woodPoints));
          ys.push_back(backward ? r.backwardRms : r.forwardRms);
        }
        if (xs.empty()) continue;
        c.series.push_back(methods[m] + " (" + halves[h] + ")");
        c.xs.push_back(xs);
        c.ys.push_back(ys);
        c.styles.push_back(SeriesStyle{static_cast<int>(m), false, false, h == 1});
      }
    }
    writeSvg(folder / ("fig_" + dir + "_vs_wood_points.svg"), renderSvg(c));
  }

  // Noise: the TLS base and its noise variants, mean over the judged trees of each half.
  std::map<std::string, double> noiseOf;
  for (const auto& r : rows)
    if (r.pattern == "tls" && (r.factor == "noise" || r.factor == "base")) noiseOf[r.condition] = r.rangeNoiseMm;
  if (noiseOf.size() < 2) return;
  const auto summaries = summarize(rows);
  for (bool backward : {true, false}) {
    const std::string dir = backward ? "backward" : "forward";
    LineChart c;
    c.title = dir + " RMS vs range noise, mean over trees (TLS base, " + leaf + "; dashed: held-out trees)";
    c.xLabel = "range noise sigma, mm";
    c.yLabel = dir + " RMS, % of bbox diagonal";
    c.logY = true;
    for (std::size_t m = 0; m < methods.size(); ++m) {
      for (std::size_t h = 0; h < halves.size(); ++h) {
        std::vector<std::pair<double, double>> pts;
        for (const auto& s : summaries) {
          auto it = noiseOf.find(s.condition);
          if (it == noiseOf.end() || s.leaf != leaf || s.method != methods[m] || s.half != halves[h]) continue;
          pts.emplace_back(it->second, backward ? s.backwardMean : s.forwardMean);
        }
        if (pts.empty()) continue;
        std::sort(pts.begin(), pts.end());
        c.series.push_back(methods[m] + " (" + halves[h] + ")");
        c.xs.emplace_back();
        c.ys.emplace_back();
        for (auto [x, y] : pts) {
          c.xs.back().push_back(x);
          c.ys.back().push_back(y);
        }
        c.styles.push_back(SeriesStyle{static_cast<int>(m), true, h == 1, false});
      }
    }
    writeSvg(folder / ("fig_" + dir + "_vs_noise.svg"), renderSvg(c));
  }
}

}  // namespace

void writeReport(const fs::path& folder, const std::vector<EvalRow>& rows,
                 const std::vector<ScanCondition>& conditions, const std::vector<std::string>& settings) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder)) throw OutputError(folder.string() + ": cannot create the directory");
  writeFileAtomically(
      folder / "table.md", [&](std::ostream& o) { o << markdownTable(rows); }, false);
  writeFileAtomically(
      folder / "summary.md",
      [&](std::ostream& o) {
        if (!settings.empty()) {
          o << "Automatic model settings changed from the defaults (`--set`):";
          for (const std::string& s : settings) o << " `" << s << "`";
          o << "\n\n";
        }
        o << markdownSummary(rows, conditions);
      },
      false);
  writeFileAtomically(
      folder / "results.csv", [&](std::ostream& o) { o << csvTable(rows); }, false);
  writeFileAtomically(
      folder / "summary.csv", [&](std::ostream& o) { o << csvSummary(summarize(rows)); }, false);
  if (rows.empty()) return;
  writeThesisPlots(folder, rows);
  writeRobustnessPlots(folder, rows);
}

}  // namespace treesketch::eval
