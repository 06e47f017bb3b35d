#!/usr/bin/env python3
"""The repository's Python scripts (scripts/), run as a user runs them.

- The scene generators reproduce the committed assets byte for byte (their docstrings promise
  it, and the task scenes must not drift from the code that documents their choices).
- evaluation-sets.py, compare-gradients.py and compare-runs.py compute what they print, and
  refuse bad input with `error: <file>: <what>` and exit status 2.
- contact-scenes.py tabulates what each scene's summary.json says, and refuses a missing scene.
- embed-applications.py puts a bench output into a document and replaces it there, keeping the
  rest.

Run by ctest (tests/CMakeLists.txt), one test per class:
  WEFT_SOURCE_DIR=. WEFT_BINARY=build/app/weft python3 tests/scripts/test_scripts.py Generators
Standard library only.
"""

import csv
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import unittest

SOURCE = os.path.abspath(os.environ.get("WEFT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")))
WEFT = os.environ.get("WEFT_BINARY", os.path.join(SOURCE, "build", "app", "weft"))
SCRIPTS = os.path.join(SOURCE, "scripts")
sys.path.insert(0, SCRIPTS)
from npyfile import open_npy, read_values  # noqa: E402


def read_npy(path):
    shape, f = open_npy(path)
    with f:
        return shape, read_values(f, math.prod(shape))


def run(args, **kwargs):
    return subprocess.run(args, capture_output=True, text=True, **kwargs)


def script(name, *args):
    return run([sys.executable, os.path.join(SCRIPTS, name), *args])


def written_files(root):
    for folder, _, files in os.walk(root):
        for f in files:
            path = os.path.join(folder, f)
            yield os.path.relpath(path, root)


class Generators(unittest.TestCase):
    """Each generator, run into an empty folder, writes exactly the committed bytes."""

    def check(self, name, args, out, committed, simulated=()):
        """Every file `name` writes into `out` equals the one in `committed`: byte for byte, except
        the files in `simulated`, motions recorded by weft, which may move by rounding when the
        solver changes (they are recorded to 1e-8 m/s^2): those within 1e-5 m."""
        result = script(name, *args)
        self.assertEqual(result.returncode, 0, result.stderr)
        files = sorted(written_files(out))
        self.assertTrue(files, f"{name} wrote nothing")
        for rel in files:
            with self.subTest(script=name, file=rel):
                mine, theirs = os.path.join(out, rel), os.path.join(committed, rel)
                if rel in simulated:
                    (sa, a), (sb, b) = read_npy(mine), read_npy(theirs)
                    self.assertEqual(sa, sb)
                    gap = max(abs(p - q) for p, q in zip(a, b))
                    self.assertLess(gap, 1e-5, f"{name}: {rel} moved by {gap:.3g} m")
                    continue
                with open(mine, "rb") as fa, open(theirs, "rb") as fb:
                    self.assertTrue(fa.read() == fb.read(), f"{name}: {rel} differs from the committed file")

    def test_asset_generators(self):
        assets = os.path.join(SOURCE, "assets")
        for name in ("make-garments.py", "make-tshirt.py", "make-dress.py"):
            with tempfile.TemporaryDirectory() as out:
                self.check(name, [out], out, assets)

    def test_napkins_and_meshes(self):
        with tempfile.TemporaryDirectory() as out:
            self.check("make-napkins.py", [out], out, os.path.join(SOURCE, "assets", "scenes"))
        with tempfile.TemporaryDirectory() as out:
            self.check("make-meshes.py", [out], out, os.path.join(SOURCE, "assets", "meshes"))

    def test_flag_scene_and_its_recorded_target(self):
        # make-flag.py records the target motion with weft itself, from the hidden values.
        with tempfile.TemporaryDirectory() as out:
            self.check("make-flag.py", ["--weft", WEFT, out], out, os.path.join(SOURCE, "assets", "scenes"),
                       simulated=("targets/flag.npy",))


