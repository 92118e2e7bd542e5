"""ParaView reads a measurement's grid series (average_<name>.xdmf,
docs/OUTPUT.md) as a structured grid: every evaluation, nx * ny * nz cells,
cell arrays of 1, 3 and 9 components; its cells add up to the whole-box row
of the measurement's CSV log (particles, and the mean solid fraction of equal
bins), and each cell (ix, iy, iz), found by its centre, holds the value of
entry [iz][iy][ix] of the HDF5 file's datasets. Run by CTest through pvpython:
    pvpython paraview_reads_grid.py RUN_DIR NAME NX NY NZ EXPECTED_STEPS"""
import csv
import glob
import sys

import h5py

from paraview import servermanager
from paraview.simple import OpenDataFile

run_dir, name = sys.argv[1], sys.argv[2]
nx, ny, nz, expected_steps = (int(a) for a in sys.argv[3:7])
reader = OpenDataFile(f"{run_dir}/average_{name}.xdmf")
if reader is None:
    sys.exit(f"ParaView found no reader for average_{name}.xdmf")
times = list(reader.TimestepValues)
if len(times) != expected_steps:
    sys.exit(f"expected {expected_steps} time steps, ParaView sees {len(times)}")
rows = list(csv.DictReader(open(f"{run_dir}/average_{name}.csv")))
if len(rows) != expected_steps:
    sys.exit(f"expected {expected_steps} rows in average_{name}.csv, found {len(rows)}")


def leaf(data):
    while data is not None and data.IsA("vtkMultiBlockDataSet"):
        data = data.GetBlock(0)
    return data


for t, row in zip(times, rows):
    reader.UpdatePipeline(t)
    grid = leaf(servermanager.Fetch(reader))
    if grid is None or not (grid.IsA("vtkImageData") or grid.IsA("vtkStructuredGrid") or grid.IsA("vtkRectilinearGrid")):
        sys.exit(f"t = {t}: not a structured grid: {grid.GetClassName() if grid else None}")
    if grid.GetNumberOfCells() != nx * ny * nz:
        sys.exit(f"t = {t}: {grid.GetNumberOfCells()} cells, expected {nx * ny * nz}")
    cells = grid.GetCellData()
    components = {cells.GetArrayName(k): cells.GetArray(k).GetNumberOfComponents() for k in range(cells.GetNumberOfArrays())}
    for array, n in (("particles", 1), ("solid_fraction", 1), ("velocity", 3), ("stress_kinetic", 9), ("stress_contact", 9)):
        if components.get(array) != n:
            sys.exit(f"t = {t}: array {array}: {components.get(array)} components, expected {n}; arrays {components}")
    count = sum(cells.GetArray("particles").GetValue(c) for c in range(nx * ny * nz))
    if count != int(row["particles"]):
        sys.exit(f"t = {t}: the cells hold {count} particles, the log {row['particles']}")
    phi = sum(cells.GetArray("solid_fraction").GetValue(c) for c in range(nx * ny * nz)) / (nx * ny * nz)
    if abs(phi - float(row["solid_fraction"])) > 1e-12:
        sys.exit(f"t = {t}: mean solid fraction {phi} of the cells, {row['solid_fraction']} in the log")
    h5 = h5py.File(sorted(glob.glob(f"{run_dir}/average_{name}_*.h5"))[times.index(t)], "r")
    if abs(h5.attrs["time"] - t) > 1e-12:
        sys.exit(f"t = {t}: the HDF5 file's time is {h5.attrs['time']}")
    origin, spacing = h5["origin"][()], h5["spacing"][()]
    for iz in range(nz):
        for iy in range(ny):
            for ix in range(nx):
                centre = [origin[a] + (i + 0.5) * spacing[a] for a, i in enumerate((ix, iy, iz))]
                ijk, local = [0, 0, 0], [0.0] * 3
                if not grid.ComputeStructuredCoordinates(centre, ijk, local):
                    sys.exit(f"t = {t}: bin centre {centre} outside the grid ParaView sees")
                cell = grid.ComputeCellId(ijk)
                for array in ("particles", "solid_fraction"):
                    if cells.GetArray(array).GetValue(cell) != h5[array][iz, iy, ix]:
                        sys.exit(f"t = {t}: cell {ix, iy, iz}: {array} {cells.GetArray(array).GetValue(cell)} in "
                                 f"ParaView, {h5[array][iz, iy, ix]} in the file")
                for c in range(9):
                    if cells.GetArray("stress_contact").GetComponent(cell, c) != h5["stress_contact"][iz, iy, ix, c]:
                        sys.exit(f"t = {t}: cell {ix, iy, iz}: stress_contact[{c}] differs")
    print(f"t = {t}: {grid.GetClassName()}, {grid.GetNumberOfCells()} cells, {count} particles, arrays {components}")
print("ParaView reads the grid series")
