#!/usr/bin/python3
"""Plot a run's gauges (gauges.csv, if the deck has gauges) and energies (history.csv) into
gauges.png.

usage: /usr/bin/python3 scripts/plot_gauges.py OUTPUT_DIR
One panel per gauge quantity kind (stress, velocity, ...), time in microseconds.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    head, data = rows[0], rows[1:]
    return {h: [float(r[k]) for r in data] for k, h in enumerate(head)}


# element quantities in Pa (docs/input.md)
STRESSES = ("sxx", "syy", "szz", "sxy", "syz", "szx", "pressure", "q")


def main(out_dir):
    # scpdyn writes gauges.csv only when the deck has gauges
    gauges_path = os.path.join(out_dir, "gauges.csv")
    gauges = read_csv(gauges_path) if os.path.exists(gauges_path) else {"time": []}
    history = read_csv(os.path.join(out_dir, "history.csv"))
    t = [1e6 * x for x in gauges["time"]]
    groups = {}
    for col in gauges:
        if col == "time":
            continue
        q = col.split(":")[-1]
        kind = "stress / pressure [MPa]" if q in STRESSES else q
        kind = "velocity [m/s]" if q in ("vx", "vy", "vz") else kind
        kind = "displacement [mm]" if q in ("dx", "dy", "dz") else kind
        kind = "joint stress [MPa], compression +" if q in ("normal_stress", "shear_stress") else kind
        kind = "joint closure, slip [mm]" if q in ("closure", "slip") else kind
        groups.setdefault(kind, []).append(col)
    n = len(groups) + 1
    fig, axes = plt.subplots(n, 1, figsize=(8, 2.6 * n), sharex=True, squeeze=False)
    for ax, (kind, cols) in zip(axes[:, 0], sorted(groups.items())):
        scale = 1e-6 if "MPa" in kind else 1e3 if "[mm]" in kind else 1.0
        for c in cols:
            ax.plot(t, [scale * v for v in gauges[c]], label=c)
        ax.set_ylabel(kind)
        ax.legend(fontsize=7, ncol=2)
        ax.grid(alpha=0.3)
    ax = axes[-1, 0]
    th = [1e6 * x for x in history["time"]]
    for key in ("kinetic", "internal", "hourglass", "external_work", "contact"):
        if key not in history:
            continue
        ax.plot(th, history[key], label=key)
    ax.set_ylabel("energy [J]")
    ax.set_xlabel("time [us]")
    ax.legend(fontsize=7, ncol=4)
    ax.grid(alpha=0.3)
    err = max(abs(v) for v in history["energy_balance_error"])
    fig.suptitle(f"{os.path.basename(os.path.normpath(out_dir))}  (max energy balance error {err:.2e})")
    fig.tight_layout()
    path = os.path.join(out_dir, "gauges.png")
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
