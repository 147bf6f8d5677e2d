"""gyrokit: Campbell diagrams, critical speeds and stability of gyroscopic systems.

Load a scene or build a system from NumPy or SciPy matrices, then call the
analyses; results are small objects holding NumPy arrays, with ``to_pandas()``
(when pandas is installed) and ``plot()`` (when matplotlib is installed).
Errors are ``gyrokit.Error`` (``InputError`` for bad input, ``SolverError``
when no verified answer was found). See docs/python.md.
"""
from __future__ import annotations

import numpy as _np

from ._core import Error, InputError, Scene, SolverError, System, __version__
from . import _core

__all__ = ["Error", "InputError", "SolverError", "System", "Scene", "load_scene", "eig", "campbell",
           "critical_speeds", "stability", "screen", "EigResult", "CampbellResult", "CriticalSpeeds",
           "StabilityChanges", "ScreenResult"]


def load_scene(path, overrides=None) -> Scene:
    """Reads a scene file (TOML); `overrides` maps "TABLE.KEY" to numbers (e.g. {"model.c_G": 400.0})."""
    return _core.load_scene(str(path), dict(overrides or {}))


def _options(model, solver, modes, target, target_order):
    """The system and the solver options: a scene's [analysis] values where a keyword is None."""
    if isinstance(model, Scene):
        system = model.system
        solver = model.solver if solver is None else solver
        modes = model.modes if modes is None else modes
        target = model.target if target is None else target
        target_order = model.target_order if target_order is None else target_order
    elif isinstance(model, System):
        system = model
    else:
        raise InputError(f"expected a gyrokit.System or gyrokit.Scene, got {type(model).__name__}")
    if modes is not None and (int(modes) != modes or modes < 0):
        raise InputError(f"modes = {modes}: allowed: a whole number >= 0 (0: all)")
    return system, dict(solver=solver or "auto", modes=int(modes or 0), target=target,
                        target_order=float(target_order or 0.0))


def _speeds(model, speeds):
    if speeds is None:
        speeds = model.speeds if isinstance(model, Scene) else None
        if speeds is None:
            raise InputError("speeds: none given and the scene has no [speeds]; give speeds=np.linspace(...)")
    w = _np.asarray(speeds, dtype=float).ravel()
    if w.size == 0 or not _np.all(_np.isfinite(w)) or _np.any(w < 0):
        raise InputError("speeds: allowed: one or more finite speeds >= 0 (rad/s)")
    return w.tolist()


class _Result:
    def _frame(self, columns):
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the machine
            raise ImportError("to_pandas() needs pandas (Debian: python3-pandas)") from e
        return pd.DataFrame(columns)

    @staticmethod
    def _pyplot():
        try:
            import matplotlib.pyplot as plt
        except ImportError as e:  # pragma: no cover - depends on the machine
            raise ImportError("plot() needs matplotlib (Debian: python3-matplotlib)") from e
        return plt

    def __repr__(self):
        fields = ", ".join(f"{k}" for k in self.__dict__ if not k.startswith("_"))
        return f"<gyrokit.{type(self).__name__}: {fields}>"


class EigResult(_Result):
    """Eigenvalues at one speed, one per conjugate pair (Im >= 0) as the CLI prints, by frequency."""

    def __init__(self, d, speed):
        self.speed = speed
        self.eigenvalues = d["eigenvalues"]
        self.frequencies = self.eigenvalues.imag
        self.damping_ratios = _np.where(_np.abs(self.eigenvalues) > 0,
                                        -self.eigenvalues.real / _np.maximum(_np.abs(self.eigenvalues), 1e-300), 0.0)
        self.backward_errors = d["backward_errors"]
        self.error_bounds = d["error_bounds"]
        self.whirl = list(d["whirl"])
        self.stability = list(d["stability"])
        self.vectors = d["vectors"]
        self.rigid_body = d["rigid_body"]
        self.method = d["method"]
        self.notes = list(d["notes"])

    def to_pandas(self):
        return self._frame({"real": self.eigenvalues.real, "frequency": self.frequencies,
                            "damping_ratio": self.damping_ratios, "whirl": self.whirl, "stability": self.stability,
                            "backward_error": self.backward_errors, "error_bound": self.error_bounds})


