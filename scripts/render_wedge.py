#!/usr/bin/env python3
"""Panels like Fig. 7 of Guo et al. (ARMA 2015) from a Rift run of scenes/examples/guo2015_wedge.yaml.

Usage:
  python3 scripts/render_wedge.py RUN_DIR [--out DIR] [--plane-z 0.025] [--times all|t1,t2,...]
                                          [--only stress|fluid|crack|series] [--window x0,x1,y0,y1]
                                          [--stress-range MIN,MAX] [--pressure-range MIN,MAX]

Reads RUN_DIR/rift.series.json (the index of every field output), timeseries.csv, fractures.csv and
scene.yaml, and writes into --out (default RUN_DIR/figures), for every chosen output time (step = the
solid step of that output, 8 digits):
  stress_<step>.png  the cut plane z = --plane-z (m): sigma_yy (MPa, tension positive) of the solid's tets
                     (deformed positions), its contour lines every 5 MPa, and the crack trace (broken joints
                     cut by the plane, thick black);
  fluid_<step>.png   the same plane: the fluid mesh's solid fraction (1 solid, 0 fluid) with the cut
                     fluid cells' edges (the adaptive refinement along the notch and the crack) and the
                     crack trace;
  crack_<step>.png   the fracture-flow network seen along y (x-z plane): its pressure (MPa), the part the
                     fluid has not reached hatched; "no crack yet" before the network exists;
and once
  series.png         crack length along y = notch tip (from fractures.csv), well pressure and injected
                     volume against time, with the times of the paper's Fig. 7 panels.
--times takes simulation times in ms; each picks the nearest output. --only renders one kind of panel.

The pixel size of every PNG is fixed (no tight bounding box): FIGSIZE_IN x DPI below, i.e.
  stress, fluid, crack: 960 x 720 px;  series: 960 x 1080 px.
Files are written to a temporary name in the output folder and renamed, so a reader never sees half a PNG.
Exit status 2, with a message, when RUN_DIR is not a Rift run or a needed field or column is missing.
Needs numpy, h5py and matplotlib (Debian: python3-h5py python3-matplotlib); reads scene.yaml with PyYAML
when it is there (python3-yaml), else takes the wedge scene's notch tip and ramp start.
"""

import argparse
import csv
import json
import os
import sys
import time as clock

import numpy as np

try:
    import h5py
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colors, tri
    from matplotlib.collections import LineCollection, PolyCollection
except ImportError as missing:  # pragma: no cover - depends on the machine
    sys.exit(f"render_wedge.py: {missing}; install python3-h5py and python3-matplotlib (Debian)")

DPI = 120
FIGSIZE_IN = {"stress": (8.0, 6.0), "fluid": (8.0, 6.0), "crack": (8.0, 6.0), "series": (8.0, 9.0)}
PANEL_SIZE_PX = {k: (round(w * DPI), round(h * DPI)) for k, (w, h) in FIGSIZE_IN.items()}
PANELS = ("stress", "fluid", "crack", "series")

# Times of the paper's Fig. 7 panels, in ms after its pressure ramp begins.
PAPER_TIMES_MS = (0.108, 0.178, 0.238, 0.263, 0.378)
# The wedge scene's values, used when scene.yaml cannot be read.
DEFAULT_TIP = (0.0245, 0.05)  # m: notch on face xmin, 24.5 mm deep, centred at y = 50 mm
DEFAULT_RAMP = {"value": 1.5e7, "start_time": 1.0e-4, "rate": 2.0e10, "limit": None}
NEAR_TIP_Y = 0.005  # m: a broken joint this close to the tip's y counts towards the crack length


class RenderError(Exception):
    """A problem of the input the user can fix: reported on one line, exit status 2."""


def output_fields_hint(field):
    return (f"add `{field}` to output.fields in the scene (or leave output.fields empty: every field) "
            "and run it again")


# ---------------------------------------------------------------------------------------------- reading


