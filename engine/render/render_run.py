"""Field pictures of a Rift run, drawn by ParaView (`rift render RUN_DIR`, or directly:
xvfb-run -a pvpython render_run.py RUN_DIR OUT_DIR [options]).

For each chosen output time it writes into OUT_DIR:
  cut_<field>_<n>.png        a plane cut of the grid that holds the field (the solid's tets, else the
                             fluid's), coloured by the field in display units, with the crack trace (the
                             broken joints the plane cuts) in black;
  cracks_<n>.png             the broken joints, coloured by the time each broke (fractures.csv), inside
                             the solid's outline; written when the run has a fracture zone.
<n> is the output's number in the run's series (0000 the first). Every picture of one field shares one
colour range (the 1st to 99th percentile over the chosen times, or --range), so a series reads
as a film. The files are written to a temporary name and renamed: a reader never sees half a PNG.
Prints each file written on its own line; exits 2 with a message on a bad argument or a missing grid.

The solid's geometry moves with the run (its points are the deformed positions), so nothing is warped.
Reads the XDMF indexes with ParaView's "XDMF Reader", the reader the README names.
"""
import argparse
import csv
import os
import sys

import numpy
from paraview import servermanager
from paraview import simple as pv
from paraview.vtk.numpy_interface import dataset_adapter

# Components a field spec may name. The XDMF Reader expands Tensor6 to a 3 x 3 tensor, which ParaView's
# Python gives as an array of shape (n, 3, 3).
TENSOR = {"xx": (0, 0), "xy": (0, 1), "xz": (0, 2), "yx": (1, 0), "yy": (1, 1), "yz": (1, 2), "zx": (2, 0),
          "zy": (2, 1), "zz": (2, 2)}
VECTOR = {"x": 0, "y": 1, "z": 2}
PRINCIPAL = {"max": 0, "mid": 1, "min": 2}  # principal_stress is written in descending order
# Display unit and factor from SI, by field.
UNITS = {"stress": ("MPa", 1e-6), "principal_stress": ("MPa", 1e-6), "pressure": ("MPa", 1e-6),
         "displacement": ("mm", 1e3), "opening": ("um", 1e6), "slip": ("um", 1e6), "aperture": ("um", 1e6),
         "velocity": ("m/s", 1.0), "force": ("N", 1.0), "fluid_force": ("N", 1.0),
         "contact_force": ("N", 1.0), "energy": ("J", 1.0), "wetting_time": ("ms", 1e3)}
GRIDS = ("solid", "fluid", "crack_network", "joints")
NORMALS = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}
# Where the camera looks from and which way is up, so that the two in-plane axes point right and up
# (x right for a y cut: it looks along +y).
VIEW_FROM = {"x": (1.0, 0.0, 0.0), "y": (0.0, -1.0, 0.0), "z": (0.0, 0.0, 1.0)}
VIEW_UP = {"x": (0.0, 0.0, 1.0), "y": (0.0, 0.0, 1.0), "z": (0.0, 1.0, 0.0)}


def fail(message):
    print("rift render: " + message, file=sys.stderr)
    sys.exit(2)


def arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run")
    p.add_argument("out")
    p.add_argument("--field", default="",
                   help="NAME[:COMPONENT], e.g. stress:yy, principal_stress:max, velocity:magnitude, pressure; "
                        "default: principal_stress:max with a solid, else velocity:magnitude")
    p.add_argument("--normal", default="z", choices=sorted(NORMALS), help="axis normal to the cut plane")
    p.add_argument("--at", type=float, default=None,
                   help="position of the cut plane along its normal, in m (default: the solid's centre)")
    p.add_argument("--times", default="last",
                   help="'last', 'all', or times in s separated by commas (each picks the nearest output)")
    p.add_argument("--size", default="1280x960", help="picture size in pixels, WIDTHxHEIGHT")
    p.add_argument("--range", default="", help="MIN,MAX of the colour map in display units "
                   "(default: the 1st to 99th percentile of the cut over the chosen times)")
    return p.parse_args()


def open_grid(run, grid):
    path = os.path.join(run, "rift_%s.xdmf" % grid)
    if not os.path.isfile(path):
        return None
    reader = pv.XDMFReader(FileNames=[path])
    reader.UpdatePipelineInformation()
    return reader


def arrays(reader):
    return {"CELLS": list(reader.CellData.keys()), "POINTS": list(reader.PointData.keys())}


def find_field(readers, name):
    for grid in GRIDS:
        reader = readers.get(grid)
        if reader is None:
            continue
        for association, names in arrays(reader).items():
            if name in names:
                return grid, association
    return None, None


