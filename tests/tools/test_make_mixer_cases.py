"""tools/make_mixer_cases.py: the shipped scenes come out unchanged, and --froude-scaled
writes the paper's scaled model (every length times s = (30/rpm)^2, the samples' mass
times s^3, the settling times sqrt(s), the Table 2 speed: the real mixer's Froude
number), which grainstorm accepts; where the fill's impacts press spheres
deeper than 30 % of a diameter (case b's scaled model), with 24 contact slots
and 0.05 contact times per step.
    python3 test_make_mixer_cases.py GRAINSTORM"""
import math
import os
import re
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
TOOL = os.path.join(ROOT, "tools", "make_mixer_cases.py")
GRAINSTORM = os.path.abspath(sys.argv.pop(1)) if len(sys.argv) > 1 else None


def write(out_dir, *options):
    subprocess.run([sys.executable, TOOL, "--out-dir", out_dir, *options], check=True, capture_output=True)


def read(path):
    with open(path) as f:
        return f.read()


def number(text, pattern):
    m = re.search(pattern, text)
    if not m:
        raise AssertionError(f"no match for {pattern}")
    return float(m.group(1))


class Scenes(unittest.TestCase):
    def test_the_shipped_scenes_come_out_unchanged(self):
        with tempfile.TemporaryDirectory() as out:
            write(out)
            for case in "abcd":
                self.assertEqual(read(os.path.join(ROOT, "cases", "mixer", f"case_{case}.yaml")),
                                 read(os.path.join(out, f"case_{case}.yaml")), case)

    def test_the_scaled_model_keeps_the_froude_number(self):
        with tempfile.TemporaryDirectory() as out:
            write(out, "--cases", "ab")
            write(out, "--cases", "ab", "--froude-scaled", "--suffix", "_scaled")
            for case, rpm in (("a", 5.6695), ("b", 3.75)):
                real = read(os.path.join(out, f"case_{case}.yaml"))
                scaled = read(os.path.join(out, f"case_{case}_scaled.yaml"))
                s = (30 / rpm) ** 2
                rel = 1e-5  # the scene's numbers carry six digits
                for name, pattern, tol in (("sphere radius", r"radius: ([0-9.e-]+)\n", rel),
                                           ("vessel radius", r"axis: \[0, 0, 1\], radius: ([0-9.e-]+), length", rel),
                                           ("floor", r"cylinder: \{base: \[0, 0, ([0-9.e-]+)\]", rel),
                                           ("fill radius", r"region: \{cylinder: .*radius: ([0-9.e-]+), length", rel),
                                           ("samples' outer ring", r"outer_radius: ([0-9.e-]+)", rel),
                                           ("samples' height", r"height: ([0-9.e-]+)", 5e-3)):  # to 0.1 mm
                    self.assertAlmostEqual(number(scaled, pattern) / number(real, pattern), s, delta=tol * s,
                                           msg=f"case {case}: {name}")
                self.assertAlmostEqual(number(scaled, r"scale: ([0-9.e-]+)"), s, delta=rel * s)
                self.assertNotIn("scale:", real)
                self.assertAlmostEqual(number(scaled, r"sample_mass: ([0-9.e-]+)") /
                                       number(real, r"sample_mass: ([0-9.e-]+)"), s**3, delta=rel * s**3)
                self.assertAlmostEqual(number(scaled, r"marking: \{time: ([0-9.e-]+)"), math.sqrt(s), delta=1e-4)
                self.assertAlmostEqual(number(scaled, r"revolution_period: ([0-9.e-]+)"), 60 / rpm, delta=1e-4)
                # omega^2 R / g over the vessel's radius: the real mixer's at 30 rpm.
                froude = (2 * math.pi * number(scaled, r"rpm: ([0-9.e-]+)") / 60) ** 2 * \
                    number(scaled, r"axis: \[0, 0, 1\], radius: ([0-9.e-]+), length") / 9.81
                self.assertAlmostEqual(froude, (math.pi) ** 2 * 0.05 / 9.81, delta=1e-6)

    def test_deep_impacts_get_more_slots_and_a_shorter_step(self):
        # A sphere falling from the top of the domain onto its floor meets a
        # resting sphere at v = sqrt(2 g h) and presses in by v sqrt(m / 2 k):
        # computed here from the scene's own numbers. Only case b's scaled
        # model passes 30 % of a diameter; it alone gets 24 slots and 0.05.
        with tempfile.TemporaryDirectory() as out:
            write(out, "--cases", "ab")
            write(out, "--cases", "ab", "--froude-scaled", "--suffix", "_scaled")
            for name, deep in (("a", False), ("b", False), ("a_scaled", False), ("b_scaled", True)):
                scene = read(os.path.join(out, f"case_{name}.yaml"))
                r = number(scene, r"radius: ([0-9.e-]+)\n")
                top = number(scene, r"max: \[[^]]*, ([0-9.e-]+)\]\}")
                floor = number(scene, r"cylinder: \{base: \[0, 0, ([0-9.e-]+)\]")
                k = number(scene, r"stiffness_normal: ([0-9.e-]+)")
                m = 2500 * 4 / 3 * math.pi * r**3
                impact = math.sqrt(2 * 9.81 * (top - floor)) * math.sqrt(m / 2 / k) / (2 * r)
                self.assertEqual(impact > 0.3, deep, f"case {name}: {impact:.3f} of a diameter")
                self.assertEqual("contact_slots: 24" in scene, deep, name)
                fraction = number(scene, r"fraction_of_contact_time: ([0-9.]+)")
                self.assertEqual(fraction, 0.05 if deep else 0.11, name)
                if deep:  # the comment's figure, to the percent
                    self.assertAlmostEqual(number(scene, r"about ([0-9]+) % of a diameter deep"), 100 * impact, delta=1.5)

    def test_the_vessel_is_closed_above_the_fill(self):
        # A sphere squeezed between a blade tip and the wall can be thrown
        # out of an open vessel (docs/MIXER.md, "Spheres thrown out of the
        # vessel"): a lid at the vessel's top, inside the domain and above
        # the fill the spheres start from.
        with tempfile.TemporaryDirectory() as out:
            write(out, "--cases", "abcd")
            write(out, "--cases", "ab", "--froude-scaled", "--suffix", "_scaled")
            for name in ("a", "b", "c", "d", "a_scaled", "b_scaled"):
                scene = read(os.path.join(out, f"case_{name}.yaml"))
                vessel = re.search(r"cylinder: \{base: \[0, 0, ([0-9.e-]+)\], axis: \[0, 0, 1\], radius: [0-9.e-]+, "
                                   r"length: ([0-9.e-]+), caps: (\w+)\}", scene)
                self.assertIsNotNone(vessel, name)
                self.assertEqual(vessel.group(3), "both", name)
                lid = float(vessel.group(1)) + float(vessel.group(2))
                fill = re.search(r"region: \{cylinder: \{base: \[0, 0, ([0-9.e-]+)\], .*length: ([0-9.e-]+)\}", scene)
                r = number(scene, r"radius: ([0-9.e-]+)\n")
                self.assertGreater(lid, float(fill.group(1)) + float(fill.group(2)) + r, name)
                self.assertLessEqual(lid, number(scene, r"max: \[[^]]*, ([0-9.e-]+)\]\}"), name)

    @unittest.skipUnless(GRAINSTORM, "no grainstorm binary given")
    def test_grainstorm_accepts_the_scaled_model(self):
        with tempfile.TemporaryDirectory() as out:
            write(out, "--cases", "ab", "--froude-scaled")
            stl = os.path.join(ROOT, "cases", "mixer", "impeller.stl")
            os.symlink(os.path.abspath(stl), os.path.join(out, "impeller.stl"))
            for case, count, fraction in (("a", 7680, "0.11"), ("b", 76800, "0.05")):
                check = subprocess.run([GRAINSTORM, "check", f"case_{case}.yaml"], cwd=out, capture_output=True,
                                       text=True)
                self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
                self.assertIn(f"particles:      {count}", check.stdout)
                self.assertIn(f"({fraction} of the contact time)", check.stdout)


if __name__ == "__main__":
    unittest.main()
