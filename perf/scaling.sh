#!/bin/bash
# MPI x OpenMP scaling of a whole run: the brick wall of perf/scaling_wall.yaml,
#   strong: one wall of >= 200k elements at 1 x 1, 1 x 2 and 2 x 1 ranks x threads;
#   weak:   half the wall on 1 x 1 against the whole wall on 2 x 1 (and on 1 x 2);
# plus the decomposition's traffic at 2, 3 and 4 ranks (oversubscribed: bytes, not times).
# Prints a table, writes OUT_DIR/scaling.md, OUT_DIR/scaling.png and every summary.json.
#
#   perf/scaling.sh [BUILD_DIR] [OUT_DIR]
#
# BUILD_DIR (default: build) holds bin/scpdyn; OUT_DIR defaults to perf/results/scaling.
# Environment: NX NY NZ (bricks of the strong wall, default 20 2 40: 204 800 + 64 elements),
# RUNS (repetitions, the fastest counts; default 2), TRAFFIC=0 skips the traffic runs,
# PYTHON (default /usr/bin/python3, with matplotlib for the chart).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../build}" && pwd)
out=${2:-$here/results/scaling}
mkdir -p "$out"
py=${PYTHON:-/usr/bin/python3}
nx=${NX:-20} ny=${NY:-2} nz=${NZ:-40} runs=${RUNS:-2}
export OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-1}
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=${OMPI_ALLOW_RUN_AS_ROOT_CONFIRM:-1}

deck() { # deck NAME NX NY NZ: the wall with the striker at the middle of its face
  "$py" - "$here/scaling_wall.yaml" "$out/$1.yaml" "$2" "$3" "$4" <<'PY'
import sys
src, dst, nx, ny, nz = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
text = open(src).read()
for k, v in (('NX', nx), ('NY', ny), ('NZ', nz), ('XS', round(nx * 0.24 / 2 - 0.06, 6)),
             ('ZS', round(nz * 0.06 / 2 - 0.06, 6))):
    text = text.replace(k, str(v))
open(dst, 'w').write(text)
PY
}

