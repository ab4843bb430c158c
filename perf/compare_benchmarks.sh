#!/usr/bin/env bash
# Two builds' benchmarks, interleaved: is the new build faster or slower than the base?
#
#   perf/compare_benchmarks.sh BASE_BIN_DIR NEW_BIN_DIR [ROUNDS]
#   e.g. perf/compare_benchmarks.sh /path/to/ref-build/bin build/bin 3
#
# Each BIN_DIR holds bench_cycle, bench_element and bench_contact (a build configured with
# -DSCPDYN_ENABLE_PERF=ON). ROUNDS (default 3) rounds; in each, every job below runs as one
# process of the base binary, then one of the new binary, with OMP_NUM_THREADS=T
# OMP_PROC_BIND=spread OMP_PLACES=threads: the host's speed drifts by a third between minutes
# (perf/README.md), so the two builds run side by side in time, as perf/interleave.py does.
# Every repetition of every run goes to OUT_DIR/repetitions.csv (OUT_DIR: environment OUT, by
# default a new temporary directory; the raw Google Benchmark JSON of each run is kept there
# too). The table printed at the end, per benchmark and thread count: the metric, the median
# over all repetitions of base (A) and new (B), B/A of those medians, the median over the
# rounds of the per-round ratio (each round's median of B over that round's median of A: the
# steadier number when the host's speed moves between rounds), and the minimum of each (the
# host's noise only slows a run down). Ratios above 1 mean the new build is slower. One build
# against itself, 3 rounds on the shared 2-core host (load average 1-3.4 from others' jobs),
# gave B/A 0.84-1.14 and paired ratios 0.85-1.09: with 3 rounds only differences beyond about
# 15 % stand out; for smaller ones use more rounds in a quiet window and read the minima too.
#
# Metric: the benchmark's own per-unit time counter, ns_per_elem_cycle (bench_cycle,
# bench_element) or ns_per_cp_cycle (BM_CpUpdate), else the real time per iteration in ms
# (BM_Detection: one whole contact search). perf/interleave.py is not used because it reads
# only ns_per_elem_cycle from the console output; this reads each run's JSON instead
# (--benchmark_out), so bench_contact fits too.
#
# Jobs and filters (one full comparison, 3 rounds, about 10 minutes on the 2-core host):
#   bench_cycle   1 thread   CycleAtomic(General)?/   whole cycle, 64^3 hex8 box; at 1 thread
#                                                      atomic and gather are both plain adds,
#                                                      so Gather would measure the same code;
#                                                      General: every pack on the general path
#   bench_cycle   2 threads  CycleGather(General)?/   the default scatter at 2 threads (the
#                                                      atomic mode there is 3.6x slower and no
#                                                      deck uses it for speed)
#   bench_element 1 thread   HexKernel(Atomic|Gather)/|UpdateNodes/|ZeroForces/NoLoads
#                                                      step 6, steps 12 and 5 alone (the corner
#                                                      store/gather pieces are inside Gather)
#   bench_contact 1 thread   Detection at 10^4 faces (2D, 3D) and CpUpdate of the middle
#                                                      sizes (2D n=71, 3D n=15), all four
#                                                      joint options: the million-face and the
#                                                      smallest cases take minutes or are all
#                                                      launch overhead (perf/README.md, Contact)
# with REPS (default 5) repetitions a process and --benchmark_min_time=MIN_TIME (default 0.5 s,
# Google Benchmark's own, a repetition). Environment: REPS, MIN_TIME, OUT.
# Exit status: 0 done, 1 a benchmark run failed, 2 usage error.
set -uo pipefail

