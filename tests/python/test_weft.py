"""The Python module weft against the `weft` command line it must agree with (docs/python.md).

Run by ctest (tests/python/CMakeLists.txt) with PYTHONPATH naming build/python and the
environment variables WEFT_BINARY (the built `weft`) and WEFT_SOURCE_DIR (the repository):
a run from Python equals `weft simulate`'s positions.npy bit for bit, gradients equal
`weft gradcheck --json`'s adjoint values, and bad input raises the CLI's messages.
"""

import json
import os
import subprocess
import tempfile
import unittest
import warnings

import numpy as np

import weft

SOURCE = os.path.abspath(
    os.environ.get("WEFT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")))
BINARY = os.path.abspath(os.environ.get("WEFT_BINARY", os.path.join(SOURCE, "build", "app", "weft")))
SCENES = os.path.join(SOURCE, "assets", "scenes")
WIND = os.path.join(SCENES, "wind.json")  # 25x25 napkin in wind, no contact
SPHERE = os.path.join(SCENES, "sphere.json")  # contact: Newton contact, adaptive time steps
WIND_SYSID = os.path.join(SCENES, "wind_sysid.json")  # 7x7 napkin, 30 steps, a trajectory task


def run_cli(*args, cwd=None):
    """Runs `weft ARGS`; returns (exit code, stdout, stderr)."""
    r = subprocess.run([BINARY, *args], capture_output=True, text=True, cwd=cwd)
    return r.returncode, r.stdout, r.stderr


def cli_positions(scene, *args):
    """positions.npy of `weft simulate SCENE ARGS`."""
    with tempfile.TemporaryDirectory() as out:
        code, _, err = run_cli("simulate", scene, "--quiet", "--out", os.path.join(out, "run"), *args)
        if code != 0:
            raise AssertionError(f"weft simulate failed ({code}): {err}")
        return np.load(os.path.join(out, "run", "positions.npy"))


def cli_error(*args):
    """The message `weft ARGS` prints for its error, without "error: "; asserts the exit code."""
    code, _, err = run_cli(*args)
    line = err.strip().splitlines()[-1]
    assert line.startswith("error: "), err
    return code, line[len("error: "):]