def component_expression(name, component, ncomp):
    """numpy expression of the chosen component over `name`, and its label."""
    if ncomp == 1:
        if component:
            fail("%s is a scalar; give it without a component" % name)
        return name, ""
    if not component:
        component = "max" if name == "principal_stress" else ("yy" if ncomp == 9 else "magnitude")
    if component == "magnitude":
        return "mag(%s)" % name, "magnitude"
    table = PRINCIPAL if name == "principal_stress" else (TENSOR if ncomp == 9 else VECTOR)
    if component not in table:
        fail("%s has the components %s (or magnitude), not '%s'" % (name, ", ".join(table), component))
    if table is TENSOR:
        return "%s[:, %d, %d]" % ((name,) + table[component]), component
    return "%s[:, %d]" % (name, table[component]), component


def chosen_times(available, spec):
    if not available:
        return [0.0]
    if spec == "last":
        return [available[-1]]
    if spec == "all":
        return list(available)
    picked = []
    for item in spec.split(","):
        try:
            t = float(item)
        except ValueError:
            fail("--times takes 'last', 'all' or times in s separated by commas, not '%s'" % spec)
        nearest = min(available, key=lambda a: abs(a - t))
        if nearest not in picked:
            picked.append(nearest)
    return picked


def break_times(run):
    """joint index -> time it broke, from fractures.csv."""
    times = {}
    path = os.path.join(run, "fractures.csv")
    if os.path.isfile(path):
        with open(path) as f:
            for row in csv.DictReader(f):
                times.setdefault(int(row["joint"]), float(row["time"]))
    return times


def broken_joints(joints, times):
    """The broken joints, each with the time it broke (fracture_time_ms; the joint's cell index is its id)."""
    labelled = pv.ProgrammableFilter(Input=joints)
    labelled.Script = (
        "import numpy as np\n"
        "times = %r\n"
        "output.ShallowCopy(inputs[0].VTKObject)\n"
        "n = inputs[0].GetNumberOfCells()\n"
        "output.CellData.append(np.array([times.get(i, -1.0) * 1e3 for i in range(n)]), 'fracture_time_ms')\n"
        % times)
    # broken: 0 intact, 1 tensile, 2 shear, 3 an initial crack
    return pv.Threshold(Input=labelled, Scalars=["CELLS", "broken"], LowerThreshold=0.5, UpperThreshold=3.5)


def readable(value, unit):
    """value (in s or m) in the unit of its size: 30 s, 0.4 ms, 12 us; 1.2 m, 25 mm."""
    if value == 0.0:
        return "0 " + unit
    scales = ((1.0, unit), (1e-3, "m" + unit), (1e-6, "u" + unit))
    for scale, name in scales:
        if abs(value) >= scale or scale == scales[-1][0]:
            return "%.4g %s" % (value / scale, name)


def cut_values(values, association, times):
    """The shown values over the cut at each of `times`, concatenated (empty when the plane cuts nothing)."""
    found = []
    for t in times:
        values.UpdatePipeline(t)
        if values.GetDataInformation().GetNumberOfCells() == 0:
            continue
        data = dataset_adapter.WrapDataObject(servermanager.Fetch(values))
        array = (data.CellData if association == "CELLS" else data.PointData)["shown"]
        if not isinstance(array, numpy.ndarray):
            fail("ParaView could not compute the shown value; see the messages above")
        found.append(numpy.asarray(array).ravel())
    return numpy.concatenate(found) if found else numpy.zeros(0)


def save(view, path, size):
    temporary = path + ".part.png"
    pv.SaveScreenshot(temporary, view, ImageResolution=size, TransparentBackground=0)
    os.replace(temporary, path)
    print(path)


def new_view(size):
    view = pv.CreateRenderView()
    view.ViewSize = size
    view.OrientationAxesVisibility = 1
    view.CameraParallelProjection = 1
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    return view


def label(view, text, location):
    annotation = pv.Text(Text=text)
    shown = pv.Show(annotation, view)
    shown.Color = [0.0, 0.0, 0.0]
    shown.FontSize = 14
    shown.WindowLocation = location
    return annotation


