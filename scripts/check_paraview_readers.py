"""ParaView's three XDMF readers on one grid of a Rift run: the stress of every cell against a known tensor.

    xvfb-run -a pvpython scripts/check_paraview_readers.py RUN_DIR XX XY XZ YY YZ ZZ [--grid solid] [--time T]

Opens RUN_DIR/rift_<grid>.xdmf (one grid alone, XDMF 3.0) with "XDMF Reader" (libXdmf 2; it expands
Tensor6 to a 3 x 3 tensor), "Xdmf3ReaderS" and "Xdmf3ReaderT" (libXdmf 3; they keep the six values in
Tensor6 order xx xy xz yy yz zz), and RUN_DIR/rift.xdmf (every grid) with "XDMF Reader", whose blocks must
carry the grids' names. Every cell's stress must equal the given tensor to 1e-9 of its largest component
(a state known exactly, e.g. the in-situ stress at t = 0). Prints one line per reader; exits 1 on any
mismatch, 2 on bad arguments. Run by tests/validation/test_output_readers.cpp when pvpython is installed
(Debian: apt-get install paraview python3-paraview xvfb).
"""
import argparse
import os
import sys

import numpy as np
from paraview import servermanager
from paraview import simple
from paraview.vtk.numpy_interface import dataset_adapter


def tensor6(values):
    values = np.asarray(values)
    if values.ndim == 3:  # expanded by the reader: rows xx xy xz / yx yy yz / zx zy zz
        return np.stack([values[:, 0, 0], values[:, 0, 1], values[:, 0, 2], values[:, 1, 1], values[:, 1, 2],
                         values[:, 2, 2]], axis=1)
    if values.ndim == 2 and values.shape[1] == 9:
        return values[:, [0, 1, 2, 4, 5, 8]]
    return values


def block_names(data):
    names = []
    if not data.IsA("vtkMultiBlockDataSet"):
        return names
    for i in range(data.GetNumberOfBlocks()):
        meta = data.GetMetaData(i)
        names.append(meta.Get(data.NAME()) if meta else "")
    return names


def stress_of(reader, time, block=None):
    reader.UpdatePipeline(time=time)
    data = servermanager.Fetch(reader)
    if block is not None:
        names = block_names(data)
        if block not in names:
            raise RuntimeError(f"no block named '{block}' (blocks: {names})")
        data = data.GetBlock(names.index(block))
    array = dataset_adapter.WrapDataObject(data).CellData["stress"]
    return tensor6(array), data.GetClassName()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run")
    parser.add_argument("tensor", nargs=6, type=float, help="expected xx xy xz yy yz zz")
    parser.add_argument("--grid", default="solid")
    parser.add_argument("--time", type=float, default=0.0)
    args = parser.parse_args()
    one = os.path.join(args.run, f"rift_{args.grid}.xdmf")
    every = os.path.join(args.run, "rift.xdmf")
    for path in (one, every):
        if not os.path.isfile(path):
            print(f"check_paraview_readers: no {path}", file=sys.stderr)
            return 2
    expected = np.asarray(args.tensor)
    scale = np.abs(expected).max()
    cases = [("XDMF Reader", lambda: simple.XDMFReader(FileNames=[one]), None),
             ("Xdmf3ReaderS", lambda: simple.Xdmf3ReaderS(FileName=[one]), None),
             ("Xdmf3ReaderT", lambda: simple.Xdmf3ReaderT(FileName=[one]), None),
             ("XDMF Reader, every grid", lambda: simple.XDMFReader(FileNames=[every]), args.grid)]
    failed = False
    for name, make, block in cases:
        try:
            stress, kind = stress_of(make(), args.time, block)
            worst = np.abs(stress - expected).max() / scale
            ok = stress.shape[1] == 6 and worst < 1e-9
            print(f"{name}: {kind}, {stress.shape[0]} cells, stress row 0 {stress[0]}, worst {worst:.1e}: "
                  f"{'ok' if ok else 'MISMATCH'}")
            failed |= not ok
        except Exception as error:  # a reader that cannot open the file is a failure, said plainly
            print(f"{name}: FAILED: {error}")
            failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
