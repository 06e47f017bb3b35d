"""System identification in a dozen lines: recover a napkin's stretch stiffness and the wind's
strength from a recorded motion (assets/scenes/wind_sysid.json, recorded with 250 N/m and 2.0;
the scene says 400 and 1.5, the start) with PyTorch's L-BFGS on Weft's adjoint gradient.

    PYTHONPATH=build/python python3 examples/python/system_identification.py
"""
import os

import torch
import weft.torch

scene = os.path.join(os.path.dirname(__file__), "..", "..", "assets", "scenes", "wind_sysid.json")
params = ["cloths.0.material.stretch", "wind.strength"]
scale = torch.tensor([400.0, 1.5], dtype=torch.float64)  # the scene's values
u = torch.ones(2, dtype=torch.float64, requires_grad=True)  # the parameters over `scale`
optimizer = torch.optim.LBFGS([u], max_iter=40, line_search_fn="strong_wolfe")


def closure():
    optimizer.zero_grad()
    loss = weft.torch.task_loss(u * scale, scene, params)  # a forward and an adjoint run
    loss.backward()
    print(f"loss {loss.item():.3e}  stretch {u[0].item() * 400:8.3f} N/m  wind {u[1].item() * 1.5:.5f}")
    return loss


optimizer.step(closure)
