#!/usr/bin/python3
"""Helpers of scripts/same_bits.sh (run with /usr/bin/python3, which has PyYAML).

  same_bits.py deck IN.yaml OUT.yaml [--max-cycles N] [--scatter MODE]
      Writes a copy of the deck with time.max_cycles lowered to N (kept if the deck's own is
      smaller) and/or numerics.scatter set to MODE. The deck is edited as a YAML node tree
      (yaml.compose / yaml.serialize), not as Python values, so every other scalar keeps the
      exact text of the original (6e-05 stays 6e-05; no float goes through a round trip) and
      the parser of scpdyn reads the same numbers. Gmsh paths, relative to the deck's own
      directory, are made absolute because the copy lives elsewhere.

  same_bits.py diff A.csv B.csv [--tolerance TOL]
      One line on two CSV files that differ: the first differing line, and for every column
      that differs its largest relative difference, max |a - b| over the rows divided by the
      largest |value| of the column's family in either file (family(): the energies share one
      scale, the momentum components one, a gauge's velocity components one, ...; so a value
      near zero, or crossing it, does not blow the ratio up; energy_balance_error, itself a
      fraction of the energy, is taken as it is). Exit 0 only with --tolerance and
      the same header and rows and every column within TOL, else 1.
"""
import math
import os
import sys

MAX_COLUMNS_SHOWN = 12


def scalar(value, tag="tag:yaml.org,2002:str"):
    import yaml
    return yaml.ScalarNode(tag=tag, value=value)


def mapping_get(node, key):
    for k, v in node.value:
        if getattr(k, "value", None) == key:
            return v
    return None


def mapping_set(node, key, value_node):
    for i, (k, v) in enumerate(node.value):
        if getattr(k, "value", None) == key:
            node.value[i] = (k, value_node)
            return
    node.value.append((scalar(key), value_node))


def rewrite_deck(args):
    import yaml
    src, dst = args[0], args[1]
    max_cycles = scatter = None
    rest = args[2:]
    while rest:
        opt = rest.pop(0)
        if opt == "--max-cycles":
            max_cycles = int(rest.pop(0))
        elif opt == "--scatter":
            scatter = rest.pop(0)
        else:
            sys.exit(f"same_bits.py deck: unknown option {opt}")
    with open(src) as f:
        root = yaml.compose(f)
    if not isinstance(root, yaml.MappingNode):
        sys.exit(f"same_bits.py deck: {src}: not a mapping")
    if max_cycles is not None:
        time = mapping_get(root, "time")
        if not isinstance(time, yaml.MappingNode):
            sys.exit(f"same_bits.py deck: {src}: no time mapping")
        old = mapping_get(time, "max_cycles")
        if old is None or int(old.value) > max_cycles:
            mapping_set(time, "max_cycles", scalar(str(max_cycles), "tag:yaml.org,2002:int"))
    if scatter is not None:
        numerics = mapping_get(root, "numerics")
        if not isinstance(numerics, yaml.MappingNode):
            # "numerics:" left empty (a null) counts as all defaults, as in scpdyn
            numerics = yaml.MappingNode(tag="tag:yaml.org,2002:map", value=[], flow_style=True)
            mapping_set(root, "numerics", numerics)
        mapping_set(numerics, "scatter", scalar(scatter))
    deck_dir = os.path.dirname(os.path.abspath(src))
    parts = mapping_get(root, "parts")
    for part in parts.value if isinstance(parts, yaml.SequenceNode) else []:
        mesh = mapping_get(part, "mesh") if isinstance(part, yaml.MappingNode) else None
        file = mapping_get(mesh, "file") if isinstance(mesh, yaml.MappingNode) else None
        if isinstance(file, yaml.ScalarNode) and not os.path.isabs(file.value):
            mapping_set(mesh, "file", scalar(os.path.normpath(os.path.join(deck_dir, file.value))))
    with open(dst, "w") as f:
        f.write(f"# {os.path.basename(src)} for scripts/same_bits.sh"
                f" (max_cycles {max_cycles}, scatter {scatter})\n")
        yaml.serialize(root, f, width=1 << 30)


