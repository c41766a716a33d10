#!/bin/sh
# `rift run` split between the ranks of an MPI job gives one process's bits (docs/distributed.md): the
# scene runs once on one process, then as jobs of each RANKSxTHREADS given, and every job must report the
# same state hash (the whole store, gathered on rank 0) and write the same fractures.csv and timeseries.csv,
# byte for byte. A restart case stops a 3-rank job half-way and continues it on 2 ranks. A guard case
# expects one process to stop on a guard (status 1): the 3-rank job must stop too, with the same status in
# summary.json and the diagnosis said once.
#   mpi_run_check.sh RIFT MPIEXEC SCENE "2x1 2x2 3x1 3x2 restart | guard" [--set key=value ...]
set -eu
rift=$1 mpiexec=$2 scene=$3 jobs=$4
shift 4
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
hash_of() { grep -o '"state_hash": "[0-9a-f]*"' "$1/summary.json" || echo "no state hash in $1"; }
same_run() {  # $1: the job's folder
  [ "$(hash_of "$out/one")" = "$(hash_of "$1")" ] || fail "$1: $(hash_of "$1"), one process $(hash_of "$out/one")"
  for f in fractures.csv timeseries.csv; do
    if [ -f "$out/one/$f" ]; then cmp "$out/one/$f" "$1/$f" || fail "$1/$f differs from one process's"; fi
  done
  echo "$1: $(hash_of "$1"), as one process"
}
status_of() { grep -o '"status": "[^"]*"' "$1/summary.json" || echo "no status in $1"; }
if [ "$jobs" = guard ]; then
  status=0
  "$rift" run "$scene" --out "$out/one" --quiet "$@" > "$out/one.log" 2>&1 || status=$?
  [ $status -eq 1 ] || { cat "$out/one.log"; fail "one process ended with $status, not on a guard"; }
  status=0
  "$mpiexec" -n 3 --oversubscribe "$rift" run "$scene" --out "$out/job" --quiet "$@" > "$out/job.log" 2>&1 || status=$?
  cat "$out/job.log"
  [ $status -eq 1 ] || fail "the job ended with $status"
  [ "$(grep -c 'guard' "$out/job.log")" -eq 1 ] || fail "the diagnosis is not said once"
  [ "$(status_of "$out/one")" = "$(status_of "$out/job")" ] || fail "the job's status differs from one process's"
  echo "the job stopped as one process: $(status_of "$out/job" | cut -c1-120)"
  exit 0
fi
"$rift" run "$scene" --out "$out/one" --quiet "$@" > "$out/one.log" 2>&1 || { cat "$out/one.log"; fail "one process"; }
steps=$(grep -o '"steps": [0-9]*' "$out/one/summary.json" | grep -o '[0-9]*$')
for job in $jobs; do
  if [ "$job" = restart ]; then
    "$mpiexec" -n 3 --oversubscribe "$rift" run "$scene" --out "$out/restart" --quiet --stop-after $((steps / 2)) \
      "$@" > "$out/restart.log" 2>&1 || { cat "$out/restart.log"; fail "3 ranks stopping at step $((steps / 2))"; }
    "$mpiexec" -n 2 --oversubscribe "$rift" run "$scene" --out "$out/restart" --quiet --restart latest \
      "$@" >> "$out/restart.log" 2>&1 || { cat "$out/restart.log"; fail "the restart on 2 ranks"; }
    same_run "$out/restart"
    continue
  fi
  ranks=${job%x*} threads=${job#*x}
  "$mpiexec" -n "$ranks" --oversubscribe "$rift" run "$scene" --out "$out/$job" --quiet --threads "$threads" \
    "$@" > "$out/$job.log" 2>&1 || { cat "$out/$job.log"; fail "$ranks ranks x $threads threads"; }
  same_run "$out/$job"
done
