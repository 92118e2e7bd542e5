"""ParaView reads a run's mesh series (meshes.xdmf): every time step, every
vertex and triangle of the meshes. Run by CTest through pvpython:
    pvpython paraview_reads_meshes.py RUN_DIR EXPECTED_VERTICES EXPECTED_TRIANGLES EXPECTED_STEPS"""
import sys

from paraview.simple import OpenDataFile

run_dir = sys.argv[1]
vertices, triangles, steps = (int(a) for a in sys.argv[2:5])
reader = OpenDataFile(run_dir + "/meshes.xdmf")
if reader is None:
    sys.exit("ParaView found no reader for meshes.xdmf")
times = list(reader.TimestepValues)
if len(times) != steps:
    sys.exit(f"expected {steps} time steps, ParaView sees {len(times)}")
for t in times:
    reader.UpdatePipeline(t)
    info = reader.GetDataInformation()
    if (info.GetNumberOfPoints(), info.GetNumberOfCells()) != (vertices, triangles):
        sys.exit(f"t = {t}: ParaView sees {info.GetNumberOfPoints()} vertices and {info.GetNumberOfCells()} "
                 f"triangles, expected {vertices} and {triangles}")
print(f"ParaView reads the mesh series: {len(times)} steps of {vertices} vertices, {triangles} triangles")
