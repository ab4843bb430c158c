#!/usr/bin/env python3
"""The whole-cycle benchmark as a chart: every repetition of every build from the CSV that
perf/interleave.py writes (CSV=FILE), one panel per thread count, row packs and the general
path side by side, with the goal (95 and 50 ns: 3x the DRAM floor) and the floor itself.

usage: /usr/bin/python3 perf/plot_cycle.py CSV OUT.png [BINARY=LABEL ...]
  BINARY=LABEL names a binary path of the CSV on the chart (default: its parent directory). A
  binary with both benchmarks gets "row packs" and "general" under its label.
Needs matplotlib (Debian's /usr/bin/python3).
"""
import collections
import csv
import os
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

GOAL = {"1": 95.0, "2": 50.0}   # ns per element-cycle: 3x the DRAM floor
FLOOR = {"1": 32.0, "2": 16.0}  # the reference element-cycle's DRAM time


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    names = dict(a.split("=", 1) for a in sys.argv[3:])
    data = collections.defaultdict(list)  # (threads, binary, general?) -> repetitions
    order = []
    with open(sys.argv[1]) as f:
        for row in csv.DictReader(f):
            b = row["binary"]
            if b not in order:
                order.append(b)
            data[(row["threads"], b, row["benchmark"].endswith("General"))].append(
                float(row["ns_per_elem_cycle"]))
    threads = sorted({k[0] for k in data})
    fig, axes = plt.subplots(1, len(threads), figsize=(5.5 * len(threads), 4.5), squeeze=False)
    for ax, t in zip(axes[0], threads):
        labels, series, colors = [], [], []
        for b in order:
            for general in (False, True):
                v = data.get((t, b, general))
                if v:
                    label = names.get(b, os.path.basename(os.path.dirname(b)) or b).replace(" ", "\n", 1)
                    paired = (t, b, not general) in data
                    if paired:
                        label += "\ngeneral" if general else "\nrow packs"
                    labels.append(label)
                    series.append(v)
                    colors.append("tab:gray" if not paired else
                                  "tab:orange" if general else "tab:blue")
        box = ax.boxplot(series, labels=labels, patch_artist=True, showfliers=True)
        for patch, c in zip(box["boxes"], colors):
            patch.set_facecolor(c)
            patch.set_alpha(0.5)
        for i, v in enumerate(series, start=1):
            ax.annotate(f"{statistics.median(v):.0f}", (i, statistics.median(v)),
                        xytext=(14, 0), textcoords="offset points", va="center", fontsize=8)
        ax.axhline(GOAL[t], color="tab:green", ls="--", label=f"goal {GOAL[t]:.0f} ns")
        ax.axhline(FLOOR[t], color="gray", ls=":", label=f"DRAM floor {FLOOR[t]:.0f} ns")
        ax.set_ylim(0, None)
        ax.set_title(f"whole cycle, 64³ hex8 box, {t} thread{'s' if t != '1' else ''}")
        ax.set_ylabel("ns per element-cycle (every repetition)")
        ax.tick_params(axis="x", labelsize=8)
        ax.legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    print("wrote", sys.argv[2])


if __name__ == "__main__":
    main()
