#!/usr/bin/python3
"""Verification T7b: Taylor bar impacts with Johnson-Cook (1983) parameters.

Decks: inputs/verification/taylor_4340_208.yaml, taylor_ofhc_190.yaml. Runs them through
scpdyn (build/bin/scpdyn or $SCPDYN_BIN) if out/<deck>/ is missing, draws the final shapes, the
length/foot histories and the energies into out/<deck>/<deck>.png, and prints the measured
errors against the test data (verification.md T7b).

usage: /usr/bin/python3 scripts/verification/plot_taylor.py [--convergence] [--t7a] [--out DIR]
  --convergence  also runs the decks at 5 x 33 and 20 x 133 elements (radius x length; the
                 decks have 10 x 66) into out/<deck>_nr5, out/<deck>_nr20 and prints a table.
  --t7a          also runs taylor_t7a_cu_227.yaml (bilinear J2 code-to-code benchmark, T7a:
                 L_f in [21.2, 21.9] mm, R_f in [6.8, 7.4] mm, measured at the end, 80 us).
  --velocities   also runs the copper deck at the two slower tests of the same rod in
                 verification.md T7b (130 and 146 m/s, Johnson & Cook 1983's own tests) into
                 out/taylor_ofhc_130, out/taylor_ofhc_146 (docs/verification_materials.md).
  --zafit        also runs taylor_ofhc_190_zafit.yaml (Johnson-Cook constants fitted to the
                 Zerilli-Armstrong copper surface, fit_jc_to_za.py: the model-form check);
                 with --velocities at 130 and 146 m/s too.

Measures (verification.md T7b; docs/verification_materials.md):
  L_f  mean of the top node's y over the last 40 us (the wall holds the impact face, so the
       rod rings elastically about its unloaded shape: +-0.4 % steel, +-0.1 % copper);
  D_f  twice the largest radius of the nodes that started on the impact face, final frame;
  energy: KE0 -> internal (plastic work, heat, elastic) + residual KE; balance error;
  profile: side radius at 10/25/40/55/70 % of the test length against the digitized test
       profile (TEST_PROFILES), drawn on the final-shape panel too.
"""
import argparse
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene_util as su  # noqa: E402

CASES = [
    # deck, label, L0, D0, reference L_f, reference D_f (verification.md T7b: test data)
    ("taylor_4340_208", "4340 steel, 208 m/s", 25.4e-3, 7.62e-3, 22.48e-3, 11.1e-3),
    ("taylor_ofhc_190", "OFHC copper, 190 m/s", 25.4e-3, 7.62e-3, 16.21e-3, 13.56e-3),
]
# T7a: centre of the tolerance band L_f in [21.2, 21.9] mm, D_f = 2 R_f in [13.6, 14.8] mm
T7A = ("taylor_t7a_cu_227", "copper bilinear J2 (T7a), 227 m/s", 32.4e-3, 6.4e-3, 21.55e-3, 14.2e-3)
T7A_BAND = ((21.2e-3, 21.9e-3), (13.6e-3, 14.8e-3))
WINDOW = 40e-6  # averaging window of the final length [s]
# Measured final side profiles (radius, height) [mm], digitized by B. Banerjee
# (github.com/bbanerjee/HighRateExptData, TaylorData/DAT): copper 190 m/s from Zerilli &
# Armstrong (1987) (taylorCuZerilliArmstrong.dat), 4340 at 208 m/s from Johnson & Cook (1983)
# p. 546 (taylorStJohnsonCook208.dat). Digitizing error ~1-3 % (the copper foot reads 13.68
# mm here against the quoted 13.56 mm).
TEST_PROFILES = {
    "taylor_ofhc_190": np.array([
        [6.842, 0.000], [6.408, 0.584], [6.011, 1.137], [5.615, 1.657], [5.396, 2.014],
        [5.107, 3.214], [5.074, 4.061], [5.000, 5.782], [4.892, 7.536], [4.748, 8.639],
        [4.529, 9.970], [4.314, 11.464], [4.099, 12.797], [3.917, 13.868], [3.880, 15.005],
        [3.810, 16.205]]),
    "taylor_4340_208": np.array([
        [5.528, 0.000], [4.780, 2.097], [4.300, 4.021], [4.033, 5.998], [3.979, 8.094],
        [3.881, 10.105], [3.881, 12.150], [3.748, 14.255], [3.783, 16.300], [3.774, 18.311],
        [3.765, 20.365], [3.810, 22.496]]),
}
# The same copper rod at the slower tests of verification.md T7b, the profiles of Johnson & Cook
# (1983) as digitized in the same repository (taylorCuJohnsonCook130.dat, ...146.dat): speed,
# test L_f, test D_f (verification.md), profile (radius, height) [mm].
COPPER_SWEEP = [
    (130, 19.56e-3, 9.91e-3, np.array([
        [4.765, 0.000], [4.593, 2.067], [4.464, 4.099], [4.455, 6.037], [4.446, 8.181],
        [4.360, 10.075], [4.266, 12.012], [4.214, 13.993], [4.077, 15.818], [3.819, 17.755],
        [3.810, 19.649]])),
    (146, 18.69e-3, 10.67e-3, np.array([
        [5.147, 0.000], [4.716, 2.055], [4.664, 4.075], [4.620, 6.216], [4.514, 8.107],
        [4.391, 10.300], [4.215, 12.363], [4.039, 14.634], [3.907, 16.706], [3.810, 18.873]])),
]
for _v, _l, _d, _p in COPPER_SWEEP:
    TEST_PROFILES[f"taylor_ofhc_{_v}"] = TEST_PROFILES[f"taylor_ofhc_{_v}_zafit"] = _p
