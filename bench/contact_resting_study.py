#!/usr/bin/python3
"""Long rest: a block resting on a plate under gravity for seconds, over block meshes (docs/validation.md).

Runs `rift` on scenes/validation/contact_resting.yaml (a 20 mm rubber cube on a fixed plate, friction 0.5)
to --end (default 2 s, 20 x the CI test's 0.1 s) for each block mesh (a lattice of n^3 cubes, or
unstructured at element size 20 mm / n), and measures, after the settling (t >= 0.1 s):
  drift: the block's mean horizontal displacement, its mean over the last 0.1 s less that over
         [0.1, 0.2] s, against 1e-6 of the block's size; and the drift rate it implies;
  jitter: the range of the block's mean vertical displacement over the last 0.1 s, against its mean
         settlement (the static compression of the contact and the block);
and the exit status (a guard stop is a failure) and the least stored contact energy relative to the
work gravity did (negative: contact put energy in).

Usage: bench/contact_resting_study.py build/ci/rift [--end 2.0] [--cells 1,2,3,4]
       [--meshes lattice,unstructured] [--threads 1] [--json out.json]
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from contact_incline_study import BLOCK, block_history, block_mesh

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "scenes/validation/contact_resting.yaml")
SETTLED = 0.1


def run_case(rift, end, cells, unstructured, threads):
    sets = [block_mesh(cells, unstructured), f"time.end={end}", "output.interval=0.01",
            "output.fields=[velocity, displacement, region]"]
    row = {"mesh": "unstructured" if unstructured else "lattice", "cells": cells, "end": end}
    with tempfile.TemporaryDirectory(prefix="resting") as out:
        args = [rift, "run", "--overwrite", SCENE, "-o", out, "--threads", str(threads), "-q"]
        for s in sets:
            args += ["--set", s]
        proc = subprocess.run(args, capture_output=True, text=True)
        row["exit"] = proc.returncode
        if proc.returncode != 0:
            row["error"] = proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else "?"
            return row
        t, _, u = block_history(out)
        ts = list(csv.DictReader(open(os.path.join(out, "timeseries.csv"))))
    eps = 1e-12
    early = (t >= SETTLED - eps) & (t < SETTLED + 0.1 - eps)
    late = t >= end - 0.1 - eps
    drift = np.hypot(*(u[late, :2].mean(0) - u[early, :2].mean(0)))
    row.update(drift=float(drift), drift_rel=float(drift / BLOCK),
               drift_rate=float(drift / (end - 0.1 - SETTLED)),
               settlement=float(-u[late, 2].mean()), jitter=float(np.ptp(u[late, 2])))
    work = max(float(ts[-1]["solid_external_work"]), 1e-300)
    row["least_contact_energy_rel"] = min(float(r["contact_energy"]) for r in ts) / work
    return row


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("rift")
    p.add_argument("--end", type=float, default=2.0)
    p.add_argument("--cells", default="1,2,3,4")
    p.add_argument("--meshes", default="lattice,unstructured")
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--json")
    args = p.parse_args()
    rows = []
    for mesh in args.meshes.split(","):
        for cells in map(int, args.cells.split(",")):
            r = run_case(args.rift, args.end, cells, mesh == "unstructured", args.threads)
            rows.append(r)
            if r["exit"] != 0:
                res = f"STOPPED: {r['error']}"
            else:
                res = (f"drift {r['drift']:.3e} m ({r['drift_rel']:.1e} of the block, {r['drift_rate']:.1e} m/s), "
                       f"settlement {r['settlement']:.3e} m, jitter {r['jitter']:.1e} m, "
                       f"least contact energy {r['least_contact_energy_rel']:+.1e} of the work")
            print(f"{mesh:>12} {cells:2d}  {res}", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
