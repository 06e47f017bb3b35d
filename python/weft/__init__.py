"""Weft, a differentiable cloth simulator, from Python (docs/python.md).

    import weft
    run = weft.simulate("assets/scenes/wind.json", steps=20, set={"wind.strength": 3.0})
    run.positions            # float64 [steps + 1, vertices, 3], as positions.npy
    grads = weft.gradient("assets/scenes/wind_sysid.json")   # {param path: dL/dp}

A scene is a scene file's path (str or os.PathLike) or the scene as a dict (what json.load gives
for a scene file). A dict's relative mesh and target paths resolve against the current working
directory, and its errors name it "<dict>". `set` overrides values by their JSON path, as the
CLI's --set does: a dict {path: value} (values as JSON: numbers, lists, strings) or a list of
"PATH=VALUE" strings.

Errors are exceptions: InputError (a ValueError) where the CLI exits 2, NumericalError (a
RuntimeError) where it exits 3. str(error) is the CLI's message without its "error: " prefix.
The engine's warnings (repaired meshes, unconverged steps) are issued as WeftWarning.
"""

import collections as _collections
import json
import os
import threading as _threading
import warnings as _warnings

import numpy as _np

from . import _weft

__version__ = _weft.__version__

InputError = _weft.InputError
NumericalError = _weft.NumericalError

__all__ = [
    "simulate",
    "gradient",
    "Gradient",
    "Run",
    "Simulator",
    "InputError",
    "NumericalError",
    "WeftWarning",
]


class WeftWarning(UserWarning):
    """A warning of the engine, as the CLI prints it after "warning: "."""


def _warn(texts):
    for text in texts:
        _warnings.warn(text, WeftWarning, stacklevel=3)


def _json_value(value):
    """A `set` value as JSON-ready Python (NumPy scalars and arrays included)."""
    if isinstance(value, _np.ndarray):
        return value.tolist()
    if isinstance(value, _np.generic):
        return value.item()
    if isinstance(value, (list, tuple)):
        return [_json_value(v) for v in value]
    return value


def _input_error(file, path, reason):
    """An InputError as the engine raises them: `<file>: <path>: <reason>`, with the parts."""
    error = InputError(f"{file}: {path}: {reason}")
    error.file, error.path, error.reason = file, path, reason
    return error


def _overrides(set, name):
    """`set` as the CLI's --set arguments, "PATH=VALUE" (a dict's values written as JSON)."""
    if set is None:
        return []
    if isinstance(set, dict):
        out = []
        for path, value in set.items():
            if not isinstance(path, str):
                raise TypeError(f"set: keys must be JSON paths (str), got {path!r}")
            try:
                text = json.dumps(_json_value(value), allow_nan=False)
            except (TypeError, ValueError) as e:
                raise _input_error(name, f"--set {path}", f"not a JSON value: {e}") from None
            out.append(f"{path}={text}")
        return out
    if isinstance(set, str):
        raise TypeError('set: give a dict {path: value} or a list of "PATH=VALUE" strings')
    out = list(set)
    for item in out:
        if not isinstance(item, str):
            raise TypeError(f'set: list items must be "PATH=VALUE" strings, got {item!r}')
    return out


