#!/usr/bin/python3
"""The paper's Fig. 5 (docs/theory.md 14.3, verification.md T5/T10b): 2D block normal impact at
1 km/s, quasi-implicit against explicit joints (limit (19) off) at S = 0.5, 0.1, 0.05.

usage: /usr/bin/python3 scripts/paper/fig5.py [--force]

Runs inputs/paper/fig5_{implicit,explicit}_S{0.5,0.1,0.05}.yaml through scpdyn (one thread) into
out/paper/fig5/<deck>/ when their outputs are missing, draws the normal stress -sxx in the
target element next to the centre of the interface and the interface velocity into
out/paper/fig5.png (a stopped run is drawn up to its stop, marked x), and prints per run: status,
plateau of -sxx over 0.4-1.0 us (T5: 5.85 GPa), E2 against implicit S = 0.5 over 0-3 us
(T10b: <= 5 % for explicit S = 0.05), total variation / range of the stress and of the interface
node velocity over 0-3 us (smoothness: 1 for a monotone signal, +2 per extra swing), the
largest energy balance error, cycles and wall time.
"""
import argparse
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paper_util as pu  # noqa: E402

S_VALUES = ["0.5", "0.1", "0.05"]
OPTIONS = ["implicit", "explicit"]
PLATEAU = (0.4e-6, 1.0e-6)
WINDOW = (0.0, 3.0e-6)
SIGMA_REF = 5.85e9  # Z v/2, LS (verification T5)
GAUGES = ["p_target:sxx", "p_impactor:sxx"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--force", action="store_true")
    args = ap.parse_args()
    R = {}
    for o in OPTIONS:
        for S in S_VALUES:
            name = f"fig5_{o}_S{S}"
            out = os.path.join(pu.OUT, "fig5", name)
            s = pu.run(pu.deck_path(name), out, force=args.force)
            R[(o, S)] = dict(summary=s, g=pu.gauges(out), h=pu.history(out))

    fig, axes = plt.subplots(1, 2, figsize=(13, 4.6))
    colors = {"0.5": "tab:blue", "0.1": "tab:orange", "0.05": "tab:green"}
    for (o, S), r in R.items():
        g, s = r["g"], r["summary"]
        ls = "-" if o == "implicit" else "--"
        lab = f"{o} S = {S}" + (" (stopped)" if pu.failed(s) else "")
        t = g["time"] * 1e6
        for ax, key, scale in ((axes[0], "p_target:sxx", -1e-9), (axes[1], "v_target:vx", 1.0)):
            ax.plot(t, g[key] * scale, ls, color=colors[S], lw=1.3, label=lab)
            if pu.failed(s) and len(t):
                ax.plot(t[-1], g[key][-1] * scale, "x", ms=10, color=colors[S])
    axes[0].axhline(SIGMA_REF * 1e-9, color="k", lw=0.7, ls=":", label="Z v/2 = 5.85 GPa")
    axes[0].set_ylabel("normal stress -sxx, target element at the interface centre (GPa)")
    axes[1].set_ylabel("x-velocity of the target's interface node (m/s)")
    axes[0].set_ylim(-1, 9)
    axes[1].set_ylim(-100, 1200)
    for ax in axes:
        ax.set_xlabel("time (us)")
        ax.set_xlim(0, 3)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Fig. 5: two 1.5 cm limestone blocks (15x15 / 16x16), 1 km/s, a = 0.2 mm, "
                 "E0 = 0.5 GPa; explicit with the limit (19) off", fontsize=11)
    fig.tight_layout()
    pu.save_figure(fig, "fig5")

    ref = R[("implicit", "0.5")]["g"]
    refs = [(ref["time"], ref[k]) for k in GAUGES]
    print("\n| run | status | -sxx plateau 0.4-1 us (GPa) | error vs 5.85 | E2 vs implicit S=0.5 "
          "| TV/range sxx, vx | max energy error | cycles | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for (o, S), r in R.items():
        g, s = r["g"], r["summary"]
        t = g["time"]
        m = (t >= PLATEAU[0]) & (t <= PLATEAU[1])
        stopped = pu.failed(s)
        plateau = -np.mean([g[k][m].mean() for k in GAUGES]) if m.any() and t[-1] >= PLATEAU[1] else None
        e2 = pu.e2_norm([(t, g[k]) for k in GAUGES], refs, WINDOW) if (o, S) != ("implicit", "0.5") else 0.0
        tv = pu.total_variation(t, g["p_target:sxx"], WINDOW)
        tv_v = pu.total_variation(t, g["v_target:vx"], WINDOW)
        emax = s.get("energy_balance_error_max", float("nan"))
        status = "completed" if not stopped else "stopped: " + pu.short_error(s)
        print(f"| {o} S = {S} | {status} | {'-' if plateau is None else '%.3f' % (plateau * 1e-9)} "
              f"| {'-' if plateau is None else '%+.1f %%' % (100 * (plateau / SIGMA_REF - 1))} "
              f"| {'-' if e2 is None else '%.3f' % e2} | {tv:.1f}, {tv_v:.1f} | {emax:.2e} | {s['cycles']} "
              f"| {s['wall_time']:.2f} |")
    print("\nExpected (docs/theory.md 14.3): explicit S = 0.5 crashes, S = 0.1 unstable, "
          "S = 0.05 agrees with implicit; implicit stable and smooth at S = 0.5.")


if __name__ == "__main__":
    main()
