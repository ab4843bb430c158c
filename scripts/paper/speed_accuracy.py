#!/usr/bin/python3
"""Speed against accuracy of the contact updates: error against a
converged reference versus wall time, for explicit and quasi-implicit joints across Courant
numbers and resolutions, and the stability map (which combinations stop with a diverging
contact), for two scenes:

  1d  the jointed wave of Fig. 2 (soft joints a = 0.1 mm, E0 = 0.05 GPa, 1 mm blocks) with 1, 2
      and 4 cells per block; gauges (velocity) at 30, 50 and 80 mm; window 0-60 us;
      reference: implicit, 16 cells per block (h = 0.0625 mm), S = 0.25.
  2d  the block normal impact of Fig. 5 (a = 0.2 mm, E0 = 0.5 GPa, 15x15 / 16x16 quads) refined
      1x, 2x and 4x; gauges (normal stress sxx) at the interface centre on both sides and 5 mm
      into each block; window 0-3.3 us; reference: implicit, 16x (240x240 / 256x256), S = 0.25.

Updates: "implicit" (quasi-implicit), "explicit" with the time-step limit (19) switched off
(C_safe: off, the paper's Fig. 5 setting: the Courant number alone sets dt, so it can diverge)
at S = 0.8, 0.5, 0.2, 0.1, 0.05, and "explicit, limit on" (C_safe = 0.5) at S = 0.5.
Error: E2 of verification.md 0.3 over the gauges and the window. Wall time: wall_time of the
run's summary.json, with OMP_NUM_THREADS=1 (one core). In the 2D decks the impactor starts
0.3 mm short of the target (impact at 0.3 us): the first cycle's dt is set before any CP
exists, so an explicit joint closing in cycle 0 would close by v dt outside the limit (19);
1D as the Fig. 2 decks (0.222 mm).

usage: /usr/bin/python3 scripts/paper/speed_accuracy.py [1d] [2d] [--force]
Writes out/paper/speed_accuracy_{1d,2d}.png, out/paper/stability_{1d,2d}.png and
out/paper/speed_accuracy_{1d,2d}.csv; the runs go to out/paper/sweep_{1d,2d}/<run>/.
"""
import argparse
import csv
import os
import re
import sys
import time

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_fig2_decks as f2  # noqa: E402
import paper_util as pu  # noqa: E402

os.environ["OMP_NUM_THREADS"] = "1"

S_GRID = [0.8, 0.5, 0.2, 0.1, 0.05]
UPDATES = [("implicit", "implicit", None), ("explicit_off", "explicit", "off"),
           ("explicit_limit", "explicit", "0.5")]
UPDATE_LABEL = {"implicit": "quasi-implicit", "explicit_off": "explicit, limit (19) off",
                "explicit_limit": "explicit, limit (19) on (C_safe 0.5)"}
MARKER = {"implicit": "o", "explicit_off": "s", "explicit_limit": "^"}


class Scene1D:
    key = "1d"
    levels = [1, 2, 4]            # cells per block
    level_label = "cells per 1 mm block"
    reference = ("implicit", 16, 0.25)
    t_impact = f2.T_IMPACT
    window = (0.0, 60e-6)
    title = ("1D jointed wave (Fig. 2): a = 0.1 mm, E0 = 0.05 GPa, 1 mm blocks; "
             "E2 of v at 30, 50, 80 mm over 0-60 us")

    def __init__(self):
        with open(pu.deck_path("fig2_solid")) as f:  # follow the committed decks: 1D or strip
            self.strip = re.search(r"^dimension: 2", f.read(), re.M) is not None

    def text(self, option, level, S, c_safe):
        return f2.deck("sweep", option, 1e-4, level, "speed/accuracy sweep", self.strip,
                       courant=S, c_safe=c_safe or "0.5", extra_gauges=(0.03, 0.05))

    def signals(self, out):
        g = pu.gauges(out)
        return [(g["time"], g[k]) for k in ("g30:vx", "g50:vx", "g80:vx")]


