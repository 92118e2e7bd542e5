"""ParaView reads a run's XDMF series: every time step, every particle, and
one triangle surface per analytic wall. Run by CTest through pvpython
(Debian package python3-paraview; reading needs no display):
    pvpython paraview_reads_xdmf.py RUN_DIR EXPECTED_PARTICLES EXPECTED_STEPS EXPECTED_WALLS"""
import sys

from paraview import servermanager
from paraview.simple import OpenDataFile

run_dir = sys.argv[1]
expected_particles, expected_steps, expected_walls = (int(a) for a in sys.argv[2:5])
reader = OpenDataFile(run_dir + "/particles.xdmf")
if reader is None:
    sys.exit("ParaView found no reader for particles.xdmf")
times = list(reader.TimestepValues)
print(f"reader {reader.GetXMLName()}: {len(times)} time steps, t = {times[0]} .. {times[-1]}")
if len(times) != expected_steps:
    sys.exit(f"expected {expected_steps} time steps, ParaView sees {len(times)}")


def leaves(data):
    """The datasets of a (possibly nested) composite data set."""
    if data is None:
        return []
    if data.IsA("vtkMultiBlockDataSet"):
        return [leaf for k in range(data.GetNumberOfBlocks()) for leaf in leaves(data.GetBlock(k))]
    if data.IsA("vtkMultiPieceDataSet"):
        return [leaf for k in range(data.GetNumberOfPieces()) for leaf in leaves(data.GetPiece(k))]
    return [data]


VTK_TRIANGLE = 5
for t in (times[0], times[-1]):
    reader.UpdatePipeline(t)
    blocks = leaves(servermanager.Fetch(reader))
    particles = [b for b in blocks if b.GetPointData().GetArray("velocity") is not None]
    walls = [b for b in blocks if b.GetNumberOfCells() > 0 and
             all(b.GetCellType(c) == VTK_TRIANGLE for c in range(b.GetNumberOfCells()))]
    if len(particles) != 1:
        sys.exit(f"expected one block with the particles at t = {t}, ParaView sees {len(particles)}")
    points = particles[0].GetNumberOfPoints()
    arrays = [particles[0].GetPointData().GetArrayName(k) for k in range(particles[0].GetPointData().GetNumberOfArrays())]
    print(f"t = {t}: {points} particles, arrays {arrays}; {len(walls)} wall surfaces of "
          f"{[w.GetNumberOfCells() for w in walls]} triangles")
    if points != expected_particles:
        sys.exit(f"expected {expected_particles} particles at t = {t}, ParaView sees {points}")
    for name in ("velocity", "radius"):
        if name not in arrays:
            sys.exit(f"array {name} missing at t = {t}")
    if len(walls) != expected_walls:
        sys.exit(f"expected {expected_walls} wall surfaces at t = {t}, ParaView sees {len(walls)}")
print("ParaView reads the series")
