#!/usr/bin/env python3
"""Lid-driven cavity at Re = 100: Rift against OpenFOAM's icoFoam at equal numbers of unknowns.

    bench/openfoam_cavity.py BENCH_FLUID [--n 16,32,64] [--end-time 25] [--co 0.5]
                             [--variants 2picard,3picard] [--json FILE] [--work DIR]

Runs, in one go:
  * icoFoam (OpenFOAM 1912, Debian package `openfoam`) on the unit square, N x N x 1 cells, nu = 0.01,
    lid u = 1 (Re = 100), with the tutorial's numerics (fluid.md 4.5: Euler, Gauss linear, PISO with 2
    correctors, p: PCG + DIC 1e-6 / relTol 0.05 then 0, U: smoothSolver symGaussSeidel 1e-5),
    dt = co / N (Courant number co), to t = end_time (steady: the script reports the change of the
    centre-line velocities over the last 5 time units, or half the run if shorter);
  * Rift's BM_FluidCavityRe100 benchmark (BENCH_FLUID = the bench_fluid executable) on n x n cells of
    the one-cell-thick slab (tests/validation/fluid_cavity.hpp), run to steady state.
Unknowns: Rift has 2 (n + 1)^2 nodes with u, v, p each (w is fixed by the free-slip z planes);
icoFoam has N^2 cells with Ux, Uy, p. N = round(sqrt(2) (n + 1)) makes them equal to 1-2 %.
Both are compared with Ghia et al. 1982 at the 15 interior stations of each centre line (max |du| on
x = 0.5, max |dv| on y = 0.5): icoFoam's cell-centre values are interpolated linearly (wall values
added at the ends; for even N the two centre columns are averaged), Rift's along its grid lines.
Time per step: icoFoam's ExecutionTime (CPU) from the log with the first step (start-up) excluded, and
its whole wall time over the steps (start-up included: ClockTime has 1 s resolution); Rift's march
alone, CPU and wall, mesh and set-up excluded. The ratios use CPU time. The two codes take different steps
(icoFoam is limited by its Courant number, Rift's implicit step is not), so the time to steady state is
recorded too.

Exits 0 with a "SKIP" line when icoFoam or blockMesh is not installed (apt-get install openfoam).
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

# Ghia, Ghia & Shin (1982), Re = 100 (fluid.md 4.1); the same table as tests/validation/fluid_cavity.hpp.
GHIA_Y = [1.0, 0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5, 0.4531, 0.2813, 0.1719, 0.1016,
          0.0703, 0.0625, 0.0547, 0.0]
GHIA_U = [1.0, 0.84123, 0.78871, 0.73722, 0.68717, 0.23151, 0.00332, -0.13641, -0.20581, -0.2109, -0.15662,
          -0.1015, -0.06434, -0.04775, -0.04192, -0.03717, 0.0]
GHIA_X = [1.0, 0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5, 0.2344, 0.2266, 0.1563, 0.0938,
          0.0781, 0.0703, 0.0625, 0.0]
GHIA_V = [0.0, -0.05906, -0.07391, -0.08864, -0.10313, -0.16914, -0.22445, -0.24533, 0.05454, 0.17527,
          0.17507, 0.16077, 0.12317, 0.1089, 0.10091, 0.09233, 0.0]

HEADER = "FoamFile\n{{\n    version 2.0;\n    format ascii;\n    class {cls};\n    object {obj};\n}}\n"


def write(path, cls, obj, body):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(HEADER.format(cls=cls, obj=obj) + body)


def write_case(case, n_cells, dt, end_time, write_interval):
    write(f"{case}/system/blockMeshDict", "dictionary", "blockMeshDict", f"""
