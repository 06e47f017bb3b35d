"""Weft's task loss as a PyTorch function of scene parameters (docs/python.md).

    import torch, weft.torch
    theta = torch.tensor([300.0, 1.5], dtype=torch.float64, requires_grad=True)
    loss = weft.torch.task_loss(theta, "assets/scenes/wind_sysid.json",
                                ["cloths.0.material.stretch", "wind.strength"])
    loss.backward()          # theta.grad = dL/dtheta by Weft's adjoint pass

The forward pass runs the scene with the parameters set to the tensor's values and returns its
task loss; the backward pass is the adjoint gradient weft.gradient computes (the forward run
and adjoint solves tightened as `weft gradcheck` does), so one call costs one forward and one
backward run. Double precision only; the tensor must be 1-D with one value per parameter.

Rollout makes the simulator's steps differentiable for losses on the states themselves (each
step's backward is weft.Simulator.backward_step).
"""

import numpy as _np
import torch as _torch

import weft as _weft


class TaskLoss(_torch.autograd.Function):
    """values (1-D float64 tensor, one per parameter path) -> the scene's task loss (0-D)."""

    @staticmethod
    def forward(ctx, values, scene, params, set):
        if values.dtype != _torch.float64:
            raise TypeError(f"values: a float64 tensor, got {values.dtype}")
        if values.dim() != 1 or values.numel() != len(params):
            raise ValueError(
                f"values: a 1-D tensor of {len(params)} values (one per parameter), "
                f"got shape {tuple(values.shape)}"
            )
        result = _weft.gradient(
            scene, params=params, set=set, values=values.detach().cpu().numpy()
        )
        grad = _torch.tensor(_np.array(list(result.values()), dtype=_np.float64))
        ctx.save_for_backward(grad.to(values.device))
        return _torch.tensor(result.loss, dtype=_torch.float64, device=values.device)

    @staticmethod
    def backward(ctx, grad_output):
        (grad,) = ctx.saved_tensors
        return grad_output * grad, None, None, None


def task_loss(values, scene, params, set=None):
    """The task loss of `scene` with the parameters `params` (JSON paths) set to `values`."""
    params = [params] if isinstance(params, str) else list(params)
    return TaskLoss.apply(values, scene, params, set)


class _Step(_torch.autograd.Function):
    """(x_n, v_n, theta, action) -> (x_{n+1}, v_{n+1}): one step of a Rollout's simulator, its
    handles driven to `action` (offsets, [handles, 3]) when one is given."""

    @staticmethod
    def forward(ctx, x, v, theta, action, rollout):
        sim = rollout.simulator
        xs, vs = x.detach().cpu().numpy(), v.detach().cpu().numpy()
        if not (_np.array_equal(xs, sim.positions) and _np.array_equal(vs, sim.velocities)):
            if sim.step_index != 0:
                raise ValueError(
                    "Rollout.step: x and v must be the simulator's current state (the previous "
                    "step's outputs); only the initial state may be replaced")
            sim.set_state(xs, vs)
        if action is not None:
            if action.dtype != _torch.float64:
                raise TypeError(f"action: a float64 tensor, got {action.dtype}")
            sim.drive_handles(action.detach().cpu().numpy())
        ctx.rollout = rollout
        ctx.step = sim.step_index
        ctx.device = x.device
        ctx.has_action = action is not None
        sim.step()
        return (_torch.tensor(sim.positions, dtype=_torch.float64, device=x.device),
                _torch.tensor(sim.velocities, dtype=_torch.float64, device=x.device))

    @staticmethod
    def backward(ctx, grad_x, grad_v):
        rollout = ctx.rollout
        dx, dv, dp, dh = rollout.simulator.backward_step(
            ctx.step, grad_x.detach().cpu().numpy(), grad_v.detach().cpu().numpy(),
            params=rollout.params)
        grad_theta = _torch.tensor([dp[p] for p in rollout.params], dtype=_torch.float64,
                                   device=ctx.device)
        grad_action = _torch.tensor(dh, device=ctx.device) if ctx.has_action else None
        return (_torch.tensor(dx, device=ctx.device), _torch.tensor(dv, device=ctx.device),
                grad_theta, grad_action, None)


class Rollout:
    """A scene's simulator as differentiable steps, for losses on the states themselves.

        rollout = weft.torch.Rollout("assets/scenes/wind_sysid.json", params=["wind.strength"])
        x, v = rollout.initial_state()
        for _ in range(10):
            x, v = rollout.step(x, v)
        loss = ((x - target) ** 2).sum()
        loss.backward()      # rollout.theta.grad = dL/d(wind.strength); x0.grad, v0.grad too

    Each step's backward is weft.Simulator.backward_step (the direct LU per step, exact to
    round-off), called by autograd from the last step to the first. `theta` is a leaf tensor of
    offsets from the parameters' scene values, zero: the run is at the scene's values (set them
    with `set=`), and theta.grad is dL/dp there, every step's part summed. The steps must be
    chained: x and v must be the simulator's current state, except at the first step, where any
    state may be given (it is set with Simulator.set_state).

    A step may take an action: step(x, v, action) drives the handles to `action`, offsets from
    their anchors ([handles, 3], float64; Simulator.drive_handles), and gradients reach it, so a
    policy a = pi(s) trained through the simulator gets dL/dtheta (DiffCloth Sec. 6.5, Fig. 13).
    """

    def __init__(self, scene, params=(), set=None):
        self.params = [params] if isinstance(params, str) else list(params)
        self.simulator = _weft.Simulator(scene, set=set)
        self.theta = _torch.zeros(len(self.params), dtype=_torch.float64, requires_grad=True)

    def initial_state(self, requires_grad=True):
        """(x_0, v_0) as float64 tensors [vertices, 3]."""
        return (_torch.tensor(self.simulator.positions, requires_grad=requires_grad),
                _torch.tensor(self.simulator.velocities, requires_grad=requires_grad))

    def step(self, x, v, action=None):
        """One step from (x, v), the current state, the handles driven to `action` when given:
        (x_{n+1}, v_{n+1})."""
        return _Step.apply(x, v, self.theta, action, self)

    @property
    def handles(self):
        """The scene's handles (Simulator.handles)."""
        return self.simulator.handles