class Field:
    """What a cut is coloured by: a field of one grid, one of its components, in display units."""

    def __init__(self, readers, spec):
        self.name, _, component = spec.partition(":")
        self.grid, self.association = find_field(readers, self.name)
        if self.grid is None:
            known = sorted({n for r in readers.values() if r for names in arrays(r).values() for n in names})
            fail("no field '%s' in this run's output; it has: %s (output.fields chooses them)"
                 % (self.name, ", ".join(known)))
        self.reader = readers[self.grid]
        data = self.reader.CellData if self.association == "CELLS" else self.reader.PointData
        expression, self.component = component_expression(self.name, component.lower(),
                                                           data[self.name].GetNumberOfComponents())
        unit, factor = UNITS.get(self.name, ("", 1.0))
        self.expression = "(%s) * %r" % (expression, factor)
        self.title = " ".join(filter(None, (self.name, self.component, "[%s]" % unit if unit else "")))
        self.tag = self.name + ("_" + self.component if self.component else "")
        self.signed = self.name in ("stress", "principal_stress", "pressure")


class Plane:
    """The cut plane: normal to an axis, through the centre of `source` (the solid, else the field's grid)
    at `time`, or at `at` along the normal."""

    def __init__(self, source, time, normal, at):
        source.UpdatePipeline(time)
        self.bounds = source.GetDataInformation().GetBounds()
        self.normal, self.axis = normal, "xyz".index(normal)
        self.centre = [0.5 * (self.bounds[2 * k] + self.bounds[2 * k + 1]) for k in range(3)]
        if at is not None:
            self.centre[self.axis] = at
        self.extent = max(self.bounds[2 * k + 1] - self.bounds[2 * k] for k in range(3))


def requested_range(text):
    if not text:
        return None
    try:
        low, high = (float(v) for v in text.split(","))
        if high > low:
            return low, high
    except ValueError:
        pass
    fail("--range takes MIN,MAX with MIN < MAX, not '%s'" % text)


def plane_slice(source, origin, normal):
    cut = pv.Slice(Input=source)
    cut.SliceType = "Plane"
    cut.SliceType.Origin = origin
    cut.SliceType.Normal = list(NORMALS[normal])
    return cut


def colour_range(field, cut, values, times, plane, requested):
    """One colour range for every picture: the 1st to 99th percentile of the cut's values over the chosen
    times (a few spiking elements at a crack tip would wash everything else out; values beyond it take the
    end colours), or --range. A plane that holds element faces (the centre of a structured mesh) may cut
    nothing: it is moved off them by 1e-6 of the extent, which the caption shows."""
    shown = cut_values(values, field.association, times)
    if shown.size == 0:
        plane.centre[plane.axis] += 1e-6 * plane.extent
        cut.SliceType.Origin = plane.centre
        shown = cut_values(values, field.association, times)
    if shown.size == 0:
        low, high = plane.bounds[2 * plane.axis], plane.bounds[2 * plane.axis + 1]
        fail("the plane %s = %g m cuts nothing of the %s grid; choose --at within [%g, %g]"
             % (plane.normal, plane.centre[plane.axis], field.grid, low, high))
    if requested:
        return requested
    low, high = (float(v) for v in numpy.percentile(shown, [1.0, 99.0]))
    if low < 0.0 < high and field.signed:
        low, high = -max(-low, high), max(-low, high)  # signed: zero is the map's middle
    return (low, high) if high > low else (low, low + 1.0)


def colour_bar(lut, view, title):
    bar = pv.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = bar.RangeLabelFormat = "%.3g"
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]


def cut_view(field, values, trace, value_range, size, plane):
    view = new_view(size)
    shown = pv.Show(values, view)
    pv.ColorBy(shown, (field.association, "shown"))
    lut = pv.GetColorTransferFunction("shown")
    # A diverging map where the range has both signs (its middle is zero), a sequential one otherwise.
    low, high = value_range
    lut.ApplyPreset("Cool to Warm" if low < 0.0 < high else "Viridis (matplotlib)", True)
    lut.RescaleTransferFunction(low, high)
    lut.AutomaticRescaleRangeMode = "Never"
    colour_bar(lut, view, field.title)
    shown.SetScalarBarVisibility(view, True)
    if trace is not None:
        crack = pv.Show(trace, view)
        crack.ColorArrayName = ["POINTS", ""]
        crack.AmbientColor = crack.DiffuseColor = [0.0, 0.0, 0.0]
        crack.Representation = "Wireframe"
        crack.LineWidth = 3.0
    view.CameraFocalPoint = plane.centre
    view.CameraPosition = [plane.centre[k] + 3.0 * plane.extent * VIEW_FROM[plane.normal][k] for k in range(3)]
    view.CameraViewUp = list(VIEW_UP[plane.normal])
    return view, label(view, "", "Upper Left Corner")