scale 1;
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 0.1) (1 0 0.1) (1 1 0.1) (0 1 0.1));
blocks (hex (0 1 2 3 4 5 6 7) ({n_cells} {n_cells} 1) simpleGrading (1 1 1));
edges ();
boundary
(
    movingWall {{ type wall; faces ((3 7 6 2)); }}
    fixedWalls {{ type wall; faces ((0 4 7 3) (2 6 5 1) (1 5 4 0)); }}
    frontAndBack {{ type empty; faces ((0 3 2 1) (4 5 6 7)); }}
);
mergePatchPairs ();
""")
    write(f"{case}/system/controlDict", "dictionary", "controlDict", f"""
application icoFoam;
startFrom startTime;
startTime 0;
stopAt endTime;
endTime {end_time};
deltaT {dt!r};
writeControl runTime;
writeInterval {write_interval};
purgeWrite 0;
writeFormat ascii;
writePrecision 10;
writeCompression off;
timeFormat general;
timePrecision 8;
runTimeModifiable false;
""")
    write(f"{case}/system/fvSchemes", "dictionary", "fvSchemes", """
ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; grad(p) Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linear; }
laplacianSchemes { default Gauss linear orthogonal; }
interpolationSchemes { default linear; }
snGradSchemes { default orthogonal; }
""")
    write(f"{case}/system/fvSolution", "dictionary", "fvSolution", """
solvers
{
    p { solver PCG; preconditioner DIC; tolerance 1e-06; relTol 0.05; }
    pFinal { $p; relTol 0; }
    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-05; relTol 0; }
}
PISO { nCorrectors 2; nNonOrthogonalCorrectors 0; pRefCell 0; pRefValue 0; }
""")
    write(f"{case}/constant/transportProperties", "dictionary", "transportProperties",
          "\nnu [0 2 -1 0 0 0 0] 0.01;\n")
    write(f"{case}/0/U", "volVectorField", "U", """
