#!/usr/bin/python3
"""Friction study: a block on an incline over angles, friction coefficients and meshes (docs/validation.md).

Runs `rift` on scenes/validation/contact_incline.yaml (a 20 mm cube on a fixed plate, gravity turned by
theta) for every angle x mu x block mesh (a lattice of n^3 cubes, or unstructured at element size 20 mm / n),
and measures between t = 0.04 s (the drop onto the plate has
settled) and the end, 0.1 s:
  sliding (tan theta > mu): the acceleration, the least-squares slope of the block's mean velocity, against
      a = g (sin theta - mu cos theta); also the friction coefficient it implies, mu_eff = (g sin - a) / (g cos);
  sticking (tan theta < mu): the drift of the block's centre of mass over STICK_WINDOW (its mean over the
      last 10 ms less that over the first 10 ms; the run goes on to STICK_END), against 1e-6 of the block's
      size: a block at rest for 0.1 s, once the drop's ringing (which lasts past 0.05 s at 20 degrees /
      mu 0.8 on 4 cubes) has settled;
and for every run its exit status (a guard stop is a failure) and the least contact energy over the run
relative to the friction dissipation (negative: contact put energy in).
The block's mean velocity and centre are volume averages over its tets of the nodal fields of the output
(every 2 ms), read with h5py through rift.series.json.

Usage: bench/contact_incline_study.py build/ci/rift [--angles 5,10,20,30,45,60] [--mus 0.1,0.3,0.5,0.8]
       [--cells 1,2,3,4] [--meshes lattice,unstructured] [--set key=value ...] [--json out.json]
(Debian's python3 with python3-h5py and python3-numpy, which scripts/deps.sh installs.)
"""
import argparse
import csv
import itertools
import json
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "scenes/validation/contact_incline.yaml")
G = 9.81
BLOCK = 0.02  # the scene's block edge [m]
T0, END = 0.04, 0.1
STICK_WINDOW, STICK_END = (0.1, 0.2), 0.2


def grid_field(out, grid, name):
    with h5py.File(os.path.join(out, grid[name]["file"])) as h:
        return h[grid[name]["path"]][...]


def block_history(out):
    """Times, mean velocity and mean displacement of the block (the scene's last region)."""
    series = json.load(open(os.path.join(out, "rift.series.json")))
    times, vel, disp = [], [], []
    weights = cells = None
    for entry in series["entries"]:
        solid = next(g for g in entry["grids"] if g["name"] == "solid")
        fields = {f["name"]: f["data"] for f in solid["fields"]}
        if weights is None:
            points = grid_field(out, solid, "points")
            conn = grid_field(out, solid, "cells").reshape(-1, 4)
            region = grid_field(out, fields, "region").ravel()
            block = conn[region == region.max()]
            x = points[block]
            vol = np.abs(np.einsum("ij,ij->i", x[:, 1] - x[:, 0], np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 0])))
            weights, cells = np.repeat(vol / 24.0, 4), block.ravel()
        v, u = grid_field(out, fields, "velocity"), grid_field(out, fields, "displacement")
        times.append(entry["time"])
        vel.append((v[cells] * weights[:, None]).sum(0) / weights.sum())
        disp.append((u[cells] * weights[:, None]).sum(0) / weights.sum())
    return np.array(times), np.array(vel), np.array(disp)


def block_mesh(cells, unstructured):
    """The block's override: a lattice of cells^3 cubes, or an unstructured mesh of element size BLOCK / cells."""
    if not unstructured:
        return f"mesh.generate.blocks[1].cells=[{cells}, {cells}, {cells}]"
    return (f"mesh.generate.blocks[1]={{name: block, origin: [-0.01, -0.01, 0.0], size: [{BLOCK}, {BLOCK}, {BLOCK}], "
            f"element_size: {BLOCK / cells!r}}}")


