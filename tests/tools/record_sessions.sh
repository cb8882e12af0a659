#!/usr/bin/env bash
# Records the bundled sessions (assets/sessions/) again, after a change that moves match hashes
# on purpose, and prints their final hashes for tests/CMakeLists.txt (the session_* tests).
#
#   tests/tools/record_sessions.sh [RICOCHET]     (default build/release/game/ricochet)
#
# Also the recording fuzzer's two seeds (tests/fuzz/corpus/recording: the arena, one player and
# one bot, as its scratch match is), which a new kSimulationVersion makes unreadable too.
#
# Each is a fixed match: level, bots, players, seed and length are below, so recording again
# with the same build gives the same bytes. Bump kSimulationVersion (game/session/recording.h)
# in the same change when the old recordings can no longer replay.
set -euo pipefail
cd "$(dirname "$0")/../.."
ricochet=${1:-build/release/game/ricochet}
out=assets/sessions
mkdir -p "$out"
# name level bots players seed ticks
sessions=(
  "arena arena 16 1 7 7200"
  "corridors corridors 12 1 3 7200"
  "maze maze 8 2 11 7200"
)
for s in "${sessions[@]}"; do
  read -r name level bots players seed ticks <<< "$s"
  "$ricochet" play "assets/levels/$level.tmj" --bots "$bots" --players "$players" --seed "$seed" \
    --ticks "$ticks" --keyframe-every 600 --record "$out/$name.rec" > /dev/null
  hash=$("$ricochet" replay "$out/$name.rec" --verify | sed -n 's/.* hash \([0-9a-f]*\) verdict ok .*/\1/p')
  [ -n "$hash" ] || { echo "record_sessions: $name.rec does not verify" >&2; exit 1; }
  echo "\"$name $hash\""
done
seeds=tests/fuzz/corpus/recording
"$ricochet" play assets/levels/arena.tmj --bots 1 --seed 5 --ticks 240 --keyframe-every 60 \
  --record "$seeds/arena_1bot.rec" > /dev/null
# A scripted player who walks, turns, fires, throws and reloads.
printf '%s\n' "0 0 1 0 0 - 0" "30 0 0 1 90 f 0" "60 0 -1 0 180 ft 0" "90 0 0 -1 270 r 1" \
  "120 0 0.5 0.5 45 f 1" | "$ricochet" play assets/levels/arena.tmj --bots 1 --seed 9 \
  --ticks 150 --keyframe-every 50 --input - --record "$seeds/arena_scripted.rec" > /dev/null
for f in "$seeds"/*.rec; do
  "$ricochet" replay "$f" --verify > /dev/null || { echo "record_sessions: $f does not verify" >&2; exit 1; }
done
