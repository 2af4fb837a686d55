#!/bin/sh
# libFuzzer runs of the scenario, URDF and policy readers (docs/fuzzing.md).
#   scripts/fuzz.sh short [TARGET...]    each target for PRONK_FUZZ_SECONDS (default 25) s from the
#                                        fixed seed PRONK_FUZZ_SEED (default 1): CI
#   scripts/fuzz.sh long N [TARGET...]   each target for N executions
#   scripts/fuzz.sh build                configure and build the fuzz preset only
# TARGET: scenario, urdf, policy (default: all three, one after the other).
# Builds with the `fuzz` preset into build/fuzz (clang); seeds come from the
# project's files and go to build/fuzz/corpus/<target> (kept between runs, so
# what a run learns seeds the next). Exit 1 on any finding, naming the file that
# reproduces it (under build/fuzz/findings/<target>/).
set -eu
cd "$(dirname "$0")/.."

usage() { echo "usage: scripts/fuzz.sh short [TARGET...] | long N [TARGET...] | build" >&2; exit 2; }
mode="${1:-}"
[ -n "$mode" ] || usage
shift
runs=""
case "$mode" in
  short) ;;
  long)
    runs="${1:-}"
    case "$runs" in ''|*[!0-9]*) usage ;; esac
    shift ;;
  build) ;;
  *) usage ;;
esac
targets="${*:-scenario urdf policy}"
for t in $targets; do
  case "$t" in scenario|urdf|policy) ;; *) echo "unknown target '$t' (scenario, urdf, policy)" >&2; exit 2 ;; esac
done

# Two jobs at most: CI and this machine have 2 cores.
jobs="${PRONK_FUZZ_JOBS:-2}"
build_start=$(date +%s)
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$jobs" --target $(for t in $targets; do printf "fuzz_%s " "$t"; done)
echo "fuzz: built in $(( $(date +%s) - build_start )) s"
[ "$mode" = build ] && exit 0

out=build/fuzz
bin=$out/fuzzers
mkdir -p "$out/logs"
# The scenario target rewrites its input file every execution: on tmpfs, as a
# disk's truncations cost ten times the reading (ext4: ~400 exec/s, tmpfs: >5000).
tmp="$out/tmp"
if [ -d /dev/shm ] && [ -w /dev/shm ]; then tmp="/dev/shm/pronk-fuzz.$(id -u)"; fi
mkdir -p "$tmp"
rm -rf "$tmp"/pronk-fuzz-scenario.*  # sandboxes a killed run left
TMPDIR="$(cd "$tmp" && pwd)"
export TMPDIR
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

# seeds TARGET MAX_LEN FILE...: copies the project's files of a kind into the
# corpus, named after their path; files longer than MAX_LEN are left out
# (libFuzzer would cut them, and a cut file seeds nothing but a syntax error).
seeds() {
  corpus="$out/corpus/$1"; max="$2"; shift 2
  mkdir -p "$corpus"
  n=0; skipped=""
  for f in "$@"; do
    [ -f "$f" ] || continue
    if [ "$(wc -c <"$f")" -gt "$max" ]; then skipped="$skipped $f"; continue; fi
    cp "$f" "$corpus/seed-$(echo "$f" | tr '/' '_')"
    n=$((n + 1))
  done
  echo "fuzz: $n seed files in $corpus${skipped:+ (over $max bytes, left out:$skipped)}"
}

failed=0
for t in $targets; do
  case "$t" in
    scenario)
      max_len=16384
      seeds "$t" "$max_len" $(find scenarios tests/scenario tests/cli tests/training -name '*.xml' | sort) ;;
    urdf)
      max_len=32768
      seeds "$t" "$max_len" $(find assets/robots tests -name '*.urdf' | sort) ;;
    policy)
      max_len=16384
      seeds "$t" "$max_len" $(find assets/policies tests/learning tests/cli tests/training -name '*.json' | sort) ;;
  esac
  findings="$out/findings/$t"
  mkdir -p "$findings"
  log="$out/logs/$t-$mode.log"
  # short (CI) draws from a fixed seed, so that a finding on a fresh corpus comes
  # back with the same command; long draws a new one each run, to explore.
  if [ "$mode" = short ]; then
    budget="-max_total_time=${PRONK_FUZZ_SECONDS:-25} -seed=${PRONK_FUZZ_SEED:-1}"
  else
    budget="-runs=$runs${PRONK_FUZZ_SEED:+ -seed=$PRONK_FUZZ_SEED}"
  fi
  before=$(ls "$findings" | wc -l)
  start=$(date +%s)
  # -timeout: an input that takes 10 s is a hang; -rss_limit_mb: one that
  # needs 2 GiB is a finding too. Each target runs alone (one core).
  rc=0
  "$bin/fuzz_$t" "$out/corpus/$t" $budget -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 \
    -dict="tests/fuzz/$t.dict" -artifact_prefix="$findings/" -print_final_stats=1 >"$log" 2>&1 || rc=$?
  seconds=$(( $(date +%s) - start ))
  executed=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
  echo "fuzz: $t: ${executed:-?} executions in $seconds s (${rate:-?} exec/s), corpus $(ls "$out/corpus/$t" | wc -l) files, log $log"
  if [ "$rc" -ne 0 ] || [ "$(ls "$findings" | wc -l)" -ne "$before" ]; then
    failed=1
    echo "fuzz: $t: FINDING (exit $rc); the end of $log:" >&2
    tail -n 40 "$log" >&2
    for f in $(ls -t "$findings" | head -n 5); do
      echo "fuzz: $t: reproduce with: $bin/fuzz_$t $findings/$f" >&2
      # The input itself, for a machine whose build directory is gone (CI):
      # base64 -d > FILE turns the line back into it.
      echo "fuzz: $t: $f as base64: $(base64 -w 0 "$findings/$f")" >&2
    done
  fi
done
rm -rf "$tmp"/pronk-fuzz-scenario.*
exit "$failed"
