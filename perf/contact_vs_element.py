#!/usr/bin/python3
"""The contact cost against the element cost of the same build, threads and run: a CP-cycle
(bench_contact BM_CpUpdate, every option, 2D n:71 and 3D n:15) over a hex8 element-cycle
(bench_cycle BM_CycleAtomic), interleaved round after round (the host's speed drifts), with
bound threads. Prints the median wall-clock ns per CP-cycle and per element-cycle over the
rounds and their ratio, per thread count, as a markdown table.

    perf/contact_vs_element.py [--rounds 3] [--threads 1 2] [--bin build/bin]

The goals of the contact-cost work (perf/README.md): implicit, explicit and slide-line CPs
within 4x an element in 3D (3x in 2D), sticky within 10x.
"""
import argparse
import json
import os
import statistics
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OPTIONS = {0: "implicit", 1: "explicit", 2: "sticky", 3: "slide line"}
CP_FILTER = "BM_CpUpdate/dim:(2/n:71|3/n:15)/option"


def ns(value):
    """A time counter: Google Benchmark writes an inverted rate in seconds."""
    return value * 1e9 if value < 1e-3 else value


def run(binary, bench_filter, threads):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND="spread",
               OMP_PLACES="threads")
    out = subprocess.run([binary, f"--benchmark_filter={bench_filter}", "--benchmark_format=json",
                          "--benchmark_min_time=0.3"], env=env, check=True,
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
    return {b["name"]: b for b in json.loads(out)["benchmarks"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    args = ap.parse_args()
    element = {t: [] for t in args.threads}
    cp = {t: {} for t in args.threads}
    for r in range(args.rounds):
        for t in args.threads:
            e = run(os.path.join(args.bin, "bench_cycle"), "BM_CycleAtomic/", t)
            element[t].append(ns(next(iter(e.values()))["ns_per_elem_cycle"]))
            for name, b in run(os.path.join(args.bin, "bench_contact"), CP_FILTER, t).items():
                cp[t].setdefault(name, []).append(ns(b["ns_per_cp_cycle"]))
        print(f"round {r + 1} of {args.rounds} done", flush=True)
    print("\n| threads | CP option | dim | ns per CP-cycle | ns per hex8 element-cycle | ratio |")
    print("|---|---|---|---|---|---|")
    for t in args.threads:
        el = statistics.median(element[t])
        for name in sorted(cp[t], key=lambda n: (n.split("option:")[1], n)):
            c = statistics.median(cp[t][name])
            dim = name.split("dim:")[1][0]
            option = OPTIONS[int(name.split("option:")[1].split("/")[0])]
            print(f"| {t} | {option} | {dim}D | {c:.0f} | {el:.1f} | {c / el:.1f} |")


if __name__ == "__main__":
    main()
