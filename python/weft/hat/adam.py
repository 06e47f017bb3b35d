"""Training the Hat controller through the simulator (DiffCloth Sec. 6.5, Fig. 13): each epoch
rolls the policy out from random starts, the loss's gradient reaches the policy's weights
through every step's backward pass (weft.torch.Rollout: Simulator.backward_step, the handles'
driven offsets included), and Adam updates the weights.

Under mpirun with mpi4py (python3-mpi4py), an epoch's rollouts are spread over the ranks: rank r
takes starts r, r + size, ...; the gradients are summed on rank 0, which takes the Adam step and
sends the weights back. The sums' order differs from a serial run's, so the weights agree with
it to rounding, not bit for bit."""

import time as _time

import numpy as _np
import torch as _torch

from .task import hemisphere_starts


def rollout(task, policy, direction):
    """The policy run from the start `direction`: (L as a tensor, the last positions, the end
    effectors' targets at every state [steps + 1, 2, 3]). Differentiable in the policy's
    weights unless run under torch.no_grad()."""
    ro = task.rollout(direction)
    x, v = ro.initial_state(requires_grad=False)
    base = _torch.as_tensor(task.initial_targets(direction))
    targets = base.clone()
    path = [targets.detach().numpy().copy()]
    loss = _torch.zeros((), dtype=_torch.float64)
    for n in range(1, task.steps + 1):
        targets = task.next_targets(targets, policy(task.state(x, targets)))
        x, v = ro.step(x, v, targets - base)
        loss = loss + task.step_loss(n, x)
        path.append(targets.detach().numpy().copy())
    return loss, x.detach().numpy(), _np.stack(path)


def evaluate(task, policy, directions):
    """The policy from each start, without gradients: a list of (L, success, mean distance to
    the target at the end, end-effector path)."""
    results = []
    with _torch.no_grad():
        for d in directions:
            loss, x, path = rollout(task, policy, d)
            ok, distance = task.success(x)
            results.append((float(loss), ok, distance, path))
    return results


def wait_politely(request):
    """Waits for a non-blocking MPI request with sleeps instead of MPI's busy polling, so that a
    rank waiting for the others leaves its core to them (as the C++ layer's waits do)."""
    while not request.Test():
        _time.sleep(0.001)


def _communicator():
    try:
        from mpi4py import MPI
    except ImportError:
        return None
    comm = MPI.COMM_WORLD
    return comm if comm.Get_size() > 1 else None


def train_adam(task, policy, epochs, starts_per_epoch=20, lr=3e-3, seed=1, log=None,
               distribute=True):
    """Adam on the mean L over `starts_per_epoch` random starts per epoch. Returns one record per
    epoch: epoch, simulated_steps (forward steps so far, each with its backward step),
    train_loss (the epoch's mean L, before its update), seconds. Under mpirun the rollouts are
    spread over the ranks unless `distribute` is false."""
    comm = _communicator() if distribute else None
    rank, size = (comm.Get_rank(), comm.Get_size()) if comm else (0, 1)
    optimizer = _torch.optim.Adam(policy.parameters(), lr=lr)
    params = list(policy.parameters())
    records, steps, start_time = [], 0, _time.perf_counter()
    for epoch in range(epochs):
        starts = hemisphere_starts(starts_per_epoch, seed * 1_000_003 + epoch)
        optimizer.zero_grad()
        total = 0.0
        for d in starts[rank::size]:
            loss, _, _ = rollout(task, policy, d)
            (loss / starts_per_epoch).backward()
            total += float(loss)
        if comm:
            for p in params:  # a rank with no start this epoch adds zeros
                if p.grad is None:
                    p.grad = _torch.zeros_like(p)
            flat = _np.concatenate([p.grad.numpy().ravel() for p in params] + [[total]])
            summed = _np.zeros_like(flat) if rank == 0 else None
            wait_politely(comm.Ireduce(flat, summed, root=0))
            if rank == 0:
                offset = 0
                for p in params:
                    p.grad.copy_(_torch.from_numpy(summed[offset:offset + p.numel()])
                                 .reshape(p.shape))
                    offset += p.numel()
                total = float(summed[-1])
        if rank == 0:
            optimizer.step()
        if comm:
            weights = _np.concatenate([p.detach().numpy().ravel() for p in params])
            wait_politely(comm.Ibcast(weights, root=0))
            offset = 0
            with _torch.no_grad():
                for p in params:
                    p.copy_(_torch.from_numpy(weights[offset:offset + p.numel()]).reshape(p.shape))
                    offset += p.numel()
        steps += starts_per_epoch * task.steps
        record = {"epoch": epoch + 1, "simulated_steps": steps,
                  "train_loss": total / starts_per_epoch,
                  "seconds": _time.perf_counter() - start_time}
        records.append(record)
        if log and rank == 0:
            log(record)
    return records
