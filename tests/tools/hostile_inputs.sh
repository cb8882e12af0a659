#!/usr/bin/env bash
# Issue 24's hostile inputs, measured: each case's exit code, wall time, peak memory and the
# first line ricochet printed on stderr (and how many lines it printed). For the README's table;
# the tests check the words, this shows the costs.
#
#   hostile_inputs.sh RICOCHET [WORK_DIR]
set -euo pipefail
ricochet=$(realpath "$1")
work=${2:-$(mktemp -d)}
mkdir -p "$work"
cd "$work"

# Files: built here, never taken from assets/ (some cases would overwrite their input).
python3 - << 'EOF'
import json, math
body = lambda extra: {"type": "dynamic", "shapes": [{"type": "circle", "radius": 0.5}], **extra}
open("deep.json", "w").write('{"bodies": [{"position": ' + "[" * 100000 + "]" * 100000 + "}]}")
n = 1000000  # 6 decimals each: 27 MB, under the 32 MiB limit, so the hull sees them all
points = [[round(math.cos(2 * math.pi * i / n), 6), round(math.sin(2 * math.pi * i / n), 6)]
          for i in range(n)]
json.dump({"bodies": [{"type": "dynamic", "shapes": [{"type": "polygon", "points": points}]}]},
          open("million_points.json", "w"))
with open("whitespace.json", "w") as f:
    for _ in range(200):
        f.write(" " * (1 << 20))
json.dump({"bodies": [body({"name": "a\nb\x1b[31m" + "x" * 1000000, "type": "wobbly"})]},
          open("name.json", "w"))
json.dump({"bodies": [body({"angle": 1e308})]}, open("big.json", "w"))
json.dump({"bodies": [body({"name": "bullet", "linearVelocity": [3e38, 0]})]},
          open("fast.json", "w"))
open("twice.json", "w").write('{"bodies": [], "bodies": []}')
json.dump({"bodies": [body({"position": [3000 + 2.5 * (i % 200), 2.5 * (i // 200)],
                            "linearVelocity": [1, 0.5]}) for i in range(20000)]},
          open("outside.json", "w"))
json.dump({"bodies": [body({})]}, open("scene.json", "w"))
EOF
mkdir -p adir

row() {
  local what=$1
  shift
  local err code
  code=0
  /usr/bin/time -f "%e %M" -o time.txt "$@" > /dev/null 2> err.txt || code=$?
  read -r seconds kib < <(tail -n 1 time.txt)
  err=$(head -c 300 err.txt | head -n 1)
  printf '| %s | %s | %s s | %s MiB | %s | %s |\n' "$what" "$code" "$seconds" "$((kib / 1024))" \
    "$(wc -l < err.txt)" "${err//|/\\|}"
}

echo "| case | exit | time | peak memory | stderr lines | first line |"
echo "|---|---:|---:|---:|---:|---|"
row "100,000 levels of nesting" "$ricochet" sim deep.json --steps 1
row "a polygon of a million points" "$ricochet" sim million_points.json --steps 1
row "200 MiB of whitespace" "$ricochet" sim whitespace.json --steps 1
row "a name with a newline, an ANSI escape, 1 MB long" "$ricochet" sim name.json --steps 1
row "an angle of 1e308" "$ricochet" sim big.json --steps 1
row "a velocity of 3e38" "$ricochet" sim fast.json --steps 1
row "a key twice" "$ricochet" sim twice.json --steps 1
row "a directory as the scene" "$ricochet" sim adir --steps 1
row "/dev/zero as the scene" "$ricochet" sim /dev/zero --steps 1
row "--out naming the scene" "$ricochet" sim scene.json --steps 1 --out scene.json
row "--out a directory" "$ricochet" sim scene.json --steps 1 --out adir
row "--size 16x16 frames" "$ricochet" sim scene.json --steps 1 --frames frames --size 16x16
row "20,000 moving circles 3 km out, 60 steps" "$ricochet" sim outside.json --steps 60
row "ricochet --version" "$ricochet" --version
row "ricochet help sim" "$ricochet" help sim
