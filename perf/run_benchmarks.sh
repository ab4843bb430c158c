#!/bin/bash
# Runs the perf/ Google Benchmarks and the whole-run deck at 1 and 2 threads, one process per
# thread count (Kokkos reads OMP_NUM_THREADS at initialize), and prints the medians.
#
#   perf/run_benchmarks.sh [BUILD_DIR] [OUT_DIR]
#
# BUILD_DIR (default: build) must hold bin/bench_element, bin/bench_cycle and bin/scpdyn
# (configure with -DSCPDYN_ENABLE_PERF=ON). OUT_DIR (default: BUILD_DIR/perf-results) gets
# the JSON of every benchmark, the summary.json of every run and summary.txt. Environment:
# THREADS (default "1 2"), REPS (benchmark repetitions, default 5), RUNS (whole runs per
# thread count and scatter, default 1), SCPDYN_BENCH_CELLS (box cells per edge, default 64),
# SUMMARY_ONLY=1 (rebuild summary.txt from the results already in OUT_DIR).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../build}" && pwd)
out=${2:-$build/perf-results}
mkdir -p "$out"
threads=${THREADS:-"1 2"}
reps=${REPS:-5}
runs=${RUNS:-1}
export OMP_PROC_BIND=spread OMP_PLACES=threads

if [ -z "${SUMMARY_ONLY:-}" ]; then
{
  echo "date:    $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "host:    $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) cores"
  echo "commit:  $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$out/summary.txt"

for t in $threads; do
  for b in bench_element bench_cycle; do
    echo "== $b, $t thread(s)" >&2
    OMP_NUM_THREADS=$t "$build/bin/$b" --benchmark_repetitions="$reps" \
      --benchmark_report_aggregates_only=true --benchmark_out_format=json \
      --benchmark_out="$out/${b}_t$t.json" >&2
  done
  for scatter in atomic gather; do
    deck="$out/box64_$scatter.yaml"
    sed "s/scatter: atomic/scatter: $scatter/" "$here/box64.yaml" > "$deck"
    for r in $(seq 1 "$runs"); do
      echo "== scpdyn box64 ($scatter), $t thread(s), run $r" >&2
      OMP_NUM_THREADS=$t "$build/bin/scpdyn" "$deck" -o "$out/box64_${scatter}_t${t}_r$r" > /dev/null
    done
  done
done
echo "load after:  $(cut -d' ' -f1-3 /proc/loadavg)" >> "$out/summary.txt"
else
  sed -i '/^$/,$d' "$out/summary.txt"
fi

python3 - "$out" "$threads" "$runs" >> "$out/summary.txt" <<'EOF'
import json, statistics, sys
out, threads, runs = sys.argv[1], sys.argv[2].split(), int(sys.argv[3])
rows = {}
for t in threads:
    for b in ("bench_element", "bench_cycle"):
        with open(f"{out}/{b}_t{t}.json") as f:
            for r in json.load(f)["benchmarks"]:
                agg = r.get("aggregate_name")
                if agg not in ("median", "min"):
                    continue
                name = r["run_name"].replace("/real_time", "") + (" [min]" if agg == "min" else "")
                scale = {"ns": 1, "us": 1e3, "ms": 1e6, "s": 1e9}[r["time_unit"]]
                cpu = r["cpu_time"] * scale / r["elements"]
                rows.setdefault(name, {})[t] = (r["ns_per_elem_cycle"] * 1e9, cpu)
                if "allocs_per_cycle" in r and agg == "median":
                    rows.setdefault(name + " allocs/cycle", {})[t] = (r["allocs_per_cycle"], None)
    for s in ("atomic", "gather"):
        vals = []
        for k in range(1, runs + 1):
            with open(f"{out}/box64_{s}_t{t}_r{k}/summary.json") as f:
                vals.append(json.load(f)["ns_per_element_cycle"])
        rows.setdefault(f"scpdyn box64 {s} (summary.json)", {})[t] = (statistics.median(vals), None)
print("\nns per element-cycle: median of the repetitions ([min]: fastest), real time")
print("(main-thread CPU time); the scpdyn rows are summary.json's ns_per_element_cycle")
print(f"{'':42s}" + "".join(f"{t + ' thread(s)':>22s}" for t in threads))
for name, v in rows.items():
    cells = []
    for t in threads:
        real, cpu = v.get(t, (float("nan"), None))
        cells.append(f"{real:10.1f}" + (f" ({cpu:7.1f})" if cpu is not None else " " * 10))
    print(f"{name:42s}" + "".join(f"{c:>22s}" for c in cells))
EOF
cat "$out/summary.txt"
