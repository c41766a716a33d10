#!/usr/bin/env python3
"""The state hash of every example and validation scene at the end of its run.

A change that must not touch the physics (a refactor, a faster kernel) leaves every hash as it was:

    scripts/state_hashes.py build/ci/rift > before.txt     # on the parent commit
    scripts/state_hashes.py build/ci/rift --compare before.txt

Each scene runs to its end on the given thread count, or, where that takes many minutes, on a coarser
mesh to a nearer end (SETTINGS); its summary.json holds the state hash of the store (every column of
every table, engine/core/state_hash.hpp). A scene whose run
fails is listed with its status, so a failure is a difference too.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
# The scenes that take minutes to their end: how they run here instead. The paper's wedges on their coarse
# preset (docs/paper-scene.md) to past their first breaks (0.13 ms).
COARSE_WEDGE = ["mesh.generate.size_min=0.004", "mesh.generate.size_max=0.008", "solid.mass_scaling_step=1.0e-8",
                "time.end=1.6e-4"]
# The penny-shaped fractures on the validation tests' 1/6 m cells (test_hydraulic_fracture.cpp), a third of
# their time.
COARSE_PENNY = ["mesh.generate.graded.size=0.1666666666666667",
                "mesh.generate.graded.fine_min=[0, 0, -0.3333333333333333]",
                "mesh.generate.graded.fine_max=[3.0, 3.0, 0.3333333333333333]",
                "solid.fracture.box_min=[-1, -1, -0.15]", "solid.fracture.box_max=[3.0, 3.0, 0.15]",
                "time.end=0.03"]
SETTINGS = {
    "validation/radial_toughness.yaml": COARSE_PENNY,
    "validation/radial_viscous.yaml": COARSE_PENNY,
    "examples/guo2015_wedge.yaml": COARSE_WEDGE + ["fluid.mesh.generate.size_min=0.004"],
    "examples/guo2015_wedge_dry.yaml": COARSE_WEDGE,
    "examples/guo2015_wedge_flow.yaml": COARSE_WEDGE,
}


def scenes():
    for folder in ("examples", "validation"):
        for path in sorted((ROOT / "scenes" / folder).glob("*.yaml")):
            yield f"{folder}/{path.name}"


def run(rift, scene, settings, threads, out):
    cmd = [rift, "run", str(ROOT / "scenes" / scene), "--quiet", "--threads", str(threads), "--out", str(out)]
    for setting in settings:
        cmd += ["--set", setting]
    started = time.monotonic()
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    seconds = time.monotonic() - started
    summary = out / "summary.json"
    if not summary.exists():
        last = (proc.stderr.strip().splitlines() or ["no output"])[-1]
        return {"hash": "-", "status": f"exit {proc.returncode}: {last[:80]}", "steps": 0, "seconds": seconds}
    s = json.loads(summary.read_text())
    return {"hash": s.get("state_hash", "-"), "status": s.get("status", "-"), "steps": s.get("steps", 0),
            "seconds": seconds}


def read_list(path):
    table = {}
    for line in pathlib.Path(path).read_text().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        scene, digest, status, *_ = line.split()
        table[scene] = (digest, status)
    return table


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("rift", help="the rift binary")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--only", nargs="*", help="scenes (as listed) to run; default all")
    p.add_argument("--compare", help="a list this script wrote before: exit 1 when any hash differs")
    args = p.parse_args()
    rift = str(pathlib.Path(args.rift).resolve())
    before = read_list(args.compare) if args.compare else {}
    differ = 0
    print(f"# scene  state_hash  status  steps  seconds   (scripts/state_hashes.py, {args.threads} threads)")
    with tempfile.TemporaryDirectory(prefix="rift_hashes_") as tmp:
        for scene in scenes():
            if args.only and scene not in args.only:
                continue
            out = pathlib.Path(tmp) / scene.replace("/", "_").removesuffix(".yaml")
            r = run(rift, scene, SETTINGS.get(scene, []), args.threads, out)
            status = r["status"].replace(" ", "_")
            mark = ""
            if scene in before and before[scene] != (r["hash"], status):
                mark = f"   DIFFERS (was {before[scene][0]} {before[scene][1]})"
                differ += 1
            print(f"{scene}  {r['hash']}  {status}  {r['steps']}  {r['seconds']:.1f}{mark}", flush=True)
    if args.compare:
        print(f"# {differ} of the compared scenes differ", file=sys.stderr)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
