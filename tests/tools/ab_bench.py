#!/usr/bin/env python3
"""Two builds of a Google Benchmark binary, run in alternation, compared row by row.

    tests/tools/ab_bench.py OLD/world_bench NEW/world_bench [--rounds 5] [--filter ours]

Alternating the two (old, new, old, new, ...) spreads the machine's drift over both; each row
prints the median CPU time per iteration of each build, new/old of the medians, the median of
each round's new/old (paired) and new/old of the fastest runs (min). Build the old one from a
worktree (git worktree add /tmp/old REV) with the same preset.
"""
import argparse
import collections
import json
import statistics
import subprocess
import sys
import tempfile

UNIT = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}


def run(exe, pattern, min_time):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([exe, "--benchmark_filter=" + pattern, "--benchmark_out=" + out.name,
                        "--benchmark_out_format=json", "--benchmark_min_time=%g" % min_time],
                       check=True, capture_output=True)
        data = json.load(open(out.name))
    return {b["name"]: b["cpu_time"] * UNIT[b["time_unit"]] for b in data["benchmarks"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--filter", default="ours")
    parser.add_argument("--min-time", type=float, default=0.2)
    args = parser.parse_args()
    times = {args.old: collections.defaultdict(list), args.new: collections.defaultdict(list)}
    for _ in range(args.rounds):
        for exe in (args.old, args.new):
            for name, t in run(exe, args.filter, args.min_time).items():
                times[exe][name].append(t)
    for name, old in times[args.old].items():
        new = times[args.new].get(name)
        if not new:
            continue
        a, b = statistics.median(old), statistics.median(new)
        # Each round's two runs are neighbours in time: their ratio cancels the host's slow
        # drift, which moves both; the fastest runs are the least disturbed.
        paired = statistics.median(n / o for o, n in zip(old, new))
        print("%-55s old %12.1f us  new %12.1f us  new/old %.3f  paired %.3f  min %.3f"
              % (name, a, b, b / a, paired, min(new) / min(old)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
