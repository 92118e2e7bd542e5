"""ParaView reads a run's XDMF series: every time step, every particle.
Run by CTest through pvpython (Debian package python3-paraview):
    pvpython paraview_reads_xdmf.py RUN_DIR EXPECTED_PARTICLES EXPECTED_STEPS"""
import sys

from paraview import servermanager
from paraview.simple import OpenDataFile

run_dir, expected_particles, expected_steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
reader = OpenDataFile(run_dir + "/particles.xdmf")
if reader is None:
    sys.exit("ParaView found no reader for particles.xdmf")
times = list(reader.TimestepValues)
print(f"reader {reader.GetXMLName()}: {len(times)} time steps, t = {times[0]} .. {times[-1]}")
if len(times) != expected_steps:
    sys.exit(f"expected {expected_steps} time steps, ParaView sees {len(times)}")
for t in (times[0], times[-1]):
    reader.UpdatePipeline(t)
    info = reader.GetDataInformation()
    points = info.GetNumberOfPoints()
    arrays = [reader.PointData.GetArray(k).GetName() for k in range(len(reader.PointData))]
    print(f"t = {t}: {points} particles, arrays {arrays}")
    if points != expected_particles:
        sys.exit(f"expected {expected_particles} particles at t = {t}, ParaView sees {points}")
    for name in ("velocity", "radius"):
        if name not in arrays:
            sys.exit(f"array {name} missing at t = {t}")
print("ParaView reads the series")
