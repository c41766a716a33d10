#!/usr/bin/python3
"""Fluid over viscosities: at rest and moving, with the quasi-static and the dynamic pressure subscale
(docs/fluid.md, docs/stability.md).

Cases, each at viscosities 1e-3 (water), 1e-1, 10, 1e3 and 1e5 Pa s (rho = 1000) and for both
fluid.pressure_subscale values:
  box           scenes/validation/hydrostatic_box.yaml: water at rest in a closed 1 m box, 8^3 cells;
  block_rest    scenes/validation/immersed_block.yaml: a neutrally buoyant block held at rest in it;
  block_moving  the same block thrown at (0.05, 0, 0.1) m/s, 1.5 x the fluid's density.
Per run: the exit status (a fluid guard stop names the solve that did not converge), the most FGMRES
iterations a step took, the pressure range at the end (hydrostatic: +-4905 Pa) and the largest speed.

Usage: bench/fluid_viscosity_study.py build/ci/rift [--json out.json] [--set key=value ...]
(--set is passed to every run, e.g. --set fluid.schur_restart=100).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASES = {
    "box": ("scenes/validation/hydrostatic_box.yaml", []),
    "block_rest": ("scenes/validation/immersed_block.yaml", []),
    "block_moving": ("scenes/validation/immersed_block.yaml",
                     ["solid.initial_velocity=[{velocity: [0.05, 0, 0.1]}]", "solid.materials[0].density=1500"]),
}
VISCOSITIES = ["1e-3", "1e-1", "10", "1e3", "1e5"]


def run(rift, scene, sets, out):
    cmd = [rift, "run", "--overwrite", os.path.join(ROOT, scene), "--threads", "1", "--out", out]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    why = ""
    if p.returncode != 0:
        why = next((l for l in (p.stderr + p.stdout).splitlines() if "error" in l), "")[:160]
    rows = []
    path = os.path.join(out, "timeseries.csv")
    if os.path.exists(path):
        rows = list(csv.DictReader(open(path)))
    result = {"status": "completed" if p.returncode == 0 else "stopped", "why": why}
    if rows:
        result["max_schur_per_step"] = max(int(float(r["fluid_schur_iterations"])) for r in rows)
        result["pressure"] = [float(rows[-1]["fluid_pressure_min"]), float(rows[-1]["fluid_pressure_max"])]
        result["max_speed"] = float(rows[-1]["fluid_max_speed"])
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("rift")
    ap.add_argument("--json")
    ap.add_argument("--set", action="append", default=[], help="key=value for every run")
    args = ap.parse_args()
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for case, (scene, extra) in CASES.items():
            for mu in VISCOSITIES:
                for sub in ("quasi_static", "dynamic"):
                    sets = [f"fluid.viscosity={mu}", f"fluid.pressure_subscale={sub}"] + extra + args.set
                    r = run(args.rift, scene, sets, os.path.join(tmp, f"{case}_{mu}_{sub}"))
                    r.update(case=case, viscosity=float(mu), subscale=sub)
                    results.append(r)
                    p = r.get("pressure", [float("nan")] * 2)
                    print(f"{case:13s} mu {mu:5s} {sub:12s} {r['status']:9s} "
                          f"schur/step {r.get('max_schur_per_step', '-'):>5} p [{p[0]:.6g}, {p[1]:.6g}] "
                          f"speed {r.get('max_speed', float('nan')):.3g} {r['why']}", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
