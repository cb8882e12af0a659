#!/usr/bin/env bash
# Batch replay in shards under GNU parallel: four shards run as four processes cover the
# sessions once between them, with the same results as one unsharded run.
#
#   shard_test.sh RICOCHET LEVEL
#
# Exits 77 (a skip for ctest) when GNU parallel is not installed (Debian package parallel).
set -euo pipefail
ricochet=$1
level=$2
command -v parallel > /dev/null || { echo "shard_test: GNU parallel is not installed"; exit 77; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for seed in 1 2 3 4 5 6 7 8 9; do
  "$ricochet" play "$level" --bots 4 --ticks 300 --seed $seed --record "$dir/s$seed.rec" > /dev/null
done
# Times differ run to run; everything else must not.
strip_times() { sed 's/"seconds": [0-9.]*, //' | sort; }
whole=$("$ricochet" replay --batch "$dir" --json | strip_times)
shards=$(parallel --will-cite "$ricochet" replay --batch "$dir" --shard {}/4 --jobs 2 --json \
  ::: 0 1 2 3 | strip_times)
lines=$(wc -l <<< "$whole")
[ "$lines" -eq 9 ] || { echo "shard_test: the unsharded run gave $lines lines, not 9"; exit 1; }
if [ "$whole" != "$shards" ]; then
  echo "shard_test: the shards' union differs from the unsharded run"
  diff <(echo "$whole") <(echo "$shards") || true
  exit 1
fi
grep -c '"verdict": "ok"' <<< "$whole" | grep -qx 9 || { echo "shard_test: not all ok"; exit 1; }
echo "shard_test: 4 shards under GNU parallel = the unsharded run (9 sessions, all ok)"