def _source(scene, set):
    """The (file, document, overrides) arguments of the compiled calls."""
    if isinstance(scene, dict):
        try:
            document = json.dumps(scene, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise _input_error("<dict>", "<json>", f"not a JSON document: {e}") from None
        return None, document, _overrides(set, "<dict>")
    if isinstance(scene, (str, os.PathLike)):
        file = os.fspath(scene)
        if not isinstance(file, str):
            raise TypeError("scene: a path given as bytes is not supported; give a str")
        return file, None, _overrides(set, file)
    raise TypeError(f"scene: a path or a dict, got {type(scene).__name__}")


class Run:
    """A simulated run: what `weft simulate` writes, as arrays.

    positions, velocities: float64 [steps + 1, vertices, 3] (state 0 is the initial state)
    stats: the per-step statistics (stats.csv's quantities), a dict of 1-D arrays of length
        steps: step, time, converged, residual, pd_iterations, takeoff, stick, slip,
        contact_sweeps, late_contacts, depth, substeps, halvings, and the impact zones' (0 and
        True without them): impact_rounds, impact_zones, impact_constraints,
        impact_qp_iterations, impact_rigid_zones, impacts_resolved, impact_move
    summary: summary.json's fields (without area_ratio), as a dict
    warnings: the engine's warnings, as strings
    """

    def __init__(self, result):
        self.positions = result["positions"]
        self.velocities = result["velocities"]
        self.stats = result["stats"]
        self.summary = json.loads(result["summary"])
        self.warnings = list(result["warnings"])

    @property
    def steps(self):
        return self.positions.shape[0] - 1

    @property
    def vertices(self):
        return self.positions.shape[1]

    def __repr__(self):
        return f"<weft.Run {self.summary.get('scene')!r}: {self.steps} steps, {self.vertices} vertices>"


def simulate(scene, steps=None, set=None):
    """Runs `scene` for `steps` steps (default: its time.steps), as `weft simulate` does.

    Returns a Run whose positions equal, bit for bit, the positions.npy `weft simulate` writes
    for the same scene, --steps and --set (and the same number of OpenMP threads).
    """
    if steps is not None and (isinstance(steps, bool) or not isinstance(steps, (int, _np.integer))):
        raise TypeError(f"steps: an int or None, got {type(steps).__name__}")
    file, document, overrides = _source(scene, set)
    run = Run(_weft.simulate(file, document, overrides, None if steps is None else int(steps)))
    _warn(run.warnings)
    return run


class Gradient(dict):
    """{parameter path: dL/dp} of the scene's task loss, with what the backward pass reports.

    loss: the task loss of the (tightened) forward run
    parameter_values: {path: value} the gradient was taken at
    error_estimate: the gradient's estimated relative error |g - g_exact| / |g| (the pass
        against one at a 100 times looser tolerance, tightened until it meets
        solver.backward.accuracy; diff/GradientErrorControl.h)
    error_estimates: {path: estimated absolute error of dL/dp}
    error: how it was estimated (basis, passes, requested, met, tolerance)
    backward: the backward pass's statistics (method, tolerance, solves, iterations, ...)
    unconverged_steps: forward steps that stopped at the iteration cap
    warnings: the engine's warnings, as strings
    """

    def __init__(self, result):
        super().__init__(zip(result["params"], (float(g) for g in result["gradient"])))
        self.loss = result["loss"]
        self.parameter_values = dict(zip(result["params"], (float(v) for v in result["values"])))
        self.error_estimate = result["error_estimate"]
        self.error_estimates = dict(
            zip(result["params"], (float(e) for e in result["error_estimates"])))
        self.error = dict(result["error"])
        self.backward = result["backward"]
        self.unconverged_steps = result["unconverged_steps"]
        self.warnings = list(result["warnings"])


def gradient(scene, params=None, set=None, values=None):
    """The adjoint gradient of the scene's task loss, as `weft gradcheck` computes it.

    params: parameter JSON paths (default: the scene's task.parameters), as gradcheck's --param
    values: the parameters' values to take the gradient at, one per parameter (default: the
        scene's own)
    Returns a Gradient, a dict {path: dL/dp} equal to `weft gradcheck --json`'s "adjoint"
    values: the same tightened forward run (Newton-PCG to 1e-8 m/s^2) and adjoint solves
    (relative residual 1e-8), without the finite differences.
    """
    file, document, overrides = _source(scene, set)
    if isinstance(params, str):
        params = [params]
    if params is not None:
        params = list(params)
    if values is not None:
        values = [float(v) for v in _np.asarray(values, dtype=_np.float64).reshape(-1)]
    result = Gradient(_weft.gradient(file, document, overrides, params, values))
    _warn(result.warnings)
    return result


StepGradient = _collections.namedtuple(
    "StepGradient", ["dL_dx", "dL_dv", "dL_dparams", "dL_dhandles"])
StepGradient.__doc__ = """Simulator.backward_step's result: dL/dx and dL/dv at the step's start
state ([vertices, 3]), {path: dL/dp} of the step, and dL/d(offset) of each handle's driven target
over the step ([handles, 3])."""


class Simulator:
    """A scene's simulator, stepped one step at a time.

        sim = weft.Simulator("assets/scenes/wind.json")
        while sim.step_index < 10:
            stats = sim.step()
        sim.positions       # [vertices, 3] copy of the current state

    The states are those of weft.simulate (and `weft simulate`) step for step. A step runs
    without the GIL; calls on one Simulator from several threads take turns.

    A script may act between steps: drive_handles moves the handles (a policy's action, as in
    DiffCloth Sec. 6.5), set_state replaces the state. backward_step returns the gradient of the
    driven handles' offsets with the rest of the step's backward pass.
    """

    def __init__(self, scene, set=None):
        file, document, overrides = _source(scene, set)
        self._sim = _weft.Simulator(file, document, overrides)
        self._lock = _threading.Lock()

    def step(self):
        """Advances one step; returns its statistics (the fields of Run.stats) as a dict."""
        with self._lock:
            return self._sim.step()

    def backward_step(self, step, dL_dx, dL_dv, params=()):
        """The backward pass of one step already taken (state `step` -> `step` + 1).

        From dL/dx and dL/dv at state step + 1 (everything the loss owes to the later states,
        through them), returns (dL/dx, dL/dv) at state `step` -- the step's part: add the loss's
        own dL/dx at that state before passing them to the step before -- and {path: dL/dp} of
        the step for the parameter paths `params` (as weft.gradient names them; the initial
        velocity's part is added at step 0). Summed from the last step to the first this is
        weft.gradient's pass; a policy acting between steps interleaves its own terms. Each step's
        adjoint is solved by the direct sparse LU (exact to round-off; DiffCloth Eqs. 16-19, 29).
        Go from later steps to earlier ones. Bad input raises InputError.

        Returns a StepGradient (dL_dx, dL_dv, dL_dparams, dL_dhandles); dL_dhandles[h] is
        dL/d(offset) of handle h's target over this step (see drive_handles), whether or not it
        was driven. Parameters of a driven handle's trajectory or stiffness are refused: the run
        no longer follows them. Steps before the last set_state are refused.
        """
        with self._lock:
            r = self._sim.backward_step(int(step), dL_dx, dL_dv, list(params))
        return StepGradient(r["dL_dx"], r["dL_dv"], dict(r["dL_dparams"]), r["dL_dhandles"])

    @property
    def contacts(self):
        """The last step's contacts (none before the first step or without contact), one row
        per contact, as a dict of arrays: `node` (the cloth vertex; the lower of a
        self-collision pair), `partner` (the pair's other vertex, else -1), `obstacle` (the
        scene obstacle, else -1), `branch` (DiffCloth Eq. 8: 1 take-off, 2 stick, 3 slip, as in
        contact_branches.npy), `friction`, and [k, 3] arrays `normal` (unit, out of the
        obstacle or from partner to node), `impulse` (N s on `node`; the mean force is
        impulse / dt) and `velocity` (the velocity the law holds for, m/s)."""
        with self._lock:
            return self._sim.contacts

    @property
    def handles(self):
        """The scene's handles (attachments of kind "handle") in scene order: a list of dicts
        with `cloth`, `attachment` (its index in the cloth's attachments), `vertices` (global
        vertex indices), `anchors` (their initial positions, [k, 3]) and `stiffness`."""
        with self._lock:
            return self._sim.handles

    def drive_handles(self, offsets):
        """Drives the handles: from the next step on, handle h's vertices are pulled to their
        anchors + offsets[h] (a translation, [handles, 3], in metres), held over each step,
        until driven again; the handles' trajectories in the scene no longer apply. A policy's
        action (the end effectors' next positions, DiffCloth Sec. 6.5): set it before each
        step. backward_step's dL_dhandles is the gradient of the offsets a step was driven to.
        """
        with self._lock:
            self._sim.drive_handles(offsets)

    def set_state(self, positions, velocities):
        """Replaces the current state ([vertices, 3] each, finite); the solver's warm start is
        dropped. The steps after it start from this state; backward_step covers only the steps
        from here on, and its dL/dx, dL/dv at this step are the gradient of the state set."""
        with self._lock:
            self._sim.set_state(positions, velocities)

    @property
    def positions(self):
        """The current positions, a [vertices, 3] copy."""
        with self._lock:
            return self._sim.positions

    @property
    def velocities(self):
        """The current velocities, a [vertices, 3] copy."""
        with self._lock:
            return self._sim.velocities

    @property
    def step_index(self):
        """The index of the current state (0 before the first step)."""
        with self._lock:
            return self._sim.step_index

    @property
    def time(self):
        with self._lock:
            return self._sim.time

    @property
    def dt(self):
        return self._sim.dt

    @property
    def vertices(self):
        return self._sim.vertices

    @property
    def steps(self):
        """The scene's time.steps."""
        return self._sim.steps
