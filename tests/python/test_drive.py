"""Acting between steps from Python: Simulator.drive_handles (a policy's action), set_state, and
the gradients backward_step returns for them, against a keyframed handle that moves the same way
and against central differences."""

import unittest

import numpy as np

import weft

STEPS = 8
DT = 0.01
# Knot k of the keyframed handles: the offset the step ending at t_k pulls them to.
KNOTS = [[0.02 * k, 0.01 * np.sin(k), -0.015 * k] for k in range(STEPS + 1)]
KNOTS_B = [[-0.01 * k, 0.02 * k, 0.005 * k * k] for k in range(STEPS + 1)]


def scene(steps=STEPS, keyframes=True):
    """A 6x6 cloth hanging from two handles (two corners each), without contact; each handle is
    keyframed at every step's end time when `keyframes`, else it stands still."""

    def trajectory(knots):
        if not keyframes:
            return {"keyframes": [{"time": 0.0, "offset": [0, 0, 0]}]}
        return {"keyframes": [{"time": DT * k, "offset": knots[k]} for k in range(steps + 1)]}

    return {
        "name": "driven",
        "time": {"dt": DT, "steps": steps},
        "gravity": [0, -9.8, 0],
        # Converged tightly and never split: a split step's pieces would follow a keyframed
        # handle's interpolation but hold a driven handle's target (Simulator::driveHandle).
        "solver": {"method": "newton", "pd_tolerance": 1e-9, "pd_iterations": 20000,
                   "max_halvings": 0},
        "cloths": [{
            "mesh": {"grid": {"size": [0.3, 0.3], "resolution": [5, 5]},
                     "transform": {"rotate_deg": [90, 0, 0], "translate": [0, 1.0, 0]}},
            "material": {"density": 0.2, "stretch": 500.0, "bend": 0.001},
            "attachments": [
                {"vertices": [0, 1], "kind": "handle", "stiffness": 5000.0,
                 "trajectory": trajectory(KNOTS)},
                {"vertices": [4, 5], "kind": "handle", "stiffness": 5000.0,
                 "trajectory": trajectory(KNOTS_B)},
            ],
        }],
    }


def driven_run(actions, x0=None, v0=None):
    """A Simulator on the still-standing scene, driven to actions[n] ([2, 3]) before step n."""
    sim = weft.Simulator(scene(keyframes=False))
    if x0 is not None:
        sim.set_state(x0, v0)
    for a in actions:
        sim.drive_handles(a)
        sim.step()
    return sim


def keyframe_actions():
    return [np.array([KNOTS[n + 1], KNOTS_B[n + 1]]) for n in range(STEPS)]


def chain(sim, weights, params=()):
    """backward_step from the last step to the first for L = sum(weights * x_N): the per-step
    dL/d(handle offsets), the summed dL/dp, and dL/dx_0, dL/dv_0."""
    dx, dv = weights.copy(), np.zeros_like(weights)
    per_step, total = [None] * sim.step_index, {p: 0.0 for p in params}
    for n in range(sim.step_index - 1, -1, -1):
        dx, dv, dp, dh = sim.backward_step(n, dx, dv, params=params)
        per_step[n] = dh
        for p in params:
            total[p] += dp[p]
    return per_step, total, dx, dv


