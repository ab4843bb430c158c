#!/usr/bin/python3
"""Verification T8a/T8b: planar and cylindrical TNT detonations (JWL, programmed burn).

Decks: inputs/verification/detonation_planar.yaml, detonation_cylindrical.yaml. Runs them
through scpdyn (build/bin/scpdyn or $SCPDYN_BIN) if out/<deck>/ is missing, plots pressure
profiles and histories against the exact solutions (detonation_reference.py) into
out/<deck>/<deck>.png and prints the measured errors.

usage: /usr/bin/python3 scripts/verification/plot_detonation.py [--convergence] [--out DIR]
  --convergence  also runs the planar column at h = 0.25 mm (400 cells) and the cylinder at
                 h = 1 mm (50 x 50) into out/<deck>_coarse.

Measures (verification.md T8a, T8b):
  front arrival: time the gauge pressure first crosses P_CJ/2 (linear interpolation), at the
                 gauge element's initial centroid; D = least-squares slope of r against t;
  planar: wall plateau = mean pressure of the gauges at x = 0.05, 2, 5 mm for t > 5 us;
          profile E_2 = ||p - p_exact|| / ||p_exact|| over the cells with 0.55 < x/(Dt) < 0.95;
  cylinder: core pressure = mean over the cells with r < 0.4 D t at the end (5 us), and the
          r = 10 mm gauges once they are in the core (t > 10 mm / (0.4 D)); profile E_2 over
          0.55 < r/(Dt) < 0.9; peak pressures are reported, not scored (smeared by the burn).
"""
import argparse
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import detonation_reference as ref  # noqa: E402
import scene_util as su  # noqa: E402

TNT = ref.model("TNT")


def arrivals(out, fields):
    """name -> (initial centroid of the gauge element, arrival time, gauge time series)."""
    g = su.read_csv(os.path.join(out, "gauges.csv"))
    t = g["time"]
    c0 = fields.centroids(fields.coords0)
    res = {}
    for name, point in su.gauge_points(out).items():
        p = g[name + ":pressure"]
        k = int(np.argmax(p > 0.5 * TNT.pcj))
        ta = np.nan
        if p[k] > 0.5 * TNT.pcj and k > 0:
            ta = t[k - 1] + (0.5 * TNT.pcj - p[k - 1]) / (p[k] - p[k - 1]) * (t[k] - t[k - 1])
        res[name] = (c0[fields.nearest_element(point)], ta, p)
    return t, res


def fit_speed(r, t):
    a, _ = np.polyfit(t, r, 1)
    return a


def e2(p, exact):
    return float(np.sqrt(np.sum((p - exact) ** 2) / np.sum(exact ** 2)))


