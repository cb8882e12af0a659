#!/usr/bin/env bash
# Recorded sessions, measured (not a test): replay speed of 16-bot sessions per level, frames per
# second of a replay written as PNG frames at 640x360, batch replay of 100 sessions with 2 jobs
# against 1, and the peak resident set of replays from 10 minutes to an hour.
#
#   tests/bench/session_bench.sh [RICOCHET] [ROUNDS]    (default build/release/game/ricochet, 3)
#
# Prints a Markdown table per part; medians of ROUNDS runs. Takes a few minutes.
set -euo pipefail
ricochet=${1:-build/release/game/ricochet}
rounds=${2:-3}
levels=$(cd "$(dirname "$0")/../../assets/levels" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

json_field() { sed -n "s/.*\"$1\": \"\{0,1\}\([^,\"}]*\).*/\1/p"; }
median() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

echo "## Replay of a 16-bot, 3-minute session (10,800 ticks), no frames"
echo
echo "| level | ticks/s | x real time |"
echo "|---|---:|---:|"
for level in arena corridors maze; do
  "$ricochet" play "$levels/$level.tmj" --bots 16 --ticks 10800 --record "$dir/$level.rec" \
    > /dev/null
  rate=$(for ((r = 0; r < rounds; r++)); do
    "$ricochet" replay "$dir/$level.rec" --json | json_field ticks_per_second
  done | median)
  echo "| $level | $rate | $((rate / 60))x |"
done
echo

if "$ricochet" replay --help | grep -q -- "--frames"; then
  echo "## Replay written as frames (640x360 PNG, every tick, 600 ticks)"
  echo
  echo "| level | frames/s |"
  echo "|---|---:|"
  for level in arena corridors maze; do
    fps=$(for ((r = 0; r < rounds; r++)); do
      rm -rf "$dir/frames"
      start=$(date +%s.%N)
      "$ricochet" replay "$dir/$level.rec" --to 600 --frames "$dir/frames" --every 1 \
        --size 640x360 > /dev/null 2>&1
      end=$(date +%s.%N)
      awk -v s="$start" -v e="$end" 'BEGIN { printf "%.0f\n", 601 / (e - s) }'
    done | median)
    echo "| $level | $fps |"
  done
  echo
fi

echo "## Batch replay of 100 sessions (30 s each, 8 bots, arena), --jobs 1 against --jobs 2"
echo
mkdir -p "$dir/batch"
for ((k = 0; k < 100; k++)); do
  "$ricochet" play "$levels/arena.tmj" --bots 8 --ticks 1800 --seed $k \
    --record "$dir/batch/s$(printf %03d $k).rec" > /dev/null
done
echo "| jobs | seconds | sessions/s |"
echo "|---:|---:|---:|"
for jobs in 1 2; do
  secs=$(for ((r = 0; r < rounds; r++)); do
    start=$(date +%s.%N)
    "$ricochet" replay --batch "$dir/batch" --jobs $jobs --json > "$dir/batch$jobs.jsonl"
    end=$(date +%s.%N)
    awk -v s="$start" -v e="$end" 'BEGIN { printf "%.2f\n", e - s }'
  done | median)
  ok=$(grep -c '"verdict": "ok"' "$dir/batch$jobs.jsonl")
  [ "$ok" -eq 100 ] || { echo "session_bench: $ok of 100 sessions verified" >&2; exit 1; }
  echo "| $jobs | $secs | $(awk -v s="$secs" 'BEGIN { printf "%.1f", 100 / s }') |"
done
echo

echo "## Peak resident set of a replay, 16 bots on arena"
echo
"$ricochet" play "$levels/arena.tmj" --bots 16 --ticks 216000 --record "$dir/hour.rec" > /dev/null
echo "| replayed | peak RSS (MiB) |"
echo "|---|---:|"
for minutes in 1 10 30 60; do
  kib=$("$ricochet" replay "$dir/hour.rec" --to $((minutes * 3600)) --json | json_field peak_rss_kib)
  echo "| $minutes min | $((kib / 1024)) |"
done
echo
echo "(recording of an hour: $(($(stat -c %s "$dir/hour.rec") / 1024)) KiB)"
