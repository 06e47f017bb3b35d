"""weft.torch: the task loss as a torch.autograd.Function of scene parameters, its backward the
adjoint pass. Checked with torch.autograd.gradcheck (central finite differences of the forward)
in double precision on small scenes, and against weft.gradient."""

import os
import unittest

import weft

try:
    import torch
    import weft.torch as weft_torch
except ImportError as e:  # python3-torch missing: the module works without it
    torch = None
    missing = str(e)

SOURCE = os.path.abspath(
    os.environ.get("WEFT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")))
WIND_SYSID = os.path.join(SOURCE, "assets", "scenes", "wind_sysid.json")

# A short rollout with contact: a 5x5 cloth thrown onto a frictional sphere, sliding on it (take-off
# and slip contacts at every step); the loss puts two vertices at points at the last step.
CONTACT = {
    "name": "contact_rollout",
    "time": {"dt": 0.01, "steps": 12},
    "gravity": [0, -9.8, 0],
    "solver": {"backward": {"method": "direct"}},
    "cloths": [{"mesh": {"grid": {"size": [0.4, 0.4], "resolution": [4, 4]},
                         "transform": {"translate": [0.05, 0.31, 0]}},
                "material": {"density": 0.2, "stretch": 300.0, "bend": 0.001},
                "initial_velocity": [0.3, -0.5, 0]}],
    "obstacles": [{"sphere": {"center": [0, 0, 0], "radius": 0.3}, "friction": 0.4}],
    "task": {"loss": {"keypoints": {"points": [
        {"step": 12, "vertices": [12, 0], "positions": [[0.1, 0.3, 0.0], [-0.1, 0.25, -0.2]]}]}},
             "parameters": ["obstacles.0.friction", "cloths.0.material.stretch"]},
}


@unittest.skipIf(torch is None, "PyTorch is not installed (python3-torch)")
class TaskLossTest(unittest.TestCase):
    PARAMS = ["wind.strength", "wind.phase"]

    def test_backward_is_weft_gradient(self):
        theta = torch.tensor([1.75, 0.4], dtype=torch.float64, requires_grad=True)
        loss = weft_torch.task_loss(theta, WIND_SYSID, self.PARAMS)
        loss.backward()
        g = weft.gradient(WIND_SYSID, params=self.PARAMS, values=[1.75, 0.4])
        self.assertEqual(loss.item(), g.loss)
        self.assertEqual(theta.grad.tolist(), list(g.values()))

    def test_gradcheck(self):
        theta = torch.tensor([1.75, 0.4], dtype=torch.float64, requires_grad=True)
        self.assertTrue(torch.autograd.gradcheck(
            lambda t: weft_torch.task_loss(t, WIND_SYSID, self.PARAMS), (theta,),
            eps=1e-5, atol=1e-8, rtol=1e-4))

    def test_gradcheck_through_contact(self):
        run = weft.simulate(CONTACT)
        self.assertTrue((run.stats["slip"][2:] > 0).all(), "the cloth should slide on the sphere")
        params = CONTACT["task"]["parameters"]
        theta = torch.tensor([0.4, 300.0], dtype=torch.float64, requires_grad=True)
        self.assertTrue(torch.autograd.gradcheck(
            lambda t: weft_torch.task_loss(t, CONTACT, params), (theta,),
            eps=1e-6, atol=1e-8, rtol=1e-4))

    def test_chain_rule_through_torch(self):
        # The loss of a parameter computed in torch: the gradient reaches the leaf.
        s = torch.tensor(0.5, dtype=torch.float64, requires_grad=True)
        theta = torch.stack([3.5 * s, torch.tensor(0.3, dtype=torch.float64)])
        weft_torch.task_loss(theta, WIND_SYSID, self.PARAMS).backward()
        g = weft.gradient(WIND_SYSID, params=self.PARAMS, values=[1.75, 0.3])
        self.assertAlmostEqual(s.grad.item(), 3.5 * g["wind.strength"],
                               delta=1e-12 * abs(g["wind.strength"]))

    def test_bad_values(self):
        with self.assertRaises(TypeError):
            weft_torch.task_loss(torch.tensor([1.0, 0.3]), WIND_SYSID, self.PARAMS)  # float32
        with self.assertRaises(ValueError):
            weft_torch.task_loss(torch.tensor([1.0], dtype=torch.float64), WIND_SYSID, self.PARAMS)


if __name__ == "__main__":
    unittest.main()


