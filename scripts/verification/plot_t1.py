#!/usr/bin/python3
"""Verification T1a: 1D elastic plate impact (inputs/verification/t1_plate_impact.yaml).

Runs the deck through build/bin/scpdyn if out/t1_plate_impact is missing, then plots the
mid-target stress against d'Alembert's solution and prints the measured errors.
usage: /usr/bin/python3 scripts/verification/plot_t1.py [OUTPUT_DIR]
"""
import csv
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DECK = os.path.join(ROOT, "inputs", "verification", "t1_plate_impact.yaml")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "t1_plate_impact")
    if not os.path.exists(os.path.join(out, "gauges.csv")):
        subprocess.run([os.path.join(ROOT, "build", "bin", "scpdyn"), DECK, "-o", out], check=True)
    with open(os.path.join(out, "gauges.csv")) as f:
        rows = list(csv.DictReader(f))
    t = [float(r["time"]) for r in rows]
    s = [float(r["target_mid:sxx"]) for r in rows]
    rho, E, nu, v, L, h = 7850.0, 200e9, 0.3, 10.0, 0.1, 0.001
    c = math.sqrt(E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho)
    sigma = -rho * c * v / 2
    # gauge element centre at 1.5 L + h/2; plateau until the free-end reflection returns
    ta, dur = (0.5 * L + h / 2) / c, 2 * (0.5 * L - h / 2) / c
    exact = [sigma if ta <= x < ta + dur else 0.0 for x in t]
    win = [k for k, x in enumerate(t) if ta + 0.2 * dur < x < ta + 0.8 * dur]
    plateau = sum(s[k] for k in win) / len(win)
    t50 = next(x for x, y in zip(t, s) if y < 0.5 * sigma)
    print(f"T1a plateau {plateau:.6e} Pa, exact {sigma:.6e} Pa, error {plateau / sigma - 1:.2e}")
    print(f"T1a arrival {t50 * 1e6:.4f} us, exact {ta * 1e6:.4f} us, {(t50 - ta) / (h / c):.2f} h/c")
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.plot([1e6 * x for x in t], [1e-6 * y for y in s], label="scpdyn (quad4, h = 1 mm, S = 0.5)")
    ax.plot([1e6 * x for x in t], [1e-6 * y for y in exact], "k--", lw=1, label="d'Alembert")
    ax.set_xlabel("time [us]")
    ax.set_ylabel("sigma_xx at mid-target [MPa]")
    ax.set_title(f"T1a plate impact: plateau error {100 * (plateau / sigma - 1):.3f} %")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path = os.path.join(out, "t1_plate_impact.png")
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
