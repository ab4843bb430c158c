#!/bin/bash
# SIGTERM to `mpirun -np 2 scpdyn DECK` (README, "Running a deck"): the ranks stop after the
# same cycle and leave one restart file, which continues the run at 2 ranks to the
# uninterrupted run's last row of history.csv bit for bit (the same rank count), and at 3 ranks
# to 1e-9 of each column's magnitude (the rank-count invariance). The signalled run would take
# hours (time.end 1 s), so the signal always comes first; the reference and the restarted runs
# stop 20 cycles after the restart with time.max_cycles, which a restart may change.
#   sigterm_restart.sh SCPDYN MPIEXEC WORKDIR
set -euo pipefail
scpdyn=$1 mpiexec=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false
sed 's/^time: {end: [^,]*,/time: {end: 1.0,/' "$here/decks/block_impact_2d.yaml" > "$work/long.yaml"
"$mpiexec" -np 2 --oversubscribe "$scpdyn" "$work/long.yaml" -o "$work/signalled" \
  > /dev/null 2> "$work/signalled.err" &
run=$!
# generous bounds: they only end a test that would otherwise hang
for _ in $(seq 600); do [ -f "$work/signalled/fields.xmf" ] && break; sleep 0.5; done
kill -TERM "$run"
wait "$run" || true # Open MPI's mpirun exits with 1 after signalling its ranks
files=("$work"/signalled/restart_*.h5)
if [ "${#files[@]}" -ne 1 ] || [ ! -f "${files[0]}" ]; then
  echo "expected one restart file, found: ${files[*]}"; cat "$work/signalled.err"; exit 1
fi
grep -q "interrupted by SIGTERM" "$work/signalled.err" || { cat "$work/signalled.err"; exit 1; }
cycle=$(basename "${files[0]}" .h5); cycle=${cycle#restart_}
sed "s/^time: {end: 1.0,/time: {end: 1.0, max_cycles: $((cycle + 20)),/" "$work/long.yaml" \
  > "$work/short.yaml"
"$mpiexec" -np 2 --oversubscribe "$scpdyn" "$work/short.yaml" -o "$work/reference" \
  > /dev/null 2>&1
for np in 2 3; do
  "$mpiexec" -np $np --oversubscribe "$scpdyn" "$work/short.yaml" -o "$work/restarted$np" \
    --restart "${files[0]}" > /dev/null 2> "$work/restarted$np.err" \
    || { cat "$work/restarted$np.err"; exit 1; }
done
python3 - "$work" "$cycle" <<'PY'
import csv, sys
work, cycle = sys.argv[1], int(sys.argv[2])
def rows(path):
    r = list(csv.reader(open(path)))
    return r[0], [[float(x) for x in row] for row in r[1:]]
def group(c):
    if c in ('kinetic', 'internal', 'hourglass', 'contact', 'external_work', 'contact_dissipation'):
        return 'energy'
    return 'momentum' if c.startswith('momentum') else c
head, ref = rows(work + '/reference/history.csv')
scale = {}
for r in ref:
    for c, x in zip(head, r):
        scale[group(c)] = max(scale.get(group(c), 0.0), abs(x))
status = 0
same = open(work + '/restarted2/history.csv').read().splitlines()[-1]
if same != open(work + '/reference/history.csv').read().splitlines()[-1]:
    print('2 ranks: the last row differs from the uninterrupted run\'s'); status = 1
_, re3 = rows(work + '/restarted3/history.csv')
worst = max(abs(a - b) / max(scale[group(c)], 1e-300) for c, a, b in zip(head, ref[-1], re3[-1]))
print(f'SIGTERM at cycle {cycle}: 2 ranks bitwise, 3 ranks worst relative difference {worst:.3e}')
if not worst <= 1e-9:
    status = 1
sys.exit(status)
PY
