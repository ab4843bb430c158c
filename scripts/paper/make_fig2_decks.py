#!/usr/bin/python3
"""Writes the decks of the paper's Fig. 2 (docs/theory.md 14.1): the 1D jointed wave.

usage: /usr/bin/python3 scripts/paper/make_fig2_decks.py [--strip] [--out DIR]
       (default DIR: inputs/paper; the decks are committed, this script only regenerates them)

A 10 mm layer at 1 km/s hits a 90 mm layer, 100 mm in all, free ends, limestone (rho 2600,
c 4500 m/s, linear elastic, M = rho c^2). Every block is its own part and every block boundary a
joint (as the reference scp-ref/bar1d.py). Set-up of the reference: S = 0.5, C_safe = 0.5,
Emax = 1e4 E0, sigma_t = 0 (C = 0), linear artificial viscosity q = 0.3 rho c |dv| only.
Velocity gauge at the left node of the block that starts at x = 80 mm.

--strip writes the same cases as a 2D plane-strain strip one element high with roller sides
(uniaxial strain, the same physics) instead of dimension 1.
"""
import argparse
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
L, V0, X_IMPACT, X_GAUGE, T_END = 0.1, 1000.0, 0.01, 0.08, 60e-6
E0 = 0.05  # GPa (docs/theory.md 14.1 [A])
# The impactor starts GAP short of the target, for two reasons: a CP created between faces that
# touch at t = 0 gets its closure from the half-step geometry (v dt/2 = 0.056 mm at h = 1 mm),
# more than the smaller apertures; and the first cycle's dt is fixed before the CPs exist, so an
# explicit joint closing in cycle 0 would close by v dt = 0.11 mm > a without the limit (19).
# With GAP > 1.5 v dt the joint is found open and closes from zero force under the limit; the
# impact happens at T_IMPACT, which the plot script subtracts. GAP is two time steps of the
# 1-mm cells at S = 0.5 (2 x 0.5 h/c x V0 = 0.2222 mm): the gap closes at a step boundary, as the
# touching joints of bar1d.py start one (else the impact time is only known to one step).
GAP = 2 * 0.5 * (L / 100) / 4500.0 * V0
T_IMPACT = GAP / V0

# name, option, a [m] (None: solid), cells per block, comment, extra contact keys
CASES = [
    ("solid", None, None, 1, "no joints: one 100-cell bar (the impact node takes v/2)"),
    ("a1e-7_implicit", "implicit", 1e-7, 1, "very stiff joints, quasi-implicit update"),
    ("a1e-7_slide", "slide_line", 1e-7, 1, "slide lines (no penetration, no tension)"),
    ("a1e-7_explicit", "explicit", 1e-7, 1, "very stiff joints, explicit update, C_safe 0.5; "
     "stopped after 2000 cycles: outcome (g) is its time step"),
    ("a1e-6_implicit", "implicit", 1e-6, 1, "stiff joints, quasi-implicit update"),
    ("a1e-5_implicit", "implicit", 1e-5, 1, "medium joints, quasi-implicit update"),
    ("a1e-5_explicit", "explicit", 1e-5, 1, "medium joints, explicit update, C_safe 0.5"),
    ("a1e-4_implicit", "implicit", 1e-4, 1, "soft joints, quasi-implicit update"),
    ("a1e-4_explicit", "explicit", 1e-4, 1, "soft joints, explicit update, C_safe 0.5"),
    ("solid_10cpb", None, None, 10, "no joints, 1000 cells (h = 0.1 mm)"),
    ("a1e-4_implicit_10cpb", "implicit", 1e-4, 10, "soft joints, 10 cells per 1 mm block"),
    ("a1e-4_explicit_10cpb", "explicit", 1e-4, 10, "soft joints, 10 cells per 1 mm block"),
]


def fmt(x):
    return ("%.6g" % x) if abs(x) >= 1e-4 or x == 0 else ("%.6e" % x)


