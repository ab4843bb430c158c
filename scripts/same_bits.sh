#!/usr/bin/env bash
# Same bits: does a build give byte-identical gauges.csv and history.csv to another build, deck
# by deck, at 1 thread, 2 threads and 2 MPI ranks? For changes that must not move results
# (restructuring, performance work): run the reference build and the changed build into two
# directories, then compare them.
#
#   scripts/same_bits.sh run BIN_DIR OUT_DIR [--quick] [--configs 1thread,2threads,2ranks]
#   scripts/same_bits.sh compare DIR_A DIR_B
#   scripts/same_bits.sh --help
#
#   e.g. scripts/same_bits.sh run /path/to/ref-build/bin /tmp/same-bits/ref
#        scripts/same_bits.sh run build/bin /tmp/same-bits/new
#        scripts/same_bits.sh compare /tmp/same-bits/ref /tmp/same-bits/new
#
# run: every deck of inputs/paper, inputs/examples, inputs/verification, tests/parallel/decks
# and the perf/ decks box64, tet32 and quad512 (100 cycles each; perf/scaling_wall.yaml is a
# template with NX/NY/NZ placeholders, not a deck; inputs/broken holds decks that must fail),
# 39 decks, in each configuration, one run at a time (the host has 2 cores), outputs in
# OUT_DIR/<config>/<deck>/:
#   1thread    OMP_NUM_THREADS=1 (the same as 1 rank, which is therefore not run again:
#              mpirun -np 1 gives the same bytes)
#   2threads   OMP_NUM_THREADS=2, every deck with numerics.scatter set to gather (below)
#   2ranks     mpirun -np 2 --oversubscribe, OMP_NUM_THREADS=1 per rank
# with OMP_PROC_BIND=spread OMP_PLACES=threads; --configs runs only some of them. Each deck
# directory also holds run.log (the run's stdout and stderr), exit_status and, where the deck
# was edited, input.yaml (the deck that ran); OUT_DIR/runs.tsv has every run's exit status
# and wall time. Two paper decks end with exit status 3 on purpose (fig2_a1e-7_explicit and
# fig5_explicit_S0.5 show the explicit contact going unstable); their outputs up to the stop
# are kept and compared like any other. Time on the 2-core host, shared with others' builds
# (load average 2-7): 375-500 s for the whole run (1thread 67-95 s, 2threads 110-300 s,
# 2ranks 125-245 s), so no deck is shortened. --quick (155 s) leaves out the perf decks and
# stops every deck after 1000 cycles (time.max_cycles in a copy of the deck; the Taylor bars
# run 5 000-31 000 cycles). A quick run is only comparable with another quick run (compare
# refuses a mix).
#
# Why 2threads uses scatter: gather. With scatter: atomic (what the perf decks ask for) the
# element forces are added to the nodes with atomic adds in whatever order the threads reach
# them: nothing fixes the order of two adds to a node from two threads, so nothing makes two
# runs give the same bits (five runs each of box64, tet32 and quad512 at 2 threads did agree,
# but only because the threads happened to reach the shared nodes in the same order). The
# gather mode, the default of every other deck (docs/input.md), sums each node's element
# forces in a fixed order at any thread count. The copy of the deck sets it for every deck (a
# no-op where it is the default already), so a deck added later with atomic scatter is
# covered too. At 1 thread and per rank both modes are plain adds, and the decks run as they
# are.
#
# Decks still not bit-reproducible at 2 threads: contact forces (step 9) and face pressure
# (step 10) are added with atomic adds whatever the scatter mode (docs/input.md), and the
# contact search fills its bins with an atomic cursor, so the order of three or more adds to
# one node can change between runs. The baseline was run 13 times at 2 threads (every deck
# 5 times, the 2D and 3D decks with contact or face pressure 8 more): the decks in the lists
# below differed between runs of the same binary, except fig5_explicit_S0.5 (2 cycles) and
# wall_pulse_2d_tied, listed for the same mechanism. compare checks them within a relative
# tolerance instead of bit for bit (relative to the largest value of the column's family, as
# tests/parallel/hybrid.sh does; scripts/same_bits.py) and says why on their line; where the
# explicit contact amplifies the round-off into a different run, not at all. Every other
# deck, wall_pulse_2d included (2D face pressure: at most two adds a node, onto zero, and
# a + b = b + a), and every deck at 1thread and 2ranks must match byte for byte. 2ranks is
# reproducible: shared nodes are summed in a fixed rank order and each rank runs one thread.
#
# compare: for every config/deck present in both directories, cmp of gauges.csv and
# history.csv: one line per file, "same" or "DIFFERENT" with the first differing line and
# the largest relative difference per column (scripts/same_bits.py, /usr/bin/python3); a
# different exit status of the run is a difference too. Last line: "N same, M different".
#
# Exit status: 0 all runs done (run) / no difference (compare); 1 a run failed (exit status
# other than 0 and 3) / a difference; 2 usage error.
set -uo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PY=/usr/bin/python3  # the python3 first on PATH may lack PyYAML
HELPER="$ROOT/scripts/same_bits.py"
CONFIGS=(1thread 2threads 2ranks)
QUICK_MAX_CYCLES=1000
# 2threads decks that are not bit-reproducible run to run (see the header), by how far two
# runs of one binary were seen to drift apart (13 runs, every pair):
# within 1.2e-13 (2D implicit contact, 3D face pressure): checked within TOLERANCE
ROUNDOFF_AT_2_THREADS=" block_impact_2d fig5_implicit_S0.05 fig5_implicit_S0.1 fig5_implicit_S0.5
  fig7_implicit_adjusted fig7_implicit_consistent merged_blocks_3d "