class Run:
    """A run folder: its index and cached reads of its HDF5 datasets."""

    def __init__(self, path):
        self.path = path
        index = os.path.join(path, "rift.series.json")
        if not os.path.isfile(index):
            raise RenderError(f"{path} is not a Rift run folder: it has no rift.series.json")
        with open(index) as f:
            self.entries = json.load(f).get("entries", [])
        if not self.entries:
            raise RenderError(f"{index} lists no outputs yet")
        self._files = {}
        self._mesh_cache = {}

    def dataset(self, ref):
        """The array a {file, path} reference of the index names."""
        name = ref["file"]
        if name not in self._files:
            self._files[name] = h5py.File(os.path.join(self.path, name), "r")
        return self._files[name][ref["path"]][()]

    def mesh(self, ref):
        # Meshes are shared by many outputs (the fluid's changes every adaptation): read each once.
        key = (ref["file"], ref["path"])
        if key not in self._mesh_cache:
            self._mesh_cache[key] = self.dataset(ref)
        return self._mesh_cache[key]

    def close(self):
        for f in self._files.values():
            f.close()
        self._files.clear()


def grid(entry, name):
    return next((g for g in entry["grids"] if g["name"] == name), None)


def need_grid(entry, name, field):
    g = grid(entry, name)
    if g is None:
        raise RenderError(f"the output at t = {entry['time'] * 1e3:.4g} ms has no grid '{name}' "
                          f"(needed for its field '{field}'): {output_fields_hint(field)}")
    return g


def field(run, entry, grid_name, name):
    g = need_grid(entry, grid_name, name)
    for f in g["fields"]:
        if f["name"] == name:
            return run.dataset(f["data"])
    raise RenderError(f"grid '{grid_name}' at t = {entry['time'] * 1e3:.4g} ms has no field '{name}': "
                      f"{output_fields_hint(name)}")


def points_and_cells(run, entry, grid_name, needed_field):
    # The solid's points in a step file are the deformed positions (reference + displacement).
    g = need_grid(entry, grid_name, needed_field)
    return run.dataset(g["points"]), run.mesh(g["cells"]).astype(np.int64)


def scene_values(run_dir):
    """(notch tip (x, y) in m, pressure ramp dict) from scene.yaml, or the wedge scene's values."""
    try:
        import yaml  # optional: python3-yaml
        with open(os.path.join(run_dir, "scene.yaml")) as f:
            scene = yaml.safe_load(f)
    except Exception:  # no PyYAML or no readable scene.yaml: the wedge scene's values
        return DEFAULT_TIP, DEFAULT_RAMP
    return notch_tip(scene), pressure_ramp(scene)


def notch_tip(scene):
    gen = (scene.get("mesh") or {}).get("generate") or {}
    for n in gen.get("notches") or []:
        if n.get("face") == "xmin" and n.get("opening_axis") == "y":
            return (gen.get("origin", [0, 0, 0])[0] + n["depth"], n["center"])
    return DEFAULT_TIP


def pressure_ramp(scene):
    for b in (scene.get("fluid") or {}).get("boundaries") or []:
        value = b.get("value")
        if b.get("type") == "pressure" and isinstance(value, dict) and "ramp" in value:
            return value["ramp"]
    return DEFAULT_RAMP