run() { # run NAME RANKS THREADS: the fastest of RUNS runs -> $out/NAME.summary.json
  local name=$1 ranks=$2 threads=$3 best=""
  for ((k = 0; k < runs; ++k)); do
    local dir="$out/run_$name"
    rm -rf "$dir"
    if [ "$ranks" = 1 ]; then
      OMP_NUM_THREADS=$threads OMP_PROC_BIND=spread OMP_PLACES=cores \
        "$build/bin/scpdyn" "$out/${name%%.*}.yaml" -o "$dir" > /dev/null 2> "$dir.log" || { cat "$dir.log"; exit 1; }
    else
      OMP_NUM_THREADS=$threads OMP_PROC_BIND=false \
        mpirun -np "$ranks" --oversubscribe --bind-to "${BIND:-core}" \
        "$build/bin/scpdyn" "$out/${name%%.*}.yaml" -o "$dir" > /dev/null 2> "$dir.log" || { cat "$dir.log"; exit 1; }
    fi
    rm -f "$dir"/*.h5  # ~100 MB of fields per run; the summary and histories are what counts
    local t
    t=$("$py" -c "import json; print(json.load(open('$dir/summary.json'))['cycle_wall_time'])")
    echo "  $name ${ranks}x$threads: $t s" >&2
    if [ -z "$best" ] || "$py" -c "import sys; sys.exit(0 if $t < $best else 1)"; then
      best=$t
      cp "$dir/summary.json" "$out/$name.summary.json"
    fi
  done
}

echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ); host: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) cores; load before: $(cut -d' ' -f1-3 /proc/loadavg)" > "$out/host.txt"
deck strong "$nx" "$ny" "$nz"
deck half "$nx" "$ny" "$((nz / 2))"
run strong.1x1 1 1
run strong.1x2 1 2
run strong.2x1 2 1
run half.1x1 1 1
if [ "${TRAFFIC:-1}" != 0 ]; then
  # oversubscribed (bytes, not times): one run each
  for np in 3 4; do runs=1 BIND=none run strong.${np}x1 "$np" 1; done
  deck quarter "$nx" "$ny" "$((nz / 4))"
  for np in 2 4; do runs=1 BIND=none run quarter.${np}x1 "$np" 1; done
fi

"$py" - "$out" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
S = {os.path.basename(p)[:-len('.summary.json')]: json.load(open(p))
     for p in glob.glob(out + '/*.summary.json')}
def t(k): return S[k]['cycle_wall_time']
lines = ['| run | ranks x threads | elements | cycles | cycle time [s] | ms per cycle | speed-up | efficiency |',
         '|---|---|---|---|---|---|---|---|']
def row(k, label, ref=None, ideal=1.0, weak=False):
    s = S[k]; r, th = s['ranks'], s['threads']
    sp = t(ref) / t(k) if ref else 1.0
    eff = (sp if weak else sp / (r * th)) if ref else 1.0
    lines.append('| %s | %d x %d | %d | %d | %.2f | %.1f | %.2f | %.0f %% |' % (
        label, r, th, s['elements'], s['cycles'], t(k), 1e3 * t(k) / s['cycles'], sp, 100 * eff))
row('strong.1x1', 'strong')
row('strong.1x2', 'strong', 'strong.1x1')
row('strong.2x1', 'strong', 'strong.1x1')
row('half.1x1', 'weak, half wall')
row('strong.2x1', 'weak, whole wall', 'half.1x1', weak=True)
row('strong.1x2', 'weak, whole wall', 'half.1x1', weak=True)
steps = sorted(set(S['strong.1x1']['timers']) | set(S['strong.2x1']['timers']))
lines += ['', '| step | 1 x 1 [s] | 1 x 2 [s] | 2 x 1: min / mean / max over ranks [s] |', '|---|---|---|---|']
for st in steps:
    a = S['strong.1x1']['timers'].get(st, 0); b = S['strong.1x2']['timers'].get(st, 0)
    c = S['strong.2x1']['timers_ranks'].get(st, {'min': 0, 'mean': 0, 'max': 0})
    lines.append('| %s | %.3f | %.3f | %.3f / %.3f / %.3f |' % (st, a, b, c['min'], c['mean'], c['max']))
traffic = [k for k in sorted(S) if 'decomposition' in S[k]]
if traffic:
    lines += ['', '| run | ranks | elements per rank (max) | shared nodes (max) | neighbours (max) | ghost faces (max) | bytes per cycle per rank: mean / max | of which step 8 ghost copies (max) |',
              '|---|---|---|---|---|---|---|---|']
    for k in traffic:
        d = S[k]['decomposition']
        lines.append('| %s | %d | %d | %d | %d | %d | %.0f / %.0f | %.0f |' % (
            k, S[k]['ranks'], d['elements']['max'], d['shared_nodes']['max'], d['neighbours']['max'],
            d['ghost_faces']['max'], d['bytes_per_cycle']['mean'], d['bytes_per_cycle']['max'],
            d['bytes_ghost_copies_per_cycle']['max']))
text = '\n'.join(lines) + '\n'
open(out + '/scaling.md', 'w').write(open(out + '/host.txt').read() + '\n' + text)
print(text)
try:
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
    labels = ['1 x 1', '1 x 2', '2 x 1']
    keys = ['strong.1x1', 'strong.1x2', 'strong.2x1']
    ms = [1e3 * t(k) / S[k]['cycles'] for k in keys]
    ax[0].bar(labels, ms, color=['grey', 'tab:blue', 'tab:orange'])
    ax[0].axhline(ms[0] / 2, ls='--', c='k', lw=1, label='ideal on 2 cores')
    for i, m in enumerate(ms):
        ax[0].text(i, m, '%.0f ms\n%.0f %%' % (m, 100 * ms[0] / (2 * m) if i else 100), ha='center', va='bottom', fontsize=8)
    ax[0].set_ylabel('wall time per cycle [ms]')
    ax[0].set_title('strong: %d elements' % S['strong.1x1']['elements'], fontsize=9)
    ax[0].legend(fontsize=8); ax[0].set_ylim(0, ms[0] * 1.25)
    wk = ['half.1x1', 'strong.1x2', 'strong.2x1']
    ms = [1e3 * t(k) / S[k]['cycles'] for k in wk]
    ax[1].bar(['1 x 1\nhalf wall', '1 x 2\nwhole wall', '2 x 1\nwhole wall'], ms,
              color=['grey', 'tab:blue', 'tab:orange'])
    ax[1].axhline(ms[0], ls='--', c='k', lw=1, label='ideal')
    for i, m in enumerate(ms):
        ax[1].text(i, m, '%.0f ms\n%.0f %%' % (m, 100 * ms[0] / m), ha='center', va='bottom', fontsize=8)
    ax[1].set_title('weak: %d elements per core' % S['half.1x1']['elements'], fontsize=9)
    ax[1].legend(fontsize=8); ax[1].set_ylim(0, max(ms) * 1.25)
    fig.suptitle('scpdyn brick wall (implicit joints), ranks x threads on a 2-core machine', fontsize=10)
    fig.tight_layout()
    fig.savefig(out + '/scaling.png', dpi=110)
except ImportError:
    print('matplotlib missing: no chart', file=sys.stderr)
PY
