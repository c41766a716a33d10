#!/usr/bin/python3
"""Refinement study of the fluid-driven crack cases (docs/hydraulic-fracture.md).

Runs `rift` on scenes/validation/sneddon_injection.yaml and scenes/validation/kgd_toughness.yaml at
several element sizes (the fracture zone stays one element either side of the crack), and compares with
the closed forms:
  Sneddon by injection: p (1 + p / K_f) = E' V / (2 pi a^2), w0 = 4 p a / E';
  KGD, toughness vertex: l = 0.9324 (E' Q0 t / K')^(2/3), w0 = 0.6828 (K'^2 Q0 t / E'^2)^(1/3),
                         p = 0.1831 (K'^4 / (E' Q0 t))^(1/3), each the mean over the 10 ms before t.
Usage: bench/hydraulic_fracture_study.py build/ci/rift [--cells 4,8,16] [--json out.json]
(Debian's python3 with python3-h5py, which scripts/deps.sh installs.)
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import h5py  # noqa: F401  (python3-h5py; the mouth opening is read from the crack_network grid)
import numpy as np

E, NU = 1.0e10, 0.25
EP = E / (1 - NU * NU)
KIC = 1.0e6
KP = 4 * math.sqrt(2 / math.pi) * KIC
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(rift, scene, out, cells_per_m, extra):
    h = 1.0 / cells_per_m
    band = 0.9 * h
    sets = [f"mesh.generate.cells=[{10 * cells_per_m}, {20 * cells_per_m}, 1]",
            f"solid.fracture.box_min=[-1, -{band}, -1]"]
    box_max_x = 1.25 if "sneddon" in scene else 5.0
    sets.append(f"solid.fracture.box_max=[{box_max_x}, {band}, 1]")
    sets.append("output.fields=[displacement, pressure, aperture]")
    args = [rift, "run", os.path.join(ROOT, "scenes/validation", scene), "-o", out, "--threads", "2", "-q"]
    for s in sets + extra:
        args += ["--set", s]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    return list(csv.DictReader(open(os.path.join(out, "timeseries.csv"))))


def well_aperture(out):
    """The mouth opening at the last output: the crack_network point nearest the well."""
    import xml.etree.ElementTree as ET
    tree = ET.parse(os.path.join(out, "rift.xdmf"))
    grids = [g for g in tree.iter("Grid") if g.get("Name") == "crack_network"]
    g = grids[-1]
    def data(item):
        f, path = item.text.strip().split(":")
        with h5py.File(os.path.join(out, f), "r") as h:
            return np.array(h[path])
    pts = data(g.find("Geometry/DataItem")).reshape(-1, 3)
    ap = [a for a in g.iter("Attribute") if a.get("Name") == "aperture"][0]
    w = data(ap.find("DataItem")).ravel()
    i = np.argmin(np.abs(pts[:, 0]) + np.abs(pts[:, 2] - 0.0625))
    return float(w[i])


def sneddon(rift, n, tmp):
    rows = []
    for bulk in (2.2e9, 1.0e7):
        out = os.path.join(tmp, f"sneddon_{n}_{bulk:g}")
        r = run(rift, "sneddon_injection.yaml", out, n, [f"fracture_flow.bulk_modulus={bulk}"])
        stiff = EP * 3.68156e-5 * 16 / (2 * math.pi)
        p = 2 * stiff / (1 + math.sqrt(1 + 4 * stiff / bulk))
        rows.append({"case": f"sneddon K_f={bulk:g}", "cells_per_m": n,
                     "pressure": float(r[-1]["flow_well_pressure"]) / p - 1,
                     "mouth_opening": well_aperture(out) / (4 * p / EP) - 1})
    return rows


def kgd(rift, n, tmp):
    out = os.path.join(tmp, f"kgd_{n}")
    r = run(rift, "kgd_toughness.yaml", out, n, [])
    q0 = 8.21e-4 / 0.0625
    row = {"case": "kgd toughness", "cells_per_m": n}
    for t in (0.05, 0.075, 0.1):
        sel = [x for x in r if t - 0.01 < float(x["time"]) <= t + 1e-12]
        ratio_l = np.mean([float(x["flow_crack_extent"]) / (0.9324 * (EP * q0 * float(x["time"]) / KP) ** (2 / 3)) for x in sel])
        ratio_p = np.mean([float(x["flow_well_pressure"]) / (0.1831 * (KP ** 4 / (EP * q0 * float(x["time"]))) ** (1 / 3)) for x in sel])
        row[f"half_length@{t}"] = ratio_l - 1
        row[f"pressure@{t}"] = ratio_p - 1
    w0 = 0.6828 * (KP ** 2 * q0 * 0.1 / EP ** 2) ** (1 / 3)
    row["mouth_opening@0.1"] = well_aperture(out) / w0 - 1
    return [row]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("rift")
    ap.add_argument("--cells", default="4,8,16", help="elements per metre (per crack half-length a = 1 m)")
    ap.add_argument("--json")
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in [int(c) for c in a.cells.split(",")]:
            for r in sneddon(a.rift, n, tmp) + kgd(a.rift, n, tmp):
                rows.append(r)
                print(json.dumps({k: (round(v, 4) if isinstance(v, float) else v) for k, v in r.items()}), flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
