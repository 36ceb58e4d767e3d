// The evaluation's report: the rows of runEvaluation as Markdown and CSV tables, the thesis's
// plots and the robustness plots, written together into one folder.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "treesketch/eval/evaluation.h"

namespace treesketch::eval {

/// Table 5.1/5.2 layout, one table per condition and leaf state (main rows only), each followed
/// by its means per method and half.
std::string markdownTable(const std::vector<EvalRow>& rows);
/// The per-condition summary: scale, split, flags and root check stated, then per method and
/// leaf state one table with a row per condition, every cell "tune / held-out".
std::string markdownSummary(const std::vector<EvalRow>& rows, const std::vector<ScanCondition>& conditions = {});
/// All rows, with a header line.
std::string csvTable(const std::vector<EvalRow>& rows);
/// summarize() as CSV.
std::string csvSummary(const std::vector<ConditionSummary>& summaries);
/// Writes into `folder` (created if missing): table.md, summary.md, results.csv, summary.csv, the
/// thesis's plots from the first condition (fig_5_12_backward_vs_forward.svg,
/// fig_5_13_user_vs_auto.svg, fig_5_14_rms_vs_nodes.svg) and the robustness plots
/// (fig_{backward,forward}_vs_wood_points.svg: every case, log-log; fig_{backward,forward}_vs_noise.svg:
/// mean per method and half over the noise conditions). `conditions` (optional) adds the
/// matrix's settings to summary.md; `settings` (optional: the automatic model's `--set`
/// assignments) heads summary.md.
void writeReport(const std::filesystem::path& folder, const std::vector<EvalRow>& rows,
                 const std::vector<ScanCondition>& conditions = {},
                 const std::vector<std::string>& settings = {});

}  // namespace treesketch::eval
