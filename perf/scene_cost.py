#!/usr/bin/python3
"""Whole-run cost of scene decks: each deck at each rank and thread count (and with each binary),
interleaved round after round (the host's speed drifts; interleaving spreads the drift over all
variants), with bound threads. Prints the median wall time of the cycle, its spread, and the
contact share (steps 3, 4, 8, 9 of the cycle's step timers) per binary, deck and thread count.

    perf/scene_cost.py [--rounds 5] [--threads 1 2] [--ranks 1 2] [--bin BIN [--bin OTHER]] DECK...

Ranks above 1 run under mpiexec (--oversubscribe; bound threads only with one rank); the
cycle time and the contact share are rank 0's.

Runs go to a temporary directory; only the summaries are read.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CONTACT_STEPS = ("03_", "04_", "08_", "09_")


def run_once(binary, deck, ranks, threads, out):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND="spread",
               OMP_PLACES="threads", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = [binary, deck, "-o", out]
    if ranks > 1:
        env["OMP_PROC_BIND"] = "false"
        cmd = ["mpiexec", "-np", str(ranks), "--oversubscribe"] + cmd
    subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    contact = sum(v for k, v in s["timers"].items() if k.startswith(CONTACT_STEPS))
    return s["cycle_wall_time"], contact / s["cycle_wall_time"], s["cycles"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("decks", nargs="+")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--ranks", type=int, nargs="+", default=[1])
    ap.add_argument("--bin", action="append", help="scpdyn binaries to compare "
                    "(default build/bin/scpdyn)")
    a = ap.parse_args()
    bins = a.bin or [os.path.join(ROOT, "build", "bin", "scpdyn")]
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            for deck in a.decks:
                for n in a.ranks:
                    for t in a.threads:
                        for b, binary in enumerate(bins):
                            out = os.path.join(tmp, f"{os.path.basename(deck)}.{n}.{t}.{b}")
                            results.setdefault((b, deck, n, t), []).append(
                                run_once(binary, deck, n, t, out))
            print(f"round {r + 1}/{a.rounds} done", file=sys.stderr)
    for b, binary in enumerate(bins):
        print(f"bin {b}: {binary}")
    print(f"{'bin':>3s} {'deck':48s} {'rnk':>3s} {'thr':>3s} {'cycles':>6s} {'median s':>9s} "
          f"{'min-max s':>15s} {'contact':>8s}")
    for (b, deck, n, t), runs in results.items():
        walls = [w for w, _, _ in runs]
        share = statistics.median(c for _, c, _ in runs)
        print(f"{b:3d} {os.path.relpath(deck, ROOT):48s} {n:3d} {t:3d} {runs[0][2]:6d} "
              f"{statistics.median(walls):9.3f} {min(walls):7.3f}-{max(walls):7.3f} "
              f"{100 * share:7.1f}%")


if __name__ == "__main__":
    main()
