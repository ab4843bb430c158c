#!/usr/bin/env bash
# Run a deck: set-up and build if needed, run scpdyn, plot the gauges and draw the pressure.
#   scripts/run.sh [DECK [scpdyn options]]   (default deck: the project's default scene)
#   scripts/run.sh --help                    this text (scpdyn's options: scpdyn --help)
# Results: -o DIR if given, else the deck's output.directory, else out/<deck name>.
# Threads: OMP_NUM_THREADS (default: all cores). SCPDYN_BIN=PATH runs that scpdyn binary
# instead of setting up and building one.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
case "${1:-}" in
  -h | --help)
    sed -n '2,7p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
    exit 0
    ;;
esac
DEFAULT_DECK="$ROOT/inputs/paper/fig5_implicit_S0.5.yaml"
DECK="${1:-$DEFAULT_DECK}"
[ $# -gt 0 ] && shift
[ -f "$DECK" ] || { echo "scripts/run.sh: no deck '$DECK' (usage: scripts/run.sh --help)" >&2; exit 2; }
if [ -n "${SCPDYN_BIN:-}" ]; then
  BIN="$SCPDYN_BIN"
else
  BIN="$(bash "$ROOT/scripts/build.sh" | tail -n 1)/bin/scpdyn"
fi
# scpdyn chooses the output directory (-o, the deck's output.directory, out/<deck name>) and
# names it on its last line: "scpdyn: done, ... results in DIR"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
"$BIN" "$DECK" "$@" | tee "$log"
OUT="$(sed -n 's/^scpdyn: done, .*; results in //p' "$log" | tail -n 1)"
[ -n "$OUT" ] || exit 0 # scpdyn --help, --version: nothing to plot
/usr/bin/python3 "$ROOT/scripts/plot_gauges.py" "$OUT" >&2 || echo "scripts/run.sh: plotting failed" >&2
# the pressure on the deformed mesh; exit status 2 (no fields.h5, no pressure field, no pvbatch
# for a 3D run) means there is nothing to draw: no picture, no message
# (with contact: its points on it, failed sleepy joints in magenta)
rc=0
with_contacts=()
[ -f "$OUT/contacts.h5" ] && with_contacts=(--contacts)
picture="$(/usr/bin/python3 "$ROOT/scripts/plot_fields.py" "$OUT" "${with_contacts[@]}" 2>"$log")" || rc=$?
picture="$(sed -n 's/^plot_fields: wrote \(.*\) field .*/\1/p' <<<"$picture")"
[ "$rc" -eq 0 ] || [ "$rc" -eq 2 ] || { cat "$log" >&2; echo "scripts/run.sh: drawing the fields failed" >&2; }
echo "results: $OUT (fields.xmf for ParaView, history.csv, gauges.csv, summary.json)"
echo "plot:    $OUT/gauges.png"
[ "$rc" -ne 0 ] || echo "picture: $picture"