TEST_PROFILES["taylor_ofhc_190_zafit"] = TEST_PROFILES["taylor_ofhc_190"]
ZAFIT = ("taylor_ofhc_190_zafit", "OFHC copper, 190 m/s, JC fitted to ZA", 25.4e-3, 7.62e-3, 16.21e-3, 13.56e-3)
PROFILE_FRACTIONS = (0.1, 0.25, 0.4, 0.55, 0.7)  # heights (fractions of the test L_f) compared


def side_profile(m):
    """Final side profile (radius, height) [mm] of the nodes that started on the rod's side."""
    f, last = m["fields"], m["last"]
    r0 = f.coords0[:, 0]
    side = np.abs(r0 - r0.max()) < 1e-9
    x = 1e3 * last["coords"][side]
    order = np.argsort(x[:, 1])
    return x[order, 0], x[order, 1]


def profile_table(name, m):
    """Radius of the run and of the test at fixed heights (fractions of the test length)."""
    if name not in TEST_PROFILES:
        return []
    test = TEST_PROFILES[name]
    r, y = side_profile(m)
    rows = []
    for fr in PROFILE_FRACTIONS:
        h = fr * test[-1, 1]
        rows.append((h, float(np.interp(h, y, r)), float(np.interp(h, test[:, 1], test[:, 0]))))
    return rows


def measure(out, averaged=True):
    """Final length (averaged over the last WINDOW, or the last value), foot diameter,
    energies and plastic strain of one run."""
    g = su.read_csv(os.path.join(out, "gauges.csv"))
    h = su.read_csv(os.path.join(out, "history.csv"))
    t, top = g["time"], g["top:y"]
    late = t >= t[-1] - WINDOW
    f = su.Fields(out)
    last = f.frame(-1)
    face = np.abs(f.coords0[:, 1]) < 1e-12
    ke0 = h["kinetic"][0]
    return dict(
        L=float(top[late].mean() if averaged else top[-1]), L_last=float(top[-1]), L_min=float(top[late].min()),
        L_max=float(top[late].max()), D=2 * float(last["coords"][face, 0].max()),
        min_y=float(last["coords"][:, 1].min()), eps_max=float(last["plastic_strain"].max()),
        T_max=float(last["temperature"].max()) if "temperature" in last else float("nan"), ke0=ke0, ke_end=float(h["kinetic"][-1]),
        ie_end=float(h["internal"][-1]), hg_end=float(h["hourglass"][-1]),
        balance=float(np.abs(h["energy_balance_error"]).max()), fields=f, last=last, g=g, h=h)


