#!/usr/bin/env bash
# Records the bundled sessions (assets/sessions/) again, after a change that moves match hashes
# on purpose, and prints their final hashes for tests/CMakeLists.txt (the session_* tests).
#
#   tests/tools/record_sessions.sh [RICOCHET]     (default build/release/game/ricochet)
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