def read_csv_columns(path, names, required, hint="", max_rows=20000):
    """The named columns of a large CSV as float arrays, every k-th row so that at most ~max_rows are kept.
    Rows that do not parse (the last one of a run still writing) are skipped."""
    if not os.path.isfile(path):
        raise RenderError(f"{path} is missing")
    with open(path, newline="") as f:
        header = next(csv.reader(f), [])
        first = f.readline()
        per_row = max(len(first), 1)
    missing = [n for n in required if n not in header]
    if missing:
        raise RenderError(f"{path} has no column {', '.join(missing)}{hint}")
    present = [n for n in names if n in header]
    idx = [header.index(n) for n in present]
    stride = max(1, os.path.getsize(path) // per_row // max_rows)
    rows = []
    with open(path, newline="") as f:
        reader = csv.reader(f)
        next(reader)
        for i, row in enumerate(reader):
            if i % stride == 0:
                try:
                    rows.append([float(row[j]) for j in idx])
                except (ValueError, IndexError):
                    continue
    data = np.array(rows, dtype=float).reshape(-1, len(idx))
    return {n: data[:, k] for k, n in enumerate(present)}


# --------------------------------------------------------------------------------------------- geometry

TET_EDGES = np.array([[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]])
TRI_EDGES = np.array([[0, 1], [1, 2], [2, 0]])


def edge_crossings(P, z0, edges):
    """Where the edges of simplices P (n, k, 3) cross the plane z = z0: (crosses (n, e), points (n, e, 2)).
    A vertex on the plane counts as above it, so every crossing edge has one end strictly below."""
    below = P[..., 2] < z0
    a, b = edges.T
    crosses = below[:, a] != below[:, b]
    da, db = P[:, a, 2] - z0, P[:, b, 2] - z0
    t = da / np.where(crosses, da - db, 1.0)
    pts = P[:, a, :2] + t[..., None] * (P[:, b, :2] - P[:, a, :2])
    return crosses, pts


def cut_tets(P, z0):
    """The polygons where tets P (n, 4, 3) cut the plane z = z0: (tet indices, polygons (m, 4, 2)).
    A cut is a triangle (3 crossing edges) or a quad (4); triangles repeat their last point."""
    below = (P[..., 2] < z0).sum(1)
    hit = np.nonzero((below > 0) & (below < 4))[0]
    crosses, pts = edge_crossings(P[hit], z0, TET_EDGES)
    # A cut is convex: ordering its points by angle around their mean gives the polygon.
    n = crosses.sum(1)
    centre = (pts * crosses[..., None]).sum(1) / n[:, None]
    angle = np.arctan2(pts[..., 1] - centre[:, None, 1], pts[..., 0] - centre[:, None, 0])
    order = np.argsort(np.where(crosses, angle, np.inf), axis=1)[:, :4]
    poly = np.take_along_axis(pts, order[..., None], axis=1)
    poly[n == 3, 3] = poly[n == 3, 2]
    return hit, poly


def cut_triangles(P, z0):
    """The segments (m, 2, 2) where triangles P (n, 3, 3) cut the plane z = z0."""
    crosses, pts = edge_crossings(P, z0, TRI_EDGES)
    hit = crosses.sum(1) == 2
    first_two = np.argsort(~crosses[hit], axis=1, kind="stable")[:, :2]
    return np.take_along_axis(pts[hit], first_two[..., None], axis=1)


def segments_cross(E, S, chunk=200):
    """For edges E (ne, 2, 2): does each properly cross any segment of S (ns, 2, 2)? In chunks of S so
    that memory stays at ne x chunk."""
    out = np.zeros(len(E), dtype=bool)

    def side(o, d, p):  # sign of the cross product (d - o) x (p - o), broadcast
        return np.sign((d[..., 0] - o[..., 0]) * (p[..., 1] - o[..., 1]) -
                       (d[..., 1] - o[..., 1]) * (p[..., 0] - o[..., 0]))

    e0, e1 = E[:, None, 0], E[:, None, 1]
    for s in range(0, len(S), chunk):
        s0, s1 = S[None, s:s + chunk, 0], S[None, s:s + chunk, 1]
        x = (side(e0, e1, s0) * side(e0, e1, s1) < 0) & (side(s0, s1, e0) * side(s0, s1, e1) < 0)
        out |= x.any(1)
    return out


# ------------------------------------------------------------------------------------------------ plots


def new_figure(panel):
    return plt.figure(figsize=FIGSIZE_IN[panel], dpi=DPI)


def save(fig, out_dir, name):
    """Atomically: a temporary name in the same folder, then a rename."""
    final = os.path.join(out_dir, name)
    tmp = os.path.join(out_dir, f".{name}.{os.getpid()}.tmp")
    try:
        fig.savefig(tmp, format="png", dpi=DPI)
        os.replace(tmp, final)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)
    return final