dimensions [0 1 -1 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{
    movingWall { type fixedValue; value uniform (1 0 0); }
    fixedWalls { type noSlip; }
    frontAndBack { type empty; }
}
""")
    write(f"{case}/0/p", "volScalarField", "p", """
dimensions [0 2 -2 0 0 0 0];
internalField uniform 0;
boundaryField
{
    movingWall { type zeroGradient; }
    fixedWalls { type zeroGradient; }
    frontAndBack { type empty; }
}
""")


def read_velocity(path, n_cells):
    with open(path) as f:
        text = f.read()
    m = re.search(r"internalField\s+nonuniform\s+List<vector>\s*(\d+)\s*\(", text)
    if not m or int(m.group(1)) != n_cells * n_cells:
        sys.exit(f"openfoam_cavity: cannot read the velocity field in {path}")
    body = text[m.end():]
    vals = re.findall(r"\(([^()]*)\)", body[: body.find("\n)")])
    return [tuple(float(c) for c in v.split()[:2]) for v in vals[: n_cells * n_cells]]


def interp(xs, ys, x):
    for k in range(len(xs) - 1):
        if xs[k] <= x <= xs[k + 1]:
            a = (x - xs[k]) / (xs[k + 1] - xs[k])
            return (1 - a) * ys[k] + a * ys[k + 1]
    raise ValueError(x)


def centre_lines(vel, n):
    """u(y) on x = 0.5 and v(x) on y = 0.5 from cell centres (cell (i, j) is i + n j), with wall values."""
    mid = [n // 2] if n % 2 else [n // 2 - 1, n // 2]
    centres = [(k + 0.5) / n for k in range(n)]
    u_line = [sum(vel[i + n * j][0] for i in mid) / len(mid) for j in range(n)]
    v_line = [sum(vel[j * n + i][1] for j in mid) / len(mid) for i in range(n)]
    ys = [0.0] + centres + [1.0]
    return (ys, [0.0] + u_line + [1.0]), (ys, [0.0] + v_line + [0.0])


def ghia_errors(u_line, v_line):
    du = max(abs(interp(*u_line, GHIA_Y[k]) - GHIA_U[k]) for k in range(1, 16))
    dv = max(abs(interp(*v_line, GHIA_X[k]) - GHIA_V[k]) for k in range(1, 16))
    return du, dv


def run_openfoam(n_cells, co, end_time, work, env):
    case = os.path.join(work, f"cavity{n_cells}")
    shutil.rmtree(case, ignore_errors=True)
    dt = co / n_cells
    interval = min(5.0, end_time / 2)
    write_case(case, n_cells, dt, end_time, interval)
    subprocess.run(["blockMesh", "-case", case], check=True, env=env, stdout=subprocess.DEVNULL)
    t0 = time.perf_counter()
    log = subprocess.run(["icoFoam", "-case", case], check=True, env=env, capture_output=True, text=True).stdout
    wall = time.perf_counter() - t0
    with open(os.path.join(case, "log.icoFoam"), "w") as f:
        f.write(log)
    times = [(float(a), float(b)) for a, b in re.findall(r"ExecutionTime = ([\d.eE+-]+) s\s+ClockTime = ([\d.eE+-]+) s", log)]
    steps = len(times)
    if steps < 3:
        sys.exit("openfoam_cavity: icoFoam ran fewer than 3 steps; see " + case + "/log.icoFoam")
    p_iters = [int(x) for x in re.findall(r"Solving for p,.*No Iterations (\d+)", log)]
    dirs = sorted((d for d in os.listdir(case) if re.fullmatch(r"[\d.eE+-]+", d) and float(d) > 0), key=float)
    last, prev = dirs[-1], dirs[-2] if len(dirs) > 1 else None
    vel = read_velocity(os.path.join(case, last, "U"), n_cells)
    u_line, v_line = centre_lines(vel, n_cells)
    du, dv = ghia_errors(u_line, v_line)
    change = None
    if prev:
        pu, pv = centre_lines(read_velocity(os.path.join(case, prev, "U"), n_cells), n_cells)
        change = max(max(abs(a - b) for a, b in zip(u_line[1], pu[1])), max(abs(a - b) for a, b in zip(v_line[1], pv[1])))
    return {
        "cells": n_cells, "unknowns": 3 * n_cells * n_cells, "dt": dt, "end_time": float(last), "steps": steps,
        "cpu_ms_per_step": 1e3 * (times[-1][0] - times[0][0]) / (steps - 1),
        "wall_ms_per_step": 1e3 * wall / steps,
        "wall_seconds": wall, "p_iterations_per_step": sum(p_iters) / steps if p_iters else None,
        "max_du": du, "max_dv": dv, "write_interval": interval, "centre_line_change_last_interval": change,
    }


def run_rift(bench, n, work, name="BM_FluidCavityRe100"):
    out = os.path.join(work, f"rift{n}.json")
    env = dict(os.environ, RIFT_CAVITY_SIZES=str(n))
    env.pop("RIFT_BENCH_TINY", None)
    subprocess.run([bench, f"--benchmark_filter=^{name}/{n}/", f"--benchmark_out={out}",
                    "--benchmark_out_format=json"], check=True, env=env, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    with open(out) as f:
        b = json.load(f)["benchmarks"][0]
    nodes = int(b["nodes"])
    return {
        "cells": n, "nodes": nodes, "unknowns": 3 * nodes, "dt": b["dt"], "steps": int(b["steps"]),
        "cpu_ms_per_step": b["march_cpu_ms_per_step"], "wall_ms_per_step": b["march_ms_per_step"],
        "wall_seconds": b["march_seconds"], "max_du": b["max_du"], "max_dv": b["max_dv"],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bench", help="the bench_fluid executable")
    ap.add_argument("--n", default="32", help="Rift cells per side, comma-separated (icoFoam: round(sqrt(2) (n + 1)))")
    ap.add_argument("--end-time", type=float, default=25.0)
    ap.add_argument("--co", type=float, default=0.5, help="icoFoam Courant number (dt = co / N)")
    ap.add_argument("--variants", default="",
                    help="also run these Rift per-step solves, comma-separated: 2picard (2 inexact Picard "
                         "iterations per step), 3picard (the earlier solve: 3, full inner solves)")
    ap.add_argument("--json", help="write the results here (e.g. bench/results/openfoam_cavity.json)")
    ap.add_argument("--work", help="case directory (default: a temporary one, removed)")
    args = ap.parse_args()
    if not shutil.which("icoFoam") or not shutil.which("blockMesh"):
        print("openfoam_cavity: SKIP: icoFoam/blockMesh not found; install OpenFOAM with "
              "`apt-get install openfoam` to run the comparison")
        return 0
    env = dict(os.environ)
    # Debian's binaries need the etc tree (controlDict); its bashrc does not source cleanly, this suffices.
    if "WM_PROJECT_DIR" not in env and os.path.isfile("/usr/share/openfoam/etc/controlDict"):
        env["WM_PROJECT_DIR"] = "/usr/share/openfoam"
    work = args.work or tempfile.mkdtemp(prefix="openfoam_cavity_")
    os.makedirs(work, exist_ok=True)
    runs = []
    try:
        for n in (int(x) for x in args.n.split(",")):
            of = run_openfoam(round(math.sqrt(2) * (n + 1)), args.co, args.end_time, work, env)
            codes = [("icoFoam", of), ("Rift", run_rift(args.bench, n, work))]
            for v in filter(None, args.variants.split(",")):
                label = {"2picard": "Rift, 2 Picard", "3picard": "Rift, 3 Picard, full inner solves"}[v]
                codes.append((label, run_rift(args.bench, n, work, f"BM_FluidCavityRe100_{v[0]}Picard")))
            runs.append(codes)
    finally:
        if not args.work:
            shutil.rmtree(work, ignore_errors=True)

    def ratio(r, of, key):  # None when icoFoam's figure is below its clock's resolution (tiny runs)
        return r[key] / of[key] if of[key] > 0 else None

    def fmt(x):
        return "n/a" if x is None else f"{x:.2f}"

    print("| code | grid | unknowns | dt | steps | CPU ms/step | wall ms/step | wall to steady [s] | "
          "CPU/step vs icoFoam | max |du| | max |dv| |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    out = []
    for codes in runs:
        of = codes[0][1]
        entry = {"openfoam": of}
        for name, r in codes:
            grid = f"{r['cells']}^2 x 1 hex" if name == "icoFoam" else f"{r['cells']}^2 x 1 x 6 tets"
            q = ratio(r, of, "cpu_ms_per_step")
            print(f"| {name} | {grid} | {r['unknowns']} | {r['dt']:.4g} | {r['steps']} | {r['cpu_ms_per_step']:.3f} | "
                  f"{r['wall_ms_per_step']:.3f} | {r['wall_seconds']:.2f} | {fmt(q)} | {r['max_du']:.4f} | {r['max_dv']:.4f} |")
            if name != "icoFoam":
                key = {"Rift": "rift", "Rift, 2 Picard": "rift_2picard"}.get(name, "rift_3picard")
                entry[key] = r
                entry[key + "_over_openfoam"] = {"cpu_per_step": q, "wall_per_step": ratio(r, of, "wall_ms_per_step"),
                                                 "wall_to_steady": ratio(r, of, "wall_seconds")}
        out.append(entry)
        print(f"(icoFoam {of['cells']}^2: centre-line change over the last {of['write_interval']:g} time units "
              f"{of['centre_line_change_last_interval']:.1e}, {of['p_iterations_per_step']:.1f} p iterations per step)")
    if args.json:
        os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
        with open(args.json, "w") as f:
            json.dump({"case": "lid-driven cavity Re = 100", "end_time": args.end_time, "co": args.co,
                       "load_average_1min": os.getloadavg()[0], "runs": out}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