class CampbellResult(_Result):
    """Tracked modes over speed: eigenvalues[i, b] of branch b at speeds[i] (NaN where b has no point)."""

    def __init__(self, d):
        self.speeds = d["speeds"]
        self.eigenvalues = d["eigenvalues"]
        self.frequencies = self.eigenvalues.imag
        self.backward_errors = d["backward_errors"]
        self.whirl = d["whirl"]
        self.branches = d["branches"]
        self.inserted_speeds = d["inserted_speeds"]
        self.ambiguous_steps = d["ambiguous_steps"]
        self.max_backward_error = d["max_backward_error"]
        self.rigid_body = d["rigid_body"]
        self.notes = list(d["notes"])

    def to_pandas(self):
        """One row per speed and branch: the CLI's campbell table."""
        rows = {"speed": [], "branch": [], "frequency": [], "real": [], "whirl": [], "backward_error": []}
        for i, w in enumerate(self.speeds):
            for b, branch in enumerate(self.branches):
                lam = self.eigenvalues[i, b]
                if _np.isnan(lam.real):
                    continue
                rows["speed"].append(w)
                rows["branch"].append(int(branch))
                rows["frequency"].append(lam.imag)
                rows["real"].append(lam.real)
                rows["whirl"].append(self.whirl[i][b])
                rows["backward_error"].append(self.backward_errors[i, b])
        return self._frame(rows)

    def plot(self, ax=None, harmonics=(1,)):
        """Frequency of every branch over speed, with the lines k * speed."""
        plt = self._pyplot()
        ax = ax or plt.subplots()[1]
        for b, branch in enumerate(self.branches):
            ax.plot(self.speeds, self.frequencies[:, b], label=f"mode {branch}")
        for k in harmonics:
            ax.plot(self.speeds, k * self.speeds, "k--", linewidth=0.8, label=f"{k}x")
        ax.set_xlabel("speed (rad/s)")
        ax.set_ylabel("frequency (rad/s)")
        ax.legend(fontsize="small")
        return ax


class CriticalSpeeds(_Result):
    """Crossings of tracked branches with the lines k * speed, refined by root finding."""

    def __init__(self, d):
        self.speeds = d["speeds"]
        self.harmonic = d["harmonic"]
        self.branch = d["branch"]
        self.whirl = list(d["whirl"])
        self.damping_ratio = d["damping_ratio"]

    def to_pandas(self):
        return self._frame({"speed": self.speeds, "branch": self.branch, "whirl": self.whirl,
                            "harmonic": self.harmonic, "damping_ratio": self.damping_ratio})


class StabilityChanges(_Result):
    """Speeds where a branch becomes unstable (or stable again), refined by root finding."""

    def __init__(self, d):
        self.speeds = d["speeds"]
        self.branch = d["branch"]
        self.becomes_unstable = d["becomes_unstable"]

    def to_pandas(self):
        return self._frame({"speed": self.speeds, "branch": self.branch,
                            "becomes_unstable": self.becomes_unstable})


def eig(model, speed, *, solver=None, modes=None, target=None, target_order=None, method="qz",
        lanczos=0) -> EigResult:
    """Eigenvalues at one speed (rad/s). solver: "auto" | "dense" | "sparse"; modes: 0 = all (dense)."""
    system, o = _options(model, solver, modes, target, target_order)
    return EigResult(_core.eig(system, float(speed), method=method, lanczos=int(lanczos), **o), float(speed))


def campbell(model, speeds=None, *, solver=None, modes=None, target=None, target_order=None, method="qz",
             lanczos=0, jobs=1) -> CampbellResult:
    """Campbell diagram over `speeds` (rad/s; default: the scene's [speeds]); jobs threads (0 = all cores)."""
    system, o = _options(model, solver, modes, target, target_order)
    return CampbellResult(_core.campbell(system, _speeds(model, speeds), method=method, lanczos=int(lanczos),
                                         jobs=int(jobs), **o))


