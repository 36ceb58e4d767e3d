#!/usr/bin/env python3
"""The leaf-off volume table of the evaluation report, from an evaluation's summary.csv.

    treesketch evaluate --trees TREES --matrix full --no-leaf-on --methods skeleton --no-sweep \\
        --out docs/evaluation/volume/matrix
    python3 scripts/volume_table.py docs/evaluation/volume/matrix/summary.csv [--update docs/evaluation/README.md]

Prints one row per condition: the cases judged (and set aside as sparse) per half, the mean
absolute volume error with the worst case and its tree, and the share of the volume on fitted
circles. A second table gives what a user of `reconstruct --report` would be told on the same
scans: how many volume ranges hold the true volume, and how many models the verdict calls
trusted, with the worst of those (a trusted model far off is a silent error). With --update,
replaces the tables between the report's volume-matrix markers.
"""
import argparse
import csv
import os
import sys

BEGIN, END = "<!-- volume-matrix -->", "<!-- /volume-matrix -->"


def table(summary_path):
    with open(summary_path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["leaf"] == "leaf-off" and r["method"] == "skeleton"]
    conditions = []
    for r in rows:
        if r["condition"] not in conditions:
            conditions.append(r["condition"])
    by = {(r["condition"], r["half"]): r for r in rows}

    def judged(r):
        return "%s (%s)" % (r["volume_judged"], r["sparse"]) if r else "—"

    def has_volume(r):
        return r and r["volume_judged"] not in ("", "0") and r["volume_error_mean_abs_pct"] != ""

    def error(r):
        if not has_volume(r):
            return "—"
        return "%.1f (%+.1f, %s)" % (float(r["volume_error_mean_abs_pct"]), float(r["volume_error_worst_pct"]),
                                     r["volume_worst_tree"])

    def share(r):
        if not has_volume(r) or r["measured_volume_share_mean"] == "":
            return "—"
        return "%.0f" % (100 * float(r["measured_volume_share_mean"]))

    lines = ["| condition | judged (sparse) | tuning: mean abs. error % (worst, tree) | "
             "held-out: mean abs. error % (worst, tree) | measured share % |",
             "|---|---:|---|---|---:|"]
    for c in conditions:
        t, h = by.get((c, "tune")), by.get((c, "held-out"))
        lines.append("| %s | %s / %s | %s | %s | %s / %s |" % (c, judged(t), judged(h), error(t), error(h), share(t),
                                                              share(h)))
    lines += ["", "| condition | range holds the true volume: tuning / held-out | trusted: tuning, worst % (tree) | "
              "trusted: held-out, worst % (tree) |", "|---|---:|---|---|"]

    def holds(r):
        if not has_volume(r) or r.get("volume_ranged", "") in ("", "0"):
            return "—"
        return "%s of %s" % (r["volume_range_holds"], r["volume_ranged"])

    def trusted(r):
        if not has_volume(r) or r.get("verdict_trusted", "") == "":
            return "—"
        n = int(r["verdict_trusted"])
        if n == 0:
            return "0"
        return "%d (%+.1f, %s)" % (n, float(r["volume_error_worst_trusted_pct"]), r["volume_worst_trusted_tree"])

    for c in conditions:
        t, h = by.get((c, "tune")), by.get((c, "held-out"))
        if not (has_volume(t) or has_volume(h)):
            continue
        lines.append("| %s | %s / %s | %s | %s |" % (c, holds(t), holds(h), trusted(t), trusted(h)))
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("summary", help="an evaluation's summary.csv")
    ap.add_argument("--update", metavar="REPORT", help="replace the table between the volume-matrix markers")
    args = ap.parse_args()
    text = table(args.summary)
    if not args.update:
        print(text)
        return 0
    with open(args.update) as f:
        report = f.read()
    if report.count(BEGIN) != 1 or report.count(END) != 1 or report.index(BEGIN) > report.index(END):
        sys.stderr.write("%s: expected one %s ... %s block\n" % (args.update, BEGIN, END))
        return 2
    head, rest = report.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    tmp = args.update + ".tmp"
    with open(tmp, "w") as f:
        f.write(head + BEGIN + "\n" + text + "\n" + END + tail)
    os.replace(tmp, args.update)
    return 0


if __name__ == "__main__":
    sys.exit(main())
