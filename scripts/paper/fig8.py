#!/usr/bin/python3
"""The paper's Figs. 8 and 9: a steel projectile at 139 m/s through a 5 cm imbricate concrete
wall (2D plane strain), at two resolutions.

usage: /usr/bin/python3 scripts/paper/fig8.py [--force] [--times T ...]

Runs inputs/paper/fig8_projectile_wall_coarse.yaml, the same deck searching for new CPs every
cycle instead of every other one, and inputs/paper/fig8_projectile_wall.yaml (the fine one)
through scpdyn (one thread) into out/paper/fig8/<run>/ when their outputs are missing (--force:
always), and writes
  out/paper/fig8_mesh_contacts.png      Fig. 8: the meshes (coarse left, fine right) and the
                                        contact points (red dots) at --times (default 0, 0.8
                                        and 2 ms)
  out/paper/fig9_tensile_strength.png   Fig. 9: the concrete's remaining tensile strength at
                                        0.8 ms, white = fully damaged (the steel in grey)
  out/paper/fig8_projectile_velocity.png  the projectile's velocity (its momentum over its
                                        mass) against time, every run
and prints per run: the projectile's velocity at the end, the largest energy balance error,
and the total x- and y-momentum change against the impulse of the velocity constraints'
reactions (spcforc.csv; the decks write a history row every cycle, so the sum of reaction
times dt is the constraints' impulse exactly); then the resolution and search-interval
differences of the end velocity. Last, the monolithic companion
inputs/paper/fig8_monolithic_penetration.yaml (a steel rod into a thick concrete block,
axisymmetric): its deepest penetration against the empirical formula of Forrestal et al.
(docs/theory.md 14.5).
"""
import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))
import paper_util as pu  # noqa: E402
import plot_fields as pf  # noqa: E402

COARSE = "fig8_projectile_wall_coarse"
FINE = "fig8_projectile_wall"


def projectile_velocity(out):
    """Time and the projectile's mean x-velocity (momentum / mass) from matsum.csv; the mass
    from the first row, p^2 / (2 KE)."""
    m = pu.read_csv(os.path.join(out, "matsum.csv"))
    p, ke = m["projectile:momentum_x"], m["projectile:kinetic"]
    mass = p[0] ** 2 / (2 * ke[0])
    return m["time"], p / mass


def momentum_closure(out):
    """Per component x, y: (change of the total momentum, impulse of the reactions)."""
    h = pu.history(out)
    r = pu.read_csv(os.path.join(out, "spcforc.csv"))
    result = []
    for c in "xy":
        dp = h["momentum_" + c][-1] - h["momentum_" + c][0]
        cols = [k for k in r if k.endswith(":" + c)]
        impulse = float(np.sum(sum(r[k] for k in cols) * h["dt"])) if cols else 0.0
        result.append((dp, impulse))
    return result


def forrestal_depth(m, a, v, rho, fc, crater=True):
    """Penetration depth of a rigid flat-nosed rod (mass m, radius a, speed v) into concrete of
    density rho and unconfined strength fc (Pa) by Forrestal et al. (1994) with the strength
    parameter S of Frew et al. (1998), nose factor N = 1 (docs/theory.md 14.5). With `crater`,
    the force grows linearly over the first 4a (their crater stage); without it, the tunnel
    stage's resisting stress S fc + N rho v^2 acts from the surface on."""
    s_fc = 82.6 * (fc / 1e6) ** -0.544 * fc
    area = np.pi * a * a
    if not crater:
        return m / (2 * area * rho) * np.log(1 + rho * v * v / s_fc)
    v1_sq = (m * v * v - 4 * np.pi * a ** 3 * s_fc) / (m + 4 * np.pi * a ** 3 * rho)
    if v1_sq <= 0:  # the rod stops in the crater stage: F = c z, c = pi a^2 S fc / (4 a)
        return v * np.sqrt(m * 4 * a / (area * s_fc))
    return m / (2 * area * rho) * np.log(1 + rho * v1_sq / s_fc) + 4 * a