def plot(out, name, label, L0, D0, Lx, Dx, m, summary):
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.6), gridspec_kw={"width_ratios": [1.1, 1.3, 1.3]})
    ax = axes[0]
    f, last = m["fields"], m["last"]
    x = 1e3 * last["coords"]
    eps = last["plastic_strain"]
    quads = x[f.topology][:, :, :2]
    from matplotlib.collections import PolyCollection

    for sign in (1, -1):
        q = quads.copy()
        q[:, :, 0] *= sign
        pc = PolyCollection(q, array=eps, cmap="viridis", edgecolors="k", linewidths=0.1)
        ax.add_collection(pc)
    fig.colorbar(pc, ax=ax, label="equivalent plastic strain", shrink=0.8)
    if name in TEST_PROFILES:
        tp = TEST_PROFILES[name]
        ax.plot(tp[:, 0], tp[:, 1], "r-", lw=1.2, label="test profile (digitized)")
        ax.plot(-tp[:, 0], tp[:, 1], "r-", lw=1.2)
    ax.plot([-D0 / 2e-3, D0 / 2e-3, D0 / 2e-3, -D0 / 2e-3, -D0 / 2e-3],
            [0, 0, L0 * 1e3, L0 * 1e3, 0], "k:", lw=0.8, label="initial")
    ax.axhline(Lx * 1e3, color="r", ls="--", lw=1, label=f"reference L_f = {Lx * 1e3:.2f} mm")
    ax.plot([-Dx / 2e-3, Dx / 2e-3], [0, 0], "r|", ms=14, mew=2, label=f"reference D_f = {Dx * 1e3:.2f} mm")
    ax.set_xlim(-1.15 * Dx * 1e3 / 2 - 0.5, 1.15 * Dx * 1e3 / 2 + 0.5)
    ax.set_ylim(-1, L0 * 1e3 + 1.5)
    ax.set_aspect("equal")
    ax.set_xlabel("r [mm]")
    ax.set_ylabel("y [mm]")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title(f"final shape at {last['time'] * 1e6:.0f} us")

    ax = axes[1]
    t = 1e6 * m["g"]["time"]
    ax.plot(t, 1e3 * m["g"]["top:y"], label="length (top node y)")
    ax.plot(t, 2e3 * m["g"]["foot_edge:x"], label="foot diameter (edge node)")
    ax.axhline(Lx * 1e3, color="C0", ls="--", lw=1, label="reference L_f")
    ax.axhline(Dx * 1e3, color="C1", ls="--", lw=1, label="reference D_f")
    if m["L"] != m["L_last"]:
        ax.axvspan(t[-1] - WINDOW * 1e6, t[-1], color="0.9", label="L_f averaging window")
    ax.set_xlabel("time [us]")
    ax.set_ylabel("[mm]")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    ax.set_title(f"L_f {1e3 * m['L']:.2f} mm ({100 * (m['L'] / Lx - 1):+.1f} %), "
                 f"D_f {1e3 * m['D']:.2f} mm ({100 * (m['D'] / Dx - 1):+.1f} %)", fontsize=9)

    ax = axes[2]
    h = m["h"]
    th = 1e6 * h["time"]
    ax.plot(th, h["kinetic"], label="kinetic")
    ax.plot(th, h["internal"], label="internal (plastic work + heat + elastic)")
    ax.plot(th, h["hourglass"], label="hourglass")
    ax.plot(th, h["kinetic"] + h["internal"] + h["hourglass"], "k--", lw=1, label="total")
    ax.set_xlabel("time [us]")
    ax.set_ylabel("energy [J/rad]")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    ax.set_title(f"energy balance error max {100 * m['balance']:.3f} %", fontsize=9)
    fig.suptitle(f"Taylor bar, {label}: {su.cost(summary)}", fontsize=10)
    fig.tight_layout()
    path = os.path.join(out, name + ".png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def report(name, label, Lx, Dx, m, summary):
    print(f"{name} ({label}): {su.cost(summary)}")
    ring = (f"; last {1e3 * m['L_last']:.3f}, ringing {1e3 * m['L_min']:.3f}..{1e3 * m['L_max']:.3f}"
            if m["L"] != m["L_last"] else "; at the end")
    print(f"  L_f {1e3 * m['L']:.3f} mm (reference {1e3 * Lx:.2f}, error {100 * (m['L'] / Lx - 1):+.2f} %{ring})")
    print(f"  D_f {1e3 * m['D']:.3f} mm (reference {1e3 * Dx:.2f}, error {100 * (m['D'] / Dx - 1):+.2f} %)")
    print(f"  EPS_max {m['eps_max']:.2f}, T_max {m['T_max']:.0f} K, lowest node y {m['min_y']:.1e} m")
    rows = profile_table(name, m)
    if rows:
        print("  side radius [mm] at height y (run / test): " + ", ".join(
            f"y {h:.1f}: {rs:.2f} / {rt:.2f} ({100 * (rs / rt - 1):+.1f} %)" for h, rs, rt in rows))
    print(f"  KE0 {m['ke0']:.3f} J/rad -> internal {m['ie_end']:.3f} "
          f"({100 * m['ie_end'] / m['ke0']:.1f} %) + residual KE {m['ke_end']:.3f} + hourglass "
          f"{m['hg_end']:.2e}; balance error max {100 * m['balance']:.3f} %")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--convergence", action="store_true")
    ap.add_argument("--t7a", action="store_true")
    ap.add_argument("--velocities", action="store_true")
    ap.add_argument("--zafit", action="store_true")
    ap.add_argument("--out", default="out")
    args = ap.parse_args()
    rows = []
    for name, label, L0, D0, Lx, Dx in CASES + ([ZAFIT] if args.zafit else []) + ([T7A] if args.t7a else []):
        out = os.path.join(args.out, name)
        summary = su.run(su.deck_path(name), out)
        m = measure(out, averaged=name != T7A[0])
        report(name, label, Lx, Dx, m, summary)
        if name == T7A[0]:
            (l0, l1), (d0, d1) = T7A_BAND
            ok = l0 <= m["L"] <= l1 and d0 <= m["D"] <= d1
            print(f"  T7a band: L_f in [{l0 * 1e3}, {l1 * 1e3}] mm, D_f in [{d0 * 1e3}, {d1 * 1e3}] mm: "
                  + ("inside" if ok else "OUTSIDE"))
        print(f"  wrote {plot(out, name, label, L0, D0, Lx, Dx, m, summary)}")
        rows.append((name, summary["elements"] // (100 if name == T7A[0] else 66), summary, m, Lx, Dx))
        if name == T7A[0]:
            continue
        if args.convergence:
            for nr, nl in ((5, 33), (20, 133)):
                vout = f"{out}_nr{nr}"
                s = su.run(su.deck_path(name), vout, elements=[nr, nl])
                rows.append((name, nr, s, measure(vout), Lx, Dx))
    if args.velocities:
        for deck in ["taylor_ofhc_190"] + (["taylor_ofhc_190_zafit"] if args.zafit else []):
            for v, Lx, Dx, _ in COPPER_SWEEP:
                name = deck.replace("190", str(v))
                label = f"OFHC copper, {v} m/s" + (", JC fitted to ZA" if "zafit" in deck else "")
                out = os.path.join(args.out, name)
                s = su.run(su.deck_path(deck), out, substitutions=[
                    (r"initial_velocity: \[0\.0, -190\.0\]", f"initial_velocity: [0.0, -{v}.0]")])
                m = measure(out)
                report(name, label, Lx, Dx, m, s)
                print(f"  wrote {plot(out, name, label, 25.4e-3, 7.62e-3, Lx, Dx, m, s)}")
                rows.append((name, 10, s, m, Lx, Dx))
    print("\n| case | elements (r x L) | h [mm] | L_f [mm] (error) | D_f [mm] (error) | EPS_max | "
          "balance | cycles | wall [s] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, nr, s, m, Lx, Dx in sorted(rows, key=lambda r: (r[0], r[1])):
        ne = s["elements"]
        print(f"| {name} | {nr} x {ne // nr} | {(3.2 if name == T7A[0] else 3.81) / nr:.3f} | {1e3 * m['L']:.2f} ({100 * (m['L'] / Lx - 1):+.1f} %) "
              f"| {1e3 * m['D']:.2f} ({100 * (m['D'] / Dx - 1):+.1f} %) | {m['eps_max']:.2f} "
              f"| {100 * m['balance']:.3f} % | {s['cycles']} | {s['wall_time']:.1f} |")


if __name__ == "__main__":
    main()