def planar(out, summary, name):
    f = su.Fields(out)
    t, arr = arrivals(out, f)
    h = su.read_csv(os.path.join(out, "history.csv"))
    _, _, _, (Vw, pw, cw) = TNT.planar()
    far = [v for v in arr.values() if v[0][0] >= 19e-3]
    D = fit_speed(np.array([v[0][0] for v in far]), np.array([v[1] for v in far]))
    wall = [arr[n][2][t > 5e-6] for n in ("x0mm", "x2mm", "x5mm")]
    plateau = float(np.mean(np.concatenate(wall)))
    last = f.frame(-1)
    x = f.centroids(last["coords"])[:, 0]
    s = x / (TNT.D * last["time"])
    band = (s > 0.55) & (s < 0.95)
    err2 = e2(last["pressure"][band], TNT.planar_profile(s[band]) * TNT.pcj)
    peak = float(max(v[2].max() for v in arr.values()))
    bal = float(np.abs(h["energy_balance_error"]).max())
    print(f"{name} (T8a planar, TNT): {su.cost(summary)}")
    print(f"  D {D:.1f} m/s (model {TNT.D:.1f}, error {100 * (D / TNT.D - 1):+.3f} %)")
    print(f"  wall plateau {plateau / 1e9:.4f} GPa (exact {pw / 1e9:.4f}, error "
          f"{100 * (plateau / pw - 1):+.3f} %); per gauge " +
          ", ".join(f"{w.mean() / 1e9:.4f}" for w in wall))
    print(f"  profile E_2 at {last['time'] * 1e6:.1f} us: {100 * err2:.2f} % (0.55 < x/Dt < 0.95); "
          f"peak {peak / 1e9:.2f} GPa = {peak / TNT.pcj:.3f} P_CJ (not scored)")
    print(f"  energy balance error max {100 * bal:.4f} %")

    fig, axes = plt.subplots(1, 3, figsize=(14, 4.4))
    ax = axes[0]
    for k in range(1, len(f.keys)):
        fr = f.frame(k)
        xx = f.centroids(fr["coords"])[:, 0]
        ax.plot(1e3 * xx, fr["pressure"] / 1e9, lw=1, color=f"C{k % 10}")
        xe = np.linspace(0, TNT.D * fr["time"] * 1.02, 400)
        ax.plot(1e3 * xe, TNT.planar_profile(xe / (TNT.D * fr["time"])) * TNT.pcj / 1e9 * (xe <= TNT.D * fr["time"]),
                "k--", lw=0.7)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("pressure [GPa]")
    ax.set_title(f"p(x) every 2 us (dashed: exact); E_2 {100 * err2:.2f} % at 14 us", fontsize=9)
    ax.grid(alpha=0.3)
    ax = axes[1]
    for n, (c, ta, p) in arr.items():
        ax.plot(1e6 * t, p / 1e9, lw=1, label=f"x0 = {1e3 * c[0]:.2f} mm")
        te = np.linspace(0, t[-1], 600)
        pe = TNT.particle_history(c[0], te, TNT.planar_velocity, TNT.planar_profile)
        ax.plot(1e6 * te, pe * TNT.pcj / 1e9, "k--", lw=0.6)
    ax.axhline(pw / 1e9, color="r", ls=":", lw=1, label=f"exact wall p_w = {pw / 1e9:.3f} GPa")
    ax.set_xlabel("time [us]")
    ax.set_ylabel("pressure [GPa]")
    ax.set_title(f"gauges (dashed: exact at the particle); plateau {plateau / 1e9:.4f} GPa ({100 * (plateau / pw - 1):+.2f} %), "
                 f"D {100 * (D / TNT.D - 1):+.2f} %", fontsize=9)
    ax.legend(fontsize=6)
    ax.grid(alpha=0.3)
    energy_panel(axes[2], h, bal)
    fig.suptitle(f"T8a planar TNT detonation lit at a rigid wall: {su.cost(summary)}", fontsize=10)
    fig.tight_layout()
    path = os.path.join(out, name + ".png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"  wrote {path}")
    return dict(D=D, plateau=plateau, pw=pw, e2=err2, balance=bal)


def cylindrical(out, summary, name):
    f = su.Fields(out)
    t, arr = arrivals(out, f)
    h = su.read_csv(os.path.join(out, "history.csv"))
    pc, xi0 = TNT.similarity_core(1)
    rr = {n: float(np.hypot(*v[0][:2])) for n, v in arr.items()}
    D = fit_speed(np.array(list(rr.values())), np.array([v[1] for v in arr.values()]))
    ray = {}
    for a in ("a0", "a22", "a45"):
        names = [n for n in arr if n.endswith("_" + a)]
        ray[a] = fit_speed(np.array([rr[n] for n in names]), np.array([arr[n][1] for n in names]))
    last = f.frame(-1)
    c = f.centroids(last["coords"])
    r = np.hypot(c[:, 0], c[:, 1])
    s = r / (TNT.D * last["time"])
    core_cells = s < 0.4
    core = float(last["pressure"][core_cells].mean())
    t_core = 10e-3 / (0.4 * TNT.D)
    core_g = float(np.mean(np.concatenate([arr[n][2][t > t_core] for n in arr if n.startswith("r10_")])))
    band = (s > 0.55) & (s < 0.9)
    err2 = e2(last["pressure"][band], TNT.similarity_profile(1, s[band]) * TNT.pcj)
    peak = float(max(v[2].max() for v in arr.values()))
    bal = float(np.abs(h["energy_balance_error"]).max())
    print(f"{name} (T8b cylinder, TNT): {su.cost(summary)}")
    print(f"  D {D:.1f} m/s (model {TNT.D:.1f}, error {100 * (D / TNT.D - 1):+.3f} %); per ray 0/22.5/45 deg "
          + " / ".join(f"{ray[a]:.1f}" for a in ray) + f"; 45 vs 0 deg {100 * (ray['a45'] / ray['a0'] - 1):+.3f} %")
    print(f"  core pressure at {last['time'] * 1e6:.2f} us (r < 0.4 Dt, {core_cells.sum()} cells): "
          f"{core / 1e9:.4f} GPa (similarity {pc / 1e9:.4f}, error {100 * (core / pc - 1):+.2f} %)")
    print(f"  core pressure at the r = 10 mm gauges for t > {t_core * 1e6:.2f} us: {core_g / 1e9:.4f} GPa "
          f"(error {100 * (core_g / pc - 1):+.2f} %)")
    print(f"  profile E_2 {100 * err2:.2f} % (0.55 < r/Dt < 0.9); peak {peak / 1e9:.2f} GPa = "
          f"{peak / TNT.pcj:.3f} P_CJ (not scored)")
    print(f"  energy balance error max {100 * bal:.4f} %")

    fig, axes = plt.subplots(1, 4, figsize=(18, 4.4), gridspec_kw={"width_ratios": [1.2, 1.2, 1.1, 1]})
    ax = axes[0]
    ang = np.degrees(np.arctan2(c[:, 1], c[:, 0]))
    sc = ax.scatter(s, last["pressure"] / 1e9, c=ang, s=2, cmap="viridis")
    fig.colorbar(sc, ax=ax, label="angle [deg]")
    xs = np.linspace(0, 1.1, 500)
    ax.plot(xs, TNT.similarity_profile(1, xs) * TNT.pcj / 1e9 * (xs <= 1), "r-", lw=1.2,
            label="Taylor (1950) similarity")
    ax.axvline(0.4, color="0.5", ls=":", lw=1)
    ax.set_xlabel("r / (D t)")
    ax.set_ylabel("pressure [GPa]")
    ax.set_title(f"cells at {last['time'] * 1e6:.1f} us: core {100 * (core / pc - 1):+.2f} %, "
                 f"E_2 {100 * err2:.1f} %", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    ax = axes[1]
    for k, (n, (c0, ta, p)) in enumerate(arr.items()):
        ax.plot(1e6 * t, p / 1e9, lw=0.9, color=f"C{k}", label=n)
    te = np.linspace(0, t[-1], 500)
    for rg in (10e-3, 20e-3, 30e-3):
        pe = TNT.particle_history(rg, te, lambda x: TNT.similarity_velocity(1, x),
                                  lambda x: TNT.similarity_profile(1, x))
        ax.plot(1e6 * te, pe * TNT.pcj / 1e9, "k--", lw=0.7)
    ax.axhline(pc / 1e9, color="r", ls=":", lw=1, label=f"core {pc / 1e9:.3f} GPa")
    ax.set_xlabel("time [us]")
    ax.set_ylabel("pressure [GPa]")
    ax.set_title(f"gauges (dashed: similarity, particles from r = 10/20/30 mm); D {100 * (D / TNT.D - 1):+.2f} %",
                 fontsize=9)
    ax.legend(fontsize=6, ncol=2)
    ax.grid(alpha=0.3)
    ax = axes[2]
    from matplotlib.collections import PolyCollection

    q = 1e3 * last["coords"][f.topology][:, :, :2]
    pcol = PolyCollection(q, array=last["pressure"] / 1e9, cmap="inferno", edgecolors="none")
    ax.add_collection(pcol)
    fig.colorbar(pcol, ax=ax, label="pressure [GPa]")
    ax.set_xlim(0, 52)
    ax.set_ylim(0, 52)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title("pressure map (quarter model)", fontsize=9)
    energy_panel(axes[3], h, bal)
    fig.suptitle(f"T8b cylindrical TNT detonation: {su.cost(summary)}", fontsize=10)
    fig.tight_layout()
    path = os.path.join(out, name + ".png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"  wrote {path}")
    return dict(D=D, core=core, pc=pc, core_g=core_g, e2=err2, balance=bal, ray=ray)


def energy_panel(ax, h, bal):
    th = 1e6 * h["time"]
    ax.plot(th, h["kinetic"], label="kinetic")
    ax.plot(th, h["internal"], label="internal (incl. E0 V of the HE)")
    ax.plot(th, h["kinetic"] + h["internal"] + h["hourglass"], "k--", lw=1, label="total")
    ax.set_xlabel("time [us]")
    ax.set_ylabel("energy [J/m]")
    ax.set_title(f"energy balance error max {100 * bal:.4f} %", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--convergence", action="store_true")
    ap.add_argument("--out", default="out")
    args = ap.parse_args()
    rows = []
    for name, func, coarse in (("detonation_planar", planar, [400, 1]),
                               ("detonation_cylindrical", cylindrical, [50, 50])):
        out = os.path.join(args.out, name)
        s = su.run(su.deck_path(name), out)
        rows.append((name, s, func(out, s, name)))
        if args.convergence:
            vout = out + "_coarse"
            s = su.run(su.deck_path(name), vout, elements=coarse)
            rows.append((name + "_coarse", s, func(vout, s, name + "_coarse")))
    print("\n| run | cells | cycles | wall [s] | D error | plateau/core error | profile E_2 | balance |")
    print("|---|---|---|---|---|---|---|---|")
    for name, s, m in rows:
        pe = m["plateau"] / m["pw"] - 1 if "plateau" in m else m["core"] / m["pc"] - 1
        print(f"| {name} | {s['elements']} | {s['cycles']} | {s['wall_time']:.2f} | "
              f"{100 * (m['D'] / TNT.D - 1):+.2f} % | {100 * pe:+.2f} % | {100 * m['e2']:.2f} % | "
              f"{100 * m['balance']:.4f} % |")


if __name__ == "__main__":
    main()