class EvaluationSets(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.csv = os.path.join(self.dir.name, "loss.csv")
        with open(self.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["evaluation", "steps", "wall_s", "loss", "cloths.0.material.stretch", "wind.direction.2"])
            w.writerow(["1", "50", "0.5", "0.25", "300", "1"])
            w.writerow(["2", "100", "1.1", "0.125", "287.52000000000001", "-0.031250000000000003"])

    def tearDown(self):
        self.dir.cleanup()

    def test_prints_the_rows_parameters_as_stored(self):
        r = script("evaluation-sets.py", self.csv, "2")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.strip(),
                         "--set cloths.0.material.stretch=287.52000000000001 "
                         "--set wind.direction.2=-0.031250000000000003")

    def test_bad_input_is_exit_2_naming_the_file(self):
        r = script("evaluation-sets.py", self.csv, "7")
        self.assertEqual(r.returncode, 2)
        self.assertEqual(r.stderr.strip(), f"error: {self.csv}: evaluation 7: no such row")
        with open(self.csv, "a") as f:
            f.write("3,150,1.5\n")
        r = script("evaluation-sets.py", self.csv, "3")
        self.assertEqual(r.returncode, 2)
        self.assertEqual(r.stderr.strip(), f"error: {self.csv}: line 4: 3 values, header has 6")
        missing = os.path.join(self.dir.name, "none.csv")
        r = script("evaluation-sets.py", missing, "1")
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith(f"error: {missing}: "), r.stderr)


class CompareGradients(unittest.TestCase):
    def write(self, name, x, loss, g):
        path = os.path.join(self.dir.name, name)
        with open(path, "w") as f:
            json.dump({"initial_parameters": x, "initial_loss": loss, "gradient": g}, f)
        return path

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.dir.cleanup()

    def test_prediction_and_gradient_change(self):
        # x moves by (3, 4): distance 5; g_A . dx = 1*3 + 2*4 = 11; g_B - g_A = (0, -1).
        a = self.write("a.json", {"p": 0.0, "q": 0.0}, 1.0, {"p": 1.0, "q": 2.0})
        b = self.write("b.json", {"p": 3.0, "q": 4.0}, 12.5, {"p": 1.0, "q": 1.0})
        r = script("compare-gradients.py", a, b)
        self.assertEqual(r.returncode, 0, r.stderr)
        values = {line[:30].strip(): line[30:].split() for line in r.stdout.splitlines()}
        self.assertAlmostEqual(float(values["distance |x_B - x_A|"][0]), 5.0)
        self.assertAlmostEqual(float(values["loss change"][0]), 11.5)
        self.assertAlmostEqual(float(values["predicted g_A . (x_B - x_A)"][0]), 11.0)
        self.assertAlmostEqual(float(values["|g_B - g_A| / |g_A|"][0]), 1.0 / math.sqrt(5.0), places=4)
        self.assertAlmostEqual(float(values["cosine(g_A, g_B)"][0]), 3.0 / math.sqrt(10.0), places=5)
        self.assertAlmostEqual(float(values["|g_B - g_A| / |x_B - x_A|"][0]), 0.2, places=4)

    def test_other_parameters_are_exit_2(self):
        a = self.write("a.json", {"p": 0.0}, 1.0, {"p": 1.0})
        b = self.write("b.json", {"r": 0.0}, 1.0, {"r": 1.0})
        r = script("compare-gradients.py", a, b)
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith(f"error: {b}: gradient: "), r.stderr)
        c = os.path.join(self.dir.name, "c.json")
        with open(c, "w") as f:
            json.dump({"initial_loss": 1.0}, f)
        r = script("compare-gradients.py", a, c)
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith(f"error: {c}: initial_parameters: missing"), r.stderr)


