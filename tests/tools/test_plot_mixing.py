"""tools/plot_mixing.py on mixing logs written as src/analysis/mixing_log.cpp writes
them: the four figures, time converted with --rpm, and clear failures on bad logs.
    python3 test_plot_mixing.py [WORK_DIR]    (CTest passes a directory that keeps the plots)"""
import importlib.util
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
from matplotlib.image import imread

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "plot_mixing.py")
WORK = sys.argv.pop(1) if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="plot_mixing_")
os.makedirs(WORK, exist_ok=True)
HEADER = "time,step,revolutions,lacey,rsd,one_minus_rsd,samples,particles_per_sample,concentration"
FIGURES = ["lacey", "lacey_log", "one_minus_rsd", "one_minus_rsd_log"]


def load_tool():
    spec = importlib.util.spec_from_file_location("plot_mixing", TOOL)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def write_log(name, revolution_period=2.0, rows=40, header=HEADER, samples=44, per_sample=39.0):
    """A log like MixingLog's: an exponential approach to a random mixture, '%.9g'
    numbers, 'nan' where a statistic is undefined, an empty revolutions column
    when the scene gave no revolution_period."""
    path = os.path.join(WORK, name)
    with open(path, "w") as f:
        f.write(header + "\n")
        for k in range(rows):
            time = 0.5 * k
            revolutions = f"{time / revolution_period:.9g}" if revolution_period else ""
            lacey = 1 - np.exp(-time / 4)
            rsd = 1 - 0.8 * lacey
            values = [f"{time:.9g}", str(int(time / 1e-5)), revolutions, "nan" if k == 0 else f"{lacey:.9g}",
                      f"{rsd:.9g}", f"{1 - rsd:.9g}", str(samples), f"{per_sample:.9g}", "0.5"]
            f.write(",".join(values[:len(header.split(","))]) + "\n")
    return path


def plot(*options):
    run = subprocess.run([sys.executable, TOOL, *options], capture_output=True, text=True)
    return run.returncode, run.stdout + run.stderr


class Figures(unittest.TestCase):
    def test_four_figures_for_two_runs(self):
        a, b = write_log("case_a.csv"), write_log("case_b.csv", samples=889, per_sample=3840)
        out_dir = os.path.join(WORK, "plots")
        code, out = plot("--run", f"case_a={a}", "--run", f"case_b={b}", "--out-dir", out_dir)
        self.assertEqual(code, 0, out)
        for figure in FIGURES:
            png = os.path.join(out_dir, f"mixing_{figure}.png")
            self.assertIn(png, out)
            image = imread(png)
            self.assertGreater(image.shape[0], 200)
            self.assertGreater(image[..., :3].std(), 0.05, f"{png} looks blank")

    def test_time_converted_with_rpm(self):
        log = write_log("no_revolutions.csv", revolution_period=None)
        code, out = plot("--run", f"x={log}", "--out-dir", os.path.join(WORK, "no_rpm"))
        self.assertNotEqual(code, 0)
        self.assertIn("--rpm", out)
        self.assertIn("revolution_period", out)
        code, out = plot("--run", f"x={log}", "--rpm", "x=30", "--prefix", "rpm", "--out-dir", WORK)
        self.assertEqual(code, 0, out)
        self.assertTrue(os.path.isfile(os.path.join(WORK, "rpm_one_minus_rsd_log.png")))

    def test_revolutions_from_the_log_or_from_time(self):
        tool = load_tool()
        log = tool.read_log(write_log("revolutions.csv", revolution_period=2.0))
        np.testing.assert_allclose(tool.revolutions_of("a", "revolutions.csv", log, {}, 0.0), log["time"] / 2.0)
        log = tool.read_log(write_log("times.csv", revolution_period=None))
        np.testing.assert_allclose(tool.revolutions_of("a", "times.csv", log, {"a": 30.0}, 1.0),
                                   (log["time"] - 1.0) / 2.0)
        self.assertTrue(np.isnan(log["lacey"][0]), "'nan' in a log reads as nan")

    def test_random_mixture_level(self):
        tool = load_tool()
        log = tool.read_log(write_log("level.csv", per_sample=39.0))
        self.assertAlmostEqual(tool.random_mixture_rsd(log), 0.16, places=2)  # docs/MIXING.md's example


class BadInput(unittest.TestCase):
    def assert_fails(self, *expected, options):
        code, out = plot(*options, "--out-dir", os.path.join(WORK, "bad"))
        self.assertNotEqual(code, 0, out)
        for text in expected:
            self.assertIn(text, out)
        self.assertNotIn("Traceback", out)

    def test_missing_columns(self):
        log = write_log("no_lacey.csv", header="time,step,revolutions,rsd,samples")
        self.assert_fails("missing column lacey, one_minus_rsd", "no_lacey.csv", options=("--run", f"a={log}"))
        log = write_log("no_axis.csv", header="step,lacey,one_minus_rsd")
        self.assert_fails("missing column revolutions (or time)", options=("--run", f"a={log}"))

    def test_not_numbers_and_short_rows(self):
        log = os.path.join(WORK, "words.csv")
        with open(log, "w") as f:
            f.write(HEADER + "\n0,0,0,high,1,0,4,10,0.5\n")
        self.assert_fails("words.csv:2", "column lacey holds 'high'", options=("--run", f"a={log}"))
        with open(log, "w") as f:
            f.write(HEADER + "\n0,0,0\n")
        self.assert_fails("words.csv:2: 3 fields", options=("--run", f"a={log}"))

    def test_empty_and_missing_files(self):
        empty = os.path.join(WORK, "empty.csv")
        open(empty, "w").close()
        self.assert_fails("empty file", options=("--run", f"a={empty}"))
        header_only = write_log("header_only.csv", rows=0)
        self.assert_fails("no evaluations", options=("--run", f"a={header_only}"))
        self.assert_fails("no such file", options=("--run", f"a={os.path.join(WORK, 'nowhere.csv')}"))

    def test_bad_options(self):
        log = write_log("good.csv")
        self.assert_fails("LABEL=PATH", options=("--run", log))
        self.assert_fails("given twice", options=("--run", f"a={log}", "--run", f"a={log}"))
        self.assert_fails("no run is labelled 'b'", options=("--run", f"a={log}", "--rpm", "b=30"))
        self.assert_fails("positive number", options=("--run", f"a={log}", "--rpm", "-5"))


if __name__ == "__main__":
    unittest.main(verbosity=2)
