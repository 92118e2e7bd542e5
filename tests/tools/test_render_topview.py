"""tools/render_topview.py on synthetic snapshots written in the layout of grainstorm's
HDF5 writer (snapshot_files.py): colours by side, occlusion, views, extent, run
directories, and clear failures on bad input.
    python3 test_render_topview.py [WORK_DIR]    (CTest passes a directory that keeps the images)"""
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
from matplotlib.colors import to_rgb
from matplotlib.image import imread

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from snapshot_files import close_packed_bed, lattice_bed, write_snapshot  # noqa: E402

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "render_topview.py")
WORK = sys.argv.pop(1) if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="render_topview_")
os.makedirs(WORK, exist_ok=True)
BLUE, ORANGE, WHITE = (np.round(np.array(to_rgb(c)) * 255).astype(int) for c in ("#1f5fbf", "#f0640f", "white"))


def path(name):
    return os.path.join(WORK, name)


def render(snapshot, image, *options):
    """Runs the tool; (exit code, stdout + stderr, RGB image or None)."""
    run = subprocess.run([sys.executable, TOOL, snapshot, "-o", image, *options], capture_output=True, text=True)
    rgb = None
    if run.returncode == 0:
        rgb = np.round(imread(image)[..., :3] * 255).astype(int)
    return run.returncode, run.stdout + run.stderr, rgb


def is_colour(rgb, colour):
    return np.all(rgb == colour, axis=-1)


def segregated_bed(name, spacing, radius):
    """A settled-looking bed 100 x 60 mm, marker 0 for x < 0 and 1 for x > 0 (as the
    seed marks its bed by the side of the central plane), a few layers deep."""
    centres = lattice_bed((-0.05 + spacing / 2, -0.03 + spacing / 2, 0.0), (0.05, 0.03, 4 * spacing), spacing)
    centres += np.random.default_rng(7).uniform(-0.1, 0.1, centres.shape) * spacing
    write_snapshot(path(name), centres, radius, (centres[:, 0] > 0).astype(np.uint8))


class Segregated(unittest.TestCase):
    def check_halves(self, rgb, margin):
        """Left of the middle only blue, right only orange, each half mostly covered."""
        middle = rgb.shape[1] // 2
        left, right = rgb[:, :middle - margin], rgb[:, middle + margin:]
        self.assertFalse(is_colour(left, ORANGE).any(), "orange pixels in the left (marker 0) half")
        self.assertFalse(is_colour(right, BLUE).any(), "blue pixels in the right (marker 1) half")
        self.assertGreater(is_colour(left, BLUE).mean(), 0.6)
        self.assertGreater(is_colour(right, ORANGE).mean(), 0.6)

    def test_disks_spanning_pixels(self):
        segregated_bed("segregated_disks.h5", 0.002, 0.001)
        code, out, rgb = render(path("segregated_disks.h5"), path("segregated_disks.png"), "--size", "400")
        self.assertEqual(code, 0, out)
        self.assertEqual(rgb.shape[1], 400, out)
        self.assertAlmostEqual(rgb.shape[0], 400 * 62 / 102, delta=4, msg=out)  # 102 x 62 mm with the rims
        self.check_halves(rgb, margin=6)  # particles near x = 0 stray by 0.1 spacing = 1 pixel
        self.assertTrue(is_colour(rgb, WHITE).any(), "touching disks leave gaps between them")

    def test_particles_smaller_than_pixels(self):
        segregated_bed("segregated_points.h5", 0.0005, 0.0002)
        code, out, rgb = render(path("segregated_points.h5"), path("segregated_points.png"), "--size", "60")
        self.assertEqual(code, 0, out)
        self.check_halves(rgb, margin=1)
        self.assertFalse(is_colour(rgb, WHITE).any(), "a dense bed of points covers every pixel")

    def test_culling_and_chunks_change_nothing(self):
        """Hidden particles are skipped, and neither that nor the chunk size changes a pixel."""
        rng = np.random.default_rng(3)
        centres = close_packed_bed(0.001, 12, 0.04)
        centres += rng.uniform(-0.05, 0.05, centres.shape) * 0.001
        radius = rng.uniform(0.35, 0.5, len(centres)) * 0.001
        write_snapshot(path("packed.h5"), centres, radius, rng.integers(0, 3, len(centres)))
        images = [render(path("packed.h5"), path(f"packed_{k}.png"), "--size", "300", *options)
                  for k, options in enumerate([(), ("--no-culling",), ("--chunk", "777")])]
        for code, out, _ in images:
            self.assertEqual(code, 0, out)
        drawn = [int(out.split(" drawn")[0].rsplit("(", 1)[1]) for _, out, _ in images]
        self.assertEqual(drawn[1], len(centres))
        self.assertLess(drawn[0], len(centres) / 2, "most particles of a bed 12 layers deep are hidden")
        np.testing.assert_array_equal(images[0][2], images[1][2])
        np.testing.assert_array_equal(images[0][2], images[2][2])