TOLERANCE=1e-12
# within 7.3e-10 (sticky and slide-line ties: the tie passes amplify the round-off): checked
# within TIE_TOLERANCE
TIES_AT_2_THREADS=" brick_stack_3d_sticky patch_2d wall_pulse_2d_tied "
TIE_TOLERANCE=1e-7
# explicit contact: up to 8e-9 (fig5) and up to a different run (fig7_explicit_adjusted once
# took 4556 cycles instead of 4868): no tolerance tells a change from the noise, so these are
# compared bit for bit only, and a difference is reported but not counted
CHAOTIC_AT_2_THREADS=" fig5_explicit_S0.05 fig5_explicit_S0.1 fig5_explicit_S0.5
  fig7_explicit_adjusted fig7_explicit_consistent "

# For a config and deck not compared bit for bit: "TOLERANCE REASON", TOLERANCE "-" for not
# compared at all; nothing otherwise
tolerance_of() {
  local config=$1 deck=$2 why="atomic contact/pressure adds at 2 threads"
  [[ $config == 2threads ]] || return 0
  if in_list "$deck" "$ROUNDOFF_AT_2_THREADS"; then
    echo "$TOLERANCE $why"
  elif in_list "$deck" "$TIES_AT_2_THREADS"; then
    echo "$TIE_TOLERANCE $why, amplified by the ties"
  elif in_list "$deck" "$CHAOTIC_AT_2_THREADS"; then
    echo "- $why, amplified by the explicit contact"
  fi
}

in_list() {
  local w
  for w in $2; do [[ $w == "$1" ]] && return 0; done
  return 1
}

usage() {
  sed -n '2,/^set -uo/{/^set -uo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"
}

die_usage() {
  echo "same_bits.sh: $*" >&2
  echo "usage: scripts/same_bits.sh run BIN_DIR OUT_DIR [--quick] [--configs LIST]" \
    "| compare DIR_A DIR_B | --help" >&2
  exit 2
}