def time_title(what, t, ramp_start):
    return (f"{what}\nt = {t * 1e3:.3f} ms; t - {ramp_start * 1e3:.3g} ms = {(t - ramp_start) * 1e3:.3f} ms "
            "after the ramp begins")


def plane_axes(fig, ctx):
    ax = fig.add_axes([0.09, 0.09, 0.72, 0.78])
    x0, x1, y0, y1 = ctx.window
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    return ax


def colorbar(fig, mappable, label, extend="neither"):
    cax = fig.add_axes([0.85, 0.12, 0.03, 0.72])
    fig.colorbar(mappable, cax=cax, extend=extend).set_label(label)


def crack_trace(run, entry, z0):
    """Broken joints cut by the plane, as segments in mm (one face triangle of each 6-node joint)."""
    broken = field(run, entry, "joints", "broken") > 0.5
    pts, cells = points_and_cells(run, entry, "joints", "broken")
    return cut_triangles(pts[cells[broken, :3]], z0) * 1e3


def draw_trace(ax, trace, color="k"):
    ax.add_collection(LineCollection(trace, colors=color, linewidths=2.5, zorder=5))


def stress_contours(ax, poly, value, barriers, levels):
    """sigma_yy contours through the cut polygons' centres (a Delaunay triangulation of them), leaving
    out the triangles that straddle the notch or the crack, where the field jumps."""
    levels = levels[(levels > value.min()) & (levels < value.max())] if len(value) else levels[:0]
    if len(poly) < 3 or len(levels) == 0:  # a uniform field (the first output) has no contour
        return
    c = poly.mean(1)
    t = tri.Triangulation(c[:, 0], c[:, 1])
    if len(barriers):
        edges = c[t.triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)]
        t.set_mask(segments_cross(edges, barriers).reshape(-1, 3).any(1))
    ax.tricontour(t, value, levels=levels, colors="k", linewidths=0.4, linestyles="solid", alpha=0.5)


def render_stress(run, entry, ctx):
    z0 = ctx.plane_z
    stress = field(run, entry, "solid", "stress")
    pts, cells = points_and_cells(run, entry, "solid", "stress")
    idx, poly = cut_tets(pts[cells], z0)
    syy = stress[idx, 3] / 1e6  # XDMF Tensor6 order: xx xy xz yy yz zz
    poly *= 1e3
    trace = crack_trace(run, entry, z0)
    lo, hi = ctx.stress_range
    norm = colors.TwoSlopeNorm(vmin=lo, vcenter=0.0, vmax=hi)
    fig = new_figure("stress")
    ax = plane_axes(fig, ctx)
    pc = PolyCollection(poly, array=syy, cmap="RdBu_r", norm=norm, edgecolors="face", linewidths=0.2)
    ax.add_collection(pc)
    # The notch's mid-line from beyond the face to the tip: no contour bridges the notch.
    tx, ty = ctx.tip[0] * 1e3, ctx.tip[1] * 1e3
    notch = np.array([[[ctx.block_x[0] - 10.0, ty], [tx, ty]]])
    barriers = np.concatenate([trace.reshape(-1, 2, 2), notch]) if len(trace) else notch
    stress_contours(ax, poly, syy, barriers, np.arange(np.floor(lo / 5) * 5, hi + 1e-9, 5.0))
    draw_trace(ax, trace)
    colorbar(fig, pc, r"$\sigma_{yy}$ (MPa, tension > 0)", extend="both")
    ax.set_title(time_title(f"vertical stress, plane z = {z0 * 1e3:.4g} mm; crack trace black", entry["time"],
                            ctx.ramp_start), fontsize=10)
    return save(fig, ctx.out, f"stress_{entry['step']:08d}.png")


