"""Transient unbalance response by time integration (gk.transient; docs/transient.md)."""
from __future__ import annotations

import numpy as _np

from ._core import InputError, Scene, System
from . import _core
from . import _defaults as _D
from ._results import Result, UNITS as _UNITS, factor as _factor
_PER_SECOND = {"rad/s": "rad/s^2", "Hz": "Hz/s", "rpm": "rpm/s"}


class TransientResponse(Result):
    """A run of `transient`: every step's time t (s) and speed (in `unit`), the displacements z[n, k] of the
    recorded DOFs `dofs` (names; their units: m, rad), the step `dt` (s), `notes` (the step chosen, coefficients
    held) and `stats` (steps, factorizations, ...). `envelope`: per window of whole revolutions (up to `windows`
    windows) the peak |z| of each DOF (windows x dofs) and the time, speed and revolution where it occurred, with
    `steady`, the steady unbalance response amplitude at that speed."""

    def __init__(self, d, names, unit, profile):
        factor = _UNITS[unit]
        self.unit = unit
        self.t = d["t"]
        self.speed = d["speed"] * factor
        self.z = d["z"]
        self.dofs = [names[k] for k in d["dofs"]]
        self.dt = d["dt"]
        self.notes = list(d["notes"])
        self.stats = dict(d["stats"])
        e = d["envelope"]
        self.envelope = {"time": e["t"], "speed": e["speed"] * factor, "revolution": e["revolution"].astype(int),
                         "peak": e["peak"], "steady": e["steady"], "end": e["end"]}
        self._profile = profile   # rad/s: from, to, acceleration
        self._take_reports(d)     # the CLI's table: the envelope against the steady response
        self._run = d["run"]

    def __repr__(self):
        return f"<gyrokit.TransientResponse: {len(self.t)} samples of {self.dofs}, dt {self.dt:.4g} s>"

    def to_pandas(self, table="history"):
        """`history`: every step (time, speed, one column per DOF); `envelope`: one row per window and DOF
        (time, speed, revolution, dof, peak, steady), as the CLI prints it."""
        import pandas as pd
        if table == "history":
            return pd.DataFrame({"time": self.t, "speed": self.speed, **{n: self.z[:, k] for k, n in enumerate(self.dofs)}})
        if table == "envelope":
            e, rows = self.envelope, len(self.envelope["peak"])
            return pd.DataFrame({"time": e["time"].ravel(), "speed": e["speed"].ravel(),
                                 "revolution": e["revolution"].ravel(), "dof": self.dofs * rows,
                                 "peak": e["peak"].ravel(), "steady": e["steady"].ravel()})
        raise InputError(f"table = {table!r}; allowed: history, envelope")

    def waterfall(self, dof=0, windows=40, frequencies=300):
        """Spectra of `windows` Hann windows (half overlapping) of the recorded DOF `dof` (a name or a column):
        a dict with the window centres' t and speed (in `unit`), the frequencies (in `unit`, up to 1.5 x the top
        speed) and amplitude[window, frequency] (a sine of amplitude A reads A)."""
        if isinstance(dof, str):
            if dof not in self.dofs:
                raise InputError(f"waterfall dof '{dof}': allowed: a recorded DOF ({', '.join(self.dofs)}) "
                                       f"or a column 0 to {len(self.dofs) - 1}")
            k = self.dofs.index(dof)
        else:
            k = int(dof)
            if not 0 <= k < len(self.dofs):
                raise InputError(f"waterfall dof {dof}: allowed: a column 0 to {len(self.dofs) - 1} or a "
                                       f"recorded DOF ({', '.join(self.dofs)})")
        w = _core.transient_waterfall(list(self.t), list(self.speed / _UNITS[self.unit]), self.z[:, k],
                                      *self._profile, self.dt, int(windows), int(frequencies))
        w["speed"] = w["speed"] * _UNITS[self.unit]
        w["frequencies"] = w["frequencies"] * _UNITS[self.unit]
        return w

    def plot(self, path=None, axes=None):
        """The CLI's --plot picture: the orbit at a constant speed (the first two DOFs, the steady orbit dashed),
        else the run-up envelope against the steady response (thin); matplotlib, or gnuplot into `path`."""
        return self._draw_figure(self._run.figure(self.unit), path, axes)

    def plot_waterfall(self, path=None, axes=None):
        """The CLI's --waterfall picture of the first two recorded DOFs, with the 1x line."""
        return self._draw_figure(self._run.waterfall_figure(self.unit), path, axes)