ENERGIES = ("kinetic", "internal", "hourglass", "external_work", "contact", "contact_dissipation")


def family(column):
    """The columns that share a scale, as tests/parallel/hybrid.sh groups them: the energies,
    the momentum components, and per gauge its velocities, displacements, positions and
    stresses (pressure with the stresses); any other column is its own family."""
    if column in ENERGIES:
        return "energy"
    if column.startswith("momentum"):
        return "momentum"
    if ":" not in column:
        return column
    gauge, q = column.split(":", 1)
    kind = ("velocity" if q[0] == "v" else "displacement" if q[0] == "d" and len(q) == 2 else
            "position" if len(q) == 1 else "stress" if q[0] == "s" or q == "pressure" else q)
    return gauge + ":" + kind


def read_csv(path):
    with open(path) as f:
        return [line.rstrip("\n").split(",") for line in f]


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def diff_csv(args):
    a_path, b_path = args[0], args[1]
    tol = float(args[3]) if len(args) > 3 and args[2] == "--tolerance" else None
    a, b = read_csv(a_path), read_csv(b_path)
    notes = []
    n = min(len(a), len(b))
    first = next((i for i in range(n) if a[i] != b[i]), n)
    if first < max(len(a), len(b)):
        ra = a[first] if first < len(a) else []
        rb = b[first] if first < len(b) else []
        col = next((j for j in range(max(len(ra), len(rb)))
                    if j >= len(ra) or j >= len(rb) or ra[j] != rb[j]), 0)
        name = a[0][col] if a and col < len(a[0]) else f"#{col + 1}"
        va = ra[col] if col < len(ra) else "(none)"
        vb = rb[col] if col < len(rb) else "(none)"
        notes.append(f"first at line {first + 1}, {name}: {va} vs {vb}")
    ok = True
    if len(a) != len(b):
        notes.append(f"{len(a)} vs {len(b)} lines")
        ok = False
    if not a or not b or a[0] != b[0]:
        notes.append("headers differ")
        print("; ".join(notes))
        return 1
    header = a[0]
    worst = [0.0] * len(header)   # largest |a - b| per column
    scale = {}                    # largest |value| per family, in both files
    for ra, rb in zip(a[1:], b[1:]):
        if len(ra) != len(header) or len(rb) != len(header):
            ok = False
            continue
        for j, (x, y) in enumerate(zip(ra, rb)):
            fx, fy = number(x), number(y)
            finite = [v for v in (fx, fy) if v is not None and math.isfinite(v)]
            f = family(header[j])
            scale[f] = max([scale.get(f, 0.0)] + [abs(v) for v in finite])
            if x == y:
                continue
            if len(finite) < 2:  # text, NaN or infinity on one side
                worst[j] = math.inf
                ok = False
            else:
                worst[j] = max(worst[j], abs(fx - fy))
    # energy_balance_error is already a fraction of the energy (and mostly cancellation):
    # its differences are compared as they are, as a fraction of 1
    scale["energy_balance_error"] = 1.0
    rel = []
    for j, name in enumerate(header):
        if worst[j] > 0:
            s = scale.get(family(name), 0.0)
            r = worst[j] / s if s > 0 else math.inf
            rel.append((j, name, r))
            if tol is None or r > tol:
                ok = False
    shown = sorted(sorted(rel, key=lambda jnr: -jnr[2])[:MAX_COLUMNS_SHOWN])
    cols = " ".join(f"{name}={r:.1e}" for _, name, r in shown)
    if len(rel) > len(shown):
        cols += f" (+{len(rel) - len(shown)} smaller)"
    notes.append(f"max rel. diff {cols}" if cols else "no numeric difference")
    print("; ".join(notes))
    return 0 if (tol is not None and ok) else 1


def main():
    if len(sys.argv) < 4 or sys.argv[1] not in ("deck", "diff"):
        sys.exit(__doc__)
    if sys.argv[1] == "deck":
        rewrite_deck(sys.argv[2:])
        return 0
    return diff_csv(sys.argv[2:])


if __name__ == "__main__":
    sys.exit(main())