def render_fluid(run, entry, ctx):
    z0 = ctx.plane_z
    fraction = field(run, entry, "fluid", "solid_fraction")
    pts, cells = points_and_cells(run, entry, "fluid", "solid_fraction")
    idx, poly = cut_tets(pts[cells], z0)
    trace = crack_trace(run, entry, z0)
    fig = new_figure("fluid")
    ax = plane_axes(fig, ctx)
    pc = PolyCollection(poly * 1e3, array=fraction[idx], cmap="coolwarm", clim=(0.0, 1.0),
                        edgecolors="k", linewidths=0.15)
    ax.add_collection(pc)
    draw_trace(ax, trace, color="lime")
    colorbar(fig, pc, "solid fraction (1 solid, 0 fluid)")
    ax.set_title(time_title(f"fluid mesh and solid fraction, plane z = {z0 * 1e3:.4g} mm; "
                            "solid's crack trace green", entry["time"], ctx.ramp_start), fontsize=10)
    return save(fig, ctx.out, f"fluid_{entry['step']:08d}.png")


def crack_axes(fig, ctx):
    ax = fig.add_axes([0.09, 0.09, 0.72, 0.78])
    x0, x1 = ctx.block_x
    z0, z1 = ctx.block_z
    ax.add_patch(plt.Rectangle((x0, z0), x1 - x0, z1 - z0, fill=False, color="0.3", lw=1))
    ax.axvline(ctx.tip[0] * 1e3, color="0.3", ls="--", lw=0.8)
    ax.set_xlim(x0 - 1, x1 + 1)
    ax.set_ylim(z0 - 1, z1 + 1)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("z (mm)")
    return ax


def render_crack(run, entry, ctx):
    fig = new_figure("crack")
    ax = crack_axes(fig, ctx)
    title = "fracture-flow network seen along y: pressure; dry part hatched; notch tip dashed"
    ax.set_title(time_title(title, entry["time"], ctx.ramp_start), fontsize=10)
    norm = colors.Normalize(*ctx.pressure_range)
    if grid(entry, "crack_network") is None:
        ax.text(0.5, 0.5, "no crack yet", transform=ax.transAxes, ha="center", va="center", fontsize=16)
        colorbar(fig, plt.cm.ScalarMappable(norm=norm, cmap="viridis"), "pressure (MPa)")
        return save(fig, ctx.out, f"crack_{entry['step']:08d}.png")
    pressure = field(run, entry, "crack_network", "pressure") / 1e6
    wetting = field(run, entry, "crack_network", "wetting_time")
    pts, cells = points_and_cells(run, entry, "crack_network", "pressure")
    xz = pts[:, [0, 2]] * 1e3
    t = tri.Triangulation(xz[:, 0], xz[:, 1], cells)
    tp = ax.tripcolor(t, pressure, cmap="viridis", norm=norm, shading="gouraud")
    ax.triplot(t, color="k", lw=0.2)
    # wetting_time is -1 at a vertex the fluid has not reached: a triangle with such a vertex is dry, and
    # its pressure (the lag pressure) means nothing, so it is greyed out.
    dry = (wetting[cells] < 0).any(1)
    with plt.rc_context({"hatch.linewidth": 0.4, "hatch.color": "0.45"}):
        ax.add_collection(PolyCollection(xz[cells[dry]], facecolors="0.85", edgecolors="0.45", hatch="///",
                                         linewidths=0.3))
    colorbar(fig, tp, "pressure (MPa)", extend="max")
    return save(fig, ctx.out, f"crack_{entry['step']:08d}.png")