def _outputs(system, dofs, node):
    if dofs is not None and node is not None:
        raise InputError("dofs and node: allowed: one of them")
    names = system.dof_names
    if node is not None:
        return [names.index(n) for n in (f"x{int(node)}", f"y{int(node)}") if n in names] or \
            _fail(f"node = {node!r}: no DOFs x{node}, y{node}; allowed: a node of the model")
    out = []
    for d in dofs or []:
        if d not in names:
            raise InputError(f"dofs: {d!r} is not a DOF of the model; allowed: names such as {names[0]!r}")
        out.append(names.index(d))
    return out


def _fail(message):
    raise InputError(message)


def _profile(speed, run_up, acceleration, unit):
    """(from, to, acceleration) in rad/s from the keywords in `unit`, checked as the CLI does."""
    factor = _UNITS[unit]
    if (speed is None) == (run_up is None):
        raise InputError("speed, run_up: allowed: one of them (a constant speed, or run_up=(W0, W1) with acceleration)")
    if speed is not None:
        if acceleration is not None:
            raise InputError("acceleration: only together with run_up=(W0, W1)")
        return float(speed) / factor, float(speed) / factor, 0.0
    w0, w1 = (float(v) for v in run_up)
    if acceleration is None:
        raise InputError(f"run_up needs acceleration ({_PER_SECOND[unit]}; > 0 for a run-up, < 0 for a run-down)")
    a = float(acceleration)
    if w0 != w1 and min(w0, w1) >= 0 and not (_np.isfinite(a) and (w1 - w0) * a > 0):
        kind, sign = ("run-up", ">") if w1 > w0 else ("run-down", "<")
        raise InputError(f"acceleration = {acceleration} {_PER_SECOND[unit]} with a {kind} from {w0:g} to {w1:g} "
                         f"{unit}: allowed: a finite number {sign} 0")
    return w0 / factor, w1 / factor, a / factor


def transient(model, speed=None, *, run_up=None, acceleration=None, duration=None, dt=None, dofs=None, node=None,
              unit=None, start="rest", max_steps=_D.MAX_STEPS, solver=None, windows=20) -> TransientResponse:
    """The unbalance response of `model` (a System or Scene) in time, by Newmark's average-acceleration method:
    at a constant `speed`, or in a run-up / run-down `run_up=(W0, W1)` at `acceleration` (in `unit` per s: rad/s^2,
    Hz/s, rpm/s), for `duration` s (default: the ramp; 100 revolutions at a constant speed; after the ramp the
    speed holds) with the step `dt` s (default: 32 steps per period of 1.5 x the top speed). Records `dofs` (names)
    or the x, y of `node` (default: the node of the largest unbalance); `start`: "rest" or "steady" (the steady
    response at the first speed). Speeds in `unit` (default the scene's [speeds] units, else rad/s).
    See docs/transient.md."""
    unit = _core.resolve_unit(model, unit)
    if start not in ("rest", "steady"):
        raise InputError(f"start = {start!r}; allowed: rest, steady")
    system = model.system if isinstance(model, Scene) else model
    if not isinstance(system, System):
        raise InputError(f"expected a gyrokit.System or gyrokit.Scene, got {type(model).__name__}")
    profile = _profile(speed, run_up, acceleration, unit)
    for key, value in (("duration", duration), ("dt", dt)):   # 0 means the default to the library
        if value is not None and value == 0:
            raise InputError(f"{key} = 0 s: allowed: a finite time > 0 (s); None: the default")
    d = _core.transient(system, *profile, float(0.0 if duration is None else duration),
                        float(0.0 if dt is None else dt), _outputs(system, dofs, node), start == "steady",
                        int(max_steps), solver or (model.solver if isinstance(model, Scene) else "auto"),
                        int(windows), unit, model.length_unit if isinstance(model, Scene) else "m")
    return TransientResponse(d, system.dof_names, unit, profile)