def cracks_view(run, readers, broken, times_of_breaks, size, plane):
    view = new_view(size)
    # The solid's outer boundary for context: the continuous surface (tag 0) when the run wrote it, else
    # the bounding box (the tets' own faces would hide the cracks).
    surface = open_grid(run, "surface")
    if surface is not None:
        boundary = pv.Threshold(Input=surface, Scalars=["CELLS", "tag"], LowerThreshold=0, UpperThreshold=0)
        outline = pv.Show(boundary, view)
        outline.ColorArrayName = ["POINTS", ""]
        outline.Opacity = 0.12
    else:
        outline = pv.Show(pv.Outline(Input=readers["solid"] or readers["joints"]), view)
    outline.AmbientColor = outline.DiffuseColor = [0.3, 0.3, 0.3]
    faces = pv.Show(broken, view)
    pv.ColorBy(faces, ("CELLS", "fracture_time_ms"))
    lut = pv.GetColorTransferFunction("fracture_time_ms")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    ordered = sorted(times_of_breaks.values()) or [0.0]
    lut.RescaleTransferFunction(ordered[0] * 1e3, max(ordered[-1] * 1e3, ordered[0] * 1e3 + 1e-9))
    lut.AutomaticRescaleRangeMode = "Never"
    lut.UseBelowRangeColor = 1  # initial cracks (no break time) in grey
    lut.BelowRangeColor = [0.6, 0.6, 0.6]
    colour_bar(lut, view, "time the joint broke [ms]")
    faces.SetScalarBarVisibility(view, True)
    c, e = plane.centre, plane.extent
    view.CameraFocalPoint = c
    view.CameraPosition = [c[0] + 1.6 * e, c[1] - 2.2 * e, c[2] + 1.4 * e]
    view.CameraViewUp = [0.0, 0.0, 1.0] if plane.normal != "z" else [0.0, 1.0, 0.0]
    return view, label(view, "", "Upper Left Corner")


def picture_size(text):
    try:
        size = [int(v) for v in text.lower().split("x")]
        if len(size) == 2 and min(size) >= 64:
            return size
    except ValueError:
        pass
    fail("--size takes WIDTHxHEIGHT in pixels, at least 64x64, not '%s'" % text)


def main():
    a = arguments()
    size = picture_size(a.size)
    readers = {grid: open_grid(a.run, grid) for grid in GRIDS}
    if not any(readers.values()):
        fail("%s holds no rift_<grid>.xdmf: give the output folder of a Rift run" % a.run)
    field = Field(readers, a.field or ("principal_stress:max" if readers["solid"] else "velocity:magnitude"))
    available = list(field.reader.TimestepValues or [])
    times = chosen_times(available, a.times)

    plane = Plane(readers["solid"] or field.reader, times[0], a.normal, a.at)
    cut = plane_slice(field.reader, plane.centre, a.normal)
    values = pv.PythonCalculator(Input=cut, Expression=field.expression, ArrayName="shown",
                                 ArrayAssociation="Cell Data" if field.association == "CELLS" else "Point Data")
    value_range = colour_range(field, cut, values, times, plane, requested_range(a.range))
    times_of_breaks = break_times(a.run)
    broken = broken_joints(readers["joints"], times_of_breaks) if readers["joints"] else None
    trace = plane_slice(broken, plane.centre, a.normal) if broken is not None else None
    view, caption = cut_view(field, values, trace, value_range, size, plane)
    if broken is not None:
        crack_view, crack_caption = cracks_view(a.run, readers, broken, times_of_breaks, size, plane)

    for t in times:
        number = "%04d" % (available.index(t) if t in available else 0)
        view.ViewTime = t
        caption.Text = "t = %s   cut %s = %s   %s grid" % (
            readable(t, "s"), a.normal, readable(plane.centre[plane.axis], "m"), field.grid)
        view.ResetCamera(False)
        save(view, os.path.join(a.out, "cut_%s_%s.png" % (field.tag, number)), size)
        if broken is not None:
            crack_view.ViewTime = t
            broken.UpdatePipeline(t)
            count = broken.GetDataInformation().GetNumberOfCells()
            crack_caption.Text = "t = %s   %s" % (
                readable(t, "s"), "%d joints broken" % count if count else "no crack yet")
            crack_view.ResetCamera(False)
            save(crack_view, os.path.join(a.out, "cracks_%s.png" % number), size)


if __name__ == "__main__":
    # ParaView's Python filters run their code in __main__ after importing numpy's and VTK's algorithms
    # there (min, max, save, ...): this file runs as a module of its own so that its names stay its own.
    import importlib.util
    spec = importlib.util.spec_from_file_location("rift_render_run", os.path.abspath(__file__))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.main()