def strength_of(run, frame):
    """The remaining tensile strength, NaN where the material has none at t = 0 (the steel)."""
    t = frame["cell_data/tensile_strength"][()].astype(float)
    t[run.frames[0]["cell_data/tensile_strength"][()] <= 0] = np.nan
    return t


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--force", action="store_true", help="rerun the decks")
    ap.add_argument("--times", nargs="+", type=float, default=[0.0, 0.8e-3, 2.0e-3],
                    metavar="T", help="times of Fig. 8's rows, s")
    args = ap.parse_args()

    coarse_deck = pu.deck_path(COARSE)
    with open(coarse_deck) as f:
        every_cycle = f.read().replace("search_interval: 2", "search_interval: 1")
    plan = [("coarse", coarse_deck, None), ("coarse, search every cycle", coarse_deck, every_cycle),
            ("fine", pu.deck_path(FINE), None)]
    outs, summaries = {}, {}
    for name, deck, text in plan:
        tag = COARSE + "_search1" if text else os.path.splitext(os.path.basename(deck))[0]
        outs[name] = os.path.join(pu.OUT, "fig8", tag)
        summaries[name] = pu.run(deck, outs[name], force=args.force, text=text)

    runs = []
    for name in ("coarse", "fine"):
        run = pf.Run(outs[name])
        run.name = name + (" (stopped)" if pu.failed(summaries[name]) else "")
        runs.append(run)
    try:
        rows = pf.select(runs, args.times)
        rows9 = pf.select(runs, [0.8e-3])
    except pf.UsageError as e:
        sys.exit(f"fig8.py: {e}")
    fig = pf.figure_2d(runs, rows, None, contacts=True, width=3.2)
    fig.suptitle("Fig. 8: meshes and contact points (red dots)", fontsize=10)
    pu.save_figure(fig, "fig8_mesh_contacts")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cmap = matplotlib.colormaps["Blues"].copy()
    cmap.set_bad("0.55")
    t0 = np.nanmax(strength_of(runs[0], runs[0].frames[0]))
    fig = pf.figure_2d(runs, rows9, "tensile_strength", (0.0, t0), width=3.2, cmap=cmap,
                       values_of=strength_of)
    for ax in fig.axes[:len(runs)]:  # fully damaged cells are white: not on a white ground
        ax.set_facecolor("0.8")
    fig.suptitle("Fig. 9: remaining tensile strength at 0.8 ms (white: fully damaged; steel "
                 "dark grey, open space light grey)", fontsize=10)
    pu.save_figure(fig, "fig9_tensile_strength")

    fig, ax = plt.subplots(figsize=(6, 3.6), constrained_layout=True)
    ends = {}
    for name, _, _ in plan:
        t, v = projectile_velocity(outs[name])
        ends[name] = v[-1]
        ax.plot(t * 1e3, v, label=name)
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("projectile velocity (momentum / mass) [m/s]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    pu.save_figure(fig, "fig8_projectile_velocity")

    for name, _, _ in plan:
        s = summaries[name]
        eb = np.max(np.abs(pu.history(outs[name])["energy_balance_error"]))
        (dpx, ix), (dpy, iy) = momentum_closure(outs[name])
        print(f"{name}: {s.get('status')} to {s['end_time'] * 1e3:.3f} ms, {pu.cost(s)}; "
              f"projectile velocity at the end {ends[name]:.2f} m/s; largest energy balance "
              f"error {eb:.2e}; momentum change x {dpx:.4f} N s, reactions' impulse {ix:.4f} "
              f"(error {abs(dpx - ix) / abs(dpx):.2e} of the change), y {dpy:.2e} vs {iy:.2e}")
    fine, coarse, s1 = ends["fine"], ends["coarse"], ends["coarse, search every cycle"]
    print(f"end velocity: coarse against fine {abs(coarse - fine) / abs(fine):.2%}; search "
          f"every cycle against every other {abs(s1 - coarse) / abs(s1):.2%} (coarse)")

    mono = os.path.join(pu.OUT, "fig8", "fig8_monolithic_penetration")
    s = pu.run(pu.deck_path("fig8_monolithic_penetration"), mono, force=args.force)
    g = pu.gauges(mono)
    depth = -float(np.min(g["nose:y"]))  # the target's face is y = 0
    m = pu.read_csv(os.path.join(mono, "matsum.csv"))
    p0, ke0 = m["rod:momentum_y"][0], m["rod:kinetic"][0]
    mass, v0 = 2 * np.pi * p0 ** 2 / (2 * ke0), abs(2 * ke0 / p0)  # per radian -> whole rod
    a, rho, fc = 5e-3, 2440.0, 47.95e6
    print(f"monolithic companion: {s.get('status')}, {pu.cost(s)}; rod {mass * 1e3:.2f} g at "
          f"{v0:.1f} m/s, deepest penetration {depth * 1e3:.2f} mm, rebound "
          f"{g['nose:vy'][-1]:.1f} m/s")
    for crater, what in ((True, "with the crater stage"), (False, "tunnel stage from the face")):
        f = forrestal_depth(mass, a, v0, rho, fc, crater)
        print(f"  Forrestal et al. (1994), S of Frew et al. (1998), {what}: {f * 1e3:.2f} mm; "
              f"model against it {(depth - f) / f:+.0%}")


if __name__ == "__main__":
    main()