class ContactScenes(unittest.TestCase):
    """contact-scenes.py on the first steps of the Hat (a handle moving a hat over a head)."""

    def test_table_of_a_short_run(self):
        scene = os.path.join(SOURCE, "assets", "scenes", "hat.json")
        r = script("contact-scenes.py", "--weft", WEFT, "--steps", "5", scene, scene)
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = r.stdout.splitlines()
        self.assertEqual(len(lines), 4)  # header, rule, one row per scene
        cells = [c.strip() for c in lines[2].strip("|").split("|")]
        self.assertEqual(cells[0], "hat")
        self.assertEqual(cells[1], "5")
        self.assertEqual(cells[2], "5/5")
        self.assertGreater(float(cells[6]), 0.0)  # CPU seconds of the run
        self.assertEqual(lines[2].split("|")[:6], lines[3].split("|")[:6])  # deterministic

    def test_missing_scene_is_exit_2(self):
        missing = os.path.join(SOURCE, "no-such-scene.json")
        r = script("contact-scenes.py", "--weft", WEFT, missing)
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith(f"error: {missing}: no such scene file"), r.stderr)


class CompareRuns(unittest.TestCase):
    """Two `weft simulate` runs of the hanging cloth, one 10 % heavier: they part from step 1."""

    def test_distances_between_two_runs(self):
        scene = os.path.join(SOURCE, "tests", "data", "scenes", "hanging.json")
        with tempfile.TemporaryDirectory() as d:
            a, b = os.path.join(d, "a"), os.path.join(d, "b")
            for out, density in ((a, "0.1"), (b, "0.11")):
                r = run([WEFT, "simulate", scene, "--threads", "1", "--set",
                         f"cloths.0.material.density={density}", "--out", out])
                self.assertEqual(r.returncode, 0, r.stderr)
            same = script("compare-runs.py", a, a, "--every", "1")
            self.assertEqual(same.returncode, 0, same.stderr)
            rows = [l.split() for l in same.stdout.splitlines()[1:-1]]
            self.assertEqual([int(r[0]) for r in rows], list(range(1, 21)))
            self.assertTrue(all(float(r[1]) == 0.0 for r in rows))
            self.assertEqual(same.stdout.splitlines()[-1], "unconverged steps: 0 (A), 0 (B)")
            other = script("compare-runs.py", a, b, "--every", "5")
            self.assertEqual(other.returncode, 0, other.stderr)
            rows = [l.split() for l in other.stdout.splitlines()[1:-1]]
            self.assertEqual([int(r[0]) for r in rows], [5, 10, 15, 20])
            # Gravity pulls both cloths alike (mass cancels), but the stiffness does not scale with
            # the mass, so the heavier one swings further: tens of micrometres apart.
            distances = [float(r[1]) for r in rows]
            self.assertTrue(all(1e-6 < x < 1e-3 for x in distances), distances)
            r = script("compare-runs.py", a, d)
            self.assertEqual(r.returncode, 2)
            self.assertTrue(r.stderr.startswith(f"error: {d}: no positions.npy"), r.stderr)


def write_npy(path, shape, values):
    """A little-endian float64 C-order .npy (format 1.0), as weft writes positions.npy."""
    header = "{'descr': '<f8', 'fortran_order': False, 'shape': %s, }" % (tuple(shape),)
    header += " " * (63 - (10 + len(header)) % 64) + "\n"
    with open(path, "wb") as f:
        f.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode("latin1"))
        f.write(struct.pack(f"<{len(values)}d", *values))