def crack_length(fractures_path, tip, t_end):
    """Step function (t, L): the largest x of broken joints within NEAR_TIP_Y of the tip's y, minus the
    tip's x (0 before any), in m."""
    cols = read_csv_columns(fractures_path, ["time", "x", "y"], ["time", "x", "y"], max_rows=10**9)
    order = np.argsort(cols["time"], kind="stable")
    t, x, y = (cols[k][order] for k in ("time", "x", "y"))
    near = np.abs(y - tip[1]) < NEAR_TIP_Y
    t, length = t[near], np.maximum.accumulate(np.maximum(x[near] - tip[0], 0.0)) if near.any() else []
    return np.r_[0.0, t, t_end], np.r_[0.0, length, length[-1] if len(length) else 0.0]


def ramp_pressure(ramp, t):
    p = ramp["value"] + ramp["rate"] * np.maximum(t - ramp["start_time"], 0.0)
    return p if ramp.get("limit") is None else np.minimum(p, ramp["limit"])


def render_series(run_dir, ctx):
    wanted = ["time", "flow_well_pressure", "flow_injected_volume", "flow_crack_extent",
              "fluid_solid_inlet_pressure"]
    ts = read_csv_columns(os.path.join(run_dir, "timeseries.csv"), wanted, wanted[:3],
                          " (the flow_ columns come with a fracture_flow section, as guo2015_wedge.yaml has)")
    t_ms = ts["time"] * 1e3
    ct, cl = crack_length(os.path.join(run_dir, "fractures.csv"), ctx.tip,
                          ts["time"][-1] if len(t_ms) else 0.0)
    fig = new_figure("series")
    axes = fig.subplots(3, 1, sharex=True)
    fig.subplots_adjust(left=0.11, right=0.96, top=0.93, bottom=0.06, hspace=0.12)
    axes[0].step(ct * 1e3, cl * 1e3, where="post", color="k", label="crack length from the tip (fractures.csv)")
    if "flow_crack_extent" in ts:
        axes[0].plot(t_ms, ts["flow_crack_extent"] * 1e3, "--", color="C1",
                     label="flow_crack_extent (from the well point)")
    axes[0].set_ylabel("length (mm)")
    axes[1].plot(t_ms, ts["flow_well_pressure"] / 1e6, color="C0", label="flow_well_pressure")
    if "fluid_solid_inlet_pressure" in ts:
        axes[1].plot(t_ms, ts["fluid_solid_inlet_pressure"] / 1e6, "--", color="C3",
                     label="fluid_solid_inlet_pressure")
    axes[1].plot(t_ms, ramp_pressure(ctx.ramp, ts["time"]) / 1e6, ":", color="0.4", label="inlet boundary")
    axes[1].set_ylabel("pressure (MPa)")
    clip_to_ramp(axes[1], ts, ctx.ramp)
    axes[2].plot(t_ms, ts["flow_injected_volume"] * 1e9, color="C2", label="flow_injected_volume")
    axes[2].set_ylabel("injected volume (mm$^3$)")
    axes[2].set_xlabel("time (ms)")
    mark_paper_times(axes, ctx.ramp_start * 1e3)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(loc="upper left", fontsize=8)
    fig.suptitle("Guo et al. (2015) wedge: Fig. 7 panel times dotted, the ramp's start dashed", fontsize=10)
    return save(fig, ctx.out, "series.png")


def clip_to_ramp(ax, ts, ramp):
    """Pressures far off the inlet's ramp (a run blowing up) would flatten the plot: keep the axis at
    0 .. 1.5 x the ramp's largest value and say what was cut."""
    top = 1.5 * ramp_pressure(ramp, ts["time"]).max() / 1e6 if len(ts["time"]) else 1.0
    cols = [c for c in ("flow_well_pressure", "fluid_solid_inlet_pressure") if c in ts]
    values = np.concatenate([ts[c] for c in cols]) / 1e6
    if len(values) and (values.max() > top or values.min() < 0):
        ax.set_ylim(0, top)
        ax.text(0.99, 0.97, f"off scale: {values.min():.3g} .. {values.max():.3g} MPa", transform=ax.transAxes,
                ha="right", va="top", fontsize=8, color="C3")