class Occlusion(unittest.TestCase):
    def test_higher_particle_hides_lower(self):
        # The higher particle comes first in the file, so file order cannot decide.
        write_snapshot(path("stack.h5"), [[0, 0, 0.003], [0, 0, 0.0]], [0.001, 0.001], [1, 0])
        for options in [(), ("--chunk", "1")]:
            code, out, rgb = render(path("stack.h5"), path("stack.png"), "--size", "41", *options)
            self.assertEqual(code, 0, out)
            self.assertTrue(is_colour(rgb[20, 20], ORANGE), "the lower particle shows through the higher one")
        code, out, rgb = render(path("stack.h5"), path("stack_below.png"), "--size", "41", "--reverse")
        self.assertTrue(is_colour(rgb[20, 20], BLUE), "seen from below, the lower particle is in front")

    def test_small_particle_on_a_large_one(self):
        """The large lower sphere shows around the small one resting on it."""
        write_snapshot(path("bead.h5"), [[0, 0, 0], [0, 0, 0.0025]], [0.002, 0.0005], [0, 1])
        code, out, rgb = render(path("bead.h5"), path("bead.png"), "--size", "80")
        self.assertEqual(code, 0, out)
        self.assertTrue(is_colour(rgb[40, 40], ORANGE))
        self.assertTrue(is_colour(rgb[40, 10], BLUE))
        self.assertTrue(is_colour(rgb[0, 0], WHITE), "the corner lies outside the large disk")

    def test_sphere_surface_decides_where_disks_overlap(self):
        """Two equal spheres side by side, the right one a little lower: near its own
        centre the right one's surface is higher, though its centre is lower."""
        write_snapshot(path("pair.h5"), [[-0.0008, 0, 0.0002], [0.0008, 0, 0.0]], 0.001, [0, 1])
        code, out, rgb = render(path("pair.h5"), path("pair.png"), "--size", "360")
        self.assertEqual(code, 0, out)
        row = rgb[rgb.shape[0] // 2]
        self.assertTrue(is_colour(row[260], ORANGE), "x = +0.8 mm shows the right sphere's top")
        self.assertTrue(is_colour(row[100], BLUE))


class Views(unittest.TestCase):
    def setUp(self):
        # marker 1 at +x, marker 0 at -x, both at y = 0
        write_snapshot(path("pair_x.h5"), [[0.004, 0, 0], [-0.004, 0, 0]], 0.001, [1, 0])

    def left_and_right(self, *options):
        code, out, rgb = render(path("pair_x.h5"), path("pair_x.png"), "--size", "100", *options)
        self.assertEqual(code, 0, out)
        middle = rgb[rgb.shape[0] // 2]
        return middle[10], middle[-10]

    def test_from_above_x_runs_right(self):
        left, right = self.left_and_right()
        self.assertTrue(is_colour(left, BLUE) and is_colour(right, ORANGE))

    def test_side_views_are_not_mirrored(self):
        left, right = self.left_and_right("--axis", "y")  # from +y, +x is on the viewer's left
        self.assertTrue(is_colour(left, ORANGE) and is_colour(right, BLUE))
        left, right = self.left_and_right("--axis", "y", "--reverse")
        self.assertTrue(is_colour(left, BLUE) and is_colour(right, ORANGE))

    def test_extent_crops(self):
        code, out, rgb = render(path("pair_x.h5"), path("pair_x_crop.png"), "--size", "50", "--extent",
                                "0.002", "0.006", "-0.002", "0.002")
        self.assertEqual(code, 0, out)
        self.assertEqual(rgb.shape[:2], (50, 50))
        self.assertFalse(is_colour(rgb, BLUE).any())
        self.assertTrue(is_colour(rgb[25, 25], ORANGE))

    def test_colour_option(self):
        code, out, rgb = render(path("pair_x.h5"), path("pair_x_green.png"), "--size", "100", "--color", "1=#00ff00")
        self.assertEqual(code, 0, out)
        self.assertTrue(is_colour(rgb[rgb.shape[0] // 2, -10], (0, 255, 0)))


class RunDirectory(unittest.TestCase):
    def setUp(self):
        self.run_dir = path("run")
        os.makedirs(self.run_dir, exist_ok=True)
        for step, marker in ((100, 0), (200, 1)):
            write_snapshot(os.path.join(self.run_dir, f"particles_{step:010d}.h5"), [[0, 0, 0]], 0.001, marker,
                           step=step, time=step * 1e-5)

    def test_newest_by_default_and_step(self):
        code, out, rgb = render(self.run_dir, path("run.png"), "--size", "11")
        self.assertEqual(code, 0, out)
        self.assertTrue(is_colour(rgb[5, 5], ORANGE), out)
        code, out, rgb = render(self.run_dir, path("run.png"), "--size", "11", "--step", "100")
        self.assertTrue(is_colour(rgb[5, 5], BLUE), out)

    def test_missing_step(self):
        code, out, _ = render(self.run_dir, path("run.png"), "--step", "300")
        self.assertNotEqual(code, 0)
        self.assertIn("no snapshot of step 300", out)


class BadInput(unittest.TestCase):
    def assert_fails(self, snapshot, *expected, options=()):
        code, out, _ = render(snapshot, path("bad.png"), *options)
        self.assertNotEqual(code, 0, out)
        for text in expected:
            self.assertIn(text, out)
        self.assertNotIn("Traceback", out)

    def test_empty_bed(self):
        write_snapshot(path("empty.h5"), np.zeros((0, 3)), np.zeros(0), np.zeros(0))
        self.assert_fails(path("empty.h5"), "no particles")

    def test_missing_marker(self):
        write_snapshot(path("no_marker.h5"), [[0, 0, 0]], 0.001, fields=("id", "radius", "position"))
        self.assert_fails(path("no_marker.h5"), "missing dataset particles/marker", "output.fields")

    def test_missing_radius(self):
        write_snapshot(path("no_radius.h5"), [[0, 0, 0]], marker=0, fields=("id", "marker", "position"))
        self.assert_fails(path("no_radius.h5"), "particles/radius")

    def test_missing_file(self):
        self.assert_fails(path("nowhere.h5"), "no such file")

    def test_not_hdf5(self):
        with open(path("text.h5"), "w") as f:
            f.write("not HDF5\n")
        self.assert_fails(path("text.h5"), "cannot be read as HDF5")

    def test_bad_options(self):
        write_snapshot(path("one.h5"), [[0, 0, 0]], 0.001, 0)
        self.assert_fails(path("one.h5"), "--extent", options=("--extent", "1", "0", "0", "1"))
        self.assert_fails(path("one.h5"), "MARKER=COLOUR", options=("--color", "red"))
        self.assert_fails(path("one.h5"), "not a matplotlib colour", options=("--color", "1=nocolour"))


if __name__ == "__main__":
    unittest.main(verbosity=2)