class TraceStallHinges(unittest.TestCase):
    """trace-stall-hinges.py on a made-up run: a hinge curved at rest (nodes 0-3), one flat at rest
    (4-7), and a trace whose unconverged steps put their residual on one, the other, or neither.

    The curvature vector e = sum_k w_k x_k is linear in the positions and its weights sum to zero,
    so a frame that is the rest shape rotated, scaled by k and moved has |e| / |e_rest| = k
    exactly, whatever the weights: the test knows the answer without recomputing the script's
    geometry. k differs per frame, so the ratio also shows which frame was read."""

    REST = [(0, 0, 0), (1, 0, 0), (0.4, 0.8, 0.3), (0.6, -0.7, 0.5),  # curved hinge, edge 0-1
            (3, 0, 0), (4, 0, 0), (3.5, 1, 0), (3.4, -1, 0)]  # flat hinge, edge 4-5
    FACES = [(0, 1, 2), (1, 0, 3), (4, 5, 6), (5, 4, 7)]

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        d = self.dir.name
        with open(os.path.join(d, "rest.obj"), "w") as f:
            f.writelines(f"v {x} {y} {z}\n" for x, y, z in self.REST)
            f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in self.FACES)
        # Frame n: the rest shape turned about z by n radians, scaled by (n + 1) / 4 (frame 1:
        # 0.5), moved by (n, 2n, 3n).
        values = []
        for n in range(5):
            c, s_, k = math.cos(n), math.sin(n), (n + 1) / 4
            for x, y, z in self.REST:
                values += [k * (c * x - s_ * y) + n, k * (s_ * x + c * y) + 2 * n, k * z + 3 * n]
        write_npy(os.path.join(d, "positions.npy"), (5, len(self.REST), 3), values)
        with open(os.path.join(d, "stats.csv"), "w") as f:
            f.write("step,residual,converged\n1,12.5,0\n2,3.0,0\n3,0.001,1\n4,7.0,0\n")
        trace = []
        for step, nodes in ((1, (2, 0, 1, 3, 6)), (2, (5, 7, 4, 6)), (3, (0, 1, 2, 3)), (4, (0, 4, 2, 6))):
            trace.append(f"step {step}: newton contact solve, residual 1.0e+00\n")
            trace += [f"  residual at node {n}: share 0.200, x (0, 0, 0), contact none\n" for n in nodes]
        self.trace = os.path.join(d, "trace.log")
        with open(self.trace, "w") as f:
            f.writelines(trace)

    def tearDown(self):
        self.dir.cleanup()

    def test_each_unconverged_step_names_its_hinge_and_ratio(self):
        r = script("trace-stall-hinges.py", self.trace, self.dir.name)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = r.stdout.splitlines()
        self.assertEqual(rows[0], "step,residual,top4_share,hinge,ratio")
        # Step 3 converged: left out. Step 1: its four largest nodes are the curved hinge's.
        self.assertEqual(rows[1:], ["1,12.5,0.800,0-1-2-3,0.500", "2,3.0,0.800,4-5-6-7,flat",
                                    "4,7.0,0.800,,"])
        self.assertIn("3 traced unconverged steps; on one hinge curved at rest: 1 "
                      "(|e|/|e_rest|: median 0.500, below 0.3: 0, below 0.5: 0, above 1: 0); "
                      "on one hinge flat at rest: 1", r.stderr)

    def test_bad_input_is_exit_2(self):
        r = script("trace-stall-hinges.py", self.trace)
        self.assertEqual(r.returncode, 2)
        os.remove(os.path.join(self.dir.name, "positions.npy"))
        r = script("trace-stall-hinges.py", self.trace, self.dir.name)
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith("error: " + os.path.join(self.dir.name, "positions.npy")),
                        r.stderr)


