"""examples/python/ run as a reader would run them, and do what their docstrings say."""

import os
import re
import subprocess
import sys
import unittest

SOURCE = os.path.abspath(
    os.environ.get("WEFT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")))
EXAMPLES = os.path.join(SOURCE, "examples", "python")

try:
    import torch  # noqa: F401
except ImportError:
    torch = None


def run(name, *args):
    r = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), *args], capture_output=True,
                       text=True, timeout=600)
    if r.returncode != 0:
        raise AssertionError(f"{name} failed ({r.returncode}): {r.stderr}")
    return r.stdout


@unittest.skipIf(torch is None, "PyTorch is not installed (python3-torch)")
class ExamplesTest(unittest.TestCase):
    def test_system_identification_recovers_the_recording_values(self):
        last = run("system_identification.py").strip().splitlines()[-1]
        stretch, wind = re.search(r"stretch\s+([\d.]+) N/m\s+wind ([\d.]+)", last).groups()
        self.assertAlmostEqual(float(stretch), 250.0, delta=0.5)
        self.assertAlmostEqual(float(wind), 2.0, delta=1e-3)

    def test_gradient_through_contact_agrees_with_central_differences(self):
        lines = [l for l in run("gradient_through_contact.py").splitlines() if "adjoint" in l]
        self.assertEqual(len(lines), 2)
        for line in lines:
            adjoint, fd = (float(v) for v in re.findall(r"([+-][\d.]+)", line))
            self.assertAlmostEqual(adjoint, fd, delta=1e-4 * max(1.0, abs(fd)))

    def test_hat_controller_trains(self):
        out = run("hat_controller.py", "2", "2")
        self.assertEqual(len(re.findall(r"epoch \d+: mean loss [\d.]+", out)), 2)


if __name__ == "__main__":
    unittest.main()
