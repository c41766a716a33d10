#!/usr/bin/env python3
"""Strong scaling of a whole scene, 1 -> N threads, per system, from the run's own timers.

    bench/scaling.py RIFT SCENE.yaml [--threads 1,2] [--set key=value ...] [--out DIR] [--json FILE]

Runs `RIFT run SCENE --threads T` once per thread count (outputs as the scene asks), reads
summary.json's wall_seconds_per_system and wall_seconds, and prints per system the wall time at each
thread count and the speed-up against the first. The same scene and overrides for every run, so the
state hashes must agree (Rift is bitwise deterministic across thread counts); a mismatch is an error.
"""
import argparse
import json
import os
import subprocess
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("rift")
    ap.add_argument("scene")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--set", action="append", default=[], dest="overrides")
    ap.add_argument("--out", default="rift-out/scaling")
    ap.add_argument("--json", help="also write the table as JSON here")
    args = ap.parse_args()
    threads = [int(t) for t in args.threads.split(",")]
    runs = {}
    for t in threads:
        out = os.path.join(args.out, f"threads{t}")
        cmd = [args.rift, "run", "--overwrite", args.scene, "--threads", str(t), "--out", out, "--quiet"]
        for o in args.overrides:
            cmd += ["--set", o]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(out, "summary.json")) as f:
            runs[t] = json.load(f)
    hashes = {runs[t]["state_hash"] for t in threads}
    if len(hashes) != 1:
        sys.exit(f"scaling: the state hashes differ across thread counts: {hashes}")
    base = threads[0]
    systems = list(runs[base]["wall_seconds_per_system"].keys()) + ["(whole run)"]

    def wall(t, s):
        return runs[t]["wall_seconds"] if s == "(whole run)" else runs[t]["wall_seconds_per_system"][s]

    table = []
    print(f"{runs[base]['steps']} steps, state hash {runs[base]['state_hash']} on every thread count")
    print("| system | " + " | ".join(f"{t} thread(s) [s]" for t in threads) + " | " +
          " | ".join(f"speed-up {base}->{t}" for t in threads[1:]) + " |")
    print("|---" * (1 + 2 * len(threads) - 1) + "|")
    for s in systems:
        w = [wall(t, s) for t in threads]
        sp = [w[0] / x if x > 0 and w[0] > 0 else None for x in w[1:]]
        table.append({"system": s, "wall_seconds": dict(zip(map(str, threads), w)),
                      "speedup": dict(zip(map(str, threads[1:]), sp))})
        print(f"| {s} | " + " | ".join(f"{x:.3f}" for x in w) + " | " + " | ".join("-" if x is None else f"{x:.2f}" for x in sp) + " |")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"scene": args.scene, "overrides": args.overrides, "steps": runs[base]["steps"],
                       "systems": table}, f, indent=1)


if __name__ == "__main__":
    main()