@unittest.skipIf(torch is None, "PyTorch is not installed (python3-torch)")
class RolloutTest(unittest.TestCase):
    """weft.torch.Rollout: a loss on the states after 12 steps, backpropagated by autograd through
    Simulator.backward_step, against central differences of the same loss."""

    TIGHT = {"solver.method": "newton", "solver.pd_tolerance": 1e-10,
             "solver.pd_iterations": 20000, "time.steps": 12}

    def loss_after(self, rollout, weights):
        x, v = rollout.initial_state()
        x0, v0 = x, v
        for _ in range(12):
            x, v = rollout.step(x, v)
        return (weights * x).sum() + 0.1 * (weights * v).sum(), x0, v0

    def test_parameter_and_initial_state_gradients_match_finite_differences(self):
        weights = torch.tensor(
            __import__("numpy").random.default_rng(5).uniform(-1, 1, (49, 3)))
        rollout = weft_torch.Rollout(WIND_SYSID, params=["wind.strength"], set=self.TIGHT)
        loss, x0, v0 = self.loss_after(rollout, weights)
        loss.backward()

        def value(strength):
            r = weft_torch.Rollout(WIND_SYSID, set=dict(self.TIGHT, **{"wind.strength": strength}))
            with torch.no_grad():
                return float(self.loss_after(r, weights)[0])

        h = 1.5e-4
        fd = (value(1.5 + h) - value(1.5 - h)) / (2 * h)
        self.assertAlmostEqual(float(rollout.theta.grad[0]), fd, delta=1e-5 * abs(fd))
        self.assertEqual(tuple(x0.grad.shape), (49, 3))
        self.assertTrue(torch.all(torch.isfinite(v0.grad)))

    def test_steps_must_be_chained(self):
        rollout = weft_torch.Rollout(WIND_SYSID)
        x, v = rollout.initial_state()
        rollout.step(x, v)
        with self.assertRaises(ValueError):
            rollout.step(x, v)  # the state before, not the simulator's current one


@unittest.skipIf(torch is None, "PyTorch is not installed (python3-torch)")
class ActionRolloutTest(unittest.TestCase):
    """Rollout.step with actions (the handles driven from Python): gradcheck of a loss on the
    last state as a function of every step's action, without and with contact."""

    def run_actions(self, scene, actions, weights):
        rollout = weft_torch.Rollout(scene)
        x, v = rollout.initial_state(requires_grad=False)
        for a in actions:
            x, v = rollout.step(x, v, a)
        return (weights * x).sum()

    def test_gradcheck_through_actions(self):
        from test_drive import scene
        s = scene(steps=4, keyframes=False)
        weights = torch.tensor(
            __import__("numpy").random.default_rng(2).uniform(-1, 1, (36, 3)))
        actions = torch.tensor(
            __import__("numpy").random.default_rng(4).uniform(-0.02, 0.02, (4, 2, 3)),
            requires_grad=True)
        self.assertTrue(torch.autograd.gradcheck(
            lambda a: self.run_actions(s, a, weights), (actions,), eps=1e-6, atol=1e-6,
            rtol=1e-5))

    def test_gradcheck_through_actions_with_contact(self):
        # CONTACT's cloth sliding on the sphere, two corners held by handles the actions drive.
        import copy
        s = copy.deepcopy(CONTACT)
        s.pop("task")
        s["cloths"][0]["attachments"] = [
            {"vertices": [0], "kind": "handle", "stiffness": 2000.0,
             "trajectory": {"keyframes": [{"time": 0.0, "offset": [0, 0, 0]}]}},
            {"vertices": [24], "kind": "handle", "stiffness": 2000.0,
             "trajectory": {"keyframes": [{"time": 0.0, "offset": [0, 0, 0]}]}}]
        steps = 8
        s["time"]["steps"] = steps
        rng = __import__("numpy").random.default_rng(6)
        weights = torch.tensor(rng.uniform(-1, 1, (25, 3)))
        drift = __import__("numpy").array([0.003, -0.005, 0.0])
        actions = torch.tensor([[drift * (n + 1), drift * (n + 1)] for n in range(steps)]
                               + rng.uniform(-0.002, 0.002, (steps, 2, 3)), requires_grad=True)
        sim = weft.Simulator(s)
        touching = 0
        for a in actions.detach().numpy():
            sim.drive_handles(a)
            stats = sim.step()
            touching += stats["takeoff"] + stats["stick"] + stats["slip"]
        self.assertGreater(touching, 0)
        self.assertTrue(torch.autograd.gradcheck(
            lambda a: self.run_actions(s, a, weights), (actions,), eps=1e-6, atol=1e-5,
            rtol=1e-4))
