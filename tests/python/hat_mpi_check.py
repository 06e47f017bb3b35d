"""Run under mpirun with 2 ranks (ctest python.hat_mpi): the Hat controller trained with its
rollouts spread over the ranks (mpi4py) against the same training on rank 0 alone. The weights
and losses agree to rounding (the gradients' sums are taken in another order), not bit for bit."""

import sys

import numpy as np
import torch
from mpi4py import MPI

from weft.hat.adam import train_adam
from weft.hat.policy import Policy
from weft.hat.task import HatTask

torch.set_num_threads(1)
comm = MPI.COMM_WORLD
assert comm.Get_size() == 2, f"run with 2 ranks, not {comm.Get_size()}"
task = HatTask(steps=6, last_frames=3)


def weights(policy):
    return np.concatenate([p.detach().numpy().ravel() for p in policy.parameters()])


spread = Policy(task.state_size, task.action_size, seed=0)
spread_records = train_adam(task, spread, epochs=2, starts_per_epoch=3, lr=1e-2)
if comm.Get_rank() == 0:
    alone = Policy(task.state_size, task.action_size, seed=0)
    alone_records = train_adam(task, alone, epochs=2, starts_per_epoch=3, lr=1e-2,
                               distribute=False)
    a, b = weights(spread), weights(alone)
    moved = np.abs(b - weights(Policy(task.state_size, task.action_size, seed=0))).max()
    difference = np.abs(a - b).max()
    print(f"weights moved by up to {moved:.3e}; spread and alone differ by {difference:.3e}")
    assert moved > 1e-4, "training did not move the weights"
    assert difference <= 1e-9 * moved, difference
    for r, q in zip(spread_records, alone_records):
        assert abs(r["train_loss"] - q["train_loss"]) <= 1e-12 * abs(q["train_loss"]), (r, q)
else:
    # Rank 1's copy of the weights is rank 0's (broadcast after every step).
    comm.send(weights(spread), dest=0)
if comm.Get_rank() == 0:
    other = comm.recv(source=1)
    assert np.array_equal(other, weights(spread)), "the ranks' weights differ"
    print("ok")
sys.exit(0)
