#!/usr/bin/env python3
"""Interleaved benchmark runs: the host's speed drifts by a third between minutes, so two
builds are compared round by round, not run after run.

usage: perf/interleave.py ROUNDS THREADS BENCH_BINARY... [-- GOOGLE_BENCHMARK_ARGS...]
  e.g. perf/interleave.py 10 1 ref/bin/bench_cycle build/bin/bench_cycle -- \
           --benchmark_filter=CycleAtomic/ --benchmark_repetitions=5

Each round runs every binary once, in the order given, as one process with
OMP_NUM_THREADS=THREADS OMP_PROC_BIND=spread OMP_PLACES=threads. Printed: each run's median
ns_per_elem_cycle per benchmark, then per binary and benchmark the median over the rounds and
the median of the per-round ratio to the first binary (same benchmark name, or with a
trailing "General" dropped), and the minimum and 10th percentile over every repetition of
every round: the host's noise only ever slows a run down, so these show what the code does on
a quiet machine, where the medians show what this host gave. Plain python3, no packages.

With CSV=FILE in the environment, every repetition is also appended to FILE (columns threads,
round, binary, benchmark, ns_per_elem_cycle) for perf/plot_cycle.py. COUNTER=NAME reads another
counter than ns_per_elem_cycle, e.g. COUNTER=ns_per_cp_cycle (or cpu_ns_per_cp_cycle) for
bench_contact: a time counter ("806.5ns") is taken in ns, a plain one ("1.3k") as printed.
"""
import collections
import os
import re
import statistics
import subprocess
import sys


def main():
    args = sys.argv[1:]
    extra = []
    if "--" in args:
        extra = args[args.index("--") + 1:]
        args = args[:args.index("--")]
    if len(args) < 3:
        sys.exit(__doc__)
    rounds, threads, binaries = int(args[0]), args[1], args[2:]
    env = dict(os.environ, OMP_NUM_THREADS=threads, OMP_PROC_BIND="spread", OMP_PLACES="threads")
    counter = os.environ.get("COUNTER", "ns_per_elem_cycle")
    value = re.compile(r"^(BM_\S+?)/real_time\s.*(?<![\w])" + re.escape(counter)
                       + r"=([0-9.]+)([kMGmunp]?)(s?)(?![\w])")
    plain = {"": 1.0, "k": 1e3, "M": 1e6, "G": 1e9, "m": 1e-3, "u": 1e-6, "n": 1e-9, "p": 1e-12}
    in_ns = {"": 1e9, "m": 1e6, "u": 1e3, "n": 1.0, "p": 1e-3}  # a time counter, printed in s
    csv = open(os.environ["CSV"], "a") if os.environ.get("CSV") else None
    if csv and csv.tell() == 0:
        csv.write(f"threads,round,binary,benchmark,{counter}\n")
    runs = collections.defaultdict(dict)  # (binary, benchmark) -> round -> median
    every = collections.defaultdict(list)  # (binary, benchmark) -> every repetition
    for r in range(rounds):
        for b in binaries:
            out = subprocess.run([b] + extra, env=env, capture_output=True, text=True).stdout
            values = collections.defaultdict(list)
            for line in out.splitlines():
                m = value.match(line)
                if m:
                    scale = (in_ns if m.group(4) else plain)[m.group(3)]
                    values[m.group(1)].append(float(m.group(2)) * scale)
            cells = []
            for name, v in sorted(values.items()):
                runs[(b, name)][r] = statistics.median(v)
                every[(b, name)] += v
                for x in v if csv else []:
                    csv.write(f"{threads},{r + 1},{b},{name},{x}\n")
                cells.append(f"{name[3:]} {statistics.median(v):.1f}")
            load = open("/proc/loadavg").read().split()[0]
            print(f"round {r + 1} T{threads} {b}: {'  '.join(cells)}  (load {load})", flush=True)
    print("median over rounds, the median per-round ratio to the first binary, and the min and")
    print("10th percentile over all repetitions:")
    first = binaries[0]
    for (b, name), per_round in runs.items():
        base = runs.get((first, name)) or runs.get((first, re.sub("General$", "", name)), {})
        ratios = [per_round[r] / base[r] for r in per_round if r in base]
        ratio = f"{statistics.median(ratios):.3f}" if ratios else "-"
        reps = sorted(every[(b, name)])
        print(f"  {b}  {name}: {statistics.median(per_round.values()):.1f} ns, ratio {ratio}, "
              f"min {reps[0]:.1f}, p10 {reps[len(reps) // 10]:.1f}, "
              f"rounds {' '.join(f'{v:.0f}' for v in sorted(per_round.values()))}")


if __name__ == "__main__":
    main()