decks() {
  local quick=$1
  local d
  for d in "$ROOT"/inputs/paper/*.yaml "$ROOT"/inputs/examples/*.yaml \
           "$ROOT"/inputs/verification/*.yaml "$ROOT"/tests/parallel/decks/*.yaml; do
    echo "$d"
  done
  if [[ $quick == 0 ]]; then
    for d in box64 tet32 quad512; do echo "$ROOT/perf/$d.yaml"; done
  fi
}

cmd_run() {
  [[ $# -ge 2 ]] || die_usage "run needs BIN_DIR OUT_DIR"
  local bin=$1 out=$2 quick=0 configs=("${CONFIGS[@]}") c
  shift 2
  while [[ $# -gt 0 ]]; do
    case $1 in
      --quick) quick=1 ;;
      --configs)
        [[ $# -ge 2 ]] || die_usage "--configs needs a list"
        IFS=, read -r -a configs <<< "$2"
        for c in "${configs[@]}"; do
          [[ " ${CONFIGS[*]} " == *" $c "* ]] || die_usage "unknown configuration '$c'"
        done
        shift ;;
      *) die_usage "unknown option '$1'" ;;
    esac
    shift
  done
  [[ -x $bin/scpdyn ]] || die_usage "no executable $bin/scpdyn"
  [[ -n $out && $out != / ]] || die_usage "bad OUT_DIR '$out'"
  bin="$(cd "$bin" && pwd)"
  mkdir -p "$out" || exit 2
  out="$(cd "$out" && pwd)"

  local list names
  mapfile -t list < <(decks $quick)
  names=$(for d in "${list[@]}"; do basename "$d" .yaml; done | sort | uniq -d)
  [[ -z $names ]] || { echo "same_bits.sh: deck names not unique: $names" >&2; exit 1; }

  export OMP_PROC_BIND=spread OMP_PLACES=threads
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  local mode=full
  [[ $quick == 1 ]] && mode=quick
  {
    echo "mode $mode"
    echo "configs ${configs[*]}"
    echo "bin $bin"
    echo "scpdyn_sha256 $(sha256sum "$bin/scpdyn" | cut -d' ' -f1)"
    echo "started $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  } > "$out/same_bits.run"
  : > "$out/runs.tsv"

  local t0=$EPOCHREALTIME failed=0 config deck name dir input status t1 secs
  for config in "${configs[@]}"; do
    for deck in "${list[@]}"; do
      name=$(basename "$deck" .yaml)
      dir="$out/$config/$name"
      rm -rf "$dir" && mkdir -p "$dir" || exit 1
      local edits=()
      [[ $quick == 1 ]] && edits+=(--max-cycles $QUICK_MAX_CYCLES)
      [[ $config == 2threads ]] && edits+=(--scatter gather)
      input=$deck
      if [[ ${#edits[@]} -gt 0 ]]; then
        input="$dir/input.yaml"
        "$PY" "$HELPER" deck "$deck" "$input" "${edits[@]}" || exit 1
      fi
      t1=$EPOCHREALTIME
      case $config in
        1thread) OMP_NUM_THREADS=1 "$bin/scpdyn" "$input" -o "$dir" ;;
        2threads) OMP_NUM_THREADS=2 "$bin/scpdyn" "$input" -o "$dir" ;;
        2ranks) OMP_NUM_THREADS=1 mpirun -np 2 --oversubscribe "$bin/scpdyn" "$input" -o "$dir" ;;
      esac > "$dir/run.log" 2>&1 < /dev/null
      status=$?
      echo $status > "$dir/exit_status"
      secs=$(awk -v a="$t1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }')
      printf '%s\t%s\t%s\t%s\n' "$config" "$name" "$status" "$secs" >> "$out/runs.tsv"
      local note=""
      if [[ $status == 3 ]]; then
        note="  ($(grep -o 'run stopped: [^(:]*' "$dir/run.log" | head -1 | sed 's/ *$//'); outputs kept)"
      elif [[ $status != 0 ]]; then
        note="  FAILED, see $dir/run.log"
        failed=1
      fi
      printf '%-8s %-28s exit %s %6.1f s%s\n' "$config" "$name" "$status" "$secs" "$note"
    done
  done
  local total
  total=$(awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.0f", b - a }')
  echo "total $total s" >> "$out/same_bits.run"
  echo "same_bits.sh run: $(wc -l < "$out/runs.tsv") runs ($mode) in $total s -> $out"
  return $failed
}

cmd_compare() {
  [[ $# == 2 ]] || die_usage "compare needs DIR_A DIR_B"
  local a=$1 b=$2
  [[ -d $a && -d $b ]] || die_usage "no directory '$a' or '$b'"
  local ma mb
  ma=$(awk '$1 == "mode" { print $2 }' "$a/same_bits.run" 2>/dev/null)
  mb=$(awk '$1 == "mode" { print $2 }' "$b/same_bits.run" 2>/dev/null)
  if [[ -n $ma && -n $mb && $ma != "$mb" ]]; then
    die_usage "$a is a $ma run and $b a $mb run: the decks ran for different lengths"
  fi
  local same=0 different=0 tolerated=0 skipped=0 config deck name f fa fb line why tol
  for config in "${CONFIGS[@]}"; do
    [[ -d $a/$config && -d $b/$config ]] || continue
    for deck in "$a/$config"/*/; do
      name=$(basename "$deck")
      if [[ ! -d $b/$config/$name ]]; then
        echo "$config/$name: only in $a (not compared)"
        continue
      fi
      read -r tol why <<< "$(tolerance_of "$config" "$name")"
      for f in gauges.csv history.csv; do
        fa="$a/$config/$name/$f" fb="$b/$config/$name/$f"
        if [[ ! -f $fa && ! -f $fb ]]; then
          continue
        elif [[ ! -f $fa || ! -f $fb ]]; then
          echo "$config/$name/$f: DIFFERENT (missing in $([[ -f $fa ]] && echo "$b" || echo "$a"))"
          different=$((different + 1))
        elif cmp -s "$fa" "$fb"; then
          echo "$config/$name/$f: same"
          same=$((same + 1))
        elif [[ $tol == - ]]; then
          echo "$config/$name/$f: not compared, not bit for bit ($why):" \
            "$("$PY" "$HELPER" diff "$fa" "$fb")"
          skipped=$((skipped + 1))
        elif [[ -n $tol ]] && line=$("$PY" "$HELPER" diff "$fa" "$fb" --tolerance "$tol"); then
          echo "$config/$name/$f: same within $tol, not bit for bit ($why): $line"
          same=$((same + 1)) tolerated=$((tolerated + 1))
        else
          [[ -n $tol ]] || line=$("$PY" "$HELPER" diff "$fa" "$fb")
          echo "$config/$name/$f: DIFFERENT${tol:+ (beyond $tol)}: $line"
          different=$((different + 1))
        fi
      done
      fa="$a/$config/$name/exit_status" fb="$b/$config/$name/exit_status"
      if [[ $tol != - && -f $fa && -f $fb ]] && ! cmp -s "$fa" "$fb"; then
        echo "$config/$name: DIFFERENT exit status of the run: $(cat "$fa") vs $(cat "$fb")"
        different=$((different + 1))
      fi
    done
    for deck in "$b/$config"/*/; do
      name=$(basename "$deck")
      [[ -d $a/$config/$name ]] || echo "$config/$name: only in $b (not compared)"
    done
  done
  [[ $tolerated == 0 ]] || echo "($tolerated of the same only within a relative tolerance)"
  [[ $skipped == 0 ]] || echo "($skipped not bit for bit and not compared: explicit contact at 2 threads)"
  echo "$same same, $different different"
  [[ $different == 0 ]]
}

case ${1:-} in
  run) shift; cmd_run "$@" ;;
  compare) shift; cmd_compare "$@" ;;
  -h|--help|help) usage; exit 0 ;;
  '') die_usage "no command" ;;
  *) die_usage "unknown command '$1'" ;;
esac
