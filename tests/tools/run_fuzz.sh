#!/usr/bin/env bash
# Runs a libFuzzer target on a kept corpus and a folder of seeds, and says how many inputs it
# ran and how fast; a crash, leak or timeout leaves its input beside the corpus and fails.
#
#   run_fuzz.sh TARGET CORPUS_DIR SEED_DIR [libFuzzer options...]
set -euo pipefail
target=$1 corpus=$2 seeds=$3
shift 3
mkdir -p "$corpus"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
"$target" -artifact_prefix="$corpus-" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 "$@" "$corpus" "$seeds" \
  > "$log" 2>&1 || status=$?
grep -E "^Done|ERROR|SUMMARY|Test unit written" "$log" || true
grep -E "stat::number_of_executed_units|stat::average_exec_per_sec" "$log" || true
if [ $status -ne 0 ]; then
  tail -n 40 "$log" >&2
  exit $status
fi