class EmbedApplications(unittest.TestCase):
    """embed-applications.py: a made-up bench output put into a made-up document, then again
    with new tables; the section's own text, the other sections and the plots' copies checked."""

    BENCH = ("# Gradient-based vs gradient-free optimisation (weft bench applications)\n\n"
             "Tasks: hat. Setup {}.\n\n## Loss reached (DiffCloth Table 2)\n\n| task |\n| --- |\n"
             "| hat |\n\n## Every seed (DiffCloth Tables 5-6)\n\n| seed |\n")
    DOC = "# Doc\n\n## Hat\n\nHow the runs were made.\n\n## Other\n\nKept as is.\n"

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        d = self.dir.name
        self.out = os.path.join(d, "bench")
        os.makedirs(self.out)
        self.write(os.path.join(self.out, "applications.md"), self.BENCH.format(1))
        for name, data in (("loss_hat.png", b"hat plot"), ("speedup.png", b"speedup plot")):
            with open(os.path.join(self.out, name), "wb") as f:
                f.write(data)
        self.doc = os.path.join(d, "docs", "applications.md")
        os.makedirs(os.path.dirname(self.doc))
        self.write(self.doc, self.DOC)

    def tearDown(self):
        self.dir.cleanup()

    @staticmethod
    def write(path, text):
        with open(path, "w") as f:
            f.write(text)

    @staticmethod
    def read(path):
        with open(path) as f:
            return f.read()

    def test_the_tables_nest_under_the_heading_and_replace_their_earlier_copy(self):
        r = script("embed-applications.py", self.out, self.doc, "Hat")
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = self.read(self.doc)
        head, rest = doc.split("<!-- generated: scripts/embed-applications.py " + self.out + " -->\n")
        self.assertEqual(head, "# Doc\n\n## Hat\n\nHow the runs were made.\n\n")
        block, tail = rest.split("<!-- end generated -->\n")
        self.assertEqual(tail, "\n## Other\n\nKept as is.\n")
        self.assertEqual(block, "\nTasks: hat. Setup 1.\n\n### Loss reached (DiffCloth Table 2)\n\n"
                         "| task |\n| --- |\n| hat |\n\n### Every seed (DiffCloth Tables 5-6)\n\n"
                         "| seed |\n\n![hat](images/applications-loss-hat.png)\n\n"
                         "![speedup](images/applications-speedup.png)\n\n")
        images = os.path.join(os.path.dirname(self.doc), "images")
        self.assertEqual(self.read(os.path.join(images, "applications-loss-hat.png")), "hat plot")
        self.assertEqual(self.read(os.path.join(images, "applications-speedup.png")), "speedup plot")

        # Narrative after the block stays; new tables replace the old ones, once.
        self.write(self.doc, doc.replace("<!-- end generated -->\n", "<!-- end generated -->\n\nWhy.\n"))
        self.write(os.path.join(self.out, "applications.md"), self.BENCH.format(2))
        r = script("embed-applications.py", self.out, self.doc, "Hat", "--images-prefix", "x-")
        self.assertEqual(r.returncode, 0, r.stderr)
        again = self.read(self.doc)
        self.assertEqual(again.count("<!-- generated:"), 1)
        self.assertIn("Setup 2.", again)
        self.assertNotIn("Setup 1.", again)
        self.assertIn("How the runs were made.", again)
        self.assertIn("<!-- end generated -->\n\nWhy.\n\n## Other", again)
        self.assertIn("![hat](images/x-loss-hat.png)", again)

        # A heading the document lacks becomes a new last section.
        r = script("embed-applications.py", self.out, self.doc, "Sock")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("Kept as is.\n\n## Sock\n\n<!-- generated:", self.read(self.doc))

    def test_bad_input_is_exit_2_and_leaves_the_document(self):
        missing = os.path.join(self.dir.name, "none")
        r = script("embed-applications.py", missing, self.doc, "Hat")
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith("error: " + missing + ": "), r.stderr)
        os.remove(os.path.join(self.out, "applications.md"))
        r = script("embed-applications.py", self.out, self.doc, "Hat")
        self.assertEqual(r.returncode, 2)
        self.assertIn("applications.md: not found", r.stderr)
        self.write(os.path.join(self.out, "applications.md"), self.BENCH.format(1))
        broken = self.DOC.replace("How", "<!-- end generated -->\n<!-- generated: x -->\nHow")
        self.write(self.doc, broken)
        r = script("embed-applications.py", self.out, self.doc, "Hat")
        self.assertEqual(r.returncode, 2)
        self.assertIn("markers", r.stderr)
        self.assertEqual(self.read(self.doc), broken)
        self.assertFalse(os.path.exists(os.path.join(os.path.dirname(self.doc), "images")))


if __name__ == "__main__":
    unittest.main()
