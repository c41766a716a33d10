#!/usr/bin/python3
"""Refinement study of the fluid-driven crack cases (docs/hydraulic-fracture.md).

Runs `rift` on the scenes of scenes/validation at several element sizes (the fracture zone stays one
element either side of the crack) and compares with the closed forms, each length and pressure the mean
over the 10 ms before 0.05, 0.075 and 0.1 s (the tests' measure):
  sneddon           Sneddon by injection: p (1 + p / K_f) = E' V / (2 pi a^2), w0 = 4 p a / E';
  kgd               KGD, toughness vertex: l = 0.9324 (E' Q0 t / K')^(2/3), w0 = 0.6828 (K'^2 Q0 t / E'^2)^(1/3),
                    p = 0.1831 (K'^4 / (E' Q0 t))^(1/3);
  kgd_viscous       KGD, M-vertex: l = 0.6152 (E' Q0^3 / mu')^(1/6) t^(2/3), w0 = 1.134 (mu' Q0^3 t^2 / E')^(1/6),
                    p_net = 0.62 (mu' Q0 E')^(1/2) / w0;
  radial_toughness  penny, K-vertex: R = 0.8546 (E' Q0 t / K')^(2/5), p = 0.3004 (K'^6 / (E' Q0 t))^(1/5);
  radial_viscous    penny, M-vertex: R = 0.6976 (E' Q0^3 t^4 / mu')^(1/9);
  --borehole sizes  borehole_breakdown.yaml at those wall cell sizes: the first softening's pressure
                    against 3 sigma_h - sigma_H + T (--penalty: joint penalties in multiples of E).
Usage: bench/hydraulic_fracture_study.py build/ci/rift [--cells 4,8,16] [--cases kgd,radial_toughness]
       [--borehole 0.004,0.002] [--json out.json]
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

NAN = float("nan")

E, NU = 1.0e10, 0.25
EP = E / (1 - NU * NU)
KIC = 1.0e6
KP = 4 * math.sqrt(2 / math.pi) * KIC
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(rift, scene, out, cells_per_m, extra):
    h = 1.0 / cells_per_m
    band = 0.9 * h
    # The scenes' graded lattices: cells of h along the crack's path and through the slab.
    reach = 1.5 if "sneddon" in scene else 5.0
    sets = [f"mesh.generate.graded.size={h}", f"mesh.generate.graded.fine_min=[0, -{2 * h}, 0]",
            f"mesh.generate.graded.fine_max=[{reach}, {2 * h}, 0.125]"]
    sets.append(f"solid.fracture.box_min=[-1, -{band}, -1]")
    box_max_x = 1.25 if "sneddon" in scene else 5.0
    sets.append(f"solid.fracture.box_max=[{box_max_x}, {band}, 1]")
    sets.append("output.fields=[displacement, pressure, aperture]")
    args = [rift, "run", "--overwrite", os.path.join(ROOT, "scenes/validation", scene), "-o", out, "--threads", "2", "-q"]
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


def windows(r, closed_form, length_of, confinement=0.0):
    """Means of measured / closed form over the 10 ms before 0.05, 0.075 and 0.1 s (the tests' measure)."""
    row = {}
    for t in (0.05, 0.075, 0.1):
        sel = [x for x in r if t - 0.01 < float(x["time"]) <= t + 1e-12]
        exact = [closed_form(float(x["time"])) for x in sel]
        row[f"length@{t}"] = np.mean([length_of(x) / e[0] for x, e in zip(sel, exact)]) - 1
        if not math.isnan(exact[0][2]):
            row[f"pressure@{t}"] = np.mean([(float(x["flow_well_pressure"]) - confinement) / e[2]
                                            for x, e in zip(sel, exact)]) - 1
    return row


def kgd_viscous(rift, n, tmp):
    """KGD, viscosity-dominated (kgd_viscous.yaml), against the M-vertex."""
    out = os.path.join(tmp, f"kgd_viscous_{n}")
    r = run(rift, "kgd_viscous.yaml", out, n, [])
    mup, q0 = 12 * 4.0e-3, 6.568e-3 / 0.0625

    def m_vertex(t):
        w0 = 1.134 * (mup * q0 ** 3 * t * t / EP) ** (1 / 6)
        return (0.6152 * (EP * q0 ** 3 / mup) ** (1 / 6) * t ** (2 / 3), w0, 0.62 * math.sqrt(mup * q0 * EP) / w0)
    row = {"case": "kgd viscous", "cells_per_m": n}
    row.update(windows(r, m_vertex, lambda x: float(x["flow_crack_extent"]), 3.0e6))
    row["mouth_opening@0.1"] = well_aperture(out) / m_vertex(0.1)[1] - 1
    return [row]


def radial(rift, n, tmp, scene):
    """The radial cases on their graded lattice at h = 1 / n: the fine box and the fracture zone follow h."""
    h = 1.0 / n
    out = os.path.join(tmp, f"{scene}_{n}")
    sets = [f"mesh.generate.graded.size={h}", f"mesh.generate.graded.fine_min=[0, 0, -{2 * h}]",
            f"mesh.generate.graded.fine_max=[3.0, 3.0, {2 * h}]", f"solid.fracture.box_min=[-1, -1, -{0.9 * h}]",
            f"solid.fracture.box_max=[3.0, 3.0, {0.9 * h}]", "output.fields=[pressure]"]
    args = [rift, "run", "--overwrite", os.path.join(ROOT, "scenes/validation", scene + ".yaml"), "-o", out, "--threads", "2", "-q"]
    for x in sets:
        args += ["--set", x]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    r = list(csv.DictReader(open(os.path.join(out, "timeseries.csv"))))
    if scene == "radial_toughness":
        q0 = 4 * 8.0e-3
        form = lambda t: (0.8546 * (EP * q0 * t / KP) ** 0.4, NAN, 0.3004 * (KP ** 6 / (EP * q0 * t)) ** 0.2)
    else:
        q0, mup = 4 * 3.18e-2, 12 * 4.0e-3
        form = lambda t: (0.6976 * (EP * q0 ** 3 * t ** 4 / mup) ** (1 / 9), NAN, NAN)
    row = {"case": scene.replace("_", " "), "cells_per_m": n}
    row.update(windows(r, form, lambda x: math.sqrt(4 * float(x["flow_crack_area"]) / math.pi)))
    return [row]


def borehole(rift, size, tmp, penalty=None):
    """Borehole breakdown: the well's pressure when the first joint softens, against Hubbert-Willis.
    penalty: the joints' penalty in multiples of E (None: the scene's default, 10 E)."""
    out = os.path.join(tmp, f"borehole_{size}_{penalty}")
    sets = [f"mesh.generate.borehole.size={size}", f"mesh.generate.box=[0.5, 1.0, {size}]",
            f"fracture_flow.injection.point=[0, 0, {size / 2}]",
            f"fracture_flow.injection.well_volume={math.pi * 0.05 ** 2 * size / 2}", "output.fields=[pressure]"]
    if penalty is not None:
        sets.append(f"solid.materials[0].fracture.penalty={penalty * E}")
    args = [rift, "run", "--overwrite", os.path.join(ROOT, "scenes/validation/borehole_breakdown.yaml"), "-o", out, "--threads",
            "2", "-q"]
    for x in sets:
        args += ["--set", x]
    # A run that stops after the crack started (the energy guard, with stiff joints) still gives the
    # initiation: its time series runs to the stop. The stop is reported beside it.
    done = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    r = list(csv.DictReader(open(os.path.join(out, "timeseries.csv"))))
    row = {"case": "borehole", "wall_cell_m": size, "penalty_over_E": penalty if penalty else 10}
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or [f"exit status {done.returncode}"])[-1]
        row["stopped"] = f"at {float(r[-1]['time']) * 1e3:.3g} ms: " + last[:200]
    summary = json.load(open(os.path.join(out, "summary.json")))
    energy = summary.get("metrics", {}).get("solid", {}).get("energy", {})
    if energy:
        row["balance_error_J"] = energy["balance_error"]
        row["external_work_J"] = energy["external_work"]
    first = next((x for x in r if float(x["flow_crack_area"]) > 0), None)
    if first is not None:
        row["initiation"] = float(first["flow_well_pressure"]) / (3 * 3.0e6 - 5.0e6 + 2.0e6) - 1
        row["initiation_ms"] = float(first["time"]) * 1e3
    return [row]


