"""The Hat controller (DiffCloth Sec. 6.5): a policy network moves two end effectors to put a hat
on a head from random starts on a hemisphere, trained with Adam through the simulator. This is
the loop of weft.hat.adam.train_adam written out; `python3 -m weft.bench hat_controller` runs the
full comparison with PPO.

    PYTHONPATH=build/python python3 examples/python/hat_controller.py [EPOCHS] [STARTS]
"""
import sys

import torch
from weft.hat.policy import Policy
from weft.hat.task import HatTask, hemisphere_starts

torch.set_num_threads(1)
epochs = int(sys.argv[1]) if len(sys.argv) > 1 else 5
starts = int(sys.argv[2]) if len(sys.argv) > 2 else 4
task = HatTask()  # assets/scenes/hat_controller.json: 239-vertex hat, 50 steps of 0.02 s
policy = Policy(task.state_size, task.action_size)
optimizer = torch.optim.Adam(policy.parameters(), lr=3e-3)
for epoch in range(epochs):
    optimizer.zero_grad()
    total = 0.0
    for direction in hemisphere_starts(starts, seed=epoch):
        rollout = task.rollout(direction)              # weft.torch.Rollout from this start
        x, v = rollout.initial_state(requires_grad=False)
        base = torch.as_tensor(task.initial_targets(direction))
        targets, loss = base.clone(), 0.0
        for n in range(1, task.steps + 1):
            targets = task.next_targets(targets, policy(task.state(x, targets)))  # a = pi(s)
            x, v = rollout.step(x, v, targets - base)  # the handles driven to the action
            loss = loss + task.step_loss(n, x)         # L_deform + L_target + L_dir
        (loss / starts).backward()                     # through every step into the policy
        total += loss.item()
    optimizer.step()
    print(f"epoch {epoch + 1}: mean loss {total / starts:.3f}")
