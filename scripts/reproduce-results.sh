#!/bin/sh
# Re-runs the evaluations behind docs/results.md and the README's figures with
# this build and the shipped policies, and writes their tables to OUT/results.md.
#
#   scripts/reproduce-results.sh OUT [NAME...]
#
# Each NAME is one run below (all when none is given); `scripts/reproduce-results.sh
# --list` prints them with their expected time on 2 cores. OUT/NAME holds each
# run's `pronk eval` output (summary.json, per-jump CSV, figures); OUT/results.md
# one table per run, its command and how long it took. A finished run is kept: running the script
# again into the same OUT runs only what is missing (`pronk eval --resume`).
# Everything runs on the build in build/release (scripts/setup.sh builds it), or
# on the binary that PRONK names.
set -eu

cd "$(dirname "$0")/.."
pronk="${PRONK:-build/release/bin/pronk}"
go1=assets/policies/go1_omni.json
flat=assets/policies/go1_flat_aim.json
aliengo=assets/policies/aliengo_omni.json

# NAME | minutes on 2 cores | policy | what `pronk eval` takes: files, and --sweep for one set
runs() {
  cat <<EOF
go1_flat_1000_omni|6|$go1|scenarios/eval/go1_flat_1000.xml
go1_flat_1000_planner|6|ballistic|scenarios/eval/go1_flat_1000.xml
go1_flat_1000_flat_aim|6|$flat|scenarios/eval/go1_flat_1000.xml
go1_flat_8192_omni|31|$go1|scenarios/eval/go1_flat_8192.xml
go1_flat_extra_omni|9|$go1|scenarios/eval/go1_flat_1000_3s.xml scenarios/eval/go1_flat_64.xml
go1_heights_omni|2|$go1|scenarios/eval/go1_heights.xml
go1_heights_planner|2|ballistic|scenarios/eval/go1_heights.xml
go1_twist_omni|1|$go1|scenarios/eval/go1_twist.xml
go1_twist_planner|1|ballistic|scenarios/eval/go1_twist.xml
go1_robust_omni|1|$go1|scenarios/eval/go1_robust_fwd.xml scenarios/eval/go1_robust_diag.xml
aliengo_robust_omni|1|$aliengo|scenarios/eval/aliengo_robust_fwd.xml scenarios/eval/aliengo_robust_diag.xml
aliengo_transfer_omni|1|$go1|scenarios/eval/aliengo_transfer_fwd.xml
aliengo_region_omni|9|$aliengo|scenarios/eval/aliengo_flat_1000.xml scenarios/eval/aliengo_heights.xml
aliengo_region_planner|9|ballistic|scenarios/eval/aliengo_flat_1000.xml scenarios/eval/aliengo_heights.xml
go1_edges_omni|2|$go1|scenarios/eval/go1_heights_edges.xml scenarios/eval/go1_edges_random.xml
go1_edges_planner|2|ballistic|scenarios/eval/go1_heights_edges.xml scenarios/eval/go1_edges_random.xml
aliengo_edges_omni|4|$aliengo|scenarios/eval/aliengo_edges_random.xml
aliengo_edges_planner|4|ballistic|scenarios/eval/aliengo_edges_random.xml
robot_vendor_go1_planner|2|ballistic|tests/robots/vendor_go1/flat_200.xml --sweep flat
robot_vendor_go1_omni|2|$go1|tests/robots/vendor_go1/flat_200.xml --sweep flat
robot_vendor_aliengo_planner|2|ballistic|tests/robots/vendor_aliengo/flat_200.xml --sweep flat
robot_vendor_aliengo_omni|2|$go1|tests/robots/vendor_aliengo/flat_200.xml --sweep flat
robot_big_go1_planner|2|ballistic|tests/robots/big_go1/flat_200.xml --sweep flat
robot_big_go1_omni|2|$go1|tests/robots/big_go1/flat_200.xml --sweep flat
EOF
}

if [ "${1:-}" = "--list" ]; then
  runs | awk -F'|' '{ total += $2; printf "%-30s %3d min  %s  %s\n", $1, $2, $3, $4 } END { printf "%-30s %3d min\n", "all", total }'
  exit 0
fi
[ $# -ge 1 ] || { echo "usage: scripts/reproduce-results.sh OUT [NAME...] | --list" >&2; exit 2; }
out="$1"
shift
[ -x "$pronk" ] || { echo "reproduce-results: $pronk is not built: run scripts/setup.sh test (or cmake --build --preset release)" >&2; exit 2; }
for name in "$@"; do
  runs | cut -d'|' -f1 | grep -qx "$name" || { echo "reproduce-results: no run named '$name' (--list names them)" >&2; exit 2; }
done
mkdir -p "$out"
report="$out/results.md"
{
  echo "# pronk results, reproduced"
  echo
  echo "$("$pronk" --version), $(date -u +%Y-%m-%dT%H:%M:%SZ), $(nproc) cores"
} > "$report"

failed=0
list="$out/.runs"
runs > "$list"
while IFS='|' read -r name minutes policy what; do
  if [ $# -gt 0 ]; then
    wanted=0
    for n in "$@"; do [ "$n" = "$name" ] && wanted=1; done
    [ $wanted = 1 ] || continue
  fi
  dir="$out/$name"
  start=$(date +%s)
  resume=""
  [ -f "$dir/summary.json" ] && resume="--resume"
  command="pronk eval $what --policy $policy --jobs 2 --out $dir"
  echo "reproduce-results: $name (about $minutes min): $command"
  status=0
  # shellcheck disable=SC2086  # $what is a list of files and flags
  "$pronk" eval $what --policy "$policy" --jobs 2 --out "$dir" $resume > "$dir.log" 2>&1 || status=$?
  table=$(grep -E '^\|' "$dir.log" || true)
  seconds=$(( $(date +%s) - start ))
  {
    echo
    echo "## $name"
    echo
    echo "\`$command\` ($(( seconds / 60 )) min $(( seconds % 60 )) s, exit $status)"
    echo
    echo "$table"
  } >> "$report"
  case $status in
    0) ;;
    *) echo "reproduce-results: $name failed (exit $status): $dir.log" >&2; failed=1 ;;
  esac
done < "$list"
rm -f "$list"
echo "reproduce-results: wrote $report"
exit $failed
