#!/bin/bash
# Hybrid MPI x OpenMP: every deck of tests/parallel/decks/ run as 1 rank x 1 thread,
# 2 ranks x 1 thread, 3 ranks x 1 thread and 1 rank x 2 threads.
# - Bitwise: under numerics.scatter gather (the default) every nodal sum is added in the serial
#   order at any rank and thread count (docs/theory.md 2.2), so gauges.csv and every dataset of
#   fields.h5 must be the same bytes as the serial run's. Face pressure is still assembled with
#   atomic adds and rank-partial sums, so a deck with a `type: pressure` condition, or with
#   `scatter: atomic`, is held to the round-off bound below instead.
# - Round-off: history.csv and gauges.csv of the other runs must agree with the first within
#   1e-9 (relative to the magnitude of each energy group, momentum vector and gauge vector or
#   tensor; see test_solver_decomposed.cpp for why such scales), and so must rcforc.csv,
#   spcforc.csv and matsum.csv where the deck has them (relative to each surface pair's forces,
#   all the reactions, each part's energies and each part's momentum): their sums over nodes,
#   elements and CPs are added per rank and thread.
#   hybrid.sh SCPDYN MPIEXEC WORKDIR
set -euo pipefail
scpdyn=$1 mpiexec=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
export OMP_PROC_BIND=false
status=0
for deck in "$here"/decks/*.yaml; do
  name=$(basename "$deck" .yaml)
  OMP_NUM_THREADS=1 "$scpdyn" "$deck" -o "$work/$name.1x1" > /dev/null 2>&1
  for np in 2 3; do
    OMP_NUM_THREADS=1 "$mpiexec" -np $np --oversubscribe "$scpdyn" "$deck" \
      -o "$work/$name.${np}x1" > /dev/null 2>&1
  done
  OMP_NUM_THREADS=2 "$scpdyn" "$deck" -o "$work/$name.1x2" > /dev/null 2>&1
  bitwise=1
  if grep -Eq 'type: *pressure|scatter: *atomic' "$deck"; then
    bitwise=0
  fi
  for run in 2x1 3x1 1x2; do
    if [ $bitwise = 1 ] && ! cmp -s "$work/$name.1x1/gauges.csv" "$work/$name.$run/gauges.csv"; then
      echo "$name $run: gauges.csv is not the serial run's bytes"
      status=1
    fi
  done
  python3 - "$work/$name" <<'PY' || status=1
import csv, os, sys
base = sys.argv[1]
def read(path):
    rows = list(csv.reader(open(path)))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]
def kind(c):
    if c in ('kinetic', 'internal', 'hourglass', 'contact', 'external_work', 'contact_dissipation'):
        return 'energy'
    if c.startswith('momentum'):
        return 'momentum'
    if ':' not in c:
        return c
    g, q = c.split(':', 1)
    k = ('velocity' if q[0] == 'v' else 'displacement' if q[0] == 'd' and len(q) == 2 else
         'position' if len(q) == 1 else 'stress' if q[0] == 's' or q == 'pressure' else q)
    return g + ':' + k
def group(c):
    g, _, q = c.partition(':')
    if q and f == 'spcforc.csv':
        return 'reaction'
    return g + (':momentum' if q.startswith('momentum') else '')
more = [f for f in ('rcforc.csv', 'spcforc.csv', 'matsum.csv') if os.path.exists(base + '.1x1/' + f)]
worst, where = 0.0, ''
for run in ('2x1', '3x1', '1x2'):
    for f in ['history.csv', 'gauges.csv'] + more:
        kind_of = kind if f in ('history.csv', 'gauges.csv') else group
        h, a = read(base + '.1x1/' + f)
        h2, b = read(base + '.' + run + '/' + f)
        if h != h2 or len(a) != len(b):
            print('%s %s %s: columns or rows differ' % (base, run, f)); sys.exit(1)
        for j, c in enumerate(h):
            if c in ('cycle', 'energy_balance_error'):
                continue
            cols = [k for k in range(len(h)) if kind_of(h[k]) == kind_of(c)]
            scale = max(max(abs(r[k]) for r in a for k in cols), 1e-300)
            e = max(abs(x[j] - y[j]) for x, y in zip(a, b)) / scale
            if e > worst:
                worst, where = e, '%s %s %s' % (run, f, c)
print('%-40s worst relative difference %.3e (%s)' % (base.split('/')[-1], worst, where))
sys.exit(0 if worst < 1e-9 else 1)
PY
  # fields.h5: the 2-rank file is written collectively (MPI-IO, each rank its own rows); every
  # dataset of every frame must match the serial file: integers exactly, reals within 1e-9 of
  # the dataset's largest magnitude (the same round-off as the histories above)
  for run in 2x1 3x1; do
  /usr/bin/python3 - "$work/$name" $run $bitwise <<'PY' || status=1
import sys
import h5py, numpy as np
base, run, bitwise = sys.argv[1], sys.argv[2], sys.argv[3] == '1'
a, b = h5py.File(base + '.1x1/fields.h5', 'r'), h5py.File(base + '.' + run + '/fields.h5', 'r')
names = []
a.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
worst, where, bad = 0.0, '', []
for n in names:
    if n not in b:
        bad.append(n + ' missing'); continue
    x, y = a[n][()], b[n][()]
    if x.shape != y.shape:
        bad.append('%s shape %s vs %s' % (n, x.shape, y.shape)); continue
    if bitwise and x.tobytes() != y.tobytes():
        bad.append(n + ' not bitwise')
    if x.dtype.kind == 'f':
        e = float(np.abs(x - y).max() / max(np.abs(x).max(), 1e-300)) if x.size else 0.0
        if e > worst:
            worst, where = e, n
    elif (x != y).any():
        bad.append(n + ' differs')
print('%-40s %s fields.h5: %d datasets, %d frames, %s, worst relative difference %.3e (%s) %s' % (
    base.split('/')[-1], run, len(names), len(a['frames']), 'bitwise' if bitwise else 'round-off',
    worst, where, '; '.join(bad)))
sys.exit(0 if worst < 1e-9 and not bad and len(a['frames']) == len(b['frames']) >= 2 else 1)
PY
  done
done
exit $status
