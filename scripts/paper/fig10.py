#!/usr/bin/python3
"""The paper's Fig. 10: a 5 m steel bar at 70 m/s, inclined at 60 degrees, into a 6.4 x 0.64 x
6.4 m English-bond concrete brick wall standing on a fixed ground (3D).

usage: /usr/bin/python3 scripts/paper/fig10.py [--force] [--deck NAME]

Runs inputs/paper/fig10_bar_wall_3d.yaml (or inputs/paper/NAME.yaml) through scpdyn into
out/paper/fig10/<NAME>/ when its outputs are missing (--force: always; OMP_NUM_THREADS as the
caller sets it, else 1), and writes
  out/paper/fig10_tensile_strength.png  the mesh at 0 (edges drawn) and the concrete's remaining
                                        tensile strength 1.3, 18.3 and 41 ms after the release
                                        (the frames nearest; ParaView, headless)
  out/paper/fig10_histories.png         the bar's momentum and the wall's energies against time
and prints: the settled state at the end of the settling stage (the footprint-weighted mean
vertical stress of every course against rho g (H - z_c), the base course's error, the wall's
kinetic over its potential energy M g H / 2), the bar's momentum and the wall's energies 41 ms
after the release (what a resolution twin is compared by), the largest energy balance error,
the fastest brick and the fastest wall node after the release against twice the bar's speed,
the wall time and the contact share of the cycle. Another deck's pictures carry its name's
tail: --deck fig10_bar_wall_3d_fine writes fig10_tensile_strength_fine.png and
fig10_histories_fine.png.

Fields: fields.h5 stores a cell's stress in the order xx, xy, xz, yy, yz, zz (XDMF Tensor6),
so sigma_zz is column 5.
"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import paper_util as pu  # noqa: E402

DECK = "fig10_bar_wall_3d"
G = 9.81
PICTURE_DELAYS = (0.0013, 0.0183, 0.041)  # s after the release (the paper's frames)
SZZ = 5  # sigma_zz in the Tensor6 order of fields.h5


def deck_facts(path):
    """Wall height, course height and count, origin, density, settling end, bar release and speed."""
    with open(path) as f:
        deck = yaml.safe_load(f)
    parts = {p["name"]: p for p in deck["parts"]}
    wall, bar = parts["wall"]["mesh"], parts["bar"]
    rho = {m["name"]: m["density"] for m in deck["materials"]}[parts["wall"]["material"]]
    h = wall["brick_size"][2]
    courses = wall["count"][2]
    return dict(H=h * courses, h=h, courses=courses, origin=wall.get("origin", [0, 0, 0]), rho=rho,
                settle=deck["settling"]["end"], release=bar["release_time"],
                speed=float(np.linalg.norm(bar["initial_velocity"])))


def frame_near(f, t):
    keys = sorted(f["frames"], key=int)
    times = np.array([f["frames"][k].attrs["time"] for k in keys])
    k = int(np.argmin(abs(times - t)))
    return f["frames"][keys[k]], times[k]


def settled_state(out, d, summary):
    """Per course: the mean sigma_zz of the wall's elements, weighted by their footprint (a
    course's force over its area: at rest exactly rho g (H - z_c), whatever the bond), against
    -rho g (H - z_c)."""
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        cells = f["mesh/topology"][()]
        x0 = f["mesh/coords0"][()]
        frame, t = frame_near(f, d["settle"])
        szz = frame["cell_data/stress"][()][:, SZZ]
        part = frame["cell_data/part"][()].astype(int)
    names = summary["parts"]
    in_wall = np.array([names[str(p)].startswith("wall.") for p in part])
    zc = x0[cells].mean(axis=1)[:, 2] - d["origin"][2]
    span = x0[cells].max(axis=1) - x0[cells].min(axis=1)
    area = span[:, 0] * span[:, 1]
    rows = []
    for c in range(d["courses"]):
        m = in_wall & (zc > c * d["h"]) & (zc < (c + 1) * d["h"])
        z = (c + 0.5) * d["h"]
        mean = (szz[m] * area[m]).sum() / area[m].sum()
        rows.append((c, int(m.sum()), mean, -d["rho"] * G * (d["H"] - z)))
    return t, rows


def fastest_brick(out, summary, after):
    """In the frames after `after`: the largest speed of a brick (the mean velocity of its
    nodes; a brick is a sub-part wall.*) and of a single wall node, with their times [m/s, s]."""
    names = summary["parts"]
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        cells = f["mesh/topology"][()]
        brick, node = (0.0, 0.0), (0.0, 0.0)
        for k in f["frames"]:
            fr = f["frames"][k]
            t = float(fr.attrs["time"])
            if t <= after:
                continue
            part = fr["cell_data/part"][()].astype(int)
            wall = np.array([names[str(p)].startswith("wall.") for p in part])
            node_part = np.full(int(cells.max()) + 1, -1)
            node_part[cells[wall].ravel()] = np.repeat(part[wall], cells.shape[1])
            nodes = np.flatnonzero(node_part >= 0)
            v = fr["point_data/velocity"][()][nodes]
            s = np.linalg.norm(v, axis=1).max()
            if s > node[0]:
                node = (float(s), t)
            count = np.bincount(node_part[nodes])
            mean = np.stack([np.bincount(node_part[nodes], weights=v[:, c]) for c in range(3)],
                            axis=1)[count > 0] / count[count > 0, None]
            s = np.linalg.norm(mean, axis=1).max()
            if s > brick[0]:
                brick = (float(s), t)
    return brick, node


def histories(out, d, suffix):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    m = pu.read_csv(os.path.join(out, "matsum.csv"))
    t = (m["time"] - d["release"]) * 1e3
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.6), constrained_layout=True)
    for c in "xyz":
        a.plot(t, m["bar:momentum_" + c] / 1e3, label=c)
    a.set_xlabel("time after the release [ms]")
    a.set_ylabel("bar momentum [kN s]")
    a.legend()
    for q in ("kinetic", "internal"):
        b.plot(t, m["wall:" + q] / 1e3, label="wall " + q)
    b.plot(t, m["bar:kinetic"] / 1e3, "--", label="bar kinetic")
    b.set_xlabel("time after the release [ms]")
    b.set_ylabel("energy [kJ]")
    b.legend()
    for ax in (a, b):
        ax.axvline(0, color="grey", lw=0.5)
    fig.suptitle("Fig. 10: the bar's momentum and the wall's energies")
    pu.save_figure(fig, "fig10_histories" + suffix)
    plt.close(fig)


def pictures(out, d, suffix):
    times = [0.0] + [d["release"] + s for s in PICTURE_DELAYS]
    png = os.path.join(pu.OUT, f"fig10_tensile_strength{suffix}.png")
    os.makedirs(pu.OUT, exist_ok=True)
    cmd = [sys.executable, os.path.join(os.path.dirname(HERE), "plot_fields.py"), out,
           "--field", "tensile_strength", "--edges", "--out", png,
           # from the bar's side of the wall (y < 0), above it, z up
           "--camera", "0.9", "-1.6", "0.7", "--up", "0", "0", "1", "--times"]
    cmd += [repr(t) for t in times]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(r.stdout.strip())
    if r.returncode != 0:
        sys.exit(r.returncode)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--force", action="store_true")
    ap.add_argument("--deck", default=DECK)
    args = ap.parse_args()
    deck = pu.deck_path(args.deck)
    out = os.path.join(pu.OUT, "fig10", args.deck)
    summary = pu.run(deck, out, args.force)
    if pu.failed(summary):
        print("run stopped:", pu.short_error(summary))
    d = deck_facts(deck)

    t, rows = settled_state(out, d, summary)
    print(f"settled state at t = {t:.4f} s (settling ends at {d['settle']} s):")
    worst = max(rows, key=lambda r: abs(r[2] / r[3] - 1))
    for c, n, s, e in rows:
        if c in (0, 1, d["courses"] // 2, d["courses"] - 1) or c == worst[0]:
            print(f"  course {c:2d} ({n} elements): mean sigma_zz {s / 1e3:9.2f} kPa, "
                  f"rho g (H - z) {e / 1e3:9.2f} kPa, error {s / e - 1:+.4f}")
    print(f"  base course error {rows[0][2] / rows[0][3] - 1:+.4f}; worst course {worst[0]}: "
          f"{worst[2] / worst[3] - 1:+.4f}")
    m = pu.read_csv(os.path.join(out, "matsum.csv"))
    k = int(np.argmin(abs(m["time"] - d["settle"])))
    pe = summary["preflight"]["parts"]["wall"]["mass"] * G * d["H"] / 2
    print(f"  wall kinetic / potential energy at t = {m['time'][k]:.4f} s: "
          f"{m['wall:kinetic'][k] / pe:.3e}")

    j = int(np.argmin(abs(m["time"] - (d["release"] + PICTURE_DELAYS[-1]))))
    print(f"at t = {m['time'][j]:.4f} s: bar momentum y, z {m['bar:momentum_y'][j] / 1e3:.2f}, "
          f"{m['bar:momentum_z'][j] / 1e3:.2f} kN s (released with "
          f"{m['bar:momentum_y'][k + 1] / 1e3:.2f}, {m['bar:momentum_z'][k + 1] / 1e3:.2f}); "
          f"wall kinetic {m['wall:kinetic'][j] / 1e3:.2f} kJ, internal "
          f"{m['wall:internal'][j] / 1e3:.2f} kJ")
    print(f"energy balance error: largest {summary['energy_balance_error_max']:.3e}, "
          f"end {summary['energy_balance_error']:.3e}")
    brick, node = fastest_brick(out, summary, d["release"])
    print(f"fastest brick after the release (its nodes' mean velocity): {brick[0]:.2f} m/s at "
          f"t = {brick[1]:.4f} s, fastest wall node {node[0]:.2f} m/s at t = {node[1]:.4f} s "
          f"(twice the bar's speed: {2 * d['speed']:.1f} m/s)")
    timers = summary["timers"]
    contact = sum(v for k_, v in timers.items() if k_[:2] in ("03", "04", "08", "09"))
    print(f"wall time {summary['wall_time']:.1f} s, {summary['cycles']} cycles, "
          f"{summary['ranks']} rank(s) x {summary['threads']} thread(s); contact (steps 3, 4, "
          f"8, 9) {contact / summary['cycle_time']:.1%} of the cycle")
    suffix = "" if args.deck == DECK else "_" + args.deck.replace(DECK + "_", "")
    histories(out, d, suffix)
    pictures(out, d, suffix)


if __name__ == "__main__":
    main()