def deck(name, option, a, cpb, comment, strip, courant=0.5, c_safe="0.5", extra_gauges=()):
    """Deck text of one case. `courant`, `c_safe` (explicit joints: a number or "off") and
    `extra_gauges` (x positions [m] of further velocity gauges, each at the left node of the
    block starting there) serve the sweep of speed_accuracy.py."""
    dim = 2 if strip else 1
    nblock = 100
    bsize = L / nblock
    h = bsize / cpb
    width = h  # strip height = one cell
    head = [
        f"# Paper Fig. 2 (docs/theory.md 14.1): 1D jointed wave, {comment}.",
        "# 10 mm at 1 km/s hits 90 mm; free ends; limestone rho 2600, c 4500 m/s (M = 52.65 GPa);",
        f"# {nblock} blocks of {bsize * 1e3:g} mm, {cpb} cell(s) per block (h = {h * 1e3:g} mm), "
        "every block its own part;",
        "# S = 0.5, linear viscosity q = 0.3 rho c |dv| (no quadratic term), as scp-ref/bar1d.py.",
    ]
    if option:
        head.append(f"# The impactor starts {GAP * 1e3:.4f} mm short of the target (impact at "
                    f"t = {T_IMPACT * 1e6:.4f} us = 2 steps), see the script.")
        head.append(f"# Joints: a = {a * 1e3:g} mm, E0 = {E0} GPa, Emax = 1e4 E0, sigma_t = 0, "
                    + (f"C_safe = {c_safe}." if option == "explicit" else "no time-step limit."))
    if strip:
        head.append("# 2D variant: plane-strain strip one cell high, roller sides (uniaxial strain);")
        head.append("# CP forces at the POC shape functions (the penetration weights of two exactly")
        head.append("# aligned faces flip with round-off and drive the quads' zigzag mode); stiffness")
        head.append("# hourglass control (with the viscous one the quads next to the impact joint")
        head.append("# hourglass in the 10-cells-per-block runs).")
    head.append("# Generated by scripts/paper/make_fig2_decks.py.")
    out = head + [
        f"title: fig2 {name}",
        f"dimension: {dim}",
        "geometry: plane_strain" if strip else None,
        f"time: {{end: {T_END:g}, courant: {courant:g}"
        + (", max_cycles: 2000}" if name == "a1e-7_explicit" else "}"),
        "output: {field_interval: 0, history_interval: 0}",
        "numerics: {bulk_viscosity: {linear: 0.3, quadratic: 0.0}"
        + (", hourglass: {type: stiffness, coefficient: 0.05}}" if strip else "}"),
        "materials:",
        "  - {name: limestone, model: elastic, density: 2600, youngs_modulus: "
        + ("43.875e9, poisson_ratio: 0.25}" if strip else "52.65e9, poisson_ratio: 0.0}"),
        "parts:",
    ]
    out = [l for l in out if l is not None]

    def part(pname, x0, size, cells, v):
        if strip:
            mesh = (f"{{element: quad4, elements: [{cells}, 1], origin: [{fmt(x0)}, 0.0], "
                    f"size: [{fmt(size)}, {fmt(width)}]}}")
            vel = f"[{v:g}, 0.0]"
        else:
            mesh = f"{{element: line2, elements: [{cells}], origin: [{fmt(x0)}], size: [{fmt(size)}]}}"
            vel = f"[{v:g}]"
        s = f"  - {{name: {pname}, material: limestone, mesh: {mesh}"
        if v:
            s += f", initial_velocity: {vel}"
        if option is None:
            s += ", merge_nodes: true"
        return s + "}"

    if option is None:  # solid: impactor and target merged at x = 10 mm
        n_imp = round(X_IMPACT / h)
        out.append(part("impactor", 0.0, X_IMPACT, n_imp, V0))
        out.append(part("target", X_IMPACT, L - X_IMPACT, round((L - X_IMPACT) / h), 0.0))
    else:
        for b in range(nblock):
            x0 = b * bsize - (GAP if b * bsize < X_IMPACT - 1e-12 else 0.0)
            out.append(part(f"b{b:03d}", x0, bsize, cpb, V0 if x0 < X_IMPACT - 1e-12 else 0.0))
    if strip:
        out += [
            "node_sets:",
            f"  - {{name: all, box: {{min: [-1, -1], max: [1, 1]}}}}",
            "boundary_conditions:",
            "  - {type: velocity, node_set: all, component: y, value: 0}",
        ]
    if option:
        out += [
            "contact:",
            "  search_interval: once",
            f"  search_gap: {fmt(2 * GAP)}",
            "  surfaces:",
            f"    - {{name: joints, part: \"*\", option: {option}, a: {fmt(a * 1e3)}, E0: {E0}, "
            "C: 0.0, sigma_t: 0.0" + (f", C_safe: {c_safe}" if option == "explicit" else "")
            + (", distribution: poc" if strip else "") + "}",
        ]
    # the gauge: the left node of the block starting at 80 mm (parts are numbered in order,
    # nodes x-fastest within a part), in the solid bar the node there; x is recorded too so that
    # the plot script can check which node the gauge reads
    out.append("gauges:")
    for k, xg in enumerate((X_GAUGE,) + tuple(extra_gauges)):
        if option:
            per_part = (cpb + 1) * (2 if strip else 1)
            g = f"node: {round(xg / bsize) * per_part}"
        else:
            g = f"point: [{fmt(xg)}, 0.0]" if strip else f"point: [{fmt(xg)}]"
        gname = "g80" if k == 0 else f"g{round(xg * 1e3)}"
        out.append(f"  - {{name: {gname}, {g}, quantities: [vx, x]}}")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--strip", action="store_true")
    ap.add_argument("--out", default=os.path.join(ROOT, "inputs", "paper"))
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for c in CASES:
        path = os.path.join(args.out, f"fig2_{c[0]}.yaml")
        with open(path, "w") as f:
            f.write(deck(*c, strip=args.strip))
        print(path)


if __name__ == "__main__":
    main()