CASES = ("sneddon", "kgd", "kgd_viscous", "radial_toughness", "radial_viscous")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("rift")
    ap.add_argument("--cells", default="4,8,16", help="elements per metre (per crack half-length a = 1 m)")
    ap.add_argument("--cases", default=",".join(CASES), help="of " + ", ".join(CASES))
    ap.add_argument("--borehole", default="", help="wall cell sizes [m] of the borehole case, e.g. 0.004,0.002")
    ap.add_argument("--penalty", default="", help="joint penalties of the borehole case in multiples of E, e.g. 10,30")
    ap.add_argument("--json")
    a = ap.parse_args()
    cases = a.cases.split(",")
    rows = []

    def report(new_rows):
        for r in new_rows:
            rows.append(r)
            print(json.dumps({k: (round(v, 4) if isinstance(v, float) else v) for k, v in r.items()}), flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        for n in [int(c) for c in a.cells.split(",")]:
            if "sneddon" in cases:
                report(sneddon(a.rift, n, tmp))
            if "kgd" in cases:
                report(kgd(a.rift, n, tmp))
            if "kgd_viscous" in cases:
                report(kgd_viscous(a.rift, n, tmp))
            for scene in ("radial_toughness", "radial_viscous"):
                if scene in cases:
                    report(radial(a.rift, n, tmp, scene))
        for size in [float(x) for x in a.borehole.split(",") if x]:
            for penalty in [float(x) for x in a.penalty.split(",") if x] or [None]:
                report(borehole(a.rift, size, tmp, penalty))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
