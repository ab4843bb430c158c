#!/usr/bin/env bash
# Run a deck: set-up and build if needed, run scpdyn, plot the gauges.
#   scripts/run.sh [DECK [scpdyn options]]     (default deck: the project's default scene)
# Threads: OMP_NUM_THREADS (default: all cores). Results: out/<deck name>/ unless -o DIR.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DEFAULT_DECK="$ROOT/inputs/paper/fig5_implicit_S0.5.yaml"
DECK="${1:-$DEFAULT_DECK}"
[ $# -gt 0 ] && shift
[ -f "$DECK" ] || { echo "scripts/run.sh: no deck '$DECK'" >&2; exit 2; }
BUILD_DIR="$(bash "$ROOT/scripts/build.sh" | tail -n 1)"
export OMP_PROC_BIND="${OMP_PROC_BIND:-spread}" OMP_PLACES="${OMP_PLACES:-threads}"
# the output directory: -o DIR if given, else the deck's own, else out/<deck name>
OUT=""
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  if [ "${args[$i]}" = "-o" ] && [ $((i + 1)) -lt ${#args[@]} ]; then OUT="${args[$((i + 1))]}"; fi
done
if [ -z "$OUT" ]; then
  name="$(basename "$DECK")"; OUT="out/${name%.*}"
  set -- -o "$OUT" "$@"
fi
"$BUILD_DIR/bin/scpdyn" "$DECK" "$@"
/usr/bin/python3 "$ROOT/scripts/plot_gauges.py" "$OUT" >&2 || echo "scripts/run.sh: plotting failed" >&2
echo "results: $OUT (fields.xmf for ParaView, history.csv, gauges.csv, summary.json)"
echo "plot:    $OUT/gauges.png"
