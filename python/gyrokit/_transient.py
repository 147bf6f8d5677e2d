"""Transient unbalance response by time integration (gk.transient; docs/transient.md)."""
from __future__ import annotations

from ._core import InputError
from . import _core
from . import _defaults as _D
from ._results import Result, UNITS as _UNITS


class TransientResponse(Result):
    """A run of `transient`: every step's time t (s) and speed (in `unit`), the displacements z[n, k] of the
    recorded DOFs `dofs` (names; their units: m, rad), the step `dt` (s), `notes` (the step chosen, coefficients
    held) and `stats` (steps, factorizations, ...). `envelope`: per window of whole revolutions (up to `windows`
    windows) the peak |z| of each DOF (windows x dofs) and the time, speed and revolution where it occurred, with
    `steady`, the steady unbalance response amplitude at that speed."""

    def __init__(self, d):
        unit = d["unit"]
        factor = _UNITS[unit]
        self.unit = unit
        self.t = d["t"]
        self.speed = d["speed"] * factor
        self.z = d["z"]
        self.dofs = list(d["dofs"])
        self.dt = d["dt"]
        self.notes = list(d["notes"])
        self.stats = dict(d["stats"])
        e = d["envelope"]
        self.envelope = {"time": e["t"], "speed": e["speed"] * factor, "revolution": e["revolution"].astype(int),
                         "peak": e["peak"], "steady": e["steady"], "end": e["end"]}
        self._profile = tuple(d["profile"])   # rad/s: from, to, acceleration
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


def transient(model, speed=None, *, run_up=None, acceleration=None, duration=None, dt=None, dofs=None, node=None,
              unit=None, start=_D.START, max_steps=_D.MAX_STEPS, solver=None, windows=20) -> TransientResponse:
    """The unbalance response of `model` (a System or Scene) in time, by Newmark's average-acceleration method:
    at a constant `speed`, or in a run-up / run-down `run_up=(W0, W1)` at `acceleration` (in `unit` per s: rad/s^2,
    Hz/s, rpm/s), for `duration` s (default: the ramp; 100 revolutions at a constant speed; after the ramp the
    speed holds) with the step `dt` s (default: 32 steps per period of 1.5 x the top speed). Records `dofs` (names)
    or the x, y of `node` (default: the node of the largest unbalance); `start`: "rest" or "steady" (the steady
    response at the first speed). Speeds in `unit` (default the scene's [speeds] units, else rad/s).
    See docs/transient.md."""
    run = dict(speed=speed, run_up=run_up, acceleration=acceleration, duration=duration, dt=dt, dofs=dofs, node=node,
               start=start, max_steps=max_steps)
    d = _core.transient(model, dict(unit=unit, solver=solver), run, int(windows))
    return TransientResponse(d)