class Scene2D:
    key = "2d"
    levels = [1, 2, 4]            # refinement of the 15x15 / 16x16 meshes
    level_label = "refinement (x 15x15 / 16x16)"
    reference = ("implicit", 16, 0.25)
    gap = 0.3e-3
    t_impact = gap / 1000.0
    window = (0.0, 3.3e-6)
    title = ("2D block impact (Fig. 5): a = 0.2 mm, E0 = 0.5 GPa; E2 of sxx at 4 gauges "
             "over 0-3 us after impact")

    def __init__(self):
        with open(pu.deck_path("fig5_implicit_S0.5")) as f:
            self.base = f.read()

    def text(self, option, level, S, c_safe):
        t = self.base
        subs = [
            (r"elements: \[15, 15\]", f"elements: [{15 * level}, {15 * level}]"),
            (r"elements: \[16, 16\]", f"elements: [{16 * level}, {16 * level}]"),
            (r"origin: \[0\.0, 0\.0\]", f"origin: [{-self.gap:g}, 0.0]"),
            (r"time: \{end: 3\.0e-6, courant: 0\.5\}",
             f"time: {{end: {3.0e-6 + self.gap / 1000.0:g}, courant: {S:g}}}"),
            (r"output: \{field_interval: [^}]*\}", "output: {field_interval: 0, history_interval: 0}"),
            (r"option: implicit", f"option: {option}"),
            (r"C_safe: 0\.5", f"C_safe: {c_safe or 0.5}"),
            (r"search_interval: 2", f"search_interval: 2\n  search_gap: {2 * self.gap:g}"),
        ]
        for pat, rep in subs:
            t, n = re.subn(pat, rep, t)
            if n != 1:
                raise RuntimeError(f"fig5 deck: expected one match of {pat}, found {n}")
        return f"# speed/accuracy sweep: {option}, C_safe {c_safe}, S = {S}, x{level}\n" + t

    def signals(self, out):
        g = pu.gauges(out)
        return [(g["time"], g[k]) for k in ("p_target:sxx", "p_impactor:sxx",
                                             "in_target:sxx", "in_impactor:sxx")]


def run_one(scene, update, option, c_safe, level, S, force):
    name = f"{update}_L{level}_S{S:g}"
    out = os.path.join(pu.OUT, "sweep_" + scene.key, name)
    s = pu.run(os.path.join(out, name + ".yaml"), out, force=force,
               text=scene.text(option, level, S, c_safe))
    return dict(name=name, update=update, level=level, S=S, summary=s, out=out,
                failed=pu.failed(s))


def sweep(scene, force):
    t0 = time.time()
    ro, rl, rs = scene.reference
    ref = run_one(scene, "reference", ro, None, rl, rs, force)
    if ref["failed"]:
        raise RuntimeError(f"reference run {ref['out']} stopped: {ref['summary']['error']}")
    refsig = scene.signals(ref["out"])
    runs = []
    for update, option, c_safe in UPDATES:
        for level in scene.levels:
            for S in (S_GRID if update != "explicit_limit" else [0.5]):
                r = run_one(scene, update, option, c_safe, level, S, force)
                r["e2"] = None if r["failed"] else pu.e2_norm(scene.signals(r["out"]), refsig,
                                                              scene.window)
                runs.append(r)
    print(f"{scene.key}: sweep of {len(runs) + 1} runs, {time.time() - t0:.0f} s "
          "(existing outputs are reused)")
    return ref, runs