def critical_speeds(model, speeds=None, *, harmonics=None, solver=None, modes=None, target=None, target_order=None,
                    method="qz", lanczos=0, jobs=1) -> CriticalSpeeds:
    """Critical speeds (rad/s) where tracked branches cross k * speed, k in `harmonics` (default: the scene's, or 1)."""
    system, o = _options(model, solver, modes, target, target_order)
    if harmonics is None:
        harmonics = model.harmonics if isinstance(model, Scene) else [1]
    return CriticalSpeeds(_core.critical_speeds(system, _speeds(model, speeds), [int(h) for h in harmonics],
                                                method=method, lanczos=int(lanczos), jobs=int(jobs), **o))


def stability(model, speeds=None, *, solver=None, modes=None, target=None, target_order=None, method="qz",
              lanczos=0, jobs=1) -> StabilityChanges:
    """Speeds where a mode becomes unstable or stable again (Re lambda beyond its error bound)."""
    system, o = _options(model, solver, modes, target, target_order)
    return StabilityChanges(_core.stability(system, _speeds(model, speeds), method=method, lanczos=int(lanczos),
                                            jobs=int(jobs), **o))


class ScreenResult(_Result):
    """Verdicts of a design study: one entry per design, in design order, as `gyrokit screen` writes them."""

    def __init__(self, d):
        self.columns = list(d["columns"])
        rows = d["rows"]
        col = {name: [r[k] for r in rows] for k, name in enumerate(self.columns)}
        number = lambda cells: _np.array([float(c) if c != "" else _np.nan for c in cells], dtype=float)
        self.design = _np.array([int(c) for c in col["design"]], dtype=int)
        self.parameters = {p: number(col[p]) for p in d["parameters"]}
        self.quantities = {q: number(col[q]) for q in d["quantities"]}
        self.verdict = col["verdict"]
        self.failed = [c.split(";") if c else [] for c in col["failed"]]
        self.reason = col["reason"]
        self.unit = d["unit"]

    @property
    def passed(self):
        return _np.array([v == "pass" for v in self.verdict])

    def to_pandas(self):
        columns = {"design": self.design, **self.parameters, **self.quantities, "verdict": self.verdict,
                   "failed": [";".join(f) for f in self.failed], "reason": self.reason}
        return self._frame(columns)

    def plot(self, x=None, y=None, ax=None):
        """The designs over two parameters, coloured by verdict (the safe region)."""
        plt = self._pyplot()
        names = list(self.parameters)
        x = x or names[0]
        y = y or names[1]
        ax = ax or plt.subplots()[1]
        for verdict, colour in (("pass", "tab:green"), ("fail", "tab:red"), ("error", "tab:gray")):
            sel = _np.array([v == verdict for v in self.verdict])
            if sel.any():
                ax.scatter(self.parameters[x][sel], self.parameters[y][sel], c=colour, label=verdict, s=12)
        ax.set_xlabel(x)
        ax.set_ylabel(y)
        ax.legend(fontsize="small")
        return ax


def screen(sweep, designs=None, *, jobs=0, progress=None) -> ScreenResult:
    """A design study: the criteria of the sweep file `sweep` on its own designs, or on `designs`, a list of
    dicts {parameter: value} (e.g. {"model.c_G": 400.0}). Designs run on `jobs` threads (0 = all cores) with
    the interpreter released; `progress(done, total)` is called after each design."""
    names = values = None
    if designs is not None:
        designs = list(designs)
        if not designs:
            raise InputError("designs: empty; allowed: a list of dicts {parameter: value}")
        names = list(designs[0])
        for i, d in enumerate(designs):
            if list(d) != names:
                raise InputError(f"designs[{i}]: parameters {sorted(d)} differ from those of designs[0] {sorted(names)}")
        values = [[float(d[n]) for n in names] for d in designs]
    return ScreenResult(_core.screen(str(sweep), names, values, int(jobs), progress))
