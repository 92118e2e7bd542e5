"""tools/mesh_reach.py on a synthetic checkpoint and STL: its closest points against
a brute-force search over each triangle, the count of triangles in reach of spheres
under a fan's centre, and the mesh turned to the checkpoint's time.
    python3 test_mesh_reach.py [WORK_DIR]"""
import importlib.util
import math
import os
import subprocess
import sys
import tempfile
import unittest

import h5py
import numpy as np

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "mesh_reach.py")
WORK = sys.argv.pop(1) if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="mesh_reach_")
os.makedirs(WORK, exist_ok=True)

spec = importlib.util.spec_from_file_location("mesh_reach", TOOL)
mesh_reach = importlib.util.module_from_spec(spec)
spec.loader.exec_module(mesh_reach)


def write_stl(name, triangles):
    path = os.path.join(WORK, name)
    with open(path, "w") as f:
        f.write("solid test\n")
        for t in triangles:
            f.write(" facet normal 0 0 1\n  outer loop\n")
            for v in t:
                f.write(f"   vertex {v[0]:.17g} {v[1]:.17g} {v[2]:.17g}\n")
            f.write("  endloop\n endfacet\n")
        f.write("endsolid test\n")
    return path


def write_checkpoint(name, positions, radius, time):
    path = os.path.join(WORK, name)
    with h5py.File(path, "w") as h:
        h.attrs["time"] = time
        h["particles/position"] = np.array(positions, dtype=float)
        h["particles/radius"] = np.full(len(positions), radius, dtype=np.float32)
    return path


def fan(n, rim=1.0):
    return [[(0, 0, 0), (rim * math.cos(2 * math.pi * j / n), rim * math.sin(2 * math.pi * j / n), 0),
             (rim * math.cos(2 * math.pi * (j + 1) / n), rim * math.sin(2 * math.pi * (j + 1) / n), 0)]
            for j in range(n)]


def run(*args):
    out = subprocess.run([sys.executable, TOOL, *args], capture_output=True, text=True)
    return out.returncode, out.stdout + out.stderr


class ClosestPoints(unittest.TestCase):
    def test_against_a_dense_sampling_of_each_triangle(self):
        rng = np.random.default_rng(3)
        tri = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.2, 0.8, 0.0]])  # one acute corner, one obtuse
        u, v = np.meshgrid(np.linspace(0, 1, 401), np.linspace(0, 1, 401))
        keep = u + v <= 1
        samples = tri[0] + np.outer(u[keep], tri[1] - tri[0]) + np.outer(v[keep], tri[2] - tri[0])
        for _ in range(300):  # points in all seven regions, off the plane
            p = rng.uniform([-1, -1, -0.5], [2, 2, 0.5])
            q = mesh_reach.closest_points(p[None], tri[0][None], tri[1][None], tri[2][None])[0]
            best = np.min(np.linalg.norm(samples - p, axis=1))
            self.assertLessEqual(np.linalg.norm(q - p), best + 1e-12)
            self.assertGreater(np.linalg.norm(q - p), best - 5e-3)  # the sampling's spacing


class InReach(unittest.TestCase):
    def test_a_sphere_under_a_fans_centre_reaches_every_triangle(self):
        stl = write_stl("fan.stl", fan(40))
        # under the centre; 0.45 out along a sector (a few sectors); far off the fan.
        ck = write_checkpoint("fan.h5", [(0, 0, -0.1), (0.45, 0.01, -0.1), (5, 5, 5)], 0.15, 0.0)
        code, out = run(ck, stl, "--rpm", "0")
        self.assertEqual(code, 0, out)
        self.assertIn("2 spheres near it, 1 with more than 16 in reach", out)
        self.assertIn("sphere 0: 40 in reach of 40 near", out)
        few = [line for line in out.splitlines() if line.strip().startswith("sphere 1:")]
        self.assertEqual(len(few), 1, out)
        self.assertLess(int(few[0].split()[2]), 10, out)

    def test_the_mesh_is_turned_to_the_checkpoints_time(self):
        # One triangle along +x; at 15 rpm from t = 1 s it has turned a quarter
        # turn at t = 2 s and lies along +y, under the first sphere.
        stl = write_stl("arm.stl", [[(1, -0.1, 0), (2, -0.1, 0), (1.5, 0.1, 0)]])
        ck = write_checkpoint("arm.h5", [(0, 1.5, -0.05), (1.5, 0, -0.05)], 0.1, 2.0)
        code, out = run(ck, stl, "--rpm", "15", "--start", "1")
        self.assertEqual(code, 0, out)
        self.assertIn("mesh turned 90.0 deg", out)
        self.assertIn("sphere 0: 1 in reach", out)
        self.assertNotIn("sphere 1: 1 in reach", out)


if __name__ == "__main__":
    unittest.main()
