"""The Hat controller (DiffCloth Sec. 6.5) in a tiny version: a few epochs of short rollouts
through the simulator lower the loss from fixed test starts; PPO runs on the same task; the
task's pieces (starts on the hemisphere, the up vector, the loss's terms) are what they say."""

import math
import unittest

import numpy as np

try:
    import torch
    from weft.hat.adam import evaluate, train_adam
    from weft.hat.policy import Policy
    from weft.hat.ppo import evaluate_ppo, train_ppo
    from weft.hat.task import HatTask, elevation_azimuth_deg, hemisphere_starts
except ImportError as e:  # python3-torch missing
    torch = None
    missing = str(e)


@unittest.skipIf(torch is None, "PyTorch is not installed (python3-torch)")
class HatControllerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        torch.set_num_threads(1)
        cls.task = HatTask(steps=12, last_frames=4)
        cls.tests = hemisphere_starts(2, 99)

    def test_starts_are_on_the_upper_hemisphere(self):
        d = hemisphere_starts(200, 1)
        np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0, atol=1e-12)
        self.assertGreaterEqual(d[:, 1].min(), 0.0)
        self.assertAlmostEqual(d[:, 1].mean(), 0.5, delta=0.06)  # uniform on the hemisphere
        self.assertAlmostEqual(elevation_azimuth_deg([0.0, 1.0, 0.0])[0], 90.0)
        self.assertAlmostEqual(elevation_azimuth_deg([0.0, 0.0, 1.0])[1], 90.0)

    def test_loss_terms(self):
        task = self.task
        target = torch.as_tensor(task.target)
        # At the target pose: no deformation, no distance, aligned: zero.
        self.assertAlmostEqual(float(task.step_loss(task.steps, target)), 0.0, places=12)
        # Upside down (mirrored in y about the target's centroid): the direction term is 2.
        flipped = target.clone()
        flipped[:, 1] = 2 * target[:, 1].mean() - target[:, 1]
        self.assertAlmostEqual(float(task.step_loss(task.steps, flipped)) - float(
            (flipped - target).norm()), 2.0, places=9)
        # Moved by 1 cm: the target term is the norm over all vertices, sqrt(m) cm.
        moved = target + torch.tensor([0.01, 0.0, 0.0], dtype=torch.float64)
        self.assertAlmostEqual(float(task.step_loss(task.steps - 1, moved)),
                               0.01 * math.sqrt(task.rest.shape[0]), places=9)
        # Outside the last frames only the deform term counts.
        self.assertAlmostEqual(float(task.step_loss(1, moved)), 0.0, places=12)

    def test_adam_through_the_simulator_lowers_the_test_loss(self):
        policy = Policy(self.task.state_size, self.task.action_size, seed=0)
        before = [r[0] for r in evaluate(self.task, policy, self.tests)]
        records = train_adam(self.task, policy, epochs=3, starts_per_epoch=2, lr=1e-2)
        after = [r[0] for r in evaluate(self.task, policy, self.tests)]
        self.assertEqual(records[-1]["simulated_steps"], 3 * 2 * 12)
        self.assertLess(np.mean(after), 0.9 * np.mean(before))

    def test_ppo_runs_on_the_same_task(self):
        agent, records = train_ppo(self.task, step_budget=48, episodes_per_batch=2,
                                   update_epochs=2)
        self.assertEqual(records[-1]["simulated_steps"], 48)
        results = evaluate_ppo(agent, self.tests)
        self.assertEqual(len(results), 2)
        self.assertTrue(all(np.isfinite(r[0]) for r in results))


if __name__ == "__main__":
    unittest.main()