def run_case(rift, theta_deg, mu, cells, unstructured, extra, threads):
    theta = math.radians(theta_deg)
    sets = [f"solid.gravity=[{G * math.sin(theta)!r}, 0, {-G * math.cos(theta)!r}]",
            f"solid.contact.friction={mu}", block_mesh(cells, unstructured),
            "output.interval=0.002", "output.fields=[velocity, displacement, region]",
            f"time.end={END if math.tan(theta) > mu else STICK_END}"]
    with tempfile.TemporaryDirectory(prefix="incline") as out:
        args = [rift, "run", "--overwrite", SCENE, "-o", out, "--threads", str(threads), "-q"]
        for s in sets + extra:
            args += ["--set", s]
        proc = subprocess.run(args, capture_output=True, text=True)
        row = {"theta": theta_deg, "mu": mu, "cells": cells, "mesh": "unstructured" if unstructured else "lattice",
               "exit": proc.returncode}
        if proc.returncode != 0:
            row["error"] = proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else "?"
            return row
        t, v, u = block_history(out)
        ts = list(csv.DictReader(open(os.path.join(out, "timeseries.csv"))))
    window = t >= T0 - 1e-12
    row["slides"] = math.tan(theta) > mu
    if row["slides"]:
        expected = G * (math.sin(theta) - mu * math.cos(theta))
        a = float(np.polyfit(t[window], v[window, 0], 1)[0])
        row.update(a=a, expected=expected, rel_error=a / expected - 1.0,
                   mu_eff=(G * math.sin(theta) - a) / (G * math.cos(theta)))
    else:
        # Means over the first and the last 10 ms of the window, so the elastic ringing left from the drop
        # does not count as drift (as in tests/validation/test_contact.cpp).
        t0, t1 = STICK_WINDOW
        early, late = (t >= t0 - 1e-12) & (t < t0 + 0.01 - 1e-12), t >= t1 - 0.01 - 1e-12
        drift = float(u[late, 0].mean() - u[early, 0].mean())
        row.update(drift=drift, drift_rel=abs(drift) / BLOCK)
    friction = max(float(ts[-1]["contact_friction_dissipation"]), 1e-300)
    row["least_contact_energy_rel"] = min(float(r["contact_energy"]) for r in ts) / friction
    return row


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("rift")
    p.add_argument("--angles", default="5,10,20,30,45,60")
    p.add_argument("--mus", default="0.1,0.3,0.5,0.8")
    p.add_argument("--cells", default="1,2,3,4", help="cells (lattice) or element sizes (block / n) per side")
    p.add_argument("--meshes", default="lattice,unstructured")
    p.add_argument("--set", action="append", default=[], help="extra scene override, key=value")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--json")
    args = p.parse_args()
    rows = []
    print(f"{'theta':>5} {'mu':>4} {'mesh':>12} {'n':>2}  result")
    cases = itertools.product(map(float, args.angles.split(",")), map(float, args.mus.split(",")),
                              args.meshes.split(","), map(int, args.cells.split(",")))
    for theta, mu, mesh, cells in cases:
        r = run_case(args.rift, theta, mu, cells, mesh == "unstructured", args.set, args.threads)
        rows.append(r)
        if r["exit"] != 0:
            res = f"STOPPED: {r['error']}"
        elif r["slides"]:
            res = (f"slides a {r['a']:.4f} expected {r['expected']:.4f} ({100 * r['rel_error']:+.2f} %), "
                   f"mu_eff {r['mu_eff']:.4f}")
        else:
            res = f"sticks, drift {r['drift']:.3e} m ({r['drift_rel']:.1e} of the block)"
        if r["exit"] == 0:
            res += f"; least contact energy {r['least_contact_energy_rel']:+.1e} of friction"
        print(f"{theta:5g} {mu:4g} {mesh:>12} {cells:2d}  {res}", flush=True)
    if args.json:
        json.dump(rows, open(args.json, "w"), indent=1)
    bad = [r for r in rows if r["exit"] != 0 or (r["slides"] and abs(r["rel_error"]) > 0.02)
           or (not r["slides"] and r["drift_rel"] > 1e-6)]
    print(f"{len(rows)} runs, {len(bad)} outside the bounds (2 % of a; drift 1e-6 of the block; no guard stop)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
