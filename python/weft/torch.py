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