def mark_paper_times(axes, ramp_ms):
    for ax in axes:
        ax.axvline(ramp_ms, color="0.3", ls="--", lw=0.8)
        for p in PAPER_TIMES_MS:
            ax.axvline(ramp_ms + p, color="m", ls=":", lw=0.9)
    for p in PAPER_TIMES_MS:
        axes[0].annotate(f"{p:g}", (ramp_ms + p, 1.0), xycoords=("data", "axes fraction"), fontsize=7,
                         color="m", ha="center", va="bottom")


# ------------------------------------------------------------------------------------------------- main


class Context:
    """What every panel needs: the plane, the window, ranges, the notch tip and the ramp."""

    def __init__(self, args, run):
        self.out = args.out or os.path.join(args.run_dir, "figures")
        self.plane_z = args.plane_z
        self.tip, self.ramp = scene_values(args.run_dir)
        self.ramp_start = float(self.ramp["start_time"])
        self.stress_range = parse_floats(args.stress_range, 2, "--stress-range")
        self.pressure_range = parse_floats(args.pressure_range, 2, "--pressure-range")
        # The block's extent from the first output (reference positions: nothing has moved yet), in mm.
        pts, _ = points_and_cells(run, run.entries[0], "solid", "displacement")
        lo, hi = pts.min(0) * 1e3, pts.max(0) * 1e3
        self.block_x, self.block_z = (lo[0], hi[0]), (lo[2], hi[2])
        ty = self.tip[1] * 1e3
        auto = (lo[0] - 5.0, hi[0] + 1.0, ty - 25.0, ty + 25.0)  # the fluid in front of the notch too
        self.window = parse_floats(args.window, 4, "--window") if args.window else auto


def parse_floats(text, n, option):
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != n:
        raise RenderError(f"{option} takes {n} comma-separated numbers, not '{text}'")
    return values


def chosen_entries(run, times):
    if times == "all":
        return run.entries
    t = np.array([e["time"] for e in run.entries])
    picks = sorted({int(np.argmin(np.abs(t - ms * 1e-3))) for ms in parse_floats(times, times.count(",") + 1,
                                                                                 "--times")})
    return [run.entries[i] for i in picks]


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run_dir", metavar="RUN_DIR", help="a Rift output folder (has rift.series.json)")
    p.add_argument("--out", help="output folder (default RUN_DIR/figures)")
    p.add_argument("--plane-z", type=float, default=0.025, help="cut plane z in m (default 0.025)")
    p.add_argument("--times", default="all", help="'all' or simulation times in ms, t1,t2,... (nearest output)")
    p.add_argument("--only", choices=PANELS, help="render only this panel")
    p.add_argument("--window", help="cut-plane view x0,x1,y0,y1 in mm (default: the block, tip y +- 25 mm)")
    p.add_argument("--stress-range", default="-30,10", help="sigma_yy colour range in MPa (default -30,10)")
    p.add_argument("--pressure-range", default="0,30", help="crack pressure colour range, MPa (default 0,30)")
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    started = clock.time()
    run = Run(args.run_dir)
    try:
        ctx = Context(args, run)
        os.makedirs(ctx.out, exist_ok=True)
        panels = [args.only] if args.only else list(PANELS)
        renderers = {"stress": render_stress, "fluid": render_fluid, "crack": render_crack}
        for entry in chosen_entries(run, args.times):
            for name in panels:
                if name in renderers:
                    print(renderers[name](run, entry, ctx), flush=True)
        if "series" in panels:
            print(render_series(args.run_dir, ctx), flush=True)
    finally:
        run.close()
    print(f"render_wedge.py: done in {clock.time() - started:.1f} s", file=sys.stderr)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except RenderError as e:
        print(f"render_wedge.py: {e}", file=sys.stderr)
        sys.exit(2)
