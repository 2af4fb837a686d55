#!/bin/sh
# The README's short tour, run as written: every `$pronk ...` line of the first
# sh block under "## A short tour", from a scratch directory that sees the
# source's scenarios/ and assets/, must end with the exit status its comment
# states ("# exit N: ..."), 0 otherwise. Every line runs; the failures are
# listed at the end.
#   readme_tour.sh README PRONK WORKDIR
set -u
readme=$1 pronk=$2 work=$3
source_dir=$(cd "$(dirname "$readme")" && pwd)
rm -rf "$work" && mkdir -p "$work" || exit 1
ln -s "$source_dir/scenarios" "$work/scenarios"
ln -s "$source_dir/assets" "$work/assets"
cd "$work" || exit 1

# The tour's block: from "## A short tour" to its first closing fence.
awk '/^## A short tour/ { tour = 1; next }
     tour && /^```sh/ { block = 1; next }
     block && /^```/ { exit }
     block && /^\$pronk / { print }' "$readme" > tour.txt
count=$(wc -l < tour.txt)
if [ "$count" -lt 10 ]; then
  echo "found only $count tour commands in $readme"
  exit 1
fi

failed=0
n=0
while IFS= read -r line; do
  n=$((n + 1))
  command=${line%%  #*}                 # the comment starts after two spaces
  command=${command%"${command##*[! ]}"}  # trailing spaces
  expected=0
  case "$line" in
    *"# exit "[0-9]*) expected=$(printf '%s\n' "$line" | sed 's/.*# exit \([0-9]*\).*/\1/') ;;
  esac
  start=$(date +%s)
  output=$(pronk="$pronk" eval "$command" 2>&1 < /dev/null)
  status=$?
  echo "[$n/$count] exit $status (expected $expected), $(( $(date +%s) - start )) s: $command"
  if [ "$status" -ne "$expected" ]; then
    failed=$((failed + 1))
    printf '%s\n' "$output" | tail -n 25 | sed 's/^/    /'
  fi
done < tour.txt

# What the tour writes goes under out/ (ignored by git): nothing else is left
# beside the links to the source and this script's own list.
left=$(ls -A | grep -v -x -e out -e scenarios -e assets -e tour.txt)
if [ -n "$left" ]; then
  echo "the tour left files outside out/: $(echo $left)"
  failed=$((failed + 1))
fi

if [ "$failed" -ne 0 ]; then
  echo "$failed of $count tour commands did not end as the README says"
  exit 1
fi
echo "all $count tour commands ended as the README says"