class SimulateTest(unittest.TestCase):
    def assertBitEqual(self, a, b):
        self.assertEqual(a.dtype, np.float64)
        self.assertEqual(a.shape, b.shape)
        self.assertTrue(np.array_equal(a.view(np.uint64), b.view(np.uint64)),
                        f"largest difference {np.max(np.abs(a - b))}")

    def test_positions_equal_the_cli_bit_for_bit(self):
        run = weft.simulate(WIND, steps=6)
        self.assertEqual(run.positions.shape, (7, 625, 3))
        self.assertBitEqual(run.positions, cli_positions(WIND, "--steps", "6"))

    def test_positions_equal_the_cli_with_contact(self):
        # The cloth starts just above the sphere, moving down: contacts from the first step.
        closer = {"cloths.0.mesh.transform.translate": [0.1, 0.31, 0],
                  "cloths.0.initial_velocity": [0, -1, 0]}
        run = weft.simulate(SPHERE, steps=4, set=closer)
        self.assertBitEqual(run.positions, cli_positions(
            SPHERE, "--steps", "4", "--set", "cloths.0.mesh.transform.translate=0.1,0.31,0",
            "--set", "cloths.0.initial_velocity=[0,-1,0]"))
        self.assertEqual(len(run.stats["converged"]), 4)
        self.assertTrue(run.stats["converged"].all())
        contacts = run.stats["takeoff"] + run.stats["stick"] + run.stats["slip"]
        self.assertTrue((contacts > 0).all(), "the cloth should touch the sphere at every step")
        self.assertEqual(run.summary["contacts"]["slip"], int(run.stats["slip"].sum()))

    def test_default_steps_are_the_scenes(self):
        run = weft.simulate(WIND_SYSID)
        self.assertEqual(run.positions.shape[0], 31)
        self.assertBitEqual(run.positions, cli_positions(WIND_SYSID))

    def test_set_equals_the_cli_set(self):
        overrides = {"wind.strength": 3.5, "gravity": [0, -5.0, 0.5], "time.dt": 0.005}
        cli = cli_positions(WIND, "--steps", "4", "--set", "wind.strength=3.5",
                            "--set", "gravity=0,-5.0,0.5", "--set", "time.dt=0.005")
        self.assertBitEqual(weft.simulate(WIND, steps=4, set=overrides).positions, cli)
        listed = ["wind.strength=3.5", "gravity=[0,-5.0,0.5]", "time.dt=0.005"]
        self.assertBitEqual(weft.simulate(WIND, steps=4, set=listed).positions, cli)
        self.assertFalse(np.array_equal(weft.simulate(WIND, steps=4).positions, cli),
                         "the overrides should change the run")

    def test_dict_scene_equals_file_scene(self):
        with open(WIND) as f:
            document = json.load(f)
        from_dict = weft.simulate(document, steps=3)
        self.assertBitEqual(from_dict.positions, weft.simulate(WIND, steps=3).positions)
        self.assertEqual(from_dict.summary["scene"], document["name"])

    def test_dict_scene_resolves_relative_paths_against_the_working_directory(self):
        with open(WIND_SYSID) as f:
            document = json.load(f)  # its task's target is "targets/wind_sysid.npy"
        cwd = os.getcwd()
        try:
            os.chdir(SCENES)
            from_dict = weft.gradient(document)
        finally:
            os.chdir(cwd)
        self.assertEqual(dict(from_dict), dict(weft.gradient(WIND_SYSID)))
        with tempfile.TemporaryDirectory() as elsewhere:
            os.chdir(elsewhere)
            try:
                with self.assertRaises(weft.InputError) as caught:
                    weft.gradient(document)
            finally:
                os.chdir(cwd)
        self.assertTrue(str(caught.exception).startswith("<dict>: task.loss"), caught.exception)

    def test_velocities_stats_and_summary(self):
        run = weft.simulate(WIND, steps=3)
        self.assertEqual(run.velocities.shape, run.positions.shape)
        dt = run.summary["dt"]
        # Implicit Euler: v_{n+1} = (x_{n+1} - x_n) / h.
        np.testing.assert_allclose(run.velocities[1:], np.diff(run.positions, axis=0) / dt,
                                   rtol=1e-9, atol=1e-12)
        self.assertEqual(list(run.stats["step"]), [1, 2, 3])
        self.assertEqual(run.summary["steps"], 3)
        self.assertEqual(run.summary["vertices"], 625)
        self.assertIn("wind", " ".join(run.summary["modules"]))
        self.assertEqual(run.summary["contacts"]["takeoff"], 0)

    def test_simulator_steps_as_simulate(self):
        closer = {"cloths.0.mesh.transform.translate": [0.1, 0.31, 0],
                  "cloths.0.initial_velocity": [0, -1, 0]}
        run = weft.simulate(SPHERE, steps=3, set=closer)
        sim = weft.Simulator(SPHERE, set=closer)
        self.assertEqual(sim.step_index, 0)
        self.assertBitEqual(sim.positions, run.positions[0])
        for k in range(1, 4):
            stats = sim.step()
            self.assertEqual(stats["step"], k)
            self.assertEqual(sim.step_index, k)
            self.assertBitEqual(sim.positions, run.positions[k])
            self.assertBitEqual(sim.velocities, run.velocities[k])

    def test_warnings_are_the_clis(self):
        with tempfile.TemporaryDirectory() as out:
            code, _, err = run_cli("simulate", WIND, "--steps", "2", "--quiet", "--out", out + "/r",
                                   "--set", "solver.pd_iterations=1")
        self.assertEqual(code, 0, err)
        cli = [line[len("warning: "):] for line in err.splitlines() if line.startswith("warning: ")]
        self.assertEqual(len(cli), 1, err)  # the steps left unconverged
        with self.assertWarns(weft.WeftWarning) as caught:
            run = weft.simulate(WIND, steps=2, set={"solver.pd_iterations": 1})
        self.assertEqual(run.warnings, cli)
        self.assertEqual(str(caught.warning), cli[0])

    def test_simulator_steps_from_several_threads_take_turns(self):
        import threading
        run = weft.simulate(WIND, steps=4)
        sim = weft.Simulator(WIND)
        threads = [threading.Thread(target=sim.step) for _ in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        self.assertEqual(sim.step_index, 4)
        self.assertBitEqual(sim.positions, run.positions[4])

    def test_version_is_the_clis(self):
        code, out, _ = run_cli("--version")
        self.assertEqual(code, 0)
        self.assertEqual(out.split()[1].rstrip(","), weft.__version__)

    def test_zero_steps(self):
        run = weft.simulate(WIND, steps=0)
        self.assertEqual(run.positions.shape, (1, 625, 3))
        self.assertEqual(len(run.stats["residual"]), 0)


class BackwardStepTest(unittest.TestCase):
    """Simulator.backward_step chained from the last step to the first against central
    differences of a linear function of the final positions."""

    TIGHT = {"solver.method": "newton", "solver.pd_tolerance": 1e-10,
             "solver.pd_iterations": 20000, "time.steps": 12}

    def final_value(self, weights, strength):
        run = weft.simulate(WIND_SYSID, set=dict(self.TIGHT, **{"wind.strength": strength}))
        return float((weights * run.positions[-1]).sum())

    def test_chained_steps_match_finite_differences(self):
        sim = weft.Simulator(WIND_SYSID, set=self.TIGHT)
        while sim.step_index < 12:
            sim.step()
        weights = np.random.default_rng(3).uniform(-1, 1, (sim.vertices, 3))
        dx, dv = weights.copy(), np.zeros((sim.vertices, 3))
        total = 0.0
        for n in range(11, -1, -1):
            dx, dv, dp, _ = sim.backward_step(n, dx, dv, params=["wind.strength"])
            total += dp["wind.strength"]
        h = 1e-4 * 1.5
        fd = (self.final_value(weights, 1.5 + h) - self.final_value(weights, 1.5 - h)) / (2 * h)
        self.assertAlmostEqual(total, fd, delta=1e-5 * abs(fd))
        self.assertEqual(dx.shape, (sim.vertices, 3))

    def test_bad_input_raises_input_error(self):
        sim = weft.Simulator(WIND_SYSID)
        sim.step()
        zeros = np.zeros((sim.vertices, 3))
        with self.assertRaises(weft.InputError) as caught:
            sim.backward_step(1, zeros, zeros)
        self.assertIn("step: must name a step taken, 0..0", str(caught.exception))
        with self.assertRaises(weft.InputError) as caught:
            sim.backward_step(0, np.zeros((3, 3)), zeros)
        self.assertIn("dL_dx: expects a", str(caught.exception))
        with self.assertRaises(weft.InputError):
            sim.backward_step(0, zeros, zeros, params=["time.dt"])


class ErrorTest(unittest.TestCase):
    def assertCliMessage(self, call, cli_args, code=2, error=weft.InputError):
        cli_code, message = cli_error(*cli_args)
        self.assertEqual(cli_code, code)
        with self.assertRaises(error) as caught:
            call()
        self.assertEqual(str(caught.exception), message)
        return caught.exception

    def test_missing_scene_file(self):
        missing = os.path.join(SCENES, "no_such_scene.json")
        e = self.assertCliMessage(lambda: weft.simulate(missing), ["simulate", missing])
        self.assertIsInstance(e, ValueError)
        self.assertEqual((e.file, e.path), (missing, "<file>"))

    def test_unknown_set_path(self):
        self.assertCliMessage(lambda: weft.simulate(WIND, steps=1, set={"time.dtt": 1}),
                              ["simulate", WIND, "--steps", "1", "--set", "time.dtt=1"])
        self.assertCliMessage(lambda: weft.simulate(WIND, steps=1, set={"cloths.5.material.bend": 1}),
                              ["simulate", WIND, "--steps", "1", "--set", "cloths.5.material.bend=1"])

    def test_set_without_value(self):
        self.assertCliMessage(lambda: weft.simulate(WIND, steps=1, set=["wind.strength"]),
                              ["simulate", WIND, "--steps", "1", "--set", "wind.strength"])

    def test_bad_scene_files(self):
        for name in ["negative_density.json", "unknown_key.json", "bad_json.json",
                     "missing_dt.json", "root_not_object.json"]:
            bad = os.path.join(SOURCE, "tests", "data", "bad", name)
            with self.subTest(name):
                self.assertCliMessage(lambda: weft.simulate(bad), ["simulate", bad])

    def test_malformed_dict(self):
        with open(WIND) as f:
            document = json.load(f)
        del document["time"]["dt"]
        document["cloths"][0]["material"]["stiffness"] = 1.0
        with tempfile.TemporaryDirectory() as folder:
            file = os.path.join(folder, "scene.json")
            with open(file, "w") as f:
                json.dump(document, f)
            _, message = cli_error("simulate", file)
        with self.assertRaises(weft.InputError) as caught:
            weft.simulate(document)
        self.assertEqual(str(caught.exception), message.replace(file, "<dict>", 1))
        with self.assertRaises(weft.InputError):
            weft.simulate({"time": {"dt": float("nan"), "steps": 1}})
        with self.assertRaises(TypeError):
            weft.simulate(42)

    def test_numerical_failure(self):
        blow_up = {"time": {"dt": 0.01, "steps": 5},
                   "cloths": [{"mesh": {"grid": {"size": [0.4, 0.4], "resolution": [2, 2]}},
                               "material": {"density": 0.1, "stretch": 100},
                               "initial_velocity": [1e6, 0, 0]}]}
        with tempfile.TemporaryDirectory() as folder:
            file = os.path.join(folder, "blowup.json")
            with open(file, "w") as f:
                json.dump(blow_up, f)
            code, message = cli_error("simulate", file, "--out", os.path.join(folder, "out"))
        self.assertEqual(code, 3)
        with self.assertRaises(weft.NumericalError) as caught:
            weft.simulate(blow_up)
        self.assertIsInstance(caught.exception, RuntimeError)
        self.assertEqual(str(caught.exception), message)
        self.assertGreaterEqual(caught.exception.step, 1)

    def test_bad_steps(self):
        with self.assertRaises(weft.InputError):
            weft.simulate(WIND, steps=-1)
        with self.assertRaises(TypeError):
            weft.simulate(WIND, steps=1.5)


class GradientTest(unittest.TestCase):
    def cli_adjoint(self, *args):
        code, out, err = run_cli("gradcheck", *args, "--json", "--quiet")
        self.assertEqual(code, 0, err)
        return {e["param"]: e["adjoint"] for e in json.loads(out)}

    def test_gradient_equals_gradcheck_adjoint(self):
        g = weft.gradient(WIND_SYSID)
        self.assertEqual(list(g), ["cloths.0.material.stretch", "wind.strength"])
        self.assertEqual(dict(g), self.cli_adjoint(WIND_SYSID))  # the same code path: bit-equal
        self.assertGreater(g.loss, 0.0)
        self.assertEqual(g.parameter_values, {"cloths.0.material.stretch": 400.0,
                                              "wind.strength": 1.5})
        self.assertEqual(g.backward["method"], "gmres")
        self.assertIsNotNone(g.error_estimate)
        self.assertLess(g.error_estimate, 1e-6)
        self.assertEqual(g.error["basis"], "difference")
        self.assertTrue(g.error["met"])
        self.assertEqual(g.error["passes"], 2)
        self.assertEqual(set(g.error_estimates), set(g))
        norm = sum(v * v for v in g.values()) ** 0.5
        for path in g:  # a component's error is at most the vector's
            self.assertLessEqual(g.error_estimates[path], g.error_estimate * norm * (1 + 1e-12))

    def test_params_and_set_equal_gradchecks(self):
        params = ["cloths.0.material.bend", "wind.phase"]
        g = weft.gradient(WIND_SYSID, params=params, set={"cloths.0.material.density": 0.2})
        cli = self.cli_adjoint(WIND_SYSID, "--param", params[0], "--param", params[1],
                               "--set", "cloths.0.material.density=0.2")
        self.assertEqual(dict(g), cli)

    def test_values_equal_set(self):
        at = weft.gradient(WIND_SYSID, values=[300.0, 1.75])
        via_set = weft.gradient(WIND_SYSID, set={"cloths.0.material.stretch": 300.0,
                                                 "wind.strength": 1.75})
        for p in at:
            self.assertAlmostEqual(at[p], via_set[p], delta=1e-12 * abs(via_set[p]))
        self.assertEqual(at.parameter_values["wind.strength"], 1.75)

    def test_gradient_errors(self):
        _, message = cli_error("gradcheck", WIND, "--json")
        with self.assertRaises(weft.InputError) as caught:
            weft.gradient(WIND)
        self.assertEqual(str(caught.exception), message)
        _, message = cli_error("gradcheck", WIND_SYSID, "--param", "cloths.0.material.colour")
        with self.assertRaises(weft.InputError) as caught:
            weft.gradient(WIND_SYSID, params=["cloths.0.material.colour"])
        self.assertEqual(str(caught.exception), message)
        with self.assertRaises(weft.InputError):
            weft.gradient(WIND_SYSID, values=[1.0])


if __name__ == "__main__":
    warnings.simplefilter("default")
    unittest.main()
