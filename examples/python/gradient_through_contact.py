"""A gradient through frictional contact: a napkin thrown onto a sphere (friction 0.4) slides
over it; how does the final position of its corner depend on the throw's initial velocity and on
the friction coefficient? weft.torch.Rollout differentiates every step, contacts included
(DiffCloth Sec. 4-5), and the result is checked against central differences.

    PYTHONPATH=build/python python3 examples/python/gradient_through_contact.py
"""
import torch
import weft
import weft.torch

scene = {
    "name": "throw_onto_sphere",
    "time": {"dt": 0.01, "steps": 30},
    "gravity": [0, -9.8, 0],
    "solver": {"method": "newton", "pd_tolerance": 1e-9, "pd_iterations": 20000},
    "cloths": [{"mesh": {"grid": {"size": [0.4, 0.4], "resolution": [6, 6]},
                         "transform": {"translate": [0.05, 0.32, 0]}},
                "material": {"density": 0.2, "stretch": 300.0, "bend": 0.001},
                "initial_velocity": [0.3, -0.5, 0]}],
    "obstacles": [{"sphere": {"center": [0, 0, 0], "radius": 0.3}, "friction": 0.4}],
}
params = ["obstacles.0.friction", "cloths.0.initial_velocity.0"]
rollout = weft.torch.Rollout(scene, params=params)
x, v = rollout.initial_state()
for _ in range(scene["time"]["steps"]):
    x, v = rollout.step(x, v)
corner = x[0, 0]  # the x coordinate of vertex 0 at the end
corner.backward()
print(f"final x of vertex 0: {corner.item():.6f} m")
for path, g in zip(params, rollout.theta.grad.tolist()):
    h = 1e-5
    ends = []
    for sign in (1, -1):
        value = {"obstacles.0.friction": 0.4, "cloths.0.initial_velocity.0": 0.3}[path]
        run = weft.simulate(scene, set={path: value + sign * h})
        ends.append(run.positions[-1, 0, 0])
    print(f"d x / d {path}: adjoint {g:+.6f}, central difference {(ends[0] - ends[1]) / (2 * h):+.6f}")