def plot_speed(scene, ref, runs):
    fig, ax = plt.subplots(figsize=(9, 6))
    cmap = plt.get_cmap("viridis")
    scol = {S: cmap(i / (len(S_GRID) - 1)) for i, S in enumerate(S_GRID)}
    for update, _, _ in UPDATES:
        for S in S_GRID:
            pts = [r for r in runs if r["update"] == update and r["S"] == S and r["e2"] is not None]
            pts.sort(key=lambda r: r["level"])
            if not pts:
                continue
            x = [r["summary"]["wall_time"] for r in pts]
            y = [r["e2"] for r in pts]
            ls = "-" if update == "implicit" else "--" if update == "explicit_off" else ":"
            ax.plot(x, y, ls, marker=MARKER[update], color=scol[S], ms=7, lw=1.2)
            for r, xi, yi in zip(pts, x, y):
                ax.annotate(str(r["level"]), (xi, yi), fontsize=6, xytext=(3, 3),
                            textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time (s, 1 core, OMP_NUM_THREADS=1)")
    ax.set_ylabel("E2 error against the reference")
    ax.grid(alpha=0.3, which="both")
    handles = [Line2D([], [], color="k", marker=MARKER[u], ls="-" if u == "implicit" else "--" if u == "explicit_off" else ":",
                      label=UPDATE_LABEL[u]) for u, _, _ in UPDATES]
    handles += [Line2D([], [], color=scol[S], lw=3, label=f"S = {S:g}") for S in S_GRID]
    nfail = sum(r["failed"] for r in runs)
    handles.append(Line2D([], [], ls="", label=f"{nfail} of {len(runs)} runs stopped (stability map)"))
    ax.legend(handles=handles, fontsize=8, loc="best")
    rs = ref["summary"]
    ax.set_title(scene.title + f"\nreference: implicit, {scene.level_label} = {scene.reference[1]}, "
                 f"S = {scene.reference[2]} ({rs['elements']} elements, {rs['wall_time']:.1f} s); "
                 "labels: " + scene.level_label, fontsize=8)
    fig.tight_layout()
    pu.save_figure(fig, f"speed_accuracy_{scene.key}")


def plot_stability(scene, runs):
    ups = [u for u, _, _ in UPDATES if u != "explicit_limit"]
    fig, axes = plt.subplots(1, len(ups), figsize=(5.5 * len(ups), 3.6))
    for ax, update in zip(axes, ups):
        grid = np.full((len(scene.levels), len(S_GRID)), np.nan)
        for r in runs:
            if r["update"] != update:
                continue
            i, j = scene.levels.index(r["level"]), S_GRID.index(r["S"])
            grid[i, j] = 0.0 if r["failed"] else 1.0
            after = r["summary"]["end_time"] - scene.t_impact
            txt = ("stopped\n" + f"at {after * 1e6:+.2g} us") if r["failed"] else \
                ("E2\n%.3g" % r["e2"] if r["e2"] is not None else "?")
            ax.text(j, i, txt, ha="center", va="center", fontsize=7)
        ax.imshow(grid, cmap=matplotlib.colors.ListedColormap(["#f4a582", "#92c5de"]), vmin=0,
                  vmax=1, aspect="auto", origin="lower")
        ax.set_xticks(range(len(S_GRID)), [f"{S:g}" for S in S_GRID])
        ax.set_yticks(range(len(scene.levels)), [str(l) for l in scene.levels])
        ax.set_xlabel("Courant number S")
        ax.set_ylabel(scene.level_label)
        ax.set_title(UPDATE_LABEL[update], fontsize=9)
    fig.suptitle(f"Stability map, {scene.key}: blue = completed (E2 shown), red = stopped (diverging "
                 "contact or inverted element; time after the impact)", fontsize=9)
    fig.tight_layout()
    pu.save_figure(fig, f"stability_{scene.key}")


def contact_share(summary):
    """Share of the cycle time spent in the contact steps (3: bins, 9: CP forces) [0-1]."""
    t = summary.get("timers", {})
    total = sum(t.values())
    return (t.get("03_sort_into_bins", 0.0) + t.get("09_contact_forces", 0.0)) / total if total > 0 else float("nan")


def report(scene, ref, runs):
    path = os.path.join(pu.OUT, f"speed_accuracy_{scene.key}.csv")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["update", "level", "S", "status", "E2", "wall_time_s", "cycles", "elements",
                    "contact_share", "error"])
        for r in [ref] + runs:
            s = r["summary"]
            w.writerow([r["update"], r["level"], r["S"], s["status"], r.get("e2", 0.0), s["wall_time"],
                        s["cycles"], s["elements"], f"{contact_share(s):.4f}", s.get("error", "")])
    print("wrote", os.path.relpath(path, pu.ROOT))
    print(f"\n{scene.key}: reference {ref['name']} ({ref['summary']['elements']} elements, "
          f"{ref['summary']['cycles']} cycles, {ref['summary']['wall_time']:.2f} s, "
          f"{100 * contact_share(ref['summary']):.0f} % of the cycle in contact)")
    print("| update | " + scene.level_label + " | S | E2 | wall (s) | cycles | contact % | status |")
    print("|---|---|---|---|---|---|---|---|")
    for r in runs:
        s = r["summary"]
        st = "completed" if not r["failed"] else "stopped: " + pu.short_error(s)
        e2 = "-" if r.get("e2") is None else f"{r['e2']:.4f}"
        print(f"| {UPDATE_LABEL[r['update']]} | {r['level']} | {r['S']:g} | {e2} | "
              f"{s['wall_time']:.2f} | {s['cycles']} | {100 * contact_share(s):.0f} | {st} |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scenes", nargs="*", default=["1d", "2d"])
    ap.add_argument("--force", action="store_true")
    args = ap.parse_args()
    os.makedirs(pu.OUT, exist_ok=True)
    for key in args.scenes:
        scene = Scene1D() if key == "1d" else Scene2D()
        ref, runs = sweep(scene, args.force)
        plot_speed(scene, ref, runs)
        plot_stability(scene, runs)
        report(scene, ref, runs)


if __name__ == "__main__":
    main()