class ContactArraysTest(unittest.TestCase):
    def test_contacts_match_the_step_statistics(self):
        import os
        source = os.environ.get("WEFT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
        sim = weft.Simulator(os.path.join(source, "assets", "scenes", "sphere.json"))
        self.assertEqual(len(sim.contacts["node"]), 0)  # before the first step
        seen = 0
        while sim.step_index < 60:
            stats = sim.step()
            c = sim.contacts
            for branch, name in ((1, "takeoff"), (2, "stick"), (3, "slip")):
                self.assertEqual(int((c["branch"] == branch).sum()), stats[name])
            self.assertEqual(c["normal"].shape, (len(c["node"]), 3))
            if len(c["node"]):
                np.testing.assert_allclose(np.linalg.norm(c["normal"], axis=1), 1.0, atol=1e-12)
                self.assertTrue(((c["obstacle"] == 0) | (c["partner"] >= 0)).all())
            seen += len(c["node"])
        self.assertGreater(seen, 0)


class DriveHandlesTest(unittest.TestCase):
    def setUp(self):
        self.weights = np.random.default_rng(11).uniform(-1, 1, (36, 3))

    def test_handles_are_listed(self):
        sim = weft.Simulator(scene())
        handles = sim.handles
        self.assertEqual(len(handles), 2)
        self.assertEqual(list(handles[1]["vertices"]), [4, 5])
        self.assertEqual(handles[0]["anchors"].shape, (2, 3))
        np.testing.assert_array_equal(handles[0]["anchors"], sim.positions[[0, 1]])
        self.assertEqual(handles[0]["stiffness"], 5000.0)

    def test_driving_follows_the_same_path_as_keyframes(self):
        keyed = weft.simulate(scene())
        driven = weft.Simulator(scene(keyframes=False))
        for n, a in enumerate(keyframe_actions()):
            driven.drive_handles(a)
            driven.step()
            # The keyframe offset at t_{n+1} is knot n+1 up to the rounding of t / dt.
            np.testing.assert_allclose(driven.positions, keyed.positions[n + 1], rtol=0, atol=1e-12)
        # And the handles move: not a run that ignores the drive.
        self.assertGreater(np.abs(keyed.positions[-1] - keyed.positions[0]).max(), 0.05)

    def test_handle_gradient_equals_the_keyframe_parameters_gradient(self):
        sim = weft.Simulator(scene())
        while sim.step_index < STEPS:
            sim.step()
        params = [f"cloths.0.attachments.{j}.trajectory.keyframes.{k}.offset.{c}"
                  for j in range(2) for k in range(1, STEPS + 1) for c in range(3)]
        per_step, total, _, _ = chain(sim, self.weights, params)
        for j in range(2):
            for k in range(1, STEPS + 1):
                for c in range(3):
                    expected = total[f"cloths.0.attachments.{j}.trajectory.keyframes.{k}.offset.{c}"]
                    self.assertAlmostEqual(per_step[k - 1][j, c], expected,
                                           delta=1e-9 * max(1.0, abs(expected)))
        self.assertGreater(np.abs(per_step[-1]).max(), 1e-3)

    def test_action_gradients_match_central_differences(self):
        actions = keyframe_actions()
        sim = driven_run(actions)
        per_step, _, _, _ = chain(sim, self.weights)
        eps = 1e-6
        for n, j, c in [(0, 0, 1), (3, 1, 0), (STEPS - 1, 0, 2), (5, 1, 2)]:
            plus = [a.copy() for a in actions]
            minus = [a.copy() for a in actions]
            plus[n][j, c] += eps
            minus[n][j, c] -= eps
            fd = ((self.weights * driven_run(plus).positions).sum()
                  - (self.weights * driven_run(minus).positions).sum()) / (2 * eps)
            self.assertAlmostEqual(per_step[n][j, c], fd, delta=1e-6 * max(1.0, abs(fd)))

    def test_initial_state_gradient_through_set_state(self):
        actions = keyframe_actions()
        base = weft.Simulator(scene(keyframes=False))
        x0, v0 = base.positions, base.velocities + 0.1
        sim = driven_run(actions, x0, v0)
        _, _, dx0, dv0 = chain(sim, self.weights)
        eps = 1e-6
        for node, c in [(7, 0), (20, 1), (35, 2)]:
            for grad, which in ((dx0, 0), (dv0, 1)):
                plus, minus = [x0.copy(), v0.copy()], [x0.copy(), v0.copy()]
                plus[which][node, c] += eps
                minus[which][node, c] -= eps
                fd = ((self.weights * driven_run(actions, *plus).positions).sum()
                      - (self.weights * driven_run(actions, *minus).positions).sum()) / (2 * eps)
                self.assertAlmostEqual(grad[node, c], fd, delta=1e-6 * max(1.0, abs(fd)))

    def test_refusals(self):
        sim = weft.Simulator(scene())
        with self.assertRaises(weft.InputError) as caught:
            sim.drive_handles(np.zeros((3, 3)))
        self.assertIn("drive_handles: offsets: expects a [2, 3] array", str(caught.exception))
        with self.assertRaises(weft.InputError) as caught:
            sim.drive_handles(np.full((2, 3), np.nan))
        self.assertIn("offsets: is not finite", str(caught.exception))
        sim.drive_handles(np.zeros((2, 3)))
        sim.step()
        zeros = np.zeros((36, 3))
        with self.assertRaises(weft.InputError) as caught:
            sim.backward_step(0, zeros, zeros,
                              params=["cloths.0.attachments.1.trajectory.keyframes.1.offset.0"])
        self.assertIn("driven from Python", str(caught.exception))
        sim.step()
        sim.set_state(sim.positions, sim.velocities)
        sim.step()
        with self.assertRaises(weft.InputError) as caught:
            sim.backward_step(0, zeros, zeros)
        self.assertIn("the state was set from Python at step 2", str(caught.exception))
        sim.backward_step(2, zeros, zeros)  # the steps after it are fine
        with self.assertRaises(weft.InputError) as caught:
            sim.set_state(zeros[:5], zeros)
        self.assertIn("set_state: positions: expects a [36, 3] array", str(caught.exception))
        no_handles = dict(scene(), cloths=[dict(scene()["cloths"][0], attachments=[])])
        with self.assertRaises(weft.InputError) as caught:
            weft.Simulator(no_handles).drive_handles(np.zeros((0, 3)))
        self.assertIn("the scene has no handles", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
