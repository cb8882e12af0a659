#!/usr/bin/env bash
# Recorders killed with SIGKILL: every file they leave plays (and verifies) up to where it ends,
# and `info` says where that is.
#
#   kill_test.sh RICOCHET LEVEL KILLS [SEED]
#
# Half the runs are paced by a script on a pipe (`play --input -`): K ticks of input are fed,
# the recorder plays them and blocks waiting for more, and is killed there; it had played K
# ticks, so its file must play to within a second (60 ticks) of K. The other half run free
# (autopilot) and are killed after a random delay, mid-tick or mid-write: their files must play
# and verify to their last whole chunk.
set -euo pipefail
ricochet=$1
level=$2
kills=$3
RANDOM=${4:-1}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

fail() {
  echo "kill_test: $*" >&2
  exit 1
}

# The size of a file, once it exists and has stopped growing (the recorder blocked or dead).
settled_size() {
  local last=-1 now
  until [ -s "$1" ]; do sleep 0.02; done
  while true; do
    now=$(stat -c %s "$1" 2>/dev/null || echo 0)
    [ "$now" = "$last" ] && { echo "$now"; return; }
    last=$now
    sleep 0.1
  done
}

for ((i = 0; i < kills; i++)); do
  rec=$dir/run$i.rec
  expected=-1
  if ((i % 2 == 0)); then
    K=$((60 + RANDOM % 1500))
    mkfifo "$dir/pipe"
    "$ricochet" play "$level" --bots 4 --ticks 1000000 --seed $i --input - --record "$rec" \
      < "$dir/pipe" > /dev/null 2> "$dir/err" &
    pid=$!
    exec 3> "$dir/pipe"
    # Lines for ticks 0..K: enough to play ticks 0..K-1 (tick K's line says K-1 is complete).
    awk -v K=$K 'BEGIN { for (t = 0; t <= K; t++)
      printf "%d 0 %d %d %d %s 0\n", t, int(t / 90) % 3 - 1, int(t / 70) % 3 - 1, (t * 3) % 360,
             t % 40 < 5 ? "f" : "-" }' >&3
    settled_size "$rec" > /dev/null
    kill -9 $pid
    wait $pid 2> /dev/null || true
    exec 3>&-
    rm -f "$dir/pipe"
    expected=$K
  else
    "$ricochet" play "$level" --bots 4 --ticks 1000000 --seed $i --record "$rec" > /dev/null &
    pid=$!
    # Killed at a random moment once recording has begun (the level loads first).
    until [ -s "$rec" ]; do sleep 0.02; done
    sleep "0.$((RANDOM % 3))$((RANDOM % 10))"
    kill -9 $pid
    wait $pid 2> /dev/null || true
  fi
  [ -s "$rec" ] || fail "run $i: the recorder left no file"
  code=0
  info=$("$ricochet" info "$rec" 2>&1) || code=$?
  [ $code -eq 4 ] || fail "run $i: info exited $code, not 4 (damaged or unfinished): $info"
  ticks=$(sed -n 's/.*it plays to tick \([0-9]*\).*/\1/p' <<< "$info")
  [ -n "$ticks" ] || fail "run $i: info does not say where the file ends: $info"
  if ((expected >= 0)); then
    ((ticks <= expected && ticks >= expected - 60)) ||
      fail "run $i: killed after $expected ticks, the file plays to tick $ticks"
  fi
  code=0
  replay=$("$ricochet" replay "$rec" --verify 2>&1) || code=$?
  [ $code -eq 4 ] || fail "run $i: replay --verify exited $code, not 4: $replay"
  grep -q "ticks 0-$ticks hash .* verdict damaged" <<< "$replay" ||
    fail "run $i: replay did not play to tick $ticks: $replay"
  fed=""
  ((expected < 0)) || fed=" (fed $expected ticks)"
  echo "run $i: $(sed -n 's/^integrity //p' <<< "$info" | cut -c1-110)$fed"
done
echo "kill_test: $kills recorders killed; every file played and verified to where it ends"