usage() { sed -n '2,/^set -uo/{/^set -uo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
case ${1:-} in -h|--help) usage; exit 0 ;; esac
if [[ $# -lt 2 || $# -gt 3 ]]; then
  echo "usage: perf/compare_benchmarks.sh BASE_BIN_DIR NEW_BIN_DIR [ROUNDS]  (--help)" >&2
  exit 2
fi
base=$1 new=$2 rounds=${3:-3}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "compare_benchmarks.sh: ROUNDS must be a positive integer" >&2; exit 2; }
for dir in "$base" "$new"; do
  for b in bench_cycle bench_element bench_contact; do
    [[ -x $dir/$b ]] || { echo "compare_benchmarks.sh: no executable $dir/$b" >&2; exit 2; }
  done
done
reps=${REPS:-5}
min_time=${MIN_TIME:-0.5}
out=${OUT:-$(mktemp -d -t compare-benchmarks.XXXXXX)}
mkdir -p "$out" || exit 2

# binary, threads, filter (a regex without spaces)
jobs=(
  "bench_cycle 1 CycleAtomic(General)?/"
  "bench_cycle 2 CycleGather(General)?/"
  "bench_element 1 HexKernel(Atomic|Gather)/|UpdateNodes/|ZeroForces/NoLoads"
  "bench_contact 1 Detection/dim:[23]/faces:10000/|CpUpdate/dim:(2/n:71|3/n:15)/"
)

export OMP_PROC_BIND=spread OMP_PLACES=threads
{
  echo "date $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "A $base"
  echo "B $new"
  echo "rounds $rounds reps $reps min_time $min_time"
  echo "load before $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$out/compare.txt"
echo "compare_benchmarks.sh: A = $base, B = $new, $rounds rounds; every repetition in $out" >&2

failed=0
t0=$SECONDS
for ((r = 1; r <= rounds; r++)); do
  for job in "${jobs[@]}"; do
    read -r bench threads filter <<< "$job"
    for side in A B; do
      dir=$base
      [[ $side == B ]] && dir=$new
      json="$out/r${r}_${side}_${bench}_t${threads}.json"
      OMP_NUM_THREADS=$threads "$dir/$bench" --benchmark_filter="$filter" \
        --benchmark_repetitions="$reps" --benchmark_min_time="$min_time" \
        --benchmark_out_format=json --benchmark_out="$json" \
        > "${json%.json}.log" 2>&1 < /dev/null
      status=$?
      if [[ $status != 0 ]]; then
        echo "compare_benchmarks.sh: $side $bench T$threads failed ($status), see ${json%.json}.log" >&2
        failed=1
      fi
      echo "round $r/$rounds  $side  $bench T$threads  ($((SECONDS - t0)) s, load $(cut -d' ' -f1 /proc/loadavg))" >&2
    done
  done
done
echo "load after $(cut -d' ' -f1-3 /proc/loadavg), $((SECONDS - t0)) s" >> "$out/compare.txt"

/usr/bin/python3 - "$out" <<'PY' || failed=1
import collections, glob, json, os, re, statistics, sys

out = sys.argv[1]
UNIT = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}  # to ms
rows = []  # round, side, bench, threads, name, metric, value
for path in sorted(glob.glob(os.path.join(out, "r*_*_*_t*.json"))):
    m = re.match(r"r(\d+)_([AB])_(\w+)_t(\d+)\.json$", os.path.basename(path))
    try:
        data = json.load(open(path))
    except (OSError, ValueError):
        continue
    for b in data.get("benchmarks", []):
        if b.get("run_type") != "iteration" or b.get("error_occurred"):
            continue
        name = b["run_name"] if "run_name" in b else b["name"]
        name = re.sub(r"/real_time$", "", name)
        for counter in ("ns_per_elem_cycle", "ns_per_cp_cycle"):
            if counter in b:  # kIsRate | kInvert counters are seconds in the JSON
                metric, value = counter, b[counter] * 1e9
                break
        else:
            metric, value = "ms_per_iteration", b["real_time"] * UNIT[b.get("time_unit", "ns")]
        rows.append((int(m.group(1)), m.group(2), m.group(3), int(m.group(4)), name, metric, value))

with open(os.path.join(out, "repetitions.csv"), "w") as f:
    f.write("round,build,binary,threads,benchmark,metric,value\n")
    for r in rows:
        f.write(",".join(map(str, r)) + "\n")

every = collections.defaultdict(list)          # (bench, T, name, side) -> values
per_round = collections.defaultdict(list)      # (bench, T, name, side, round) -> values
metric_of, order = {}, []
for rnd, side, bench, t, name, metric, value in rows:
    key = (bench, t, name)
    if key not in metric_of:
        order.append(key)
    metric_of[key] = metric
    every[key + (side,)].append(value)
    per_round[key + (side, rnd)].append(value)

rounds = sorted({r[0] for r in rows})
binaries = ["bench_cycle", "bench_element", "bench_contact"]  # the jobs' order, then run order
order.sort(key=lambda k: (binaries.index(k[0]) if k[0] in binaries else len(binaries), k[1]))
head = f"{'benchmark':<42} {'T':>1} {'metric':<17} {'median A':>10} {'median B':>10} {'B/A':>6} " \
       f"{'paired':>6} {'min A':>10} {'min B':>10}"
print(head)
print("-" * len(head))
for key in order:
    a, b = every.get(key + ("A",), []), every.get(key + ("B",), [])
    if not a or not b:
        print(f"{key[2]:<42} {key[1]:>1} missing in {'A' if not a else 'B'}")
        continue
    ma, mb = statistics.median(a), statistics.median(b)
    paired = [statistics.median(per_round[key + ("B", r)]) / statistics.median(per_round[key + ("A", r)])
              for r in rounds if per_round.get(key + ("A", r)) and per_round.get(key + ("B", r))]
    print(f"{key[2]:<42} {key[1]:>1} {metric_of[key]:<17} {ma:>10.4g} {mb:>10.4g} {mb / ma:>6.3f} "
          f"{statistics.median(paired):>6.3f} {min(a):>10.4g} {min(b):>10.4g}")
print(f"{len(rounds)} rounds; medians over every repetition; B/A > 1: B is slower; "
      f"paired: median over the rounds of that round's B/A")
PY
exit $failed
